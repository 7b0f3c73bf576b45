"""The closed forms of TIM 2014 §III-A…C checked two ways.

1. Exactly, with no tolerance, against dense brute-force matrices for every N ≤ 12 and k ≤ 4:
   rational weights in ``fractions.Fraction``; trigonometric weights in the cyclotomic field
   Q(ζ), ζ = exp(2πi/(4N)), where sin(2πj/N), cos(2πj/N), sin(π/N) and i are all polynomials in ζ
   with rational coefficients and equality is equality of remainders modulo the cyclotomic
   polynomial Φ_{4N} (the minimal polynomial of ζ).
2. In mpmath at 50 and at 30 significant digits against direct O(N) summation for N up to 10⁴,
   and in float64 against O(N) numpy sums for N up to a few million (Hypothesis).
"""

from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import numpy as np
import pytest
import sympy as sp
from hypothesis import example, given, settings
from hypothesis import strategies as st

from carousel_theory import closed_forms as cf
from carousel_theory.symbols import N, a, alpha, b, k, m, rho, var_x, var_y

Z = sp.Symbol("z")
CSC = sp.Symbol("CSC")
COT = sp.Symbol("COT")


# ---------------------------------------------------------------------------------------------
# Exact arithmetic in Q(ζ_M), M = 4N
# ---------------------------------------------------------------------------------------------


class CyclotomicField:
    """Q(ζ), ζ = exp(2πi/M): elements are polynomials in z reduced modulo Φ_M(z)."""

    def __init__(self, order: int):
        self.order = order
        self.modulus = sp.Poly(sp.cyclotomic_poly(order, Z), Z, domain="QQ")

    def element(self, value) -> sp.Poly:
        return sp.Poly(value, Z, domain="QQ").rem(self.modulus)

    def power(self, exponent: int) -> sp.Poly:
        return self.element(Z ** (exponent % self.order))

    def mul(self, left: sp.Poly, right: sp.Poly) -> sp.Poly:
        return (left * right).rem(self.modulus)

    def inverse(self, value: sp.Poly) -> sp.Poly:
        return sp.Poly(sp.invert(value.as_expr(), self.modulus.as_expr(), Z), Z, domain="QQ").rem(
            self.modulus
        )

    def zero(self) -> sp.Poly:
        return self.element(0)


class CarouselField:
    """The carouseling weights of TIM 2014 eq. (13) for one N, exactly, in Q(ζ_{4N})."""

    def __init__(self, n: int):
        self.n = n
        self.field = F = CyclotomicField(4 * n)
        i_unit = F.power(n)  # ζ^N = exp(iπ/2) = i
        minus_half_i = F.mul(F.element(sp.Rational(-1, 2)), i_unit)  # 1/(2i)
        self.sine = []
        self.cosine = []
        for j in range(1, n + 1):
            plus, minus = F.power(4 * j), F.power(-4 * j)  # exp(±2πij/N)
            self.sine.append(F.mul(F.mul(plus - minus, minus_half_i), F.element(sp.Rational(1, n))))
            self.cosine.append(F.mul(plus + minus, F.element(sp.Rational(1, 2 * n))))
        sin_pi_over_n = F.mul(F.power(2) - F.power(-2), minus_half_i)  # sin(π/N)
        cos_pi_over_n = F.mul(F.power(2) + F.power(-2), F.element(sp.Rational(1, 2)))
        if n >= 2:  # sin(π/N) = 0 at N = 1, where no closed form uses csc or cot
            self.csc = F.inverse(sin_pi_over_n)
            self.cot = F.mul(cos_pi_over_n, self.csc)

    def value_of(self, expression: sp.Expr) -> sp.Poly:
        """A closed form at this N as a field element (csc(π/N), cot(π/N) mapped exactly)."""
        generic = expression.subs({sp.csc(sp.pi / N): CSC, sp.cot(sp.pi / N): COT}).subs(N, self.n)
        generic = sp.expand(generic)
        assert generic.free_symbols <= {CSC, COT}, generic
        F = self.field
        total = F.zero()
        for (p_csc, p_cot), coefficient in sp.Poly(generic, CSC, COT).terms():
            term = F.element(coefficient)
            for _ in range(p_csc):
                term = F.mul(term, self.csc)
            for _ in range(p_cot):
                term = F.mul(term, self.cot)
            total = total + term
        return total.rem(F.modulus)


