"""The generalized Schur recursion for Σ = σ_w² L Lᵀ + σ_v² I against dense matrices and exact
determinants, and the conditional forecast against dense Gaussian conditioning."""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest

from carousel_theory.generalized_schur import conditional_forecast, whiten
from carousel_theory.processes import fractional_coefficients, fractional_coefficients_exact


def _dense_covariance(d: float, driving: float, white: float, length: int, observed: int) -> np.ndarray:
    """σ_w² L Lᵀ + σ_v² D over ``length`` samples, white noise on the first ``observed`` only."""
    psi = fractional_coefficients(d, length)
    index = np.arange(length)
    lag = index[:, None] - index[None, :]
    mixing = np.where(lag >= 0, psi[np.clip(lag, 0, None)], 0.0)
    covariance = driving * mixing @ mixing.T
    covariance[np.arange(observed), np.arange(observed)] += white
    return covariance


CASES = [
    (1, 1, 0.5, 1.0, 1.0),
    (2, 1, 0.5, 1.0, 1e-6),
    (37, 3, 0.25, 2.0, 0.3),
    (120, 2, 0.5, 1.0, 4.0),
    (150, 20, 0.75, 0.5, 1e3),  # more columns than the BLAS-per-column limit
    (200, 1, 0.9, 1.0, 1e-3),
]


@pytest.mark.parametrize(
    ("n", "m", "d", "driving", "white"), CASES, ids=[f"n{c[0]}-m{c[1]}-d{c[2]}" for c in CASES]
)
def test_whitened_vectors_and_log_determinant_equal_the_dense_cholesky(n, m, d, driving, white):
    rng = np.random.default_rng(n * 31 + m)
    right_hand_sides = rng.standard_normal((n, m)) * 3.0 + 1.0
    covariance = _dense_covariance(d, driving, white, n, n)
    factor = np.linalg.cholesky(covariance)
    expected = np.linalg.solve(factor, right_hand_sides)
    result = whiten(right_hand_sides, d=d, driving_variance=driving, white_variance=white)
    assert np.abs(result.whitened - expected).max() <= 1e-10 * max(1.0, float(np.abs(expected).max()))
    sign, log_determinant = np.linalg.slogdet(covariance)
    assert sign == 1.0
    assert result.log_determinant == pytest.approx(log_determinant, rel=1e-12, abs=1e-11)
    assert result.whitened.shape == right_hand_sides.shape


@pytest.mark.parametrize(("leaf", "quadratic_limit"), [(1, 0), (4, 0), (16, 40), (256, 4096)])
@pytest.mark.parametrize(("n", "m"), [(1, 1), (97, 2), (300, 20)])
def test_divide_and_conquer_gives_the_dense_factor_for_every_window_size(
    monkeypatch, leaf, quadratic_limit, n, m
):
    import carousel_theory.generalized_schur as module

    monkeypatch.setattr(module, "_LEAF", leaf)
    monkeypatch.setattr(module, "_QUADRATIC_LIMIT", quadratic_limit)
    rng = np.random.default_rng(leaf + n)
    right_hand_sides = rng.standard_normal((n, m)) + 5.0
    covariance = _dense_covariance(0.5, 1.0, 2.0, n, n)
    expected = np.linalg.solve(np.linalg.cholesky(covariance), right_hand_sides)
    result = whiten(right_hand_sides, d=0.5, driving_variance=1.0, white_variance=2.0)
    assert np.abs(result.whitened - expected).max() <= 1e-10 * max(1.0, float(np.abs(expected).max()))
    assert result.log_determinant == pytest.approx(np.linalg.slogdet(covariance)[1], rel=1e-12, abs=1e-11)
    forecast = conditional_forecast(right_hand_sides, 7, d=0.5, driving_variance=1.0, white_variance=2.0)
    np.testing.assert_allclose(
        forecast.whitened, expected, rtol=0, atol=1e-10 * max(1.0, float(np.abs(expected).max()))
    )


def test_log_determinant_equals_the_exact_rational_determinant():
    # d = ½, σ_w² = 1, σ_v² = ⅓: Σ has rational entries; its determinant by Fraction elimination.
    n = 9
    psi = fractional_coefficients_exact(Fraction(1, 2), n)
    white = Fraction(1, 3)
    matrix = [
        [
            sum((psi[s - k] * psi[t - k] for k in range(min(s, t) + 1)), Fraction(0))
            + (white if s == t else 0)
            for t in range(n)
        ]
        for s in range(n)
    ]
    determinant = Fraction(1)
    for column in range(n):
        pivot = matrix[column][column]
        determinant *= pivot
        for row in range(column + 1, n):
            factor = matrix[row][column] / pivot
            matrix[row] = [a - factor * b for a, b in zip(matrix[row], matrix[column], strict=True)]
    result = whiten(np.ones((n, 1)), d=0.5, driving_variance=1.0, white_variance=1.0 / 3.0)
    assert result.log_determinant == pytest.approx(math.log(determinant), rel=1e-13)


