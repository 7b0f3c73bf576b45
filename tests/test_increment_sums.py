"""Fourth sums of increment autocovariances: the telescoping identity proved in SymPy, the numeric
evaluator held to 1e-12 relative against 50-digit mpmath and against brute-force sums of γ_z, the finite
(AR) fourth sum against exact Fractions.

The even asymptotic series of the Gamma ratio (its coefficients against SymPy's own expansion, its
values against mpmath) and the power-sum evaluation of Σ (Γ(j + d)/Γ(j))² against 40-digit sums over
every j.

Stated tolerance of the 1/f Allan variance evaluator: 1e-12 relative for every 0 < d < 1 (including
d = ½ and its neighbourhood, where the closed form has a removable singularity) and m up to 10⁷.
"""

from __future__ import annotations

from fractions import Fraction

import mpmath
import numpy as np
import pytest
import sympy as sp
from hypothesis import example, given
from hypothesis import strategies as st
from scipy import special

from carousel_theory import symbols
from carousel_theory.increment_sums import (
    _SERIES_TERMS,
    FLICKER_FOURTH_SUM,
    FLICKER_INCREMENT_AUTOCOVARIANCE,
    LOG_RATIO_COEFFICIENTS,
    LOG_RATIO_SLOPES,
    SQUARE_SUM_HEAD,
    _polygamma_rows,
    allan_variance_from_fourth_sum,
    finite_fourth_sum,
    flicker_allan_variance_closed,
    flicker_fourth_sum,
    log_ratio_coefficient,
    rising_factorial,
    squared_rising_factorial_sum,
)
from carousel_theory.noise_model import increment_autocovariance

_x = next(s for s in FLICKER_FOURTH_SUM.free_symbols if s.name == "x")
_d = symbols.d
TOLERANCE = 1e-12


def test_fourth_backward_difference_of_the_fourth_sum_is_the_increment_autocovariance():
    # ∇⁴H(x)/γ_z(x) is a ratio of rising factorials of integer length: a rational function, exactly 1.
    ratio = sum(
        c * sp.combsimp(FLICKER_FOURTH_SUM.subs(_x, _x - k) / FLICKER_INCREMENT_AUTOCOVARIANCE)
        for k, c in enumerate((1, -4, 6, -4, 1))
    )
    assert sp.simplify(ratio - 1) == 0


def test_the_gamma_ratio_telescopes():
    # F_e(y) = Γ(y + e)/Γ(y + 1 − e): F_{e+½}(y + ½) − F_{e+½}(y − ½) = 2e F_e(y).
    e, y = sp.symbols("e y")

    def ratio(order, argument):
        return sp.gamma(argument + order) / sp.gamma(argument + 1 - order)

    half = sp.Rational(1, 2)
    step = ratio(e + half, y + half) - ratio(e + half, y - half)
    assert sp.simplify(sp.combsimp(step / ratio(e, y)) - 2 * e) == 0


@pytest.mark.parametrize("d", [sp.Rational(1, 10), sp.Rational(1, 2), sp.Rational(7, 9)])
def test_closed_form_autocovariance_is_the_product_of_the_noise_model(d):
    # Γ(3−2d)/Γ(2−d)² Π_{j≤k} (j−2+d)/(j+1−d) (noise_model's definition) at 50 digits, also at negative k.
    with mpmath.workdps(50):
        start = mpmath.gamma(3 - 2 * mpmath.mpf(d)) / mpmath.gamma(2 - mpmath.mpf(d)) ** 2
        product = start
        for k in range(12):
            if k:
                product *= (k - 2 + mpmath.mpf(d)) / (k + 1 - mpmath.mpf(d))
            for lag in (k, -k):
                value = FLICKER_INCREMENT_AUTOCOVARIANCE.subs({_x: lag, _d: d}).evalf(50)
                assert abs(value - product) <= mpmath.mpf(10) ** -45 * abs(product)
    numeric = increment_autocovariance("flicker", 12, float(d))
    assert float(product) == pytest.approx(numeric[-1], rel=1e-13)


def _allan_mpmath(d: mpmath.mpf, m: int) -> mpmath.mpf:
    """σ_A²(m) from the SymPy fourth sum at the working precision (the five positions of the module)."""
    rising = {"RisingFactorial": lambda a, step: mpmath.gamma(a + step) / mpmath.gamma(a)}
    expression = sp.lambdify((_x, _d), FLICKER_FOURTH_SUM, [rising, "mpmath"])
    values = [expression(mpmath.mpf(x), d) for x in (-2, m - 2, -m - 2, 2 * m - 2, -2 * m - 2)]
    return (6 * values[0] - 4 * (values[1] + values[2]) + values[3] + values[4]) / (2 * m * m)


