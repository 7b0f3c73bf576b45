"""Theorem (TIM 2014 eq. (19)): for every d > 0,

    lim_{i→∞} [Γ(i + d) / (Γ(i + 1) Γ(d))] / i^{d−1} = lim_{i→∞} Γ(i + d) / (i^d Γ(i) Γ(d)) = 1/Γ(d).

Consequently ψ_i ~ i^{d−1}/Γ(d) for the coefficients of eq. (3), and (order d + 1) the cumulative
sums Ψ_M = ψ_0 + … + ψ_M ~ M^d/Γ(d + 1).

Assumptions: d > 0 real, i → ∞ through the positive reals.

Proof: Step 1 shows the two printed forms equal; Step 2 expands log(Γ(i + d)/(i^d Γ(i))) at i = ∞
(Stirling's series, SymPy) to d(d − 1)/(2i) + O(i⁻²); Step 3 takes the limit of that expansion (0),
so by continuity of exp the ratio tends to 1 and the limit is 1/Γ(d). Step 4 checks the rate at
50 digits.
"""

import mpmath
import sympy as sp

from carousel_theory.flicker_asymptotics import fractional_coefficient, limit_19_log_series
from carousel_theory.symbols import d

i = sp.Symbol("i", positive=True)


def step_1_the_printed_forms_are_equal():
    """ψ_i / i^{d−1} = Γ(i+d) i^{1−d} / (i Γ(i) Γ(d)) = Γ(i+d) / (i^d Γ(i) Γ(d))."""
    first = fractional_coefficient(i) / i ** (d - 1)
    second = sp.gamma(i + d) * i ** (1 - d) / (i * sp.gamma(i) * sp.gamma(d))
    third = sp.gamma(i + d) / (i**d * sp.gamma(i) * sp.gamma(d))
    assert sp.simplify(sp.gammasimp(first - second)) == 0
    assert sp.simplify(sp.powsimp(second - third, force=True)) == 0


def step_2_stirling_series_of_the_log_ratio():
    """log Γ(i + d) − log Γ(i) − d log i = d(d − 1)/(2i) + O(i⁻²)."""
    assert sp.simplify(limit_19_log_series() - d * (d - 1) / (2 * i)) == 0


def step_3_the_log_ratio_tends_to_zero():
    """The expansion tends to 0, so Γ(i + d)/(i^d Γ(i)) → e⁰ = 1 and the limit (19) is 1/Γ(d) > 0."""
    assert sp.limit(limit_19_log_series(), i, sp.oo) == 0
    assert (1 / sp.gamma(d)).is_positive


def step_4_rate_at_50_digits():
    """At d = 1/3: |Γ(i+d)/(i^d Γ(i)) − 1| ≈ d(1 − d)/(2i) for i = 10³ … 10¹², the relative error of
    this rate below 10/i."""
    with mpmath.workdps(50):
        order = mpmath.mpf(1) / 3
        for exponent in (3, 6, 9, 12):
            big = mpmath.mpf(10) ** exponent
            ratio = mpmath.gammaprod([big + order], [big]) / big**order
            predicted = order * (1 - order) / (2 * big)
            assert abs((1 - ratio) / predicted - 1) < 1 / big * 10
