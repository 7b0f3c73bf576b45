"""Theorem (TIM 2014 §IV after (30)-(31): the Allan-based estimate "is not the MVUE", which "can be
found by using the Moore–Penrose pseudoinverse"): for x ~ N(0, I_n) and R = C K x, every n ≥ 2,

    Var[2σ_A²(2^m)] = 2C⁴ (2^p + 1) / (3 (2^p − 1)),  p = n − m,
    Ĉ² = ‖K⁺R‖²/n is the MVUE of C², Var Ĉ² = 2C⁴/n,

and Var[2σ_A²(2^m)] > Var Ĉ² for every m = 0 … n − 1. The sample variance of K⁺R about its sample
mean (divisor n − 1) is unbiased too, but has variance 2C⁴/(n − 1) > 2C⁴/n.

Assumptions: single-innovation theorem (x_i enters the 2^{n−m} − 1 differences at τ = 2^m exactly
2^{i−1} times, i = 1 … p) and K⁺K = I (proofs/proof_graycode_gram.py); Gaussian x: Var x_i² = 2, and
‖x‖² is a complete sufficient statistic for C² in N(0, C² I_n) (Lehmann–Scheffé).

Proof: direct for all n, m; each step a SymPy identity.
"""

import sympy as sp

from carousel_theory.graycode import ALLAN_ESTIMATOR_VARIANCE, MVUE_VARIANCE, C_symbol, m_symbol, n_symbol

C, n, m = C_symbol, n_symbol, m_symbol
p, i, k = sp.symbols("p i k", integer=True, positive=True)


def two_adic_valuation(j: int) -> int:
    return (j & -j).bit_length() - 1


def step_1_how_often_each_innovation_enters():
    """#{j ≤ 2^p − 1 : ν₂(j) = k} = 2^{p−1−k} (j = 2^k (2q + 1), q = 0 … 2^{p−k−1} − 1), so x_i with
    i = p − k enters 2^{i−1} differences; the counts add up to 2^p − 1. Exhaustive for p ≤ 14, and the
    total as a SymPy identity for all p."""
    for order in range(1, 15):
        counts = [0] * order
        for j in range(1, 2**order):
            counts[two_adic_valuation(j)] += 1
        assert counts == [2 ** (order - 1 - kk) for kk in range(order)]
    total = sp.Sum(2 ** (i - 1), (i, 1, p)).doit()
    assert sp.simplify(total - (2**p - 1)) == 0


def step_2_variance_of_the_allan_estimator():
    """2σ_A² = C²/(2^p − 1) Σ_i 2^{i−1} x_i²; independent x_i² with Var 2:
    Var = 2C⁴ Σ 4^{i−1} / (2^p − 1)² = ALLAN_ESTIMATOR_VARIANCE."""
    variance = 2 * C**4 * sp.Sum(4 ** (i - 1), (i, 1, p)).doit() / (2**p - 1) ** 2
    assert sp.simplify(variance - ALLAN_ESTIMATOR_VARIANCE.subs(n, p + m)) == 0


def step_3_mvue():
    """K⁺R = C x, so ‖K⁺R‖²/n = C² ‖x‖²/n: unbiased, a function of the complete sufficient statistic,
    variance C⁴ · 2n / n² = 2C⁴/n = MVUE_VARIANCE."""
    assert sp.simplify(C**4 * 2 * n / n**2 - MVUE_VARIANCE) == 0


def step_4_sample_variance_about_the_mean_is_worse():
    """Σ(x_i − x̄)²/(n − 1) ~ C² χ²_{n−1}/(n − 1): variance 2C⁴/(n − 1); the excess over the MVUE is
    2C⁴/(n(n − 1)) > 0."""
    excess = 2 * C**4 / (n - 1) - MVUE_VARIANCE
    assert sp.simplify(excess - 2 * C**4 / (n * (n - 1))) == 0


def step_5_allan_estimator_is_worse_at_every_tau():
    """Ratio Var[2σ_A²]/Var Ĉ² = n (2^p + 1)/(3 (2^p − 1)) = (n/3)(1 + 2/(2^p − 1)), decreasing in p, so
    smallest at p = n (τ = 1), where ratio − 1 = ((n − 3) 2^n + n + 3) / (3 (2^n − 1)): positive for n = 2
    (1/9) and for n = k + 3, k ≥ 0 (every term of k 2^{k+3} + k + 6 is non-negative, 6 > 0)."""
    ratio = sp.simplify(ALLAN_ESTIMATOR_VARIANCE / MVUE_VARIANCE)
    assert sp.simplify(ratio.subs(m, n - p) - n / 3 * (1 + 2 / (2**p - 1))) == 0
    at_tau_one = ratio.subs(m, 0)
    assert sp.simplify(at_tau_one - 1 - ((n - 3) * 2**n + n + 3) / (3 * (2**n - 1))) == 0
    assert (at_tau_one - 1).subs(n, 2) == sp.Rational(1, 9)
    kk = sp.Symbol("kk", integer=True, nonnegative=True)
    shifted = sp.expand(((n - 3) * 2**n + n + 3).subs(n, kk + 3))
    assert sp.simplify(shifted - (8 * kk * 2**kk + kk + 6)) == 0