def closed_form_at(expression: sp.Expr, n: int, field: CarouselField) -> sp.Poly:
    """A Piecewise closed form at N = n as a field element: pick the branch, then map it exactly."""
    while isinstance(expression, sp.Piecewise):
        expression = next(branch for branch, condition in expression.args if condition.subs(N, n) == sp.true)
    if not expression.has(sp.csc, sp.cot):
        return field.field.element(expression.subs(N, n))
    return field.value_of(expression)


def transposed_cumsum(vector, zero):
    """Rᵀ v for the lower-triangular ones matrix R of TIM 2014 eq. (10): entry t is Σ_{u ≥ t} v_u."""
    n = len(vector)
    result = []
    for t in range(n):
        total = zero
        for u in range(n):
            if u >= t:  # R[u, t] = 1 for u ≥ t, the dense matrix entry by entry
                total = total + vector[u]
        result.append(total)
    return result


def dot(left, right, field=None):
    if field is None:
        return sum((p * q for p, q in zip(left, right, strict=True)), Fraction(0))
    total = field.zero()
    for p, q in zip(left, right, strict=True):
        total = total + field.mul(p, q)
    return total.rem(field.modulus)


N_RANGE = range(1, 13)
K_MAX = 4

# ---------------------------------------------------------------------------------------------
# Rational brute force: bias, white averaging, RRW averaging
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("n", N_RANGE)
def test_rrw_average_covariance_equals_dense_matrices_exactly(n):
    length = K_MAX * n
    for first in range(1, K_MAX + 1):
        for second in range(1, K_MAX + 1):
            weights = []
            for bin_number in (first, second):
                w = [Fraction(0)] * length
                for i in range(n):
                    w[(bin_number - 1) * n + i] = Fraction(1, n)  # eq. (12) placed in bin `bin_number`
                weights.append(w)
            brute = dot(
                transposed_cumsum(weights[0], Fraction(0)), transposed_cumsum(weights[1], Fraction(0))
            )
            closed = cf.RRW_AVERAGE_COVARIANCE.subs({N: n, a: first, b: second})
            assert closed == sp.Rational(brute.numerator, brute.denominator)
            if first == second:
                assert cf.RRW_AVERAGE_VARIANCE.subs({N: n, k: first}) == closed


def test_rrw_average_matches_printed_eq15_matrix():
    # TIM 2014 eq. (15), last line, as printed
    printed_variance = (2 * N**3 + 3 * N**2 + N) / (6 * N**2)
    assert sp.simplify(cf.RRW_AVERAGE_COVARIANCE.subs({a: 1, b: 1}) - printed_variance) == 0
    assert sp.simplify(cf.RRW_AVERAGE_COVARIANCE.subs({a: 1, b: 2}) - (N + 1) / 2) == 0
    assert sp.simplify(cf.RRW_AVERAGE_COVARIANCE.subs({a: 2, b: 2}) - (printed_variance + N)) == 0


