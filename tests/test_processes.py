"""Error processes of TIM 2014 §II: coefficients, exact covariances, samplers."""

from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import numpy as np
import pytest
import sympy as sp
from conftest import Z_MONTE_CARLO, functions_called_in, public_functions
from hypothesis import example, given
from hypothesis import strategies as st

from carousel_theory import processes
from carousel_theory.processes import (
    bias_covariance,
    covariance_matrix,
    flicker_covariance,
    fractional_coefficients,
    fractional_coefficients_exact,
    fractionally_integrate,
    rate_random_walk_covariance,
    sample_bias,
    sample_flicker,
    sample_rate_random_walk,
    sample_white,
    white_covariance,
)


def gamma_ratio(d: sp.Rational, j: int) -> sp.Rational:
    """ψ_j of TIM 2014 eq. (3) straight from its Gamma form, simplified to a rational by SymPy."""
    value = sp.gammasimp(sp.gamma(j + d) / (sp.gamma(j + 1) * sp.gamma(d)))
    assert value.is_Rational
    return value


def dense_transfer_exact(d: Fraction, size: int) -> list[list[Fraction]]:
    """F of TIM 2014 §III-D: F[t][i] = ψ_{t−i} for i ≤ t, built entry by entry from the Gamma form."""
    psi = [
        Fraction(int(v.p), int(v.q))
        for v in (gamma_ratio(sp.Rational(d.numerator, d.denominator), j) for j in range(size))
    ]
    return [[psi[t - i] if i <= t else Fraction(0) for i in range(size)] for t in range(size)]


# --- coefficients ---------------------------------------------------------------------------------


@pytest.mark.parametrize("d", [Fraction(1, 2), Fraction(1, 3), Fraction(7, 8)], ids=str)
def test_exact_coefficients_equal_the_gamma_form(d):
    expected = [gamma_ratio(sp.Rational(d.numerator, d.denominator), j) for j in range(25)]
    got = fractional_coefficients_exact(d, 25)
    assert [sp.Rational(v.numerator, v.denominator) for v in got] == expected
    floats = fractional_coefficients(d, 25)
    assert np.allclose(floats, [float(v) for v in got], rtol=4e-16 * 25, atol=0)


def test_coefficients_stable_up_to_ten_million():
    """ψ_j by recursion against the Gamma form at 30 digits, at j up to 10⁷ (TIM 2014 eq. (3))."""
    length = 10**7
    psi = fractional_coefficients(0.5, length)
    assert np.all(np.isfinite(psi)) and np.all(np.diff(psi[:1000]) < 0)
    with mpmath.workdps(30):
        for j in (10, 1000, 10**5, 10**6, length - 1):
            exact = mpmath.gammaprod([j + mpmath.mpf(1) / 2], [j + 1, mpmath.mpf(1) / 2])
            # cumprod over j factors: the rounding error grows at most like j ulps
            assert abs(psi[j] / float(exact) - 1) <= j * 2.3e-16


# --- exact covariances ----------------------------------------------------------------------------


@pytest.mark.parametrize("d", [Fraction(1, 2), Fraction(1, 3)], ids=str)
def test_flicker_covariance_equals_dense_product(d):
    size = 9
    F = dense_transfer_exact(d, size)
    for s in range(1, size + 1):
        for t in range(1, size + 1):
            expected = sum((F[s - 1][i] * F[t - 1][i] for i in range(size)), Fraction(0))
            assert flicker_covariance(s, t, d) == expected
            assert flicker_covariance(s, t, d, variance=Fraction(3, 7)) == expected * Fraction(3, 7)
    matrix = covariance_matrix("flicker", size, d=float(d))
    expected_matrix = np.array(
        [[float(flicker_covariance(s, t, d)) for t in range(1, 10)] for s in range(1, 10)]
    )
    assert np.allclose(matrix, expected_matrix, rtol=1e-14, atol=0)


def test_rate_random_walk_covariance_equals_cumulative_sum_product():
    """cov(r) = R Rᵀ with R the lower-triangular cumulative-sum matrix of TIM 2014 eq. (10)."""
    size = 8
    R = [[Fraction(int(i <= t)) for i in range(size)] for t in range(size)]
    for s in range(1, size + 1):
        for t in range(1, size + 1):
            expected = sum((R[s - 1][i] * R[t - 1][i] for i in range(size)), Fraction(0))
            assert rate_random_walk_covariance(s, t) == expected
            assert rate_random_walk_covariance(s, t, variance=Fraction(1, 3)) == expected / 3
    np.testing.assert_array_equal(covariance_matrix("rrw", size), np.array(R, float) @ np.array(R, float).T)


