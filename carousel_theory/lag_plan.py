"""Which lags of a τ pair's covariance sum are summed one by one and which by Gauss blocks.

Setting: :mod:`carousel_theory.lag_quadrature` sums Σ_δ N_ij(δ) c_ij(δ)² over the lags
δ = −(K_i − 1) … K_j − 1 of a pair of cluster sizes (m_i, m_j). c_ij is smooth away from the breakpoints
b_q = q + 2 of the pair's ramps (:func:`ramp_positions`), and N_ij is linear between its kinks 0 and
K_j − K_i. The plan of a pair:

    Exact: every integer lag within ``zone`` = max(exact_reach, reach + 8, points + 2) of a breakpoint,
    every segment between cuts that holds a breakpoint or is shorter than 2 points, and every block of at
    most 2 points lags.
    Blocks: the rest of each segment between consecutive cuts (the kinks, the record's ends and the
    zones' edges) is covered by blocks grown away from the breakpoints on either side, meeting half-way:
    each block is the longest of the lengths ⌊2^{k/4}⌋ that is at most block_ratio times its distance
    to the breakpoint it grows from and at most what remains of its half.

``points``, ``block_ratio`` and ``exact_reach`` are a :class:`QuadratureRule`. The lag quadrature's
error bound holds for any rule; :data:`PROVED_RULE` keeps it far below the covariance for the models
of a gyro fit, :data:`WEIGHTS_RULE` takes a quarter of the nodes and lags where seven digits of the
values suffice (a fit's weights; :mod:`carousel_theory.lag_quadrature`, module text: Rules).

:func:`plan_pairs` plans all the pairs of one covariance together: the segments of every pair are rows
of one array, and the blocks of every half-segment grow in one loop over the growth steps (about thirty
for a record of 10⁶ samples) rather than one Python loop per block. The result is the concatenation of
each pair's own plan, in the pairs' order: the exact lags of a pair sorted, its blocks in the order of its
segments, each segment's blocks grown from the left breakpoint first, then from the right one, each half
in the order grown.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from carousel_theory._validation import check_positive_integer

__all__ = [
    "PROVED_RULE",
    "WEIGHTS_RULE",
    "LagPlan",
    "QuadratureRule",
    "plan_pairs",
    "ramp_positions",
]


@dataclass(frozen=True)
class QuadratureRule:
    """How a pair's lag sum is split: ``points`` nodes of the discrete Gauss rule on each block, each block
    at most ``block_ratio`` times its distance to the nearest breakpoint, and the lags within
    ``exact_reach`` of a breakpoint (or the finite terms' reach, when longer) summed one by one."""

    points: int
    block_ratio: float
    exact_reach: int

    def __post_init__(self) -> None:
        # N c² of the finite terms is a polynomial of degree 7 on a block: the rule must be exact for it
        # (degree 2·points − 1 ≥ 7).
        check_positive_integer("points", self.points, minimum=4)
        check_positive_integer("exact_reach", self.exact_reach)
        if not 0.0 < self.block_ratio <= 1.0:
            raise ValueError(f"block_ratio={self.block_ratio!r}: must be in (0, 1]")


#: The reported covariance's rule: its proved bound is below 10⁻¹¹ of each pair's sum (held by the tests
#: for d from 0.02 to 0.98); measured at octave τ of 10⁶ samples, 3·10⁻¹⁵ of √(C_ii C_jj) for white + RRW
#: + 1/f (d = 0.5) + Gauss–Markov and 7·10⁻¹¹ for 1/f alone at d = 0.95 (below the rounding there).
PROVED_RULE = QuadratureRule(points=12, block_ratio=0.5, exact_reach=32)
#: A fit's weights: a quarter of the Gauss nodes and of the exact lags of :data:`PROVED_RULE`, the same
#: values to 2·10⁻⁷ of the covariance (measured: lag_quadrature's module text, Rules).
WEIGHTS_RULE = QuadratureRule(points=4, block_ratio=1.0, exact_reach=16)

BLOCK_LENGTHS = np.array(sorted({math.floor(2.0 ** (k / 4.0)) for k in range(4 * 62)}), dtype=np.int64)
_RAMPS = 9  # at most nine ramps per pair


@functools.lru_cache(maxsize=4096)
def ramp_positions(m_i: int, m_j: int) -> tuple[tuple[int, int], ...]:
    """(q, w) with W_ij(−δ) = Σ w R₃(q − δ): q = −p_αβ, merged where positions coincide (module text of
    :mod:`carousel_theory.tau_covariance`)."""
    merged: dict[int, int] = {}
    for alpha, w_alpha in enumerate((1, -2, 1)):
        for beta, w_beta in enumerate((1, -2, 1)):
            q = -(2 - 2 * m_i + alpha * m_i + beta * m_j)
            merged[q] = merged.get(q, 0) + w_alpha * w_beta
    return tuple((q, w) for q, w in sorted(merged.items()) if w)


@dataclass(frozen=True)
class LagPlan:
    """The plan of many pairs: the integer ``lags`` summed one by one (each pair's sorted, pairs in order)
    with the pair of each (``lag_owner``), and the Gauss ``blocks`` as rows (first lag, length) with the
    pair of each (``block_owner``)."""

    lags: np.ndarray
    lag_owner: np.ndarray
    blocks: np.ndarray
    block_owner: np.ndarray


@dataclass(frozen=True)
class _Segments:
    """The non-empty segments first … last between consecutive cuts of every pair (rows in the pairs'
    order, then the segments' order), with the nearest breakpoint on either side (±inf where none)."""

    owner: np.ndarray
    first: np.ndarray
    last: np.ndarray
    left: np.ndarray
    right: np.ndarray
    inside: np.ndarray


def _breakpoints(pairs: Sequence[tuple[int, int, int, int]]) -> np.ndarray:
    """Each pair's breakpoints q + 2 as a row, padded to nine by repeating the first."""
    result = np.empty((len(pairs), _RAMPS), dtype=np.int64)
    for row, (m_i, m_j, _, _) in enumerate(pairs):
        points = [q + 2 for q, _ in ramp_positions(m_i, m_j)]
        result[row] = points + points[:1] * (_RAMPS - len(points))
    return result


def _segments(sizes: np.ndarray, breakpoints: np.ndarray, zone: int) -> _Segments:
    """The segments between the sorted cuts {record ends, kinks 0 and K_j − K_i, b ± zone} of each pair;
    repeated cuts give empty segments, which are dropped with those outside the record."""
    K_i, K_j = sizes[:, 2], sizes[:, 3]
    low, high = -(K_i - 1), K_j - 1
    ends = np.column_stack((low, high + 1, np.zeros_like(low), K_j - K_i))
    cuts = np.sort(np.hstack((ends, breakpoints - zone, breakpoints + zone + 1)), axis=1)
    first = np.maximum(cuts[:, :-1], low[:, None])
    last = np.minimum(cuts[:, 1:] - 1, high[:, None])
    row, _ = np.nonzero(first <= last)
    first, last = first[first <= last], last[first <= last]
    points = breakpoints[row].astype(np.float64)  # exact: |b| < 2⁵³
    below, above = points < first[:, None], points > last[:, None]
    left = np.where(below, points, -np.inf).max(axis=1)
    right = np.where(above, points, np.inf).min(axis=1)
    return _Segments(row, first, last, left, right, ~np.all(below | above, axis=1))


def _halves(segments: _Segments, grown: np.ndarray) -> tuple[np.ndarray, ...]:
    """(segment, side 0/1, start, span, distance of start to its breakpoint, direction ±1) of the halves
    of the ``grown`` segments: from the left breakpoint up to the middle, from the right one down to it."""
    index = np.flatnonzero(grown)
    first, last = segments.first[index], segments.last[index]
    left, right = segments.left[index], segments.right[index]
    middle = np.where(
        np.isinf(right), last, np.where(np.isinf(left), first - 1, np.floor((left + right) / 2))
    )
    middle = np.minimum(np.maximum(middle, first - 1), last).astype(np.int64)
    up = np.isfinite(left) & (middle >= first)
    down = np.isfinite(right) & (middle < last)
    return (
        np.concatenate((index[up], index[down])),
        np.concatenate((np.zeros(int(up.sum()), np.int64), np.ones(int(down.sum()), np.int64))),
        np.concatenate((first[up], last[down])),
        np.concatenate((middle[up] - first[up] + 1, last[down] - middle[down])),
        np.concatenate((first[up] - left[up], right[down] - last[down])).astype(np.int64),
        np.concatenate((np.ones(int(up.sum()), np.int64), -np.ones(int(down.sum()), np.int64))),
    )


def _grow(
    start: np.ndarray, span: np.ndarray, distance: np.ndarray, direction: np.ndarray, block_ratio: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(half, step, first lag, length) of the blocks covering each half: every active half takes, per
    step, the longest of :data:`BLOCK_LENGTHS` ≤ min(``block_ratio`` × its distance, what remains), at
    least 1."""
    offset, remaining = np.zeros_like(span), span.copy()
    active = np.flatnonzero(remaining > 0)
    halves, steps, firsts, lengths = [], [], [], []
    step = 0
    while len(active):
        reached = distance[active] + offset[active]
        ratio = np.floor(block_ratio * reached).astype(np.int64)
        allowed = np.maximum(1, np.minimum(ratio, remaining[active]))
        length = BLOCK_LENGTHS[np.searchsorted(BLOCK_LENGTHS, allowed, side="right") - 1]
        up = direction[active] > 0
        moved = start[active] + direction[active] * offset[active]
        firsts.append(np.where(up, moved, moved - length + 1))
        halves.append(active)
        steps.append(np.full(len(active), step, dtype=np.int64))
        lengths.append(length)
        offset[active] += length
        remaining[active] -= length
        active = active[remaining[active] > 0]
        step += 1
    if not halves:
        empty = np.zeros(0, dtype=np.int64)
        return empty, empty, empty, empty
    return tuple(np.concatenate(parts) for parts in (halves, steps, firsts, lengths))  # type: ignore[return-value]


def plan_pairs(
    pairs: Sequence[tuple[int, int, int, int]], reach: int, rule: QuadratureRule = PROVED_RULE
) -> LagPlan:
    """The :class:`LagPlan` of the (m_i, m_j, K_i, K_j) ``pairs`` for finite terms reaching ``reach``
    lags by ``rule`` (module text): each pair's plan, as if planned alone, concatenated in the pairs'
    order."""
    sizes = np.array(pairs, dtype=np.int64).reshape(-1, 4)
    points = rule.points
    zone = max(rule.exact_reach, reach + 8, points + 2)
    segments = _segments(sizes, _breakpoints(pairs), zone)
    near = np.minimum(segments.first - segments.left, segments.right - segments.last)
    exact = segments.inside | (near <= zone) | (segments.last - segments.first < 2 * points)
    segment, side, start, span, distance, direction = _halves(segments, ~exact)
    half, step, first, length = _grow(start, span, distance, direction, rule.block_ratio)
    order = np.lexsort((step, side[half], segment[half]))
    first, length, owner = first[order], length[order], segments.owner[segment[half[order]]]
    small = length <= 2 * points
    ranges_first = np.concatenate((segments.first[exact], first[small]))
    ranges_last = np.concatenate((segments.last[exact], first[small] + length[small] - 1))
    ranges_owner = np.concatenate((segments.owner[exact], owner[small]))
    # The segments are disjoint and the blocks partition theirs, so each pair's ranges are disjoint:
    # sorted by their first lag, they concatenate into the pair's sorted lags.
    by_pair = np.lexsort((ranges_first, ranges_owner))
    counts = (ranges_last - ranges_first + 1)[by_pair]
    lags = _concatenated_ranges(ranges_first[by_pair], counts)
    blocks = np.column_stack((first[~small], length[~small]))
    return LagPlan(lags, np.repeat(ranges_owner[by_pair], counts), blocks, owner[~small])


def _concatenated_ranges(firsts: np.ndarray, counts: np.ndarray) -> np.ndarray:
    """The integers first … first + count − 1 of each range, one range after the other."""
    starts = np.cumsum(counts) - counts  # where each range begins in the result
    return np.repeat(firsts - starts, counts) + np.arange(int(counts.sum()), dtype=np.int64)
