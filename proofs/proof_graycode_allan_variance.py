"""Theorem (TIM 2014 eq. (23), (30) and the unbiasedness remark after (30)): for every n ≥ 2 and
τ = 2^m, m = 0 … n − 1, R = C K x with x_1 … x_n uncorrelated, zero mean, unit variance (any
distribution), the non-overlapping Allan variance (20) satisfies

    E[σ_A²(τ)] = C²/2,   i.e.   E[2σ_A²(τ)] = C²:

(20) without its factor ½ is unbiased for C² (the main rendering); (20) without 1/τ (the alternative
rendering, bin sums instead of means) has expectation τ² C²/2 instead.

Assumptions: the single-innovation theorem (proofs/proof_graycode_single_innovation.py): each bin
difference of R at τ = 2^m is ±C x_i for exactly one i.

Proof: direct for all n, m; each step a SymPy identity.
"""

import sympy as sp

from carousel_theory.graycode import ALLAN_VARIANCE, C_symbol, allan_variance_exact

M, j, tau = sp.symbols("M j tau", integer=True, positive=True)
C = C_symbol


def step_1_each_difference_has_variance_C_squared():
    """E[(±C x_i)²] = C² E[x_i²] = C² (unit variance); the sign and the index i do not matter."""
    x_squared_mean = sp.Integer(1)
    assert sp.simplify((C**2) * x_squared_mean - C**2) == 0


def step_2_expectation_of_20():
    """E σ_A² = Σ_{j=1}^{M−1} C² / (2(M − 1)) = C²/2 = ALLAN_VARIANCE, for every M = 2^{n−m} ≥ 2."""
    expectation = sp.Sum(C**2, (j, 1, M - 1)).doit() / (2 * (M - 1))
    assert sp.simplify(expectation - ALLAN_VARIANCE) == 0
    assert sp.simplify(2 * expectation - C**2) == 0  # (20) without ½


def step_3_without_one_over_tau():
    """A bin sum is τ times the bin mean, so the statistic on sums has expectation τ² C²/2: C² only at
    τ = √2, never at τ = 2^m."""
    on_sums = tau**2 * ALLAN_VARIANCE
    assert sp.simplify(on_sums - tau**2 * C**2 / 2) == 0
    length = sp.Symbol("length", positive=True)  # τ as a real variable, to solve for it
    assert sp.solve(sp.Eq(on_sums.subs(tau, length), C**2), length) == [sp.sqrt(2)]


def step_4_the_package_value():
    """allan_variance_exact returns the same value (exact input, exact output)."""
    for n in range(2, 12):
        for m in range(n):
            assert allan_variance_exact(n, m, sp.Rational(3, 7)) == sp.Rational(9, 98)
