"""Theorem (TIM 2014 §III-C, after eq. (15)): every subsequent N-average of rate random walk has a
variance higher by exactly σ_q² N than the previous one, for every bin k ≥ 1 and every N ≥ 1; more
generally the averaged bins a, b have

    Cov(X_a, X_b) / σ_q² = (min(a, b) − 1) N + (N + 1)(2N + 1)/(6N)   if a = b,
                         = (min(a, b) − 1) N + (N + 1)/2             if a ≠ b.

The paper states the increment "can be seen by repeating the calculations for R_3 etc." and omits
the proof by induction; here it is.

Assumptions: r_t = r_{t−1} + q_t with r_0 = 0 (eq. (2)); q_t independent, zero mean, variance
σ_q² = 1 (scale by σ_q²); X_k = (1/N) Σ_{i=1}^{N} r_{(k−1)N+i} (eqs. (12), (14)).
"""

from __future__ import annotations

from fractions import Fraction

import sympy as sp

from carousel_theory.closed_forms import RRW_AVERAGE_COVARIANCE, RRW_AVERAGE_VARIANCE
from carousel_theory.symbols import N, a, b, i, k

t = sp.Symbol("t", integer=True, nonnegative=True)
j = sp.Symbol("j", integer=True, positive=True)
V = (N + 1) * (2 * N + 1) / (6 * N)  # the base-case value, derived in step 2


def step_1_rrw_covariance_is_min():
    """Cov(r_s, r_t) = Σ_u [u ≤ s][u ≤ t] = min(s, t): (R Rᵀ)_{st} for the ones matrix R of eq. (10).
    Exhaustive over all s, t ≤ 30."""
    n = 30
    R = [[1 if u <= s else 0 for u in range(n)] for s in range(n)]
    for s in range(n):
        for r in range(n):
            assert sum(R[s][u] * R[r][u] for u in range(n)) == min(s, r) + 1


def step_2_base_case_first_bin():
    """Var X_1 = (1/N²) Σ_{s,t ≤ N} min(s, t) = Σ_i ((N − i + 1)/N)² = (N + 1)(2N + 1)/(6N) = V.

    The number of pairs (s, t) with min(s, t) ≥ i is (N − i + 1)², so Σ min = Σ_i (N − i + 1)²."""
    assert sp.simplify(sp.summation((N - i + 1) ** 2, (i, 1, N)) / N**2 - V) == 0
    for n in range(1, 13):  # the counting argument, exhaustively
        pairs = sum(min(s, r) for s in range(1, n + 1) for r in range(1, n + 1))
        assert Fraction(pairs, n * n) == Fraction(int(sp.numer(V.subs(N, n))), int(sp.denom(V.subs(N, n))))


def step_3_shift_identity():
    """min(kN + i, kN + j) = kN + min(i, j): with j = i + t, t ≥ 0, both sides are kN + i."""
    assert sp.Min(k * N + i, k * N + i + t) - (k * N + i) == 0
    assert sp.Min(i, i + t) - i == 0


def step_4_induction_step():
    """Var X_{k+1} = (1/N²) Σ_{i,j} min(kN + i, kN + j) = kN + (1/N²) Σ_{i,j} min(i, j) = kN + V
    (step 3, then step 2); hence Var X_{k+1} − Var X_k = (kN + V) − ((k − 1)N + V) = N."""
    variance = k * N + V
    previous = (k - 1) * N + V
    assert sp.simplify(variance - previous - N) == 0
    # and the closed form of the package is exactly this sequence
    assert sp.simplify(RRW_AVERAGE_VARIANCE.subs(k, k + 1) - variance) == 0
    assert sp.simplify(RRW_AVERAGE_VARIANCE.subs(k, 1) - V) == 0


def step_5_cross_covariance():
    """For a < b every sample of bin a precedes every sample of bin b, so
    Cov(X_a, X_b) = (1/N²) Σ_{i,j} ((a − 1)N + i) = (a − 1)N + (N + 1)/2."""
    cross = sp.summation(sp.summation((a - 1) * N + i, (i, 1, N)), (j, 1, N)) / N**2
    assert sp.simplify(cross - ((a - 1) * N + (N + 1) / 2)) == 0
    assert sp.simplify(RRW_AVERAGE_COVARIANCE.subs(b, a + 1 + t) - cross) == 0  # a < b
    assert sp.simplify(RRW_AVERAGE_COVARIANCE.subs(a, b + 1 + t).subs(b, a) - cross) == 0  # b < a, swapped


def step_6_exhaustive_dense_matrices():
    """Exhaustive check with the dense R_k of eq. (11), exact Fractions: all N ≤ 10, k ≤ 5, all a, b."""
    for n in range(1, 11):
        bins = 5
        length = bins * n
        tails = []
        for bin_number in range(bins):
            tail = [Fraction(0)] * length
            for u in range(length):  # (R_kᵀ w)_u = Σ_{v ≥ u} w_v
                tail[u] = sum(
                    (Fraction(1, n) for v in range(max(u, bin_number * n), (bin_number + 1) * n)), Fraction(0)
                )
            tails.append(tail)
        for first in range(bins):
            for second in range(bins):
                value = sum((p * q for p, q in zip(tails[first], tails[second], strict=True)), Fraction(0))
                expected = RRW_AVERAGE_COVARIANCE.subs({N: n, a: first + 1, b: second + 1})
                assert sp.Rational(value.numerator, value.denominator) == expected
            if first > 0:
                assert sum(x * x for x in tails[first]) - sum(x * x for x in tails[first - 1]) == n
