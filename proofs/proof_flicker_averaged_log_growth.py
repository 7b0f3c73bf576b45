"""Theorem (TIM 2014 §V-B: "the rate of increase seems to be logarithmic", made exact): for 1/f noise
of order d = 1/2 (eq. (3), σ_w² = 1), every N ≥ 1 and every K ≥ 2, the variances Var_k of the
averaged bins (N-sample means) satisfy

    (1/π) log((KN + 1/2) / (2N + 1/2))  ≤  Var_K − Var_2  ≤  (1/π) log(K − 1),

so Var_K = log(K)/π + O(1), with the O(1) bounded by constants independent of K.

Assumptions: d = 1/2; ψ_j = Γ(j + 1/2)/(Γ(j + 1)√π); Var_k = Σ_{j<kN} g_j², g_j = (Ψ_j − Ψ_{j−N})/N
(proof_flicker_bin_coefficients).

Proof:
Step 1. a_j = j ψ_j² is strictly increasing (j ≥ 1) and b_j = (j + 1/2) ψ_j² strictly decreasing (j ≥ 0).
Step 2. Both tend to 1/π (eq. (19): √j ψ_j → 1/Γ(1/2) = 1/√π); hence 1/(π(j + 1/2)) < ψ_j² < 1/(πj), j ≥ 1.
Step 3. For j ≥ N − 1, g_j is the mean of ψ_{j−N+1} … ψ_j, so ψ_j ≤ g_j ≤ ψ_{j−N+1} (ψ decreases).
Step 4. The increment I_k = Var_k − Var_{k−1} (k ≥ 3) lies between Σ_{j=(k−1)N}^{kN−1} 1/(π(j+1/2)) ≥
        (1/π) log((kN + 1/2)/((k−1)N + 1/2)) and Σ_{m=(k−2)N+1}^{(k−1)N} 1/(πm) ≤ (1/π) log((k−1)/(k−2))
        (integral comparison for decreasing functions); the sums over k = 3 … K telescope.
Step 5. Exhaustive check of the final inequality at 50 digits for N ∈ {1, 2, 3, 10, 200}, K ≤ 40.
"""

from fractions import Fraction

import mpmath
import sympy as sp

from carousel_theory.flicker_asymptotics import fractional_coefficient
from carousel_theory.processes import fractional_coefficients_exact
from carousel_theory.propagation import flicker_bin_variances_high_precision
from carousel_theory.symbols import d

j = sp.Symbol("j", integer=True, positive=True)
half = sp.Rational(1, 2)
ratio = sp.gammasimp(fractional_coefficient(j) / fractional_coefficient(j - 1)).subs(d, half)


def step_1_monotone_envelopes():
    assert sp.simplify(ratio - (j - half) / j) == 0
    increasing = sp.factor(sp.simplify(j / (j - 1) * ratio**2 - 1))  # a_j / a_{j−1} − 1
    decreasing = sp.factor(sp.simplify((j + half) / (j - half) * ratio**2 - 1))  # b_j / b_{j−1} − 1
    assert sp.simplify(increasing - 1 / (4 * j * (j - 1))) == 0  # > 0 for j ≥ 2
    assert sp.simplify(decreasing + 1 / (4 * j**2)) == 0  # < 0 for j ≥ 1


def step_2_limits_and_the_two_sided_bound():
    x = sp.Symbol("x", positive=True)
    root_limit = sp.limit(
        sp.exp(
            sp.series(sp.loggamma(x + half) - sp.loggamma(x + 1) + half * sp.log(x), x, sp.oo, n=2).removeO()
        ),
        x,
        sp.oo,
    )
    assert root_limit == 1  # √x Γ(x+1/2)/Γ(x+1) → 1, so j ψ_j² → 1/Γ(1/2)² = 1/π
    assert sp.gamma(half) ** 2 == sp.pi
    assert sp.limit((j + half) / j, j, sp.oo) == 1  # b_j / a_j → 1
    # a_1 = 1/4 < 1/π and b_0 = 1/2 > 1/π are the first terms of the two monotone sequences
    assert sp.Rational(1, 4) < 1 / sp.pi < half


def step_3_window_mean_between_its_ends():
    """ψ_j ≤ g_j ≤ ψ_{j−N+1} for j ≥ N − 1: a mean of N values of a decreasing sequence lies between its
    last and its first value. Exhaustive exact check, d = 1/2, N ≤ 12, N − 1 ≤ j < 6N."""
    psi = fractional_coefficients_exact(Fraction(1, 2), 72)
    for N in range(1, 13):
        for index in range(N - 1, 6 * N):
            mean = sum(psi[index - N + 1 : index + 1], Fraction(0)) / N
            assert psi[index] <= mean <= psi[index - N + 1]


def same_logarithm(first: sp.Expr, second: sp.Expr) -> bool:
    """first = second for sums of logarithms of positive quantities: exp(first − second) simplifies to 1."""
    return sp.simplify(sp.exp(first - second)) == 1


def step_4_integral_comparisons():
    x = sp.Symbol("x", positive=True)
    a, b = sp.symbols("a b", positive=True)
    lower = sp.integrate(1 / (x + half), (x, a, b + 1))
    upper = sp.integrate(1 / x, (x, a - 1, b))
    assert same_logarithm(lower, sp.log(b + 1 + half) - sp.log(a + half))
    assert same_logarithm(upper, sp.log(b) - sp.log(a - 1))
    N, k = sp.symbols("N k", positive=True)
    # lower: a = (k−1)N, b = kN − 1; upper: a = (k−2)N + 1, b = (k−1)N
    assert same_logarithm(
        lower.subs({a: (k - 1) * N, b: k * N - 1}), sp.log((k * N + half) / ((k - 1) * N + half))
    )
    assert same_logarithm(upper.subs({a: (k - 2) * N + 1, b: (k - 1) * N}), sp.log((k - 1) / (k - 2)))
    # the sums over k = 3 … K telescope
    K = 7
    assert same_logarithm(
        sum(sp.log((k * N + half) / ((k - 1) * N + half)) for k in range(3, K + 1)),
        sp.log((K * N + half) / (2 * N + half)),
    )
    assert same_logarithm(sum(sp.log(sp.Rational(k - 1, k - 2)) for k in range(3, K + 1)), sp.log(K - 1))


def step_5_exhaustive_check_at_50_digits():
    with mpmath.workdps(50):
        for N in (1, 2, 3, 10, 200):
            every = flicker_bin_variances_high_precision(half, N, 40, "averaged", digits=50)
            for K in range(2, 41):
                growth = every[K - 1] - every[1]
                assert (
                    mpmath.log((K * N + mpmath.mpf(1) / 2) / (2 * N + mpmath.mpf(1) / 2)) / mpmath.pi
                    <= growth
                )
                assert growth <= mpmath.log(K - 1) / mpmath.pi
