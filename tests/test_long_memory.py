"""Fractional integration/differencing (TIM 2014 eq. (3), SJ 2012 eq. (3) corrected, (6)) and the exact
local Whittle estimator."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import sympy as sp
from conftest import Z_MONTE_CARLO

from carousel_theory.long_memory import (
    autoregressive_coefficients,
    exact_local_whittle,
    fractional_difference,
    fractional_difference_coefficients,
    fractional_integral,
)
from carousel_theory.processes import fractional_coefficients


def _binomial_coefficients(order: Fraction, length: int) -> list[Fraction]:
    """Coefficients of (1 − z)^order by the generalised binomial theorem, exactly."""
    out = [Fraction(1)]
    for j in range(1, length):
        out.append(out[-1] * (j - 1 - order) / j)
    return out


@pytest.mark.parametrize("d", [Fraction(1, 2), Fraction(1, 3), Fraction(9, 10), Fraction(-1, 4)])
def test_difference_coefficients_are_gamma_ratios(d):
    # The Gamma ratio Γ(j − d)/(Γ(j + 1)Γ(−d)) evaluated by SymPy at 40 digits is the expected value.
    got = fractional_difference_coefficients(float(d), 12)
    for j in range(12):
        expected = sp.gamma(j - sp.Rational(d)) / (sp.gamma(j + 1) * sp.gamma(-sp.Rational(d)))
        assert got[j] == pytest.approx(float(sp.N(expected, 40)), rel=1e-14, abs=1e-300)


@pytest.mark.parametrize("d", [Fraction(1, 2), Fraction(1, 5), Fraction(4, 5)])
def test_difference_inverts_integration_exactly_in_fractions(d):
    # Σ_{k=0}^{m} φ_k ψ_{m−k} = δ_{m0}: (1 − z)^d (1 − z)^{−d} = 1, checked with exact Fractions.
    phi = _binomial_coefficients(d, 80)
    psi = _binomial_coefficients(-d, 80)
    for m in range(80):
        assert sum(phi[k] * psi[m - k] for k in range(m + 1)) == (1 if m == 0 else 0)
    # ... and the float arrays agree with the exact ones.
    assert np.allclose(fractional_difference_coefficients(float(d), 80), [float(x) for x in phi], rtol=1e-13)
    assert np.allclose(fractional_coefficients(float(d), 80), [float(x) for x in psi], rtol=1e-13)


@pytest.mark.parametrize("d", [0.5, 0.2, 0.9])
def test_autoregressive_weights_reproduce_the_impulse_response(d):
    # SJ 2012 eq. (6): f_t = Σ_{j=1}^{t−1} π_j f_{t−j} + w_t; for w = impulse, f = ψ.
    psi = fractional_coefficients(d, 200)
    pi = autoregressive_coefficients(d, 199)
    assert pi[0] == pytest.approx(d, rel=1e-15)
    for m in range(1, 200):
        assert psi[m] == pytest.approx(np.dot(pi[:m], psi[m - 1 :: -1]), rel=1e-12)
    assert np.all((pi > 0) & (pi < 1))


@pytest.mark.parametrize("length", [50, 700])  # direct sums and the FFT path
@pytest.mark.parametrize("d", [0.5, 0.35, 0.95])
def test_integral_matches_dense_matrix_and_difference_inverts_it(length, d):
    rng = np.random.default_rng(7)
    white = rng.standard_normal(length)
    psi = fractional_coefficients(d, length)
    index = np.arange(length)
    lower = np.where(index[:, None] >= index[None, :], psi[np.abs(index[:, None] - index[None, :])], 0.0)
    integrated = fractional_integral(white, d)
    np.testing.assert_allclose(integrated, lower @ white, rtol=1e-10, atol=1e-10)
    np.testing.assert_allclose(fractional_difference(integrated, d), white, rtol=1e-9, atol=1e-9)


def test_two_dimensional_input_filters_each_row():
    rng = np.random.default_rng(3)
    block = rng.standard_normal((3, 400))
    together = fractional_integral(block, 0.5)
    for row in range(3):
        np.testing.assert_allclose(
            together[row], fractional_integral(block[row], 0.5), rtol=1e-12, atol=1e-12
        )


@pytest.mark.parametrize("d", [0.3, 0.5, 0.7])
def test_exact_local_whittle_recovers_the_order(d):
    # Shimotsu–Phillips: √m (d̂ − d) → N(0, ¼) for the process started at t = 1, any d in (−½, 2).
    rng = np.random.default_rng(int(d * 100))
    series = 4.0 + fractional_integral(rng.standard_normal(8192), d)
    estimate = exact_local_whittle(series)
    assert estimate.frequencies == int(8192**0.65)
    assert abs(estimate.d - d) <= Z_MONTE_CARLO * estimate.standard_error


def test_exact_local_whittle_on_white_noise_is_near_zero():
    rng = np.random.default_rng(11)
    estimate = exact_local_whittle(rng.standard_normal(8192), frequencies=400)
    assert abs(estimate.d) <= Z_MONTE_CARLO * estimate.standard_error


INVALID = [
    ("difference_coefficients_d_high", lambda: fractional_difference_coefficients(2.0, 5), ValueError),
    ("difference_coefficients_length_zero", lambda: fractional_difference_coefficients(0.5, 0), ValueError),
    ("difference_coefficients_d_string", lambda: fractional_difference_coefficients("0.5", 5), TypeError),
    ("autoregressive_length_float", lambda: autoregressive_coefficients(0.5, 3.0), TypeError),
    ("integral_d_one", lambda: fractional_integral(np.ones(5), 1.0), ValueError),
    ("integral_d_nan", lambda: fractional_integral(np.ones(5), float("nan")), ValueError),
    ("integral_nan_data", lambda: fractional_integral(np.array([1.0, np.nan]), 0.5), ValueError),
    ("integral_three_dimensional", lambda: fractional_integral(np.ones((2, 2, 2)), 0.5), ValueError),
    ("difference_inf_data", lambda: fractional_difference(np.array([1.0, np.inf]), 0.5), ValueError),
    ("whittle_too_short", lambda: exact_local_whittle(np.ones(8)), ValueError),
    (
        "whittle_too_many_frequencies",
        lambda: exact_local_whittle(np.arange(100.0), frequencies=60),
        ValueError,
    ),
    ("whittle_bounds_reversed", lambda: exact_local_whittle(np.arange(100.0), bounds=(1.0, 0.0)), ValueError),
]


@pytest.mark.parametrize(("call", "error"), [(c, e) for _, c, e in INVALID], ids=[i for i, _, _ in INVALID])
def test_invalid_arguments_are_refused(call, error):
    with pytest.raises(error):
        call()