def test_white_and_bias_covariances():
    assert white_covariance(3, 3, Fraction(2, 5)) == Fraction(2, 5)
    assert white_covariance(3, 4) == 0
    assert bias_covariance(1, 9, Fraction(2, 5)) == Fraction(2, 5)
    np.testing.assert_array_equal(covariance_matrix("white", 4, variance=2.0), 2.0 * np.eye(4))
    np.testing.assert_array_equal(covariance_matrix("bias", 3, variance=0.5), np.full((3, 3), 0.5))
    assert isinstance(white_covariance(2, 2, 0.5), float)


def test_float_order_gives_float_covariance():
    value = flicker_covariance(5, 3, 0.5)
    assert isinstance(value, float)
    assert value == pytest.approx(float(flicker_covariance(5, 3, Fraction(1, 2))), rel=1e-15)


# --- samplers -------------------------------------------------------------------------------------


def eq3_loop(innovations: np.ndarray, d: float) -> np.ndarray:
    """TIM 2014 eq. (3) written out: f_t = Σ_{i=1}^{t} Γ(t−i+d) / (Γ(t−i+1) Γ(d)) w_i.

    Log-Gamma keeps the weights finite for large t."""
    n = innovations.shape[0]
    out = np.zeros(n)
    for t in range(1, n + 1):
        total = 0.0
        for i in range(1, t + 1):
            weight = math.exp(math.lgamma(t - i + d) - math.lgamma(t - i + 1) - math.lgamma(d))
            total += weight * innovations[i - 1]
        out[t - 1] = total
    return out


@pytest.mark.parametrize("d", [0.5, 0.2, 0.9])
def test_same_noise_as_a_loop_of_eq3(d):
    """Identical innovations through the FFT sampler and through the literal sum of eq. (3)."""
    innovations = np.random.default_rng(20140702).standard_normal(300)
    expected = eq3_loop(innovations, d)
    got = fractionally_integrate(innovations, d)
    assert np.max(np.abs(got - expected)) <= 1e-12 * np.max(np.abs(expected))
    rows = np.vstack([innovations, -2.0 * innovations])
    both = fractionally_integrate(rows, d)
    assert np.allclose(both[1], -2.0 * got, rtol=0, atol=1e-12)


def test_samplers_draw_in_the_documented_order():
    seed = 5
    w = np.random.default_rng(seed).standard_normal((3, 50))
    np.testing.assert_array_equal(sample_white(50, rng=np.random.default_rng(seed), realisations=3), w)
    np.testing.assert_allclose(
        sample_rate_random_walk(50, rng=np.random.default_rng(seed), variance=4.0, realisations=3),
        np.cumsum(2.0 * w, axis=1),
    )
    np.testing.assert_array_equal(
        sample_flicker(50, rng=np.random.default_rng(seed), d=0.3, variance=4.0, realisations=3),
        fractionally_integrate(2.0 * w, 0.3),
    )
    bias = sample_bias(7, rng=np.random.default_rng(seed), realisations=3)
    assert bias.shape == (3, 7) and np.all(bias == bias[:, :1])
    assert sample_flicker(11, rng=np.random.default_rng(1), d=0.5).shape == (11,)


@pytest.mark.parametrize(
    ("process", "sampler", "time"),
    [
        ("white", lambda n, rng, r: sample_white(n, rng=rng, realisations=r), 40),
        ("rrw", lambda n, rng, r: sample_rate_random_walk(n, rng=rng, realisations=r), 40),
        ("flicker", lambda n, rng, r: sample_flicker(n, rng=rng, d=0.5, realisations=r), 40),
        ("bias", lambda n, rng, r: sample_bias(n, rng=rng, realisations=r), 40),
    ],
    ids=["white", "rrw", "flicker", "bias"],
)
def test_sampler_variance_monte_carlo(process, sampler, time):
    """Var(x_t) of 120 000 seeded realisations against the exact covariance (Gaussian: SE = σ² √(2/n))."""
    realisations = 120_000
    x = sampler(time, np.random.default_rng(1981), realisations)[:, time - 1]
    theory = float(covariance_matrix(process, time, d=0.5 if process == "flicker" else None)[-1, -1])
    standard_error = theory * math.sqrt(2 / realisations)
    assert 0.02 * theory > Z_MONTE_CARLO * standard_error  # a 2 % error would be detected
    assert abs(np.mean(x * x) - theory) <= Z_MONTE_CARLO * standard_error