@pytest.mark.parametrize("n", N_RANGE)
def test_bias_and_white_closed_forms_equal_exact_sums(n):
    field = CarouselField(n)
    F = field.field
    assert closed_form_at(cf.BIAS_SINE_RESIDUAL, n, field) == sum(field.sine, F.zero()).rem(F.modulus)
    assert closed_form_at(cf.BIAS_COSINE_RESIDUAL, n, field) == sum(field.cosine, F.zero()).rem(F.modulus)
    ones = [F.element(1)] * n
    scale = F.element(n * n)  # the weights carry 1/N; the sums of squares do not
    assert F.mul(dot(field.sine, field.sine, F), scale) == closed_form_at(cf.SINE_SQUARES_SUM, n, field)
    assert F.mul(dot(field.cosine, field.cosine, F), scale) == closed_form_at(cf.COSINE_SQUARES_SUM, n, field)
    assert dot(ones, ones, F) == F.element(n)
    for variance_x, variance_y in [(1, 1), (Fraction(1, 3), 2), (0, 5)]:
        brute = F.element(variance_x) * dot(field.sine, field.sine, F) + F.element(variance_y) * dot(
            field.cosine, field.cosine, F
        )
        closed = cf.WHITE_CAROUSEL_VARIANCE.subs({var_x: variance_x, var_y: variance_y})
        assert closed_form_at(closed, n, field) == brute.rem(F.modulus)
    # equal variances: carouseling and averaging give the same 1/N for every N (TIM 2014 eq. (9))
    assert sp.simplify(cf.WHITE_CAROUSEL_VARIANCE.subs({var_x: 1, var_y: 1, N: n}) - sp.Rational(1, n)) == 0


# ---------------------------------------------------------------------------------------------
# Trigonometric brute force: carouselled RRW, every N ≤ 12, k ≤ 4, in Q(ζ_{4N})
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("n", N_RANGE)
def test_rrw_carousel_quadratic_forms_equal_dense_products_exactly(n):
    field = CarouselField(n)
    F = field.field
    sine_tail = transposed_cumsum(field.sine, F.zero())
    cosine_tail = transposed_cumsum(field.cosine, F.zero())
    sine = dot(sine_tail, sine_tail, F)
    cosine = dot(cosine_tail, cosine_tail, F)
    cross = dot(sine_tail, cosine_tail, F)
    assert closed_form_at(cf.RRW_CAROUSEL_SINE_VARIANCE, n, field) == sine
    assert closed_form_at(cf.RRW_CAROUSEL_COSINE_VARIANCE, n, field) == cosine
    assert closed_form_at(cf.RRW_CAROUSEL_VARIANCE, n, field) == (sine + cosine).rem(F.modulus)
    assert closed_form_at(cf.RRW_CAROUSEL_CROSS, n, field) == cross
    for correlation in (-1, sp.Rational(-1, 2), 0, sp.Rational(1, 3), 1):
        # Var(g) for g = (−Rᵀs, Rᵀc) and joint increment covariance [[I, ρI], [ρI, I]]
        stacked = [-t for t in sine_tail] + cosine_tail
        covariance_times_g = [
            stacked[t] + F.element(correlation) * stacked[(t + n) % (2 * n)] for t in range(2 * n)
        ]
        brute = dot(stacked, covariance_times_g, F)
        closed = cf.RRW_CAROUSEL_VARIANCE_CORRELATED.subs(rho, correlation)
        assert closed_form_at(closed, n, field) == brute


@pytest.mark.parametrize("n", N_RANGE)
def test_rrw_carousel_bin_covariances_equal_dense_R_k_exactly(n):
    """Every pair of bins of R_k (k = 4): the generalisation of TIM 2014 eq. (17) to k bins."""
    field = CarouselField(n)
    F = field.field
    length = K_MAX * n
    tails = {}
    for bin_number in range(1, K_MAX + 1):
        for name, weights in (("sine", field.sine), ("cosine", field.cosine)):
            vector = [F.zero()] * length
            vector[(bin_number - 1) * n : bin_number * n] = weights
            tails[name, bin_number] = transposed_cumsum(vector, F.zero())
    for first in range(1, K_MAX + 1):
        for second in range(1, K_MAX + 1):
            brute = (
                dot(tails["sine", first], tails["sine", second], F)
                + dot(tails["cosine", first], tails["cosine", second], F)
            ).rem(F.modulus)
            closed = cf.RRW_CAROUSEL_COVARIANCE.subs({a: first, b: second})
            assert closed_form_at(closed, n, field) == brute, (first, second)


