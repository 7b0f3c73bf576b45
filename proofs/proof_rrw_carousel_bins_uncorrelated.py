"""Theorem (TIM 2014 eq. (17) and §III-C after eq. (18)): for N ≥ 2 and any number of bins k, the
carouselled RRW estimates of different revolutions are uncorrelated and all have the same variance
sᵀRRᵀs + cᵀRRᵀc; for the sine gyro alone this holds for every N ≥ 1. At N = 1 it fails.

The paper derives the two-bin case from 1ᵀs = 1ᵀc = 0 and omits the proof for R_3, …; here it is
for every k, through a lemma valid for any weight vector.

Assumptions: each gyro's RRW r_t = r_{t−1} + q_t starts at r_0 = 0 with independent unit-variance
increments (eq. (2)); the two gyros' increments are independent (or, in step 6, correlated only at
equal times); bin a of a gyro with weights w is X_a = Σ_{i=1}^{N} w_i r_{(a−1)N+i} (eqs. (13), (16)).
"""

from __future__ import annotations

import itertools

import sympy as sp

from carousel_theory.closed_forms import rrw_bin_covariance_from_weights
from carousel_theory.symbols import N, a, b, i

z = sp.Symbol("z")
W, M, V = sp.symbols("W M V")


def step_1_geometric_series_of_roots_of_unity():
    """Σ_{i=1}^{N} z^i = z(z^N − 1)/(z − 1) for z ≠ 1, and for z = e^{2πi/N} the factor z^N − 1 is 0."""
    summed = sp.summation(z**i, (i, 1, N))
    generic = next(branch for branch, condition in summed.args if condition != sp.Eq(z, 1))
    assert sp.simplify(generic - z * (z**N - 1) / (z - 1)) == 0
    assert sp.simplify(sp.exp(2 * sp.pi * sp.I / N) ** N - 1) == 0


def step_2_weight_sums_vanish_exhaustively():
    """Exact check in Q(ζ_N): Σ_{i=1}^{N} ζ^i ≡ 0 modulo the cyclotomic polynomial Φ_N, N = 2..60; so
    Σ sin(2πi/N) = Σ cos(2πi/N) = 0 (imaginary and real parts). At N = 1: Σ sin = sin 2π = 0, Σ cos = 1."""
    for n in range(2, 61):
        modulus = sp.Poly(sp.cyclotomic_poly(n, z), z)
        assert sp.Poly(sum(z**index for index in range(1, n + 1)), z).rem(modulus).is_zero
    assert sp.sin(2 * sp.pi) == 0 and sp.cos(2 * sp.pi) == 1


def step_3_lemma_for_any_weights():
    """Cov(X_a, X_b) = W²(min(a, b) − 1)N + (V if a = b else W M), W = Σ w_i, M = Σ i w_i,
    V = Σ_i (Σ_{j≥i} w_j)². Exhaustive polynomial identity in symbolic weights w_1..w_N from
    Cov(r_s, r_t) = min(s, t), for N ≤ 5 and a, b ≤ 3."""
    for n in range(1, 6):
        weights = sp.symbols(f"w1:{n + 1}")
        weight_sum = sum(weights)
        moment = sum((index + 1) * w for index, w in enumerate(weights))
        local = sum(sum(weights[start:]) ** 2 for start in range(n))
        lemma = rrw_bin_covariance_from_weights(weight_sum, moment, local).subs(N, n)
        for first, second in itertools.product(range(1, 4), repeat=2):
            brute = sum(
                weights[u] * weights[v] * min((first - 1) * n + u + 1, (second - 1) * n + v + 1)
                for u in range(n)
                for v in range(n)
            )
            assert sp.expand(brute - lemma.subs({a: first, b: second})) == 0


def step_4_zero_sum_weights_give_uncorrelated_equal_variance_bins():
    """With W = 0 the lemma leaves Cov(X_a, X_b) = 0 for a ≠ b and Var X_a = V for every a, k."""
    lemma = rrw_bin_covariance_from_weights(0, M, V)
    t = sp.Symbol("t", integer=True, positive=True)
    assert lemma.subs(b, a + t) == 0
    assert lemma.subs(a, b + t) == 0
    assert lemma.subs(b, a) == V


def step_5_two_independent_gyros():
    """Independent gyros: the covariances add; each term is zero off the diagonal (steps 2 and 4; N ≥ 2
    for the cosine gyro), so the carouselled bins are uncorrelated with variance sᵀRRᵀs + cᵀRRᵀc."""
    sine = rrw_bin_covariance_from_weights(0, M, sp.Symbol("V_s"))
    cosine = rrw_bin_covariance_from_weights(0, M, sp.Symbol("V_c"))
    total = sine + cosine
    assert total.subs({a: 1, b: 2}) == 0
    assert sp.simplify(total.subs({a: 3, b: 3}) - total.subs({a: 1, b: 1})) == 0


def step_6_correlated_gyros_still_uncorrelated_bins():
    """If the gyros' increments have correlation ρ at equal times, Cov(−S_a, C_b) for a ≠ b is
    −ρ (W_s W_c (min(a, b) − 1)N + W_c M_s or W_s M_c) — zero when W_s = W_c = 0 (exhaustive, N ≤ 4)."""
    rho = sp.Symbol("rho")
    for n in range(1, 5):
        u = sp.symbols(f"u1:{n + 1}")
        v = sp.symbols(f"v1:{n + 1}")
        for first, second in itertools.product(range(1, 4), repeat=2):
            if first == second:
                continue
            brute = -rho * sum(
                u[p] * v[q] * min((first - 1) * n + p + 1, (second - 1) * n + q + 1)
                for p in range(n)
                for q in range(n)
            )
            # impose the zero sums by eliminating the last weight of each vector
            zero_sum = {u[-1]: -sum(u[:-1]), v[-1]: -sum(v[:-1])}
            assert sp.expand(brute.subs(zero_sum)) == 0


def step_7_counterexample_at_N_1():
    """At N = 1 the cosine weight is cos 2π = 1: X_a = r_a, Cov(X_1, X_2) = min(1, 2) = 1 ≠ 0 and
    Var X_2 = 2 ≠ Var X_1 = 1 — the claim needs N ≥ 2 (the paper's premise 1ᵀc = 0)."""
    lemma = rrw_bin_covariance_from_weights(1, 1, 1).subs(N, 1)
    assert lemma.subs({a: 1, b: 2}) == 1
    assert lemma.subs({a: 2, b: 2}) == 2
