"""One row of the fleet table: a recording and an axis, its fitted parameters, the loop's findings, and
what happened (time taken, attempts, the error when there was one)."""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace
from typing import Any

__all__ = ["COLUMNS", "ERROR_KINDS", "BatchRow", "error_row", "row_from_mapping"]

NAN = math.nan

#: Why a row holds no result. "data": the file or its content was refused (deterministic for a given
#: content hash, so a resumed run keeps it); "timeout", "worker", "internal": the run failed for a reason
#: outside the file (a resumed run tries again).
ERROR_KINDS = ("data", "timeout", "worker", "internal")


@dataclass(frozen=True)
class BatchRow:
    """A row of the fleet table; numbers a task does not produce are NaN.

    Field units follow IEEE Std 952 as in :meth:`carousel_theory.fitting.FitResult.field_units`: angle
    random walk in °/√h, rate random walk in °/h/√h, bias and bias instability in °/h (the minimum of
    the Allan deviation divided by 0.664). ``*_se`` is one standard error.
    """

    path: str
    task: str
    axis: str = ""
    content_hash: str = ""
    status: str = "ok"
    error_kind: str = ""
    error: str = ""
    samples: int = 0
    sample_rate_hz: float = NAN
    duration_s: float = NAN
    bias_deg_per_h: float = NAN
    bias_deg_per_h_se: float = NAN
    angle_random_walk_deg_per_sqrt_h: float = NAN
    angle_random_walk_deg_per_sqrt_h_se: float = NAN
    rate_random_walk_deg_per_h_per_sqrt_h: float = NAN
    rate_random_walk_deg_per_h_per_sqrt_h_se: float = NAN
    bias_instability_deg_per_h: float = NAN
    bias_instability_deg_per_h_se: float = NAN
    minimum_allan_deviation_rad_s: float = NAN
    tau_at_minimum_s: float = NAN
    fit_chi_square: float = NAN
    fit_degrees_of_freedom: float = NAN
    effects: str = ""
    misfit_metric: str = ""
    misfit_before: float = NAN
    misfit_after: float = NAN
    design_scheme: str = ""
    design_duration_s: float = NAN
    design_heading_sigma_deg: float = NAN
    design_heading_rms_deg: float = NAN
    seconds: float = NAN
    attempts: int = 0
    worker: str = ""
    options: str = ""

    def stamped(self, **bookkeeping: Any) -> BatchRow:
        """A copy with the run's bookkeeping (hash, seconds, attempts, worker, options) filled in."""
        return replace(self, **bookkeeping)


#: Column order of the written table.
COLUMNS: tuple[str, ...] = tuple(f.name for f in fields(BatchRow))
_TYPES = {f.name: f.type for f in fields(BatchRow)}


def error_row(path: str, task: str, kind: str, reason: str, axis: str = "") -> BatchRow:
    """The row of a recording (or axis) that produced no result, with the reason."""
    if kind not in ERROR_KINDS:
        raise ValueError(f"kind={kind!r}: must be one of {ERROR_KINDS}")
    return BatchRow(path=path, task=task, axis=axis, status="error", error_kind=kind, error=reason)


def row_from_mapping(values: dict[str, Any]) -> BatchRow:
    """Rebuild a row from a table record (as read back from Parquet); unknown keys are ignored."""
    converted: dict[str, Any] = {}
    for name in COLUMNS:
        if name not in values:
            continue
        value = values[name]
        kind = _TYPES[name]
        if kind == "str":
            converted[name] = "" if value is None else str(value)
        elif kind == "int":
            converted[name] = int(value)
        else:
            converted[name] = NAN if value is None else float(value)
    return BatchRow(**converted)