# ---------------------------------------------------------------------------------------------
# The derivation reproduces the closed forms; the expansions have the paper's leading terms
# ---------------------------------------------------------------------------------------------


def test_derivation_reproduces_generic_closed_forms():
    derived = cf.derive_rrw_carousel_quadratic_forms()
    assert sp.simplify(derived["sine"] - cf.RRW_CAROUSEL_SINE_GENERIC) == 0
    assert sp.simplify(derived["cosine"] - cf.RRW_CAROUSEL_COSINE_GENERIC) == 0
    assert sp.simplify(derived["cross"] - cf.RRW_CAROUSEL_CROSS_GENERIC) == 0
    total = cf.RRW_CAROUSEL_SINE_GENERIC + cf.RRW_CAROUSEL_COSINE_GENERIC
    assert sp.simplify(total - cf.RRW_CAROUSEL_TOTAL_GENERIC) == 0


@pytest.mark.parametrize(
    ("expression", "expected"),
    [
        (cf.RRW_CAROUSEL_SINE_GENERIC, 3 * N / (8 * sp.pi**2) - 1 / (8 * N) + sp.pi**2 / (40 * N**3)),
        (
            cf.RRW_CAROUSEL_COSINE_GENERIC,
            N / (8 * sp.pi**2) + sp.Rational(7, 24) / N + sp.pi**2 / (120 * N**3),
        ),
        (cf.RRW_CAROUSEL_TOTAL_GENERIC, N / (2 * sp.pi**2) + 1 / (6 * N) + sp.pi**2 / (30 * N**3)),
        (cf.RRW_CAROUSEL_CROSS_GENERIC, -1 / (4 * sp.pi) + sp.pi / (12 * N**2)),
    ],
    ids=["sine", "cosine", "total", "cross"],
)
def test_expansions_in_inverse_N(expression, expected):
    # expected terms from the Laurent series csc²x = 1/x² + 1/3 + x²/15 + …, cot x = 1/x − x/3 − x³/45 …
    assert sp.simplify(cf.expansion_in_inverse_N(expression, order=4) - expected) == 0


def test_leading_coefficients_are_the_papers():
    assert cf.leading_coefficient(cf.RRW_CAROUSEL_SINE_GENERIC) == 3 / (8 * sp.pi**2)
    assert cf.leading_coefficient(cf.RRW_CAROUSEL_COSINE_GENERIC) == 1 / (8 * sp.pi**2)
    assert cf.leading_coefficient(cf.RRW_CAROUSEL_TOTAL_GENERIC) == 1 / (2 * sp.pi**2)
    assert cf.leading_coefficient(cf.RRW_AVERAGE_VARIANCE.subs(k, 2)) == sp.Rational(4, 3)


def test_sum_over_period_on_known_sums():
    # Σ_{m=0}^{N−1} cos²(α_m) = N/2 and Σ sin α_m cos α_m = 0, valid for N ≥ 3
    assert sp.simplify(cf.sum_over_period(sp.cos(alpha) ** 2) - N / 2) == 0
    assert cf.sum_over_period(sp.sin(alpha) * sp.cos(alpha)) == 0
    assert cf.sum_over_period(sp.Integer(7)) == 7 * N


# ---------------------------------------------------------------------------------------------
# High precision: mpmath at 50 and 30 digits against direct O(N) summation, N up to 10⁴
# ---------------------------------------------------------------------------------------------


def direct_quadratic_forms_mpmath(n: int):
    """sᵀRRᵀs, cᵀRRᵀc, sᵀRRᵀc by summing the tails (Rᵀs)_i = Σ_{j≥i} s_j, at the current precision."""
    sine_tail = cosine_tail = mpmath.mpf(0)
    sine = cosine = cross = mpmath.mpf(0)
    for j in range(n, 0, -1):
        angle = 2 * mpmath.pi * j / n
        sine_tail += mpmath.sin(angle) / n
        cosine_tail += mpmath.cos(angle) / n
        sine += sine_tail**2
        cosine += cosine_tail**2
        cross += sine_tail * cosine_tail
    return sine, cosine, cross


