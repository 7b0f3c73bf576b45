"""Theorem (beyond TIM 2014; its §III method applied to 2-position indexing): for two horizontal gyros
indexed between 0° and 180°, k whole cycles, N samples per dwell and g dropped transition samples
after each dwell, each horizontal component of the demodulated estimate has, for unit driving
variance,

    bias (eq. (1)):  0,
    white noise:     1/(2kN),
    RRW (eq. (2)):   (2N² + 3gN + 1)/(12kN),

for every k ≥ 1, N ≥ 1, g ≥ 0; the two components are uncorrelated.

Assumptions: component 1 of Ω̂ = (1/n_used) Σ R_z(φ_t) ω_t weights the x gyro by cos φ_t/(2kN) on
used samples (+h at 0°, −h at 180°, h = 1/(2kN)) and the y gyro by −sin φ_t/(2kN) = 0; component 2
weights the y gyro the same way and the x gyro by 0. Each gyro's processes start at t = 1.
"""

from __future__ import annotations

from fractions import Fraction

import sympy as sp

from carousel_theory.closed_forms import (
    INDEXING2_BIAS_VARIANCE,
    INDEXING2_RRW_VARIANCE,
    INDEXING2_WHITE_VARIANCE,
)
from carousel_theory.symbols import N, g, k

u = sp.Symbol("u", integer=True, nonnegative=True)
h = 1 / (2 * k * N)


def _cycle_weights(dwell: int, gap: int) -> list[int]:
    """One cycle in units of h: +1 for N samples, 0 for g, −1 for N, 0 for g."""
    return [1] * dwell + [0] * gap + [-1] * dwell + [0] * gap


def _suffix_squares(weights: list[Fraction]) -> Fraction:
    total, suffix = Fraction(0), Fraction(0)
    for value in reversed(weights):
        suffix += value
        total += suffix * suffix
    return total


def step_1_bias_cancels():
    """Σ_t w_t = k(Nh − Nh) = 0, so Var = σ_b² (Σ w)² = 0; and the registry's form is 0."""
    assert sp.simplify(k * (N * h - N * h)) == 0
    assert INDEXING2_BIAS_VARIANCE == 0


def step_2_white():
    """Var = Σ w_t² = 2kN h² = 1/(2kN)."""
    assert sp.simplify(2 * k * N * h**2 - INDEXING2_WHITE_VARIANCE) == 0


def step_3_suffix_sums_within_a_cycle():
    """Since every cycle's weights sum to 0, the suffix Σ_{t≥i} w_t from a sample of cycle c is the suffix
    within cycle c: −u h at offset u of the first dwell, −Nh in its gap, −(N − u) h at offset u of the
    second dwell, 0 in the last gap. Exhaustive over N ≤ 8, g ≤ 4."""
    for dwell in range(1, 9):
        for gap in range(5):
            cycle = _cycle_weights(dwell, gap)
            expected = (
                [-offset for offset in range(dwell)]
                + [-dwell] * gap
                + [-(dwell - offset) for offset in range(dwell)]
                + [0] * gap
            )
            suffixes = [sum(cycle[i:]) for i in range(len(cycle))]
            assert suffixes == expected


def step_4_one_cycle_sum_of_squares():
    """Σ_u u² + g N² + Σ_u (N − u)² over u = 0 … N − 1 equals N(2N² + 1)/3 + gN²."""
    total = sp.summation(u**2, (u, 0, N - 1)) + g * N**2 + sp.summation((N - u) ** 2, (u, 0, N - 1))
    assert sp.simplify(total - (N * (2 * N**2 + 1) / 3 + g * N**2)) == 0


def step_5_k_cycles():
    """Var_RRW = k h² (N(2N² + 1)/3 + gN²) = (2N² + 3gN + 1)/(12kN), the registry's form."""
    value = k * h**2 * (N * (2 * N**2 + 1) / 3 + g * N**2)
    assert sp.simplify(value - INDEXING2_RRW_VARIANCE) == 0


def step_6_exhaustive_exact():
    """Exact Fractions from the whole weight vector (no structure used): N ≤ 6, g ≤ 3, k ≤ 3, and the
    cross-covariance of the two components is 0 because they use different gyros."""
    for dwell in range(1, 7):
        for gap in range(4):
            for cycles in range(1, 4):
                step = Fraction(1, 2 * cycles * dwell)
                weights = [step * value for value in _cycle_weights(dwell, gap)] * cycles
                substitution = {N: dwell, g: gap, k: cycles}
                assert _suffix_squares(weights) == Fraction(str(INDEXING2_RRW_VARIANCE.subs(substitution)))
                assert sum(w * w for w in weights) == Fraction(
                    str(INDEXING2_WHITE_VARIANCE.subs(substitution))
                )
                assert sum(weights) == 0
