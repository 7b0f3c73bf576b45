"""The AR coefficients' sampling error and its place in the fit's standard errors.

Bartlett's large-sample covariance of the sample autocovariance is held against the exact finite-n one
(Isserlis: Cov(γ̂(h), γ̂(k)) = n⁻² Σ_u N_hk(u) [γ(u) γ(u + k − h) + γ(u + k) γ(u − h)], N_hk(u) the number
of (t, s) with s − t = u), and the estimators' linearization dφ = G dγ̂ against central differences of the
estimators themselves. On seeded records the coefficient's standardized error and the fitted AR
variance's spread like a standard normal (bounds from the spread's own sampling error over the records:
the AR variance's spread was 1.9 at 10⁶ samples before its coefficient's error was carried into it).
"""

from __future__ import annotations

import numpy as np
import pytest

from carousel_theory.autoregression import (
    HIGH_ORDER,
    PLAIN,
    bartlett_covariance,
    coefficient_gradient,
    coefficients_from_autocovariance,
    short_noise_estimate,
)
from carousel_theory.fitting import fit_noise_model
from carousel_theory.noise_model import NoiseModel, ar_autocovariance
from carousel_theory.simulate import sample_noise


def _white_and_ar_autocovariance(lags: int, phi: float = 0.6, white: float = 2.0) -> np.ndarray:
    gamma = np.array(ar_autocovariance((phi,), lags + 1))
    gamma[0] += white
    return gamma


def _exact_finite_covariance(gamma: np.ndarray, n: int, h: int, k: int) -> float:
    """Isserlis' formula summed over every difference u = s − t of the two sums' indices."""
    u = np.arange(-n, n + 1)

    def at(lag: np.ndarray) -> np.ndarray:
        lag = np.abs(lag)
        out = np.zeros(lag.shape)
        inside = lag < len(gamma)
        out[inside] = gamma[lag[inside]]
        return out

    t_low = np.maximum(0, -u)
    t_high = np.minimum(n - h, n - k - u)  # t < n − h and t + u < n − k
    count = np.maximum(t_high - t_low, 0)
    return float(np.sum(count * (at(u) * at(u + k - h) + at(u + k) * at(u - h)))) / n**2


def test_bartlett_covariance_matches_the_exact_finite_sample_covariance():
    gamma = _white_and_ar_autocovariance(200)
    n, lags = 4000, 6
    bartlett = bartlett_covariance(gamma, lags, n)
    scale = float(np.sqrt(np.outer(np.diag(bartlett), np.diag(bartlett))).max())
    for h in range(lags + 1):
        for k in range(lags + 1):
            exact = _exact_finite_covariance(gamma, n, h, k)
            # The edge terms are O((h + k + correlation length)/n) of the whole: under 1 % here.
            assert bartlett[h, k] == pytest.approx(exact, abs=0.01 * scale)


def test_bartlett_covariance_of_white_noise_is_the_textbook_one():
    gamma = np.array([3.0])
    covariance = bartlett_covariance(gamma, 3, 100)
    # Var γ̂(0) = 2σ⁴/n, Var γ̂(k) = σ⁴/n for k ≥ 1, uncorrelated.
    assert np.allclose(covariance, np.diag([18.0, 9.0, 9.0, 9.0]) / 100, rtol=1e-15, atol=0)


@pytest.mark.parametrize(("estimator", "lags"), [(PLAIN, 4), (HIGH_ORDER, 24)])
def test_linearization_equals_central_differences_of_the_estimator(estimator, lags):
    def solve(gamma: np.ndarray) -> tuple[float, ...]:
        return coefficients_from_autocovariance(gamma, 10**12, estimator, 4)

    gamma = _white_and_ar_autocovariance(lags)
    coefficients = solve(gamma)
    assert len(coefficients) == (4 if estimator == PLAIN else 1)  # plain YW sees the sum: an ARMA
    gradient = coefficient_gradient(gamma, coefficients, estimator, 4)
    step = 1e-6 * gamma[0]
    for lag in range(lags + 1):
        up, down = gamma.copy(), gamma.copy()
        up[lag] += step
        down[lag] -= step
        numeric = (np.asarray(solve(up)) - np.asarray(solve(down))) / (2 * step)
        assert np.allclose(gradient[:, lag], numeric, rtol=1e-5, atol=1e-7 * np.abs(gradient).max())


def test_coefficient_standard_error_is_calibrated_on_seeded_records():
    model = NoiseModel(sample_rate=100.0, white_variance=3.6e-5, ar_variance=4e-6, ar_coefficients=(0.8,))
    rng = np.random.default_rng(31)
    z = []
    for _ in range(60):
        estimate = short_noise_estimate(sample_noise(model, 100_000, rng=rng), 100.0, 4)
        assert estimate.estimator == HIGH_ORDER and len(estimate.coefficients) == 1
        z.append((estimate.coefficients[0] - 0.8) / np.sqrt(estimate.covariance[0, 0]))
    # The spread of 60 standard normal values lies in [0.8, 1.25] with probability > 0.99.
    assert 0.8 <= float(np.std(z, ddof=1)) <= 1.25


def test_fitted_ar_variance_error_carries_the_coefficient_error():
    model = NoiseModel(sample_rate=100.0, white_variance=3.6e-5, ar_variance=4e-6, ar_coefficients=(0.8,))
    rng = np.random.default_rng(41)
    z, widened = [], []
    for _ in range(40):
        y = sample_noise(model, 200_000, rng=rng)
        fit = fit_noise_model(y, 100.0, ("white", "ar"))
        held = fit_noise_model(y, 100.0, ("white", "ar"), ar_coefficients=fit.model.ar_coefficients)
        widened.append(fit.standard_errors["ar_variance"] / held.standard_errors["ar_variance"])
        assert len(fit.ar_coefficient_errors) == 1 and fit.ar_coefficient_errors[0] > 0
        assert held.ar_coefficient_errors == ()
        z.append((fit.model.ar_variance - 4e-6) / fit.standard_errors["ar_variance"])
    assert min(widened) > 1.0
    # The spread of 40 standard normal values lies in [0.75, 1.3] with probability > 0.99.
    assert 0.75 <= float(np.std(z, ddof=1)) <= 1.3


def test_an_unknown_estimator_is_refused_by_name():
    gamma = _white_and_ar_autocovariance(24)
    with pytest.raises(ValueError, match="estimator='Burg'"):
        coefficients_from_autocovariance(gamma, 1000, "Burg", 4)
    with pytest.raises(ValueError, match="estimator='Burg'"):
        coefficient_gradient(gamma, (0.6,), "Burg", 4)
