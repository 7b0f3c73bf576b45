"""The contract between the loop and its detectors: a :class:`Detection` result and two one-method
protocols, :class:`Detector` (``detect``) and :class:`Remedy` (``fit``), over a public
:class:`~carousel_theory.closed_loop.view.ResidualView`.

Each detector computes a test statistic whose null distribution is that of the *fitted* noise model,
and reports the base-10 logarithm of its p-value, family-wise over its own scan and the axes
(Bonferroni). The loop decides what ``alpha`` each detector gets (see
:mod:`carousel_theory.closed_loop.calibration`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Protocol

import numpy as np
from scipy import stats

from carousel_theory.closed_loop.view import FittedEffect, ResidualView

__all__ = [
    "Detection",
    "Detector",
    "Remedy",
    "json_value",
    "log10_two_sided",
    "threshold_two_sided",
    "untestable",
]


@dataclass(frozen=True)
class Detection:
    """The outcome of one detector on one residual.

    ``log10_p`` is the base-10 logarithm of the family-wise p-value (Bonferroni over the scan and the
    axes); ``significant`` is ``p < alpha``. ``testable`` is False when the data cannot show the effect
    at all (no temperature column, a constant one, a record too short); ``note`` then says why.
    """

    effect: str
    statistic: float
    statistic_name: str
    threshold: float
    log10_p: float
    significant: bool
    axes: tuple[str, ...] = ()
    details: dict[str, Any] = field(default_factory=dict)
    testable: bool = True
    note: str = ""

    def as_dict(self) -> dict[str, Any]:
        return {
            "effect": self.effect,
            "statistic": json_value(self.statistic),
            "statistic_name": self.statistic_name,
            "threshold": json_value(self.threshold),
            "log10_p": json_value(self.log10_p),
            "significant": self.significant,
            "axes": list(self.axes),
            "details": {k: json_value(v) for k, v in self.details.items()},
            "testable": self.testable,
            "note": self.note,
        }


class Detector(Protocol):
    """Tests a residual for one effect."""

    name: str

    def detect(self, view: ResidualView, alpha: float) -> Detection: ...


class Remedy(Protocol):
    """Fits one effect that a detection found; ``stochastic`` effects change the noise model only."""

    name: str
    stochastic: bool

    def fit(self, view: ResidualView, detection: Detection, alpha: float) -> FittedEffect: ...


def untestable(name: str, statistic_name: str, threshold: float, note: str) -> Detection:
    """A detection that the data cannot make, with the reason."""
    return Detection(name, 0.0, statistic_name, threshold, 0.0, False, testable=False, note=note)


def json_value(value: Any) -> Any:
    """``value`` with NumPy scalars as Python numbers and non-finite floats as strings (valid JSON)."""
    if isinstance(value, (float, np.floating)):
        number = float(value)
        return number if math.isfinite(number) else str(number)
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, np.bool_):
        return bool(value)
    if isinstance(value, (list, tuple, np.ndarray)):
        return [json_value(v) for v in value]
    if isinstance(value, dict):
        return {str(k): json_value(v) for k, v in value.items()}
    return value


def log10_two_sided(z: float, tests: int) -> float:
    """log10 of min(1, tests · 2 Φ̄(|z|)) computed in logs, so that z = 200 does not underflow."""
    log_p = math.log(2.0 * max(tests, 1)) + float(stats.norm.logsf(abs(z)))
    return min(0.0, log_p / math.log(10.0))


def threshold_two_sided(alpha: float, tests: int) -> float:
    return float(stats.norm.isf(alpha / (2.0 * max(tests, 1))))
