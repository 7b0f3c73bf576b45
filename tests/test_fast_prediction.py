"""The fast predictor equals the growing-state Kalman filter of SJ 2012 §IV-A, and both equal a
dense generalised-least-squares predictor written out here."""

from __future__ import annotations

import math

import numpy as np
import pytest

from carousel_theory.fast_prediction import Forecast, fast_kalman_forecast, fractional_covariance_rows
from carousel_theory.long_memory import fractional_integral
from carousel_theory.prediction import kalman_forecast
from carousel_theory.processes import fractional_coefficients


def _dense_gls_forecast(y, horizon, d, sigma2_w, sigma2_v, bias_mean, bias_variance):
    """Gaussian conditioning of (b + f_{n+k}) on y with covariance built from the explicit matrix Ψ."""
    n = y.shape[0]
    total = n + horizon
    psi = fractional_coefficients(d, total)
    index = np.arange(total)
    lag = index[:, None] - index[None, :]
    mixing = np.where(lag >= 0, psi[np.clip(lag, 0, None)], 0.0)  # f = Ψ w
    gamma = sigma2_w * mixing @ mixing.T
    covariance = gamma[:n, :n] + sigma2_v * np.eye(n)
    cross = gamma[:n, n:]
    if math.isinf(bias_variance):  # BLUP with a GLS mean (Goldberger 1962)
        inverse = np.linalg.inv(covariance)
        ones = np.ones(n)
        s = ones @ inverse @ ones
        bias = ones @ inverse @ y / s
        q = cross.T @ inverse @ ones
        mean = bias + cross.T @ inverse @ (y - bias)
        variance = np.diag(gamma[n:, n:]) - np.einsum("ik,ij,jk->k", cross, inverse, cross) + (1 - q) ** 2 / s
        return mean, variance
    total_covariance = covariance + bias_variance
    target = cross + bias_variance
    solved = np.linalg.solve(total_covariance, target)
    mean = bias_mean + solved.T @ (y - bias_mean)
    variance = np.diag(gamma[n:, n:]) + bias_variance - np.einsum("ik,ik->k", target, solved)
    return mean, variance


CASES = [
    # (n, h, d, σ_w², σ_v², bias mean, bias variance)
    (120, 80, 0.5, 1.0, 0.0, None, math.inf),
    (120, 80, 0.5, 2.0, 0.0, 0.4, 0.0),
    (90, 150, 0.3, 1.0, 0.0, -1.0, 3.0),
    (100, 60, 0.5, 1.0, 0.5, None, math.inf),
    (70, 70, 0.8, 0.3, 2.0, 0.2, 0.0),
    (60, 90, 0.15, 1.5, 0.1, 1.0, 10.0),
]


@pytest.mark.parametrize(
    ("n", "h", "d", "sigma2_w", "sigma2_v", "bias_mean", "bias_variance"),
    CASES,
    ids=[f"n{c[0]}-h{c[1]}-d{c[2]}-sv{c[4]}-P{c[6]}" for c in CASES],
)
def test_fast_forecast_equals_kalman_filter_and_dense_gls(
    n, h, d, sigma2_w, sigma2_v, bias_mean, bias_variance
):
    rng = np.random.default_rng(n + h)
    y = 2.5 + fractional_integral(rng.standard_normal(n) * math.sqrt(sigma2_w), d)
    y = y + rng.standard_normal(n) * math.sqrt(sigma2_v)
    options = {
        "d": d,
        "driving_variance": sigma2_w,
        "white_variance": sigma2_v,
        "bias_mean": bias_mean,
        "bias_variance": bias_variance,
    }
    fast = fast_kalman_forecast(y, h, **options)
    kalman = kalman_forecast(y, h, **options)
    dense_mean, dense_variance = _dense_gls_forecast(y, h, d, sigma2_w, sigma2_v, bias_mean, bias_variance)
    scale = max(1.0, float(np.abs(kalman.mean).max()))
    assert np.abs(fast.mean - kalman.mean).max() <= 1e-9 * scale
    assert np.abs(fast.bias_variance - kalman.bias_variance).max() <= 1e-9 * float(kalman.bias_variance.max())
    assert np.abs(fast.mean - dense_mean).max() <= 1e-8 * scale
    assert np.abs(fast.bias_variance - dense_variance).max() <= 1e-8 * float(dense_variance.max())
    np.testing.assert_allclose(fast.observation_variance, fast.bias_variance + sigma2_v, rtol=1e-15)


@pytest.mark.slow
def test_fast_forecast_equals_kalman_filter_at_table1_size():
    rng = np.random.default_rng(2012)
    y = fractional_integral(rng.standard_normal(1000), 0.5)
    fast = fast_kalman_forecast(y, 1000)
    kalman = kalman_forecast(y, 1000)
    assert np.abs(fast.mean - kalman.mean).max() <= 1e-9
    assert np.abs(fast.bias_variance - kalman.bias_variance).max() <= 1e-9