@given(d=st.fractions(min_value=Fraction(1, 1000), max_value=Fraction(999, 1000)), j=st.integers(1, 60))
@example(d=Fraction(1, 2), j=1)
@example(d=Fraction(1, 10**6), j=60)
def test_coefficients_decrease_and_stay_positive(d, j):
    """0 < ψ_j < ψ_{j−1} for 0 < d < 1: each recursion factor (j − 1 + d)/j lies in (0, 1)."""
    psi = fractional_coefficients_exact(d, j + 1)
    assert 0 < psi[j] < psi[j - 1]


# --- bad input ------------------------------------------------------------------------------------

RNG = np.random.default_rng(0)

INVALID_CALLS = [
    ("coefficients d=0", lambda: fractional_coefficients(0, 5), ValueError, "0 < d < 1"),
    ("coefficients length=0", lambda: fractional_coefficients(0.5, 0), ValueError, "length=0"),
    (
        "exact coefficients float d",
        lambda: fractional_coefficients_exact(0.5, 3),
        TypeError,
        "exact rational",
    ),
    (
        "exact coefficients d=1",
        lambda: fractional_coefficients_exact(Fraction(1), 3),
        ValueError,
        "0 < d < 1",
    ),
    ("integrate nan", lambda: fractionally_integrate([1.0, float("nan")], 0.5), ValueError, "index 1"),
    ("integrate 3-D", lambda: fractionally_integrate(np.zeros((2, 2, 2)), 0.5), ValueError, "shape"),
    ("integrate d nan", lambda: fractionally_integrate([1.0], float("nan")), ValueError, "NaN"),
    ("bias s=0", lambda: bias_covariance(0, 1), ValueError, "s=0"),
    ("white t float", lambda: white_covariance(1, 2.0), TypeError, "t=2.0"),
    ("rrw variance<0", lambda: rate_random_walk_covariance(1, 1, -1), ValueError, "variance=-1"),
    ("flicker d=1.5", lambda: flicker_covariance(1, 1, 1.5), ValueError, "0 < d < 1"),
    ("matrix unknown", lambda: covariance_matrix("pink", 3), ValueError, "process='pink'"),
    ("matrix not str", lambda: covariance_matrix(3, 3), TypeError, "process=3"),
    ("matrix flicker no d", lambda: covariance_matrix("flicker", 3), ValueError, "d=None"),
    ("matrix rrw with d", lambda: covariance_matrix("rrw", 3, d=0.5), ValueError, "d=0.5"),
    ("matrix size=0", lambda: covariance_matrix("white", 0), ValueError, "size=0"),
    ("bias rng missing", lambda: sample_bias(3, rng=None), TypeError, "numpy.random.Generator"),
    ("white legacy rng", lambda: sample_white(3, rng=np.random.RandomState(0)), TypeError, "Generator"),
    ("white realisations=0", lambda: sample_white(3, rng=RNG, realisations=0), ValueError, "realisations=0"),
    ("rrw size=-1", lambda: sample_rate_random_walk(-1, rng=RNG), ValueError, "size=-1"),
    ("flicker d=0", lambda: sample_flicker(3, rng=RNG, d=0), ValueError, "0 < d < 1"),
    (
        "flicker variance nan",
        lambda: sample_flicker(3, rng=RNG, d=0.5, variance=float("nan")),
        ValueError,
        "NaN",
    ),
]


@pytest.mark.parametrize(
    ("call", "error", "fragment"), [c[1:] for c in INVALID_CALLS], ids=[c[0] for c in INVALID_CALLS]
)
def test_invalid_calls(call, error, fragment):
    with pytest.raises(error) as excinfo:
        call()
    assert fragment in str(excinfo.value)


def test_every_public_function_is_exported_and_covered_by_the_invalid_call_table():
    public = public_functions(processes)
    assert public == set(processes.__all__) - {"PROCESSES"}
    assert public <= functions_called_in(INVALID_CALLS)
