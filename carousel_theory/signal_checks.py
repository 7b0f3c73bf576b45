"""Can a gyro signal carry a noise model? One check, before any fit, with the file and column named.

A fit of the noise model (Allan variance GLS, REML of the bias predictor, the closed loop's residual
model) needs a signal that varies and whose variances, and their squares in the GLS covariance, stay
inside float64's range. Without this check such signals fail deep inside the linear algebra ("Matrix
is not positive definite", "array must not contain infs or NaNs", "math domain error"); with it they
are refused with the file, the column, the value and the rule.

The bounds on magnitude are deliberately wide: rates in rad/s, deg/s or deg/h lie many decades
inside them; only data in a wrong unit or corrupted data reach them.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

import numpy as np

from carousel_theory._validation import check_not_complex
from carousel_theory.binary_scaling import binary_exponent, scaled_by_power_of_two

__all__ = [
    "LARGEST_RATE",
    "MINIMUM_SAMPLES",
    "SMALLEST_SPREAD",
    "UnusableSignalError",
    "check_noise_signal",
    "check_recording_length",
    "check_recording_signals",
]

#: Fewest samples of a column a noise model is fitted to (the Allan variance's minimum).
MINIMUM_SAMPLES = 3

#: Largest magnitude of a rate sample: σ_A² ≈ 10¹²⁰ and its square in the GLS covariance stay finite.
LARGEST_RATE = 1e60

#: Smallest standard deviation of a column: σ_A² ≈ 10⁻¹²⁰ and its square stay normal numbers.
SMALLEST_SPREAD = 1e-60


class UnusableSignalError(ValueError):
    """A column cannot carry a noise model (too short, constant, or of a magnitude float64 cannot
    square); the message names the column, the value and the rule."""


def _standard_deviation(values: np.ndarray) -> float:
    """The standard deviation, computed at a power-of-two scale so that it neither overflows nor
    underflows on the way (the scale is exact in binary)."""
    exponent = binary_exponent(values)
    scaled = scaled_by_power_of_two(values, -exponent)
    return float(np.ldexp(np.std(scaled), exponent))


def check_noise_signal(values: Any, where: str) -> np.ndarray:
    """Return ``values`` as float64 if a noise model can be fitted to them, else raise.

    Parameters
    ----------
    values : 1-D array of finite numbers
        The rate samples of one column.
    where : str
        How the message names them, e.g. ``"run.csv: column 'wx'"``.

    Raises
    ------
    UnusableSignalError
        Fewer than :data:`MINIMUM_SAMPLES` samples; every sample equal; a sample beyond
        ±:data:`LARGEST_RATE`; a standard deviation below :data:`SMALLEST_SPREAD`.
    """
    check_not_complex(where, values)
    samples = np.asarray(values, dtype=np.float64)
    if samples.ndim != 1 or len(samples) < MINIMUM_SAMPLES:
        raise UnusableSignalError(
            f"{where}: {samples.size} sample(s); a noise model needs at least {MINIMUM_SAMPLES}"
        )
    if not np.all(np.isfinite(samples)):
        index = int(np.argmin(np.isfinite(samples)))
        raise UnusableSignalError(
            f"{where}: sample {index} is {float(samples[index])!r}; every sample must be finite"
        )
    low, high = float(samples.min()), float(samples.max())
    if low == high:
        raise UnusableSignalError(
            f"{where}: constant (every sample is {low!r}); a noise model needs a signal that varies"
        )
    peak = max(abs(low), abs(high))
    if peak > LARGEST_RATE:
        raise UnusableSignalError(
            f"{where}: a sample of magnitude {peak:.3g}; rates must stay within ±{LARGEST_RATE:.0e} so that "
            "their variances fit in float64 (are the rates in the right unit?)"
        )
    spread = _standard_deviation(samples)
    if spread < SMALLEST_SPREAD:
        raise UnusableSignalError(
            f"{where}: standard deviation {spread:.3g}; it must be at least {SMALLEST_SPREAD:.0e} so that "
            "its variance stays a normal float64 (are the rates in the right unit?)"
        )
    return samples


def check_recording_length(recording: Any, minimum: int = MINIMUM_SAMPLES) -> None:
    """Refuse a recording of fewer than ``minimum`` samples, naming the file and its gyro columns."""
    if len(recording.time) < minimum:
        raise UnusableSignalError(
            f"{recording.source}: {len(recording.time)} sample(s) in column(s) {', '.join(recording.rates)}; "
            f"an Allan variance needs at least {minimum}"
        )


def check_recording_signals(recording: Any, axes: Iterable[str] | None = None) -> None:
    """:func:`check_noise_signal` on each gyro column of ``recording`` (or on ``axes``), naming the file."""
    names = list(recording.rates) if axes is None else list(axes)
    for name in names:
        if name in recording.rates:
            check_noise_signal(recording.rates[name], f"{recording.source}: column {name!r}")
