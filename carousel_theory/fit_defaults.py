"""The default noise model of ``fit`` (and of the fleet's fit task) and its default τ range.

Chosen by measurement (``benchmarks/fit_default_model.py``, χ²/dof of each candidate on every axis of the
shared ADIS16405 and MPU6050 static recordings):

- white noise + rate random walk alone is rejected by its own χ² test on 16 of 18 axes over every τ, and
  still on 14 of 18 at τ ≥ 1 s: real MEMS gyros have 1/f noise (bias instability), so
  :data:`DEFAULT_MODEL` adds it, with its order d fitted;
- over every τ that model is still rejected on the ADIS16405 (χ²/dof up to 2·10⁴): the sensor's
  internal filter correlates neighbouring samples and bends the short-τ end of the Allan deviation below
  the white-noise slope; above :data:`DEFAULT_TAU_MIN` = 1 s no axis rejects it. A recording without such a
  filter (the MPU6050 bin-averaged onto 12.4 Hz) accepts it over every τ, where white noise is estimated
  far more precisely (a 1-s cut-off on a 300-s record widens its standard error from about 1 % to 8 %).

Hence the default range: every τ first; an axis whose fit is rejected there (p < 0.01) is fitted again
at τ ≥ 1 s when the recording leaves at least :data:`DEFAULT_TAU_MIN_OCTAVES` octave τ above it, and a
note says so. A τ range the caller gives is used as given.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from carousel_theory.fit_diagnostics import REJECTION_LEVEL
from carousel_theory.fitting import FitResult, fit_recording

__all__ = [
    "DEFAULT_MODEL",
    "DEFAULT_TAU_MIN",
    "DEFAULT_TAU_MIN_OCTAVES",
    "fit_with_default_range",
    "octaves_above",
]

#: White noise, rate random walk and 1/f noise (order d fitted).
DEFAULT_MODEL = ("white", "rrw", "flicker")
#: The short-τ cut-off (s) used when a fit over every τ is rejected: above the internal filters of common
#: MEMS gyros (bandwidths of tens of Hz), where white noise follows its −1/2 slope again.
DEFAULT_TAU_MIN = 1.0
#: Octave τ a recording must leave at or above DEFAULT_TAU_MIN (3 clusters each) for the refit.
DEFAULT_TAU_MIN_OCTAVES = 6


def octaves_above(recording: Any, tau_min: float, tau_max: float | None = None) -> int:
    """How many octave τ = 2^k / f_s in [tau_min, tau_max] hold at least 3 disjoint clusters."""
    sizes = 2 ** np.arange(64, dtype=np.float64)
    longest = (
        len(recording) // 3 if tau_max is None else min(len(recording) // 3, tau_max * recording.sample_rate)
    )
    return int(np.sum((sizes >= tau_min * recording.sample_rate * (1 - 1e-12)) & (sizes <= longest)))


def fit_with_default_range(
    recording: Any,
    model: Any = DEFAULT_MODEL,
    *,
    axes: Any = None,
    tau_min: float | None = None,
    tau_max: float | None = None,
    label: str = "fit: axes",
    **options: Any,
) -> tuple[dict[str, FitResult], list[str]]:
    """:func:`carousel_theory.fitting.fit_recording` with the default τ range of the module text.

    Returns the fits (in axis order) and the notes that say where the range was changed or could not be.
    """
    fits = fit_recording(
        recording, model, axes=axes, tau_min=tau_min, tau_max=tau_max, label=label, **options
    )
    rejected = [name for name, fit in fits.items() if fit.p_value < REJECTION_LEVEL]
    if tau_min is not None or not rejected:
        return fits, []
    available = octaves_above(recording, DEFAULT_TAU_MIN, tau_max)
    if available < DEFAULT_TAU_MIN_OCTAVES:
        return fits, [
            f"{', '.join(rejected)}: the model is rejected over every τ, and the recording "
            f"({recording.duration:.4g} s) leaves only {available} octave τ above {DEFAULT_TAU_MIN:g} s "
            f"(needs {DEFAULT_TAU_MIN_OCTAVES}), too few to refit above a sensor's internal filter"
        ]
    refits = fit_recording(
        recording, model, axes=rejected, tau_min=DEFAULT_TAU_MIN, tau_max=tau_max, label=label, **options
    )
    notes = [
        f"{name}: the model is rejected over every τ (χ² = {fits[name].chi_square:.3g} on "
        f"{fits[name].degrees_of_freedom} degrees of freedom), so it is fitted at τ ≥ {DEFAULT_TAU_MIN:g} s, "
        "above the short-τ end that an internal filter bends (give --tau-min to choose the range)"
        for name in rejected
    ]
    return {name: refits.get(name, fit) for name, fit in fits.items()}, notes