def _allan_brute_force(d: mpmath.mpf, m: int) -> mpmath.mpf:
    """Var d/(2m²) = gᵀΓ_z g/(2m²), g the triangle 1 … m … 1, γ_z from the product definition."""
    gamma = [mpmath.gamma(3 - 2 * d) / mpmath.gamma(2 - d) ** 2]
    for k in range(1, 2 * m):
        gamma.append(gamma[-1] * (k - 2 + d) / (k + 1 - d))
    g = [min(k + 1, 2 * m - 1 - k) for k in range(2 * m - 1)]
    total = mpmath.fsum(g[a] * g[b] * gamma[abs(a - b)] for a in range(len(g)) for b in range(len(g)))
    return total / (2 * m * m)


@given(
    d=st.fractions(min_value=Fraction(1, 100), max_value=Fraction(99, 100)),
    m=st.integers(min_value=1, max_value=9),
)
@example(d=Fraction(1, 2), m=1)
@example(d=Fraction(1, 2), m=7)
@example(d=Fraction(1, 2) + Fraction(1, 10**9), m=5)
@example(d=Fraction(1, 2) - Fraction(1, 10), m=3)
@example(d=Fraction(1, 2) + Fraction(1, 10), m=3)
def test_closed_form_allan_variance_equals_brute_force_sums(d, m):
    with mpmath.workdps(50):
        exact = mpmath.mpf(d.numerator) / d.denominator
        brute = _allan_brute_force(exact, m)
        if d != Fraction(1, 2):  # the SymPy form has its removable singularity at d = ½
            assert abs(_allan_mpmath(exact, m) - brute) <= mpmath.mpf(10) ** -40 * brute
    value = flicker_allan_variance_closed(float(d), (m,))[0]
    assert abs(value - float(brute)) <= TOLERANCE * float(brute)


@pytest.mark.parametrize("dps", [30, 50])
@pytest.mark.parametrize("d", ["0.02", "0.3", "0.4999999", "0.5000001", "0.61", "0.98"])
def test_closed_form_allan_variance_at_large_m_against_mpmath(d, dps):
    sizes = (16, 1000, 4096, 8192, 123457, 3333333, 10_000_000)
    values = flicker_allan_variance_closed(float(d), sizes)
    with mpmath.workdps(dps):
        for m, value in zip(sizes, values, strict=True):
            exact = _allan_mpmath(mpmath.mpf(float(d)), m)
            assert abs(value - float(exact)) <= TOLERANCE * abs(float(exact))


@given(
    a=st.floats(min_value=1e-3, max_value=3e7, allow_nan=False),
    step=st.floats(min_value=1.0, max_value=3.0, allow_nan=False),
)
@example(a=16.0, step=2.0)
@example(a=8191.02, step=2.96)
def test_rising_factorial_to_a_few_ulps_of_its_logarithm(a, step):
    # exp of a logarithm of size ≈ step·log a ≤ 52: relative rounding ≤ 52 · 2⁻⁵³ ≈ 6e-15, times a few.
    with mpmath.workdps(50):
        exact = mpmath.rf(mpmath.mpf(a), mpmath.mpf(step))
        assert abs(mpmath.mpf(float(rising_factorial(a, step))) / exact - 1) <= 5e-14


@given(
    taps=st.lists(st.integers(min_value=-9, max_value=9), min_size=1, max_size=6),
    points=st.lists(st.integers(min_value=-40, max_value=400), min_size=1, max_size=8),
)
def test_finite_fourth_sum_against_exact_fractions(taps, points):
    gamma = np.array(taps, dtype=np.float64)
    values = finite_fourth_sum(gamma, points)
    reach = len(taps) - 1
    for x, value in zip(points, values, strict=True):
        exact = sum(
            Fraction(taps[abs(k)]) * Fraction((x - k + 1) * (x - k + 2) * (x - k + 3), 6)
            for k in range(-reach, reach + 1)
            if x - k >= -3
        )
        assert value == pytest.approx(float(exact), rel=1e-12, abs=1e-9)


def test_allan_variance_from_the_fourth_sum_of_white_and_rate_random_walk_taps():
    # White γ_z = (2, −1): σ_A² = 1/m; rate random walk γ_z = (1): (2m² + 1)/(6m). Exact integers.
    sizes = np.array([1, 2, 3, 10, 1000, 2**20])
    white = allan_variance_from_fourth_sum(lambda x: finite_fourth_sum(np.array([2.0, -1.0]), x), sizes)
    np.testing.assert_allclose(white * sizes, 1.0, rtol=1e-14)
    rrw = allan_variance_from_fourth_sum(lambda x: finite_fourth_sum(np.array([1.0]), x), sizes)
    np.testing.assert_allclose(rrw, (2.0 * sizes**2 + 1) / (6.0 * sizes), rtol=1e-14)