def test_without_white_noise_and_known_bias_the_forecast_error_variance_is_the_psi_sum():
    # Known b, σ_v = 0: the past w are recovered exactly, so Var = σ_w² Σ_{j<k} ψ_j².
    y = np.linspace(-1.0, 1.0, 50)
    forecast = fast_kalman_forecast(y, 30, d=0.5, driving_variance=2.0, bias_mean=0.0, bias_variance=0.0)
    np.testing.assert_allclose(forecast.bias_variance, 2.0 * np.cumsum(fractional_coefficients(0.5, 30) ** 2))


def test_constant_data_forecast_the_constant_with_a_diffuse_bias():
    for white in (0.0, 0.3):
        forecast = fast_kalman_forecast(np.full(40, 7.25), 25, white_variance=white)
        np.testing.assert_allclose(forecast.mean, 7.25, rtol=1e-12)


def test_batch_rows_equal_single_forecasts():
    rng = np.random.default_rng(5)
    block = rng.standard_normal((4, 64))
    for white in (0.0, 0.7):
        together = fast_kalman_forecast(block, 20, white_variance=white, d=0.4)
        for row in range(4):
            alone = fast_kalman_forecast(block[row], 20, white_variance=white, d=0.4)
            np.testing.assert_allclose(together.mean[row], alone.mean, rtol=1e-12, atol=1e-12)
            np.testing.assert_allclose(together.bias_variance[row], alone.bias_variance, rtol=1e-12)


def test_covariance_rows_equal_dense_product():
    d = 0.45
    psi = fractional_coefficients(d, 40)
    index = np.arange(40)
    lag = index[:, None] - index[None, :]
    mixing = np.where(lag >= 0, psi[np.clip(lag, 0, None)], 0.0)
    np.testing.assert_allclose(fractional_covariance_rows(d, 25, 40), (mixing @ mixing.T)[:25], rtol=1e-13)


def test_interval_is_two_sigma_of_the_observation():
    forecast = Forecast(np.array([1.0, 2.0]), np.array([1.0, 4.0]), np.array([4.0, 9.0]))
    low, high = forecast.interval()
    np.testing.assert_array_equal(low, [-3.0, -4.0])
    np.testing.assert_array_equal(high, [5.0, 8.0])


INVALID = [
    ("calibration_one_sample", lambda: fast_kalman_forecast(np.ones(1), 3), ValueError),
    ("calibration_nan", lambda: fast_kalman_forecast(np.array([1.0, np.nan, 2.0]), 3), ValueError),
    ("calibration_inf", lambda: fast_kalman_forecast(np.array([1.0, np.inf]), 3), ValueError),
    ("calibration_3d", lambda: fast_kalman_forecast(np.ones((2, 2, 2)), 3), ValueError),
    ("horizon_zero", lambda: fast_kalman_forecast(np.ones(5), 0), ValueError),
    ("horizon_float", lambda: fast_kalman_forecast(np.ones(5), 2.0), TypeError),
    ("d_half_open_upper", lambda: fast_kalman_forecast(np.ones(5), 2, d=1.0), ValueError),
    ("d_zero", lambda: fast_kalman_forecast(np.ones(5), 2, d=0.0), ValueError),
    ("driving_variance_zero", lambda: fast_kalman_forecast(np.ones(5), 2, driving_variance=0.0), ValueError),
    ("white_variance_negative", lambda: fast_kalman_forecast(np.ones(5), 2, white_variance=-1.0), ValueError),
    (
        "bias_variance_negative",
        lambda: fast_kalman_forecast(np.ones(5), 2, bias_mean=0.0, bias_variance=-1.0),
        ValueError,
    ),
    ("bias_mean_missing", lambda: fast_kalman_forecast(np.ones(5), 2, bias_variance=1.0), ValueError),
    ("kalman_two_dimensional", lambda: kalman_forecast(np.ones((2, 5)), 2), ValueError),
    ("kalman_one_sample", lambda: kalman_forecast(np.ones(1), 2), ValueError),
    ("covariance_rows_zero", lambda: fractional_covariance_rows(0.5, 0, 3), ValueError),
    (
        "interval_width_negative",
        lambda: Forecast(np.ones(1), np.ones(1), np.ones(1)).interval(-1.0),
        ValueError,
    ),
]


@pytest.mark.parametrize(("call", "error"), [(c, e) for _, c, e in INVALID], ids=[i for i, _, _ in INVALID])
def test_invalid_arguments_are_refused(call, error):
    with pytest.raises(error):
        call()