@pytest.mark.parametrize(
    ("n", "h", "m", "d", "white"), [(40, 25, 2, 0.5, 0.7), (90, 130, 1, 0.3, 5.0), (60, 1, 18, 0.8, 0.05)]
)
def test_conditional_forecast_equals_dense_gaussian_conditioning(n, h, m, d, white):
    rng = np.random.default_rng(n + h + m)
    driving = 1.7
    data = rng.standard_normal((n, m))
    full = _dense_covariance(d, driving, white, n + h, n)
    calibration, cross = full[:n, :n], full[n:, :n]
    expected_mean = cross @ np.linalg.solve(calibration, data)
    expected_variance = np.diag(full[n:, n:]) - np.einsum(
        "ki,ik->k", cross, np.linalg.solve(calibration, cross.T)
    )
    result = conditional_forecast(data, h, d=d, driving_variance=driving, white_variance=white)
    assert result.mean.shape == (h, m)
    assert np.abs(result.mean - expected_mean).max() <= 1e-10 * max(1.0, float(np.abs(expected_mean).max()))
    assert np.abs(result.variance - expected_variance).max() <= 1e-10 * float(expected_variance.max())
    alone = whiten(data, d=d, driving_variance=driving, white_variance=white)
    np.testing.assert_allclose(result.whitened, alone.whitened, rtol=0, atol=1e-12)
    assert result.log_determinant == pytest.approx(alone.log_determinant, rel=1e-14)


def test_right_hand_sides_are_not_modified():
    data = np.arange(12.0).reshape(6, 2)
    copy = data.copy()
    whiten(data, d=0.5, driving_variance=1.0, white_variance=1.0)
    conditional_forecast(data, 3, d=0.5, driving_variance=1.0, white_variance=1.0)
    np.testing.assert_array_equal(data, copy)


INVALID = [
    (
        "one_dimensional",
        lambda: whiten(np.ones(5), d=0.5, driving_variance=1.0, white_variance=1.0),
        ValueError,
    ),
    ("no_rows", lambda: whiten(np.ones((0, 1)), d=0.5, driving_variance=1.0, white_variance=1.0), ValueError),
    (
        "nan",
        lambda: whiten(np.array([[np.nan]]), d=0.5, driving_variance=1.0, white_variance=1.0),
        ValueError,
    ),
    (
        "white_zero",
        lambda: whiten(np.ones((3, 1)), d=0.5, driving_variance=1.0, white_variance=0.0),
        ValueError,
    ),
    (
        "driving_negative",
        lambda: whiten(np.ones((3, 1)), d=0.5, driving_variance=-1.0, white_variance=1.0),
        ValueError,
    ),
    ("d_one", lambda: whiten(np.ones((3, 1)), d=1.0, driving_variance=1.0, white_variance=1.0), ValueError),
    (
        "horizon_zero",
        lambda: conditional_forecast(np.ones((3, 1)), 0, d=0.5, driving_variance=1.0, white_variance=1.0),
        ValueError,
    ),
]


@pytest.mark.parametrize(("call", "error"), [(c, e) for _, c, e in INVALID], ids=[i for i, _, _ in INVALID])
def test_invalid_arguments_are_refused(call, error):
    with pytest.raises(error):
        call()


@pytest.mark.parametrize("bias_variance", [math.inf, 0.0, 2.0])
def test_fast_forecast_with_white_noise_equals_the_growing_state_kalman_filter(bias_variance):
    from carousel_theory.fast_prediction import fast_kalman_forecast
    from carousel_theory.long_memory import fractional_integral
    from carousel_theory.prediction import kalman_forecast

    rng = np.random.default_rng(2012)
    n, h = 300, 120
    data = 1.5 + fractional_integral(rng.standard_normal(n), 0.5) + 0.8 * rng.standard_normal(n)
    options = {"d": 0.5, "driving_variance": 1.0, "white_variance": 0.64, "bias_mean": 1.0}
    fast = fast_kalman_forecast(data, h, bias_variance=bias_variance, **options)
    kalman = kalman_forecast(data, h, bias_variance=bias_variance, **options)
    assert np.abs(fast.mean - kalman.mean).max() <= 1e-10 * float(np.abs(kalman.mean).max())
    assert np.abs(fast.bias_variance - kalman.bias_variance).max() <= 1e-10 * float(
        kalman.bias_variance.max()
    )
