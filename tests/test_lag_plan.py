"""The plan of the lag quadrature: which lags are summed one by one and which by Gauss blocks.

- each pair's exact lags and blocks cover its lags −(K_i − 1) … K_j − 1 once, no block holds a
  breakpoint or is longer than the rule's block_ratio times its distance to the nearest one;
- the plan of many pairs, made together, is each pair's plan made alone, in the pairs' order;
- it is the plan of a plain reference planner (one segment and one block at a time, written from the
  module text), lag for lag and block for block, including the blocks' order.

Each for both rules, PROVED_RULE and WEIGHTS_RULE.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

from carousel_theory.lag_plan import (
    BLOCK_LENGTHS,
    PROVED_RULE,
    WEIGHTS_RULE,
    QuadratureRule,
    plan_pairs,
    ramp_positions,
)

rules = st.sampled_from([PROVED_RULE, WEIGHTS_RULE])

pair_sizes = st.tuples(
    st.integers(min_value=1, max_value=3000),
    st.integers(min_value=1, max_value=3000),
    st.integers(min_value=2_000, max_value=2_000_000),
)


def _pair(m_a: int, m_b: int, length: int) -> tuple[int, int, int, int]:
    m_i, m_j = min(m_a, m_b), max(m_a, m_b)
    return m_i, m_j, length - 2 * m_i + 1, length - 2 * m_j + 1


def _reference_blocks(
    start: int, stop: int, breakpoint: int, direction: int, ratio: float
) -> list[tuple[int, int]]:
    """Blocks from ``start`` towards ``stop``, one at a time: the longest allowed length each."""
    blocks, x, remaining = [], start, abs(stop - start) + 1
    while remaining > 0:
        allowed = max(1, min(int(ratio * abs(x - breakpoint)), remaining))
        length = int(BLOCK_LENGTHS[allowed >= BLOCK_LENGTHS].max())
        blocks.append((x if direction > 0 else x - length + 1, length))
        x, remaining = x + direction * length, remaining - length
    return blocks


def _reference_segment(first, last, left, right, ratio: float) -> list[tuple[int, int]]:
    middle = last if right is None else first - 1 if left is None else (left + right) // 2
    middle = min(max(middle, first - 1), last)
    blocks = []
    if left is not None and middle >= first:
        blocks = _reference_blocks(first, middle, left, 1, ratio)
    if right is not None and middle < last:
        blocks += _reference_blocks(last, middle + 1, right, -1, ratio)
    return blocks


def _reference_plan(m_i: int, m_j: int, K_i: int, K_j: int, reach: int, rule: QuadratureRule):
    low, high = -(K_i - 1), K_j - 1
    points = sorted({q + 2 for q, _ in ramp_positions(m_i, m_j)})
    gauss = rule.points
    zone = max(rule.exact_reach, reach + 8, gauss + 2)
    cuts = sorted({low, high + 1, 0, K_j - K_i} | {b + s for b in points for s in (-zone, zone + 1)})
    exact, blocks = [], []
    for start, stop in itertools.pairwise(cuts):
        first, last = max(start, low), min(stop - 1, high)
        if first > last:
            continue
        left = max((b for b in points if b < first), default=None)
        right = min((b for b in points if b > last), default=None)
        near = min(
            first - left if left is not None else math.inf, right - last if right is not None else math.inf
        )
        if any(first <= b <= last for b in points) or near <= zone or last - first < 2 * gauss:
            exact.append((first, last))
        else:
            blocks += _reference_segment(first, last, left, right, rule.block_ratio)
    exact += [(f, f + n - 1) for f, n in blocks if n <= 2 * gauss]
    lags = [lag for first, last in sorted(exact) for lag in range(first, last + 1)]
    return np.array(lags, dtype=np.int64), [(f, n) for f, n in blocks if n > 2 * gauss]


@given(sizes=pair_sizes, reach=st.integers(min_value=3, max_value=200), rule=rules)
def test_plan_covers_every_lag_once(sizes, reach, rule):
    """The exact lags (sorted) and the Gauss blocks cover −(K_i − 1) … K_j − 1, each lag once; no block
    reaches a breakpoint nor grows beyond block_ratio times its distance to the nearest one."""
    assume(3 * max(sizes[:2]) <= sizes[2])
    m_i, m_j, K_i, K_j = _pair(*sizes)
    plan = plan_pairs([(m_i, m_j, K_i, K_j)], reach, rule)
    low = -(K_i - 1)
    covered = np.zeros(K_i + K_j - 1, dtype=np.int64)
    np.add.at(covered, plan.lags - low, 1)
    for first, size in plan.blocks.tolist():
        covered[first - low : first + size - low] += 1
    assert np.all(covered == 1)
    assert np.all(np.diff(plan.lags) > 0)
    breakpoints = np.array([q + 2 for q, _ in ramp_positions(m_i, m_j)])
    for first, size in plan.blocks.tolist():
        distance = np.minimum(np.abs(breakpoints - first), np.abs(breakpoints - (first + size - 1)))
        inside = (breakpoints >= first) & (breakpoints <= first + size - 1)
        assert not np.any(inside)
        assert size <= max(1, rule.block_ratio * int(distance.min()))
        assert size > 2 * rule.points


@given(
    many=st.lists(st.tuples(st.integers(1, 3000), st.integers(1, 3000)), min_size=1, max_size=8),
    length=st.integers(min_value=9_000, max_value=3_000_000),
    reach=st.integers(min_value=3, max_value=200),
    rule=rules,
)
def test_plan_of_many_pairs_is_each_pairs_own_and_the_reference(many, length, reach, rule):
    pairs = [_pair(m_a, m_b, length) for m_a, m_b in many]
    plan = plan_pairs(pairs, reach, rule)
    assert np.all(np.diff(plan.lag_owner) >= 0) and np.all(np.diff(plan.block_owner) >= 0)
    for row, pair in enumerate(pairs):
        alone = plan_pairs([pair], reach, rule)
        np.testing.assert_array_equal(plan.lags[plan.lag_owner == row], alone.lags)
        np.testing.assert_array_equal(plan.blocks[plan.block_owner == row], alone.blocks)
        lags, blocks = _reference_plan(*pair, reach, rule)
        np.testing.assert_array_equal(alone.lags, lags)
        assert alone.blocks.tolist() == [list(block) for block in blocks]


@pytest.mark.parametrize("rule", [PROVED_RULE, WEIGHTS_RULE])
def test_plan_of_octave_pairs_at_a_twelve_hour_record_is_the_reference(rule):
    """All the octave pairs of 4.32·10⁷ samples (blocks up to millions of lags long)."""
    length = 43_200_000
    sizes = [2**k for k in range(int(math.log2(length / 3)) + 1)]
    pairs = [_pair(sizes[i], sizes[j], length) for j in range(len(sizes)) for i in range(j + 1)]
    plan = plan_pairs(pairs, 40, rule)
    for row in range(0, len(pairs), 7):
        lags, blocks = _reference_plan(*pairs[row], 40, rule)
        np.testing.assert_array_equal(plan.lags[plan.lag_owner == row], lags)
        assert plan.blocks[plan.block_owner == row].tolist() == [list(block) for block in blocks]


@pytest.mark.parametrize(
    ("arguments", "error", "message"),
    [
        ((3, 0.5, 32), ValueError, "points=3: must be an integer >= 4"),
        ((8.0, 0.5, 32), TypeError, "points=8.0: must be an integer"),
        ((8, 0.0, 32), ValueError, "block_ratio=0.0"),
        ((8, 1.5, 32), ValueError, "block_ratio=1.5"),
        ((8, float("nan"), 32), ValueError, "block_ratio=nan"),
        ((8, 1.0, 0), ValueError, "exact_reach=0: must be an integer >= 1"),
    ],
)
def test_quadrature_rule_refuses_what_the_bound_does_not_cover(arguments, error, message):
    with pytest.raises(error, match=message):
        QuadratureRule(*arguments)
