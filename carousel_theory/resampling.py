"""Irregularly timed samples block-averaged onto a uniform grid (bin means), with honest limits.

Method
    The grid starts at the first timestamp and steps by T = 1/f. A sample taken t seconds after the
    first falls in bin ⌊(t + r) f + ε⌋, r the resolution of the timestamps (two float spacings of
    epoch seconds, one tick of integer ones) and ε = 10⁻⁶, so that a timestamp that sits on a bin
    edge but was rounded down falls in the bin it starts; each bin's value is the mean of its samples.

Why bin means and not interpolation
    The Allan variance (TIM 2014 eq. (20)) is the variance of differences of averages over τ. A bin
    mean averages the rate samples taken in the bin, so an average over τ = mT of bin means is a
    weighted average of the samples taken in those τ seconds and of no others, and white noise stays
    uncorrelated from bin to bin. Linear interpolation makes each grid value a weighted mean of the two
    samples around it instead, which may lie in different bins: it correlates neighbouring values, a
    low-pass filter that lowers the Allan variance of white noise at the shortest τ (by up to a half:
    a midpoint (a + b)/2 has variance σ²/2). On a uniform input at its own rate each bin holds exactly
    one sample and the output equals the input; at f/k it is the means of consecutive blocks of k
    samples.

What is refused
    Empty bins are filled by linear interpolation between the neighbouring bin means only when they
    are few and short: at most ``MAX_EMPTY_FRACTION`` (1 %) of the bins, so the filled values change
    an Allan variance by about that fraction at most, and no run of more than ``MAX_EMPTY_RUN`` (8)
    consecutive empty bins. A longer silence is a gap in the recording, where interpolation would
    draw a straight line where the noise should be: it is refused with the time where it happened.
    Timestamps may repeat (a burst stamped at once) but not go backwards.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from carousel_theory._validation import check_positive_real

__all__ = ["MAX_EMPTY_FRACTION", "MAX_EMPTY_RUN", "BlockAverage", "block_average", "default_resample_rate"]

#: Most empty (interpolated) bins, as a fraction of all bins.
MAX_EMPTY_FRACTION = 0.01
#: Most consecutive empty bins bridged by interpolation; a longer run is a gap and is refused.
MAX_EMPTY_RUN = 8
#: Fraction of a bin by which a timestamp may sit below an edge and still count in the bin above it.
_EDGE_TOLERANCE = 1e-6
#: Halvings of the mean rate :func:`default_resample_rate` tries.
_HALVINGS = 12


@dataclass(frozen=True)
class BlockAverage:
    """Columns block-averaged onto a uniform grid.

    Attributes
    ----------
    columns : dict[str, ndarray]
        Bin means, one value per bin (empty bins interpolated).
    sample_rate : float
        The grid's rate f in Hz; bin k starts ``k / f`` s after the first timestamp.
    empty_bins, bins : int
        Bins without a sample (interpolated), and all bins.
    mean_rate : float
        The input's mean sample rate (samples − 1) / span, in Hz.
    note : str
        One sentence saying what was done.
    """

    columns: dict[str, np.ndarray]
    sample_rate: float
    empty_bins: int
    bins: int
    mean_rate: float
    note: str


def _bin_indices(offsets: np.ndarray, sample_rate: float, resolution: float) -> np.ndarray:
    return np.floor((offsets + resolution) * sample_rate + _EDGE_TOLERANCE).astype(np.int64)


def _longest_empty_run(filled: np.ndarray) -> tuple[int, int]:
    """(length, first bin) of the longest run of empty bins (0, -1 when none)."""
    edges = np.diff(np.concatenate(([0], (~filled).astype(np.int8), [0])))
    starts, ends = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)
    if starts.size == 0:
        return 0, -1
    longest = int(np.argmax(ends - starts))
    return int(ends[longest] - starts[longest]), int(starts[longest])


def _honest(filled: np.ndarray) -> bool:
    return bool(np.mean(~filled) <= MAX_EMPTY_FRACTION and _longest_empty_run(filled)[0] <= MAX_EMPTY_RUN)


def _check_offsets(offsets: np.ndarray, source: str) -> float:
    """The mean rate of ``offsets`` (s after the first sample); refuses timestamps that go backwards."""
    steps = np.diff(offsets)
    backwards = np.flatnonzero(steps < 0)
    if backwards.size:
        i = int(backwards[0])
        raise ValueError(
            f"{source}: timestamps go backwards: t[{i}]={float(offsets[i])!r} then "
            f"t[{i + 1}]={float(offsets[i + 1])!r} s "
            f"after the first ({backwards.size} such steps); resampling needs them in order"
        )
    span = float(offsets[-1] - offsets[0])
    if len(offsets) < 2 or span <= 0:
        raise ValueError(f"{source}: resampling needs at least 2 samples at different times")
    return (len(offsets) - 1) / span


def default_resample_rate(offsets: np.ndarray, resolution: float = 0.0) -> float | None:
    """The highest of f̄/2^k (f̄ the mean rate, k < 12) at which the grid's empty bins are few and short
    enough to bridge (see the module text); None when there is none."""
    mean_rate = (len(offsets) - 1) / float(offsets[-1] - offsets[0])
    for halvings in range(_HALVINGS):
        rate = mean_rate / 2.0**halvings
        filled = np.bincount(_bin_indices(offsets, rate, resolution)) > 0
        if _honest(filled):
            return rate
    return None


def _refuse_dishonest(filled: np.ndarray, rate: float, offsets: np.ndarray, source: str) -> None:
    empty = int((~filled).sum())
    run, first = _longest_empty_run(filled)
    if run > MAX_EMPTY_RUN:
        after = int(np.searchsorted(offsets, (first + run) / rate - 0.5 / rate))  # first sample after it
        raise ValueError(
            f"{source}: resampling at {rate:.6g} Hz: no sample between t={offsets[after - 1]:.6g} s and "
            f"t={offsets[after]:.6g} s after the first ({run} empty bins in a row, more than "
            f"{MAX_EMPTY_RUN}): a gap that interpolation cannot honestly bridge; analyse the parts before "
            "and after it separately, or resample at a lower rate if the gap is only a burst"
        )
    if empty > MAX_EMPTY_FRACTION * len(filled):
        raise ValueError(
            f"{source}: resampling at {rate:.6g} Hz leaves {empty} of {len(filled)} bins empty "
            f"({empty / len(filled):.1%}, more than {MAX_EMPTY_FRACTION:.0%}); the recording's mean rate is "
            f"{(len(offsets) - 1) / float(offsets[-1]):.6g} Hz: resample at a lower rate"
        )


#: A grid of more than this many bins per sample is refused before its bins are counted.
SPARSE_GRID_FACTOR = 16


def _refuse_sparse_grid(offsets: np.ndarray, rate: float, resolution: float, source: str) -> None:
    """Refuse, before the bins are counted, a grid of more than SPARSE_GRID_FACTOR bins per sample (most
    of them empty: :func:`_refuse_dishonest` would refuse it after counting them, which at a rate far
    above the data's costs memory and time; nearer the data's rate it names the gap or the share)."""
    bins = float(np.floor((offsets[-1] + resolution) * rate + _EDGE_TOLERANCE)) + 1.0
    if bins > SPARSE_GRID_FACTOR * len(offsets):
        raise ValueError(
            f"{source}: resampling at {rate:.6g} Hz makes {bins:.6g} bins for {len(offsets)} samples, so "
            f"more than {MAX_EMPTY_FRACTION:.0%} of them would be empty; the recording's mean rate is "
            f"{(len(offsets) - 1) / float(offsets[-1]):.6g} Hz: resample at a lower rate"
        )


def block_average(
    offsets: np.ndarray,
    columns: Mapping[str, np.ndarray],
    sample_rate: float | None = None,
    source: str = "arrays",
    resolution: float = 0.0,
) -> BlockAverage:
    """Bin means of ``columns`` on a uniform grid of ``sample_rate`` Hz (see the module text).

    ``offsets`` are the sample times in s after the first (non-decreasing), ``resolution`` the
    precision of the timestamps in s. Without ``sample_rate``, :func:`default_resample_rate` chooses
    it. Raises ValueError for a gap or too many empty bins.
    """
    offsets = np.asarray(offsets, dtype=np.float64)
    mean_rate = _check_offsets(offsets, source)
    if sample_rate is None:
        sample_rate = default_resample_rate(offsets, resolution)
        if sample_rate is None:
            sample_rate = mean_rate / 2.0 ** (_HALVINGS - 1)  # refused below, naming the gap
    rate = float(check_positive_real("sample_rate", sample_rate))
    _refuse_sparse_grid(offsets, rate, resolution, source)
    index = _bin_indices(offsets, rate, resolution)
    count = np.bincount(index).astype(np.float64)
    filled = count > 0
    _refuse_dishonest(filled, rate, offsets, source)
    positions = np.arange(len(count), dtype=np.float64)

    def average(values: np.ndarray) -> np.ndarray:
        sums = np.bincount(index, weights=values, minlength=len(count))
        means = np.divide(sums, count, out=np.zeros_like(sums), where=filled)
        if filled.all():
            return means
        return np.interp(positions, positions[filled], means[filled])

    empty = int((~filled).sum())
    note = (
        f"irregular timestamps (mean rate {mean_rate:.4g} Hz): bin-averaged onto a uniform "
        f"{rate:.4g} Hz grid, {empty} of {len(filled)} bins empty and interpolated"
    )
    averaged = {name: average(np.asarray(values, dtype=np.float64)) for name, values in columns.items()}
    return BlockAverage(averaged, rate, empty, len(filled), mean_rate, note)
