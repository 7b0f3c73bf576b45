"""Theorem (premises of the Leibniz argument, TIM 2014 §III-D): for 0 < d < 1 the coefficients
ψ_j = Γ(j + d)/(Γ(j + 1) Γ(d)) of eq. (3) are positive, strictly decreasing in j, and tend to 0.
Hence, for even N, each of the N/2 series Σ_m ± |a_u| ψ_{m_0 + mN/2} obtained by grouping the
opposite pairs a_{u+N/2} = −a_u of s or c is alternating with terms decreasing to 0, and converges.

Assumptions: 0 < d < 1, j ≥ 1 an integer.

Proof: Step 1: ψ_j/ψ_{j−1} = (j − 1 + d)/j, which lies in (0, 1) because 1 − ratio = (1 − d)/j > 0 and
ratio ≥ d/j > 0. Step 2: ψ_j → 0 because ψ_j j^{1−d} → 1/Γ(d) (eq. (19), proof_flicker_limit_19) and
j^{d−1} → 0 for d < 1. Step 3: the opposite pairs of (13).
"""

import sympy as sp

from carousel_theory.flicker_asymptotics import fractional_coefficient
from carousel_theory.symbols import d

j = sp.Symbol("j", integer=True, positive=True)


def step_1_ratio_lies_between_zero_and_one():
    ratio = sp.gammasimp(fractional_coefficient(j) / fractional_coefficient(j - 1))
    assert sp.simplify(ratio - (j - 1 + d) / j) == 0
    gap = sp.simplify(1 - ratio)
    assert sp.simplify(gap - (1 - d) / j) == 0
    # with d = 1 − e, e > 0 (d < 1): the gap e/j is positive
    e = sp.Symbol("e", positive=True)
    assert gap.subs(d, 1 - e).is_positive
    # with j = n + 1, n ≥ 0 an integer: the ratio (n + d)/(n + 1) is positive for d > 0
    n = sp.Symbol("n", integer=True, nonnegative=True)
    assert ratio.subs(j, n + 1).is_positive


def step_2_terms_tend_to_zero():
    e = sp.Symbol("e", positive=True)  # d = 1 − e
    assert sp.limit(j ** (-e), j, sp.oo) == 0


def step_3_opposite_pairs():
    N = sp.Symbol("N", integer=True, positive=True)
    u = sp.Symbol("u", integer=True, positive=True)
    for function in (sp.sin, sp.cos):
        term = function(2 * sp.pi * u / N)
        assert sp.simplify(sp.expand_trig(term.subs(u, u + N / 2) + term)) == 0