@pytest.mark.parametrize("digits", [50, 30])
@pytest.mark.parametrize("n", [3, 10, 97, 1000, 10_000])
def test_carousel_forms_at_high_precision(n, digits):
    guard = 10  # the direct sum of n terms loses at most log10(n) < 5 digits; 10 guard digits cover it
    with mpmath.workdps(digits + guard):
        direct = direct_quadratic_forms_mpmath(n)
    with mpmath.workdps(digits):
        for expression, reference in zip(
            (cf.RRW_CAROUSEL_SINE_VARIANCE, cf.RRW_CAROUSEL_COSINE_VARIANCE, cf.RRW_CAROUSEL_CROSS),
            direct,
            strict=True,
        ):
            value = sp.lambdify(N, expression, "mpmath")(n)
            assert abs(value - reference) <= mpmath.mpf(10) ** (2 - digits) * abs(reference)


# ---------------------------------------------------------------------------------------------
# Hypothesis: large N against O(N) float64 sums; bins a, b against O(kN) exact integer sums
# ---------------------------------------------------------------------------------------------

_numeric = {
    name: sp.lambdify(N, expression, "numpy")
    for name, expression in {
        "sine": cf.RRW_CAROUSEL_SINE_GENERIC,
        "cosine": cf.RRW_CAROUSEL_COSINE_GENERIC,
        "cross": cf.RRW_CAROUSEL_CROSS_GENERIC,
    }.items()
}


@settings(max_examples=6)
@given(st.integers(min_value=3, max_value=3_000_000))
@example(3).via("smallest generic N")
@example(4).via("quarter turns")
@example(1_000_000).via("N = 10⁶")
def test_carousel_forms_for_large_N_against_float_sums(n):
    angle = 2 * np.pi * np.arange(1, n + 1, dtype=np.float64) / n
    sine_tail = np.cumsum((np.sin(angle) / n)[::-1])[::-1]
    cosine_tail = np.cumsum((np.cos(angle) / n)[::-1])[::-1]
    # Rounding: each tail is a cumulative sum of ≤ 3·10⁶ terms of size ≤ 1/N, so its absolute
    # error is ≤ N·ε·(1/N)·N ≈ 3·10⁶ · 2.2·10⁻¹⁶ < 10⁻⁹ of a tail of size ~1/π; rtol 1e-7 is a
    # bound with a margin, far below the size of any wrong term (the first correction, 1/(8N)
    # against 3N/8π², is already 4·10⁻⁸ relative only at N ≈ 3000 and grows for smaller N).
    assert math.isclose(float(np.dot(sine_tail, sine_tail)), _numeric["sine"](n), rel_tol=1e-7)
    assert math.isclose(float(np.dot(cosine_tail, cosine_tail)), _numeric["cosine"](n), rel_tol=1e-7)
    assert math.isclose(
        float(np.dot(sine_tail, cosine_tail)), _numeric["cross"](n), rel_tol=1e-7, abs_tol=1e-9
    )


@given(
    n=st.integers(min_value=1, max_value=2000),
    first=st.integers(min_value=1, max_value=400),
    second=st.integers(min_value=1, max_value=400),
)
@example(n=1, first=1, second=1)
@example(n=2, first=1, second=2)
@example(n=3, first=3, second=3)
@example(n=4, first=4, second=1)
def test_rrw_average_covariance_for_any_bins(n, first, second):
    # N·(R_kᵀ w_a)_t is an integer vector: N before bin a, (aN − t + 1) inside it, 0 after (exact int64)
    length = max(first, second) * n
    t = np.arange(1, length + 1, dtype=np.int64)

    def scaled_tail(bin_number):
        tail = np.where(t <= (bin_number - 1) * n, n, bin_number * n - t + 1)
        return np.where(t <= bin_number * n, tail, 0)

    numerator = int(np.dot(scaled_tail(first), scaled_tail(second)))
    assert cf.RRW_AVERAGE_COVARIANCE.subs({N: n, a: first, b: second}) == sp.Rational(numerator, n * n)


