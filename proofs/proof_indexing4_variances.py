"""Theorem (beyond TIM 2014; its §III method applied to 4-position indexing): for two horizontal gyros
indexed through 0°, 90°, 180°, 270°, k whole cycles, N samples per dwell and g dropped transition
samples after each dwell, each horizontal component of the demodulated estimate has, for unit
driving variance,

    bias (eq. (1)):  0,
    white noise:     1/(4kN),
    RRW (eq. (2)):   (5N² + 6gN + 1)/(24kN),

for every k ≥ 1, N ≥ 1, g ≥ 0, and the two components are uncorrelated.

Assumptions: Ω̂ = (1/n_used) Σ R_z(φ_t) ω_t on used samples, h = 1/(4kN). Component 1 weights the
x gyro by cos φ (+h in dwell 1, −h in dwell 3) and the y gyro by −sin φ (−h in dwell 2, +h in
dwell 4); component 2 weights x by sin φ (+h in dwell 2, −h in dwell 4) and y by cos φ (+h in
dwell 1, −h in dwell 3). Each gyro's processes start at t = 1; the gyros are independent.
"""

from __future__ import annotations

from fractions import Fraction

import sympy as sp

from carousel_theory.closed_forms import (
    INDEXING4_BIAS_VARIANCE,
    INDEXING4_RRW_VARIANCE,
    INDEXING4_WHITE_VARIANCE,
)
from carousel_theory.symbols import N, g, k

u = sp.Symbol("u", integer=True, nonnegative=True)
h = 1 / (4 * k * N)


def _cycle(signs: tuple[int, int, int, int], dwell: int, gap: int) -> list[int]:
    """One cycle in units of h: dwell p carries signs[p], every gap 0."""
    values: list[int] = []
    for sign in signs:
        values += [sign] * dwell + [0] * gap
    return values


#: (x gyro, y gyro) sign patterns of components 1 and 2 over the four dwells.
COMPONENT_1 = ((1, 0, -1, 0), (0, -1, 0, 1))
COMPONENT_2 = ((0, 1, 0, -1), (1, 0, -1, 0))


def _suffixes(weights: list[Fraction]) -> list[Fraction]:
    values, suffix = [], Fraction(0)
    for value in reversed(weights):
        suffix += value
        values.append(suffix)
    return values[::-1]


def step_1_bias_cancels():
    """Each gyro's weights in each component sum to h N (1 − 1) = 0 per cycle: the bias leaves 0."""
    for pattern in (*COMPONENT_1, *COMPONENT_2):
        assert sum(pattern) == 0
    assert INDEXING4_BIAS_VARIANCE == 0


def step_2_white():
    """Each gyro has 2kN samples at ±h in a component: Var = 2 · 2kN h² = 1/(4kN)."""
    assert sp.simplify(2 * 2 * k * N * h**2 - INDEXING4_WHITE_VARIANCE) == 0


def step_3_one_gyro_one_cycle():
    """Signs (+, 0, −, 0): suffixes −u h in dwell 1, −Nh over gap, dwell 2 and gap (N + 2g samples),
    −(N − u) h in dwell 3, 0 after; sum of squares N(2N² + 1)/3 + (N + 2g) N². The other gyro's pattern
    (0, −, 0, +) is a shift of (+, 0, −, 0) with zeros before it, whose suffixes there are 0, and its
    suffixes squared sum to the same value. Symbolic, then exhaustive over N ≤ 7, g ≤ 3."""
    total = sp.summation(u**2, (u, 0, N - 1)) + (N + 2 * g) * N**2 + sp.summation((N - u) ** 2, (u, 0, N - 1))
    assert sp.simplify(total - (N * (2 * N**2 + 1) / 3 + (N + 2 * g) * N**2)) == 0
    for dwell in range(1, 8):
        for gap in range(4):
            expected = dwell * (2 * dwell**2 + 1) // 3 + (dwell + 2 * gap) * dwell**2
            for pattern in (*COMPONENT_1, *COMPONENT_2):
                cycle = _cycle(pattern, dwell, gap)
                assert sum(sum(cycle[i:]) ** 2 for i in range(len(cycle))) == expected


def step_4_k_cycles():
    """Cycles decouple (each sums to 0): Var_RRW = 2 k h² (N(2N² + 1)/3 + (N + 2g)N²), the registry's form."""
    value = 2 * k * h**2 * (N * (2 * N**2 + 1) / 3 + (N + 2 * g) * N**2)
    assert sp.simplify(value - INDEXING4_RRW_VARIANCE) == 0


def step_5_exhaustive_exact_with_cross_covariance():
    """Exact Fractions over the whole weight vectors: N ≤ 5, g ≤ 3, k ≤ 3; the RRW and white
    covariances of components 1 and 2 vanish (x and y contributions cancel exactly)."""
    for dwell in range(1, 6):
        for gap in range(4):
            for cycles in range(1, 4):
                step = Fraction(1, 4 * cycles * dwell)
                first = [[step * v for v in _cycle(p, dwell, gap)] * cycles for p in COMPONENT_1]
                second = [[step * v for v in _cycle(p, dwell, gap)] * cycles for p in COMPONENT_2]
                substitution = {N: dwell, g: gap, k: cycles}
                variance = sum(sum(s * s for s in _suffixes(w)) for w in first)
                assert variance == Fraction(str(INDEXING4_RRW_VARIANCE.subs(substitution)))
                assert variance == sum(sum(s * s for s in _suffixes(w)) for w in second)
                cross = sum(
                    sum(p * q for p, q in zip(_suffixes(a), _suffixes(b), strict=True))
                    for a, b in zip(first, second, strict=True)
                )
                assert cross == 0
                assert sum(w * w for row in first for w in row) == Fraction(
                    str(INDEXING4_WHITE_VARIANCE.subs(substitution))
                )
                assert (
                    sum(
                        sum(a * b for a, b in zip(x, y, strict=True))
                        for x, y in zip(first, second, strict=True)
                    )
                    == 0
                )
