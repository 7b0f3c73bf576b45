"""Theorem (TIM 2014 §III-D, "F1 computes the cumulative sum of the first column of F"; the entries
tend to infinity): for every d > 0 and M ≥ 0,

    Ψ_M = Σ_{j=0}^{M} ψ_j = Γ(M + 1 + d) / (Γ(M + 1) Γ(d + 1)),   ψ_j = Γ(j + d)/(Γ(j + 1) Γ(d)),

so Ψ is the coefficient sequence of order d + 1 and, by (19) at order d + 1, Ψ_M ~ M^d/Γ(d + 1) → ∞.

Assumptions: d > 0; ψ as in TIM 2014 eq. (3).

Proof: induction on M. Base case M = 0 (Step 1); induction step M → M + 1 (Step 2). Step 3 checks
the closed form against the exact recursion for d = 1/3, 1/2, 2/3 and M < 200.
"""

from fractions import Fraction

import sympy as sp

from carousel_theory.flicker_asymptotics import cumulative_coefficient, fractional_coefficient
from carousel_theory.processes import fractional_coefficients_exact
from carousel_theory.symbols import d

M = sp.Symbol("M", integer=True, nonnegative=True)


def step_1_base_case():
    """Ψ_0 = ψ_0 = 1 and the closed form at M = 0 is Γ(1 + d)/(Γ(1)Γ(1 + d)) = 1."""
    assert sp.gammasimp(cumulative_coefficient(sp.Integer(0))) == 1
    assert sp.gammasimp(fractional_coefficient(sp.Integer(0))) == 1


def step_2_induction_step():
    """closed(M + 1) − closed(M) = ψ_{M+1}."""
    difference = cumulative_coefficient(M + 1) - cumulative_coefficient(M) - fractional_coefficient(M + 1)
    assert sp.simplify(sp.gammasimp(difference)) == 0


def step_3_exhaustive_check_against_the_exact_recursion():
    """Exact rationals, d ∈ {1/3, 1/2, 2/3}, M = 0 … 199."""
    for order in (Fraction(1, 3), Fraction(1, 2), Fraction(2, 3)):
        psi = fractional_coefficients_exact(order, 200)
        total = Fraction(0)
        rational = sp.Rational(order.numerator, order.denominator)
        closed = sp.Integer(1)  # Γ(M+1+d)/(Γ(M+1)Γ(d+1)) by its own ratio (M + 1 + d)/(M + 1)
        for index in range(200):
            total += psi[index]
            if index > 0:
                closed *= (index + rational) / index
            assert sp.Rational(total.numerator, total.denominator) == closed


def step_4_growth():
    """log(Γ(M+1+d)/(Γ(M+1) M^d)) = d(d + 1)/(2M) + O(M⁻²) → 0: Ψ_M ~ M^d/Γ(d+1), unbounded for d > 0."""
    m = sp.Symbol("m", positive=True)
    series = sp.series(sp.loggamma(m + 1 + d) - sp.loggamma(m + 1) - d * sp.log(m), m, sp.oo, n=2).removeO()
    assert sp.simplify(series - d * (d + 1) / (2 * m)) == 0
    assert sp.limit(m**d / sp.gamma(d + 1), m, sp.oo) == sp.oo