def test_log_ratio_coefficients_are_the_asymptotic_series_of_the_gamma_ratio():
    # log Γ(w + (1+s)/2) − log Γ(w + (1−s)/2) − s log w, expanded by SymPy at w = ∞ (an independent
    # route through the Stirling series of each log Γ), has only even powers, with the coefficients e_k.
    s, u = sp.Symbol("s", positive=True), sp.Symbol("u", positive=True)  # u = 1/w
    difference = sp.loggamma(1 / u + (1 + s) / 2) - sp.loggamma(1 / u + (1 - s) / 2) + s * sp.log(u)
    series = sp.series(difference, u, 0, 9).removeO()
    for k, coefficient in enumerate(LOG_RATIO_COEFFICIENTS[:4], start=1):
        assert sp.simplify(series.coeff(u, 2 * k) - coefficient) == 0  # the same symbol s
        assert sp.simplify(series.coeff(u, 2 * k - 1)) == 0
    for coefficient, slope in zip(LOG_RATIO_COEFFICIENTS, LOG_RATIO_SLOPES, strict=True):
        symbol = next(iter(coefficient.free_symbols))
        assert sp.expand(coefficient - coefficient.subs(symbol, 2) - (symbol - 2) * slope) == 0


@pytest.mark.parametrize("dps", [30, 50])
@pytest.mark.parametrize("d", ["0.02", "0.3", "0.41", "0.4999999", "0.5", "0.5000001", "0.59", "0.98"])
def test_flicker_fourth_sum_at_large_arguments_against_mpmath(d, dps):
    # Beyond j = 16 the fourth sum comes from the even series; j not an integer (Gauss nodes), up to 10⁷.
    order = float(d)
    j = np.array([16.0, 16.5, 17.25, 31.75, 100.125, 1000.4, 12345.6, 3.3e6, 1.2e7])
    got = flicker_fourth_sum(j - 2.0, order)
    with mpmath.workdps(dps):
        dm, half = mpmath.mpf(d), mpmath.mpf(1) / 2
        scale = mpmath.gamma(3 - 2 * dm) / (mpmath.gamma(2 - dm) * mpmath.gamma(dm - 1))
        scale /= 16 * (dm - 1) * dm * (dm + half)
        for argument, value in zip(j.tolist(), got, strict=True):
            x = mpmath.mpf(argument)

            def ratio(e: mpmath.mpf, x: mpmath.mpf = x) -> mpmath.mpf:
                return mpmath.gamma(x + 1 + e) / mpmath.gamma(x - e)

            if abs(order - 0.5) > 0.1:
                exact = scale * ratio(dm) / (dm - half)
            elif dm == half:  # the removable singularity: the derivative in d
                exact = scale * mpmath.diff(ratio, half)
            else:  # the d = ½ quadratic j² − ¼ removed, as the evaluator does
                exact = scale * (ratio(dm) - (x * x - mpmath.mpf(1) / 4)) / (dm - half)
            assert abs(value - float(exact)) <= TOLERANCE * abs(float(exact))


@pytest.mark.parametrize("d", ["0.02", "0.25", "0.5", "0.5000001", "0.77", "0.98"])
@pytest.mark.parametrize(
    "count", [1, SQUARE_SUM_HEAD - 1, SQUARE_SUM_HEAD, SQUARE_SUM_HEAD + 1, 5_000, 250_001]
)
def test_squared_rising_factorial_sum_against_every_term_summed(d, count):
    # Reference: Σ_j (Γ(j + d)/Γ(j))² over every j, each term from mpmath at 40 digits (the product
    # recurrence F(j + 1) = F(j)(j + d)/j), summed exactly by fsum.
    got = squared_rising_factorial_sum(float(d), count)
    with mpmath.workdps(40):
        step = mpmath.mpf(float(d))
        term, terms = mpmath.gamma(1 + step), []
        for j in range(1, count + 1):
            terms.append(term * term)
            term *= (j + step) / j
        exact = mpmath.fsum(terms)
    assert abs(got - float(exact)) <= 1e-13 * float(exact)


@pytest.mark.parametrize(("k", "largest"), [(4, sp.Rational(1, 4)), (9, sp.Rational(98, 100))])
def test_first_omitted_coefficients_of_the_even_series_are_bounded(k, largest):
    # The truncation statement of the evaluator: |e_4(s)| ≤ ¼ and |e_9(s)| ≤ 0.98 for s = 1 + 2d ∈ [1, 3],
    # by the exact extrema of the polynomial (end points and real roots of its derivative).
    expression = log_ratio_coefficient(k)
    (s,) = expression.free_symbols
    coefficient = sp.Poly(expression, s)
    candidates = [sp.Integer(1), sp.Integer(3)]
    candidates += [root for root in sp.real_roots(coefficient.diff(s)) if 1 <= root <= 3]
    assert max(abs(coefficient.eval(point)).evalf(30) for point in candidates) <= largest


@pytest.mark.parametrize(
    "a", [[0.5, 1.5, 2.5, 7.5, 15.5, 0.5], [3.5], [0.75, 1.5, 9.25], [0.5 + k for k in range(16)]]
)
def test_polygamma_rows_kept_per_half_integer_are_the_one_call_values(a):
    """The near-½ series' ψ^{(r)}: kept per half-integer a (integer lags), or computed in one call
    otherwise; either way bit for bit the one broadcast call."""
    a = np.array(a)
    expected = special.polygamma(np.arange(_SERIES_TERMS)[:, None], a)
    for _ in range(2):  # computed, then from the kept columns
        assert np.array_equal(_polygamma_rows(a), expected)