_carousel_covariance = sp.lambdify((N, a, b), cf.RRW_CAROUSEL_COVARIANCE, "numpy")


@given(
    n=st.integers(min_value=1, max_value=300),
    first=st.integers(min_value=1, max_value=60),
    second=st.integers(min_value=1, max_value=60),
)
@example(n=1, first=2, second=5)
@example(n=2, first=3, second=3)
@example(n=3, first=1, second=2)
@example(n=4, first=4, second=4)
def test_rrw_carousel_covariance_for_any_bins(n, first, second):
    """Cov of carouselled bins a, b from the O(kN) tails R_kᵀw (sine plus cosine gyro) in float64."""
    angle = 2 * np.pi * np.arange(1, n + 1) / n
    length = max(first, second) * n

    def tails(bin_number, weights):
        vector = np.zeros(length)
        vector[(bin_number - 1) * n : bin_number * n] = weights
        return np.cumsum(vector[::-1])[::-1]

    brute = sum(
        float(np.dot(tails(first, weights), tails(second, weights)))
        for weights in (np.sin(angle) / n, np.cos(angle) / n)
    )
    # float64 sums of ≤ 18000 terms of size ≤ 1 (N = 1: terms up to 60): absolute error far below 1e-9
    assert math.isclose(brute, float(_carousel_covariance(n, first, second)), rel_tol=1e-9, abs_tol=1e-9)


# ---------------------------------------------------------------------------------------------
# Invalid calls of the public helpers (the registry's table is in test_formulas.py)
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("call", "error", "message"),
    [
        pytest.param(
            lambda: cf.rectangle_rule_steps("tangent"), ValueError, "weight=", id="rectangle-rule-weight"
        ),
        pytest.param(
            lambda: cf.sum_over_period(sp.tan(alpha)), ValueError, "polynomial", id="period-sum-not-poly"
        ),
        pytest.param(
            lambda: cf.expansion_in_inverse_N(cf.RRW_CAROUSEL_TOTAL_GENERIC, 0),
            ValueError,
            "order=",
            id="expansion-order-zero",
        ),
        pytest.param(
            lambda: cf.expansion_in_inverse_N(cf.RRW_CAROUSEL_TOTAL_GENERIC, 2.5),
            TypeError,
            "order=",
            id="expansion-order-float",
        ),
        pytest.param(
            lambda: cf.expansion_in_inverse_N("csc(pi/N)"), TypeError, "expression=", id="expansion-string"
        ),
        pytest.param(lambda: cf.leading_coefficient(None), TypeError, "expression=", id="leading-none"),
        pytest.param(
            lambda: cf.sum_over_period(sp.cos(alpha), angle="alpha"), TypeError, "angle=", id="period-angle"
        ),
        pytest.param(lambda: cf.geometric_partial_sum("m"), TypeError, "length=", id="geometric-string"),
        pytest.param(
            lambda: cf.sine_partial_sum(m, float("nan")), ValueError, "angle=nan", id="sine-partial-nan"
        ),
        pytest.param(lambda: cf.cosine_partial_sum(True), TypeError, "length=True", id="cosine-partial-bool"),
        pytest.param(
            lambda: cf.rrw_bin_covariance_from_weights(1, "M", 1),
            TypeError,
            "first_moment=",
            id="lemma-string",
        ),
    ],
)
def test_invalid_calls(call, error, message):
    with pytest.raises(error, match=message):
        call()


def test_all_is_honest():
    for name in cf.__all__:
        assert hasattr(cf, name), name
    defined_functions = {
        name
        for name, value in vars(cf).items()
        if callable(value) and getattr(value, "__module__", None) == cf.__name__ and not name.startswith("_")
    }
    constants = {name for name, value in vars(cf).items() if name.isupper() and len(name) > 1}
    assert defined_functions | constants == set(cf.__all__)
