"""Irregular timestamps bin-averaged onto a uniform grid (the loop's predictions assume uniform sampling)."""

from __future__ import annotations

import numpy as np

from carousel_theory._validation import check_positive_real
from carousel_theory.data import Recording, recording_from_arrays

__all__ = ["uniform_resample"]


def _default_rate(time: np.ndarray, mean_rate: float) -> float:
    """The highest of f̄/2^k (f̄ the mean rate) at which at most 1 % of the bins are empty."""
    sample_rate = mean_rate
    for _ in range(12):
        edges = np.arange(time[0], time[-1] + 1.0 / sample_rate, 1.0 / sample_rate)
        if np.mean(np.histogram(time, edges)[0] == 0) <= 0.01:
            break
        sample_rate /= 2.0
    return sample_rate


def uniform_resample(recording: Recording, sample_rate: float | None = None) -> tuple[Recording, str]:
    """Bin-average an irregularly sampled recording onto a uniform grid (empty bins linearly
    interpolated). Default rate: the highest of f̄/2^k (f̄ the mean rate) at which at most 1 % of the bins
    are empty. Returns the new recording and a sentence saying what was done."""
    time = recording.time
    mean_rate = (len(time) - 1) / float(time[-1] - time[0])
    rate = float(
        check_positive_real(
            "sample_rate", _default_rate(time, mean_rate) if sample_rate is None else sample_rate
        )
    )
    edges = np.arange(time[0], time[-1] + 1.0 / rate, 1.0 / rate)
    index = np.clip(np.searchsorted(edges, time, side="right") - 1, 0, len(edges) - 2)
    count = np.bincount(index, minlength=len(edges) - 1).astype(np.float64)
    centres = edges[:-1] + 0.5 / rate
    filled = count > 0

    def average(values: np.ndarray) -> np.ndarray:
        sums = np.bincount(index, weights=values, minlength=len(edges) - 1)
        means = np.divide(sums, count, out=np.zeros_like(sums), where=filled)
        return np.interp(centres, centres[filled], means[filled])

    rates = {name: average(values) for name, values in recording.rates.items()}
    temperature = None if recording.temperature is None else average(recording.temperature)
    angle = None if recording.angle is None else average(np.unwrap(recording.angle))
    note = (
        f"irregular timestamps (mean rate {mean_rate:.4g} Hz): bin-averaged onto a uniform "
        f"{rate:.4g} Hz grid, {int((~filled).sum())} of {len(filled)} bins empty and interpolated"
    )
    resampled = recording_from_arrays(
        rates, sample_rate=rate, temperature=temperature, angle=angle, source=recording.source
    )
    return resampled, note
