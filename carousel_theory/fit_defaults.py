"""The default noise model of ``fit``: the simplest of a short ladder of models that the recording does
not reject.

Chosen by measurement (``benchmarks/fit_default_model.py``: χ²/dof of each candidate on every axis of the
shared ADIS16405 and MPU6050 static recordings):

- white noise + rate random walk over every τ is rejected by its own χ² test on 16 of 18 axes (χ²/dof
  up to 2·10⁴ on the ADIS16405), and still on 14 of 18 at τ ≥ 1 s: real MEMS gyros have 1/f noise (bias
  instability);
- adding 1/f noise (order d fitted) is enough for the MPU6050 (bin-averaged onto 12.4 Hz) but not for the
  ADIS16405, whose internal filter correlates neighbouring samples and bends the short-τ end of the
  Allan deviation below the white-noise slope; above τ = 1 s no axis rejects it;
- a fixed single choice costs precision where it is not needed: on white noise the free 1/f order drifts
  towards d = 0, where 1/f noise looks white, and the white-noise standard error grows a
  hundredfold; a 1-s cut-off on a 300-s record widens it from about 1 % to 8 %.

Hence :data:`LADDER`: each axis gets the first step whose fit the recording does not reject at
p ≥ :data:`carousel_theory.fit_diagnostics.REJECTION_LEVEL` — white + RRW over every τ; white + RRW + 1/f
over every τ; white + RRW + 1/f at τ ≥ :data:`DEFAULT_TAU_MIN` (only when the recording leaves
:data:`DEFAULT_TAU_MIN_OCTAVES` octave τ above it). When every step is rejected the last one tried is
kept, with its rejection notice. A note says which step each axis needed and why. The kept step is
chosen by the same χ² test that its p-value reports, so that p-value is a check of the choice, not an
independent test; the standard errors assume the kept model.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from carousel_theory.fit_diagnostics import REJECTION_LEVEL
from carousel_theory.fitting import FitResult, fit_recording

__all__ = [
    "DEFAULT_TAU_MIN",
    "DEFAULT_TAU_MIN_OCTAVES",
    "LADDER",
    "LadderStep",
    "octaves_above",
    "select_default_fit",
]

#: The short-τ cut-off (s) of the last step: above the internal filters of common MEMS gyros (bandwidths
#: of tens of Hz), where white noise follows its −1/2 slope again.
DEFAULT_TAU_MIN = 1.0
#: Octave τ a recording must leave at or above DEFAULT_TAU_MIN (3 clusters each) for the last step.
DEFAULT_TAU_MIN_OCTAVES = 6


@dataclass(frozen=True)
class LadderStep:
    """One candidate: the components and the short-τ cut-off (None: every τ)."""

    components: tuple[str, ...]
    tau_min: float | None

    def describe(self) -> str:
        where = "over every τ" if self.tau_min is None else f"at τ ≥ {self.tau_min:g} s"
        return f"{'+'.join(self.components)} {where}"


#: The candidates, simplest first.
LADDER = (
    LadderStep(("white", "rrw"), None),
    LadderStep(("white", "rrw", "flicker"), None),
    LadderStep(("white", "rrw", "flicker"), DEFAULT_TAU_MIN),
)


def octaves_above(recording: Any, tau_min: float, tau_max: float | None = None) -> int:
    """How many octave τ = 2^k / f_s in [tau_min, tau_max] hold at least 3 disjoint clusters."""
    sizes = 2 ** np.arange(64, dtype=np.float64)
    longest = len(recording) // 3
    if tau_max is not None:
        longest = min(longest, tau_max * recording.sample_rate)
    return int(np.sum((sizes >= tau_min * recording.sample_rate * (1 - 1e-12)) & (sizes <= longest)))


def _usable_steps(
    recording: Any, tau_min: float | None, tau_max: float | None
) -> tuple[list[LadderStep], str]:
    """The ladder's steps this recording can take (all at ``tau_min`` when given), and why a step is left
    out ("" when none is)."""
    if tau_min is not None:
        return [
            LadderStep(components, tau_min) for components in dict.fromkeys(s.components for s in LADDER)
        ], ""
    available = octaves_above(recording, DEFAULT_TAU_MIN, tau_max)
    if available >= DEFAULT_TAU_MIN_OCTAVES:
        return list(LADDER), ""
    return [step for step in LADDER if step.tau_min is None], (
        f"the recording ({recording.duration:.4g} s) leaves only {available} octave τ above "
        f"{DEFAULT_TAU_MIN:g} s (needs {DEFAULT_TAU_MIN_OCTAVES}), too few to fit above a sensor's internal "
        "filter"
    )


def select_default_fit(
    recording: Any,
    *,
    axes: Any = None,
    tau_min: float | None = None,
    tau_max: float | None = None,
    label: str = "fit: axes",
    **options: Any,
) -> tuple[dict[str, FitResult], list[str]]:
    """Fit every axis (or ``axes``) with the first :data:`LADDER` step it does not reject (module text);
    a given ``tau_min`` replaces the ladder's τ ranges (its models are tried at ``tau_min``).

    ``options`` are the keywords of :func:`carousel_theory.fitting.fit_noise_model` (not ``flicker_d``,
    which the ladder leaves free). Returns the fits in axis order and the notes.
    """
    steps, left_out = _usable_steps(recording, tau_min, tau_max)
    notes = []
    names = list(recording.rates) if axes is None else list(axes)
    chosen: dict[str, FitResult] = {}
    tried: dict[str, list[str]] = {name: [] for name in names}
    pending = names
    for step in steps:
        if not pending:
            break
        fits = fit_recording(
            recording,
            step.components,
            axes=pending,
            tau_min=step.tau_min,
            tau_max=tau_max,
            label=label,
            **options,
        )
        chosen.update(fits)
        for name, fit in fits.items():
            tried[name].append(
                f"{step.describe()} (χ² = {fit.chi_square:.3g} on {fit.degrees_of_freedom} dof)"
            )
        pending = [name for name in pending if fits[name].p_value < REJECTION_LEVEL]
    if pending and left_out:
        notes.append(f"{', '.join(pending)}: {left_out}")
    for name in names:
        if len(tried[name]) > 1:
            kept = "still rejected" if name in pending else "not rejected"
            notes.append(
                f"{name}: the default model is the first the recording does not reject; rejected: "
                f"{'; '.join(tried[name][:-1])}; kept: {tried[name][-1]}, {kept}"
            )
    return {name: chosen[name] for name in names}, notes
