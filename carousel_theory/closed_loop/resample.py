"""Irregular timestamps bin-averaged onto a uniform grid (the loop's predictions assume uniform sampling).

The method and what it refuses live in :mod:`carousel_theory.resampling`, shared by every command."""

from __future__ import annotations

from carousel_theory.data import Recording, resample_recording

__all__ = ["uniform_resample"]


def uniform_resample(recording: Recording, sample_rate: float | None = None) -> tuple[Recording, str]:
    """:func:`carousel_theory.data.resample_recording` (default rate: the highest f̄/2^k, f̄ the mean
    rate, whose empty bins can be bridged). Returns the new recording and a sentence saying what was
    done."""
    resampled = resample_recording(recording, "auto" if sample_rate is None else sample_rate)
    return resampled, resampled.notes[-1]
