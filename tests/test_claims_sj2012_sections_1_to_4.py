"""SJ 2012 eq. (1), (2), (7)–(9) and §I–§IV statements: the exact helpers agree with independent hand
or brute-force values, and a wrong statement is detected (every status is pinned in
tests/test_claims_status.py)."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import sympy as sp

from carousel_theory.claim import Status
from carousel_theory.claims import (
    sj2012_sec1_introduction,
    sj2012_sec3_noise_processes,
    sj2012_sec4_predictors,
)
from carousel_theory.prediction import calibration_mean_forecast
from carousel_theory.processes import flicker_covariance

# --- exact helpers against hand values ------------------------------------------------------------


def test_allan_variance_eq2_by_hand():
    # τ = 1: differences 2, −1, 4 → 21/(2·3); τ = 2: bin means 2, 4 → 4/(2·1)
    assert sj2012_sec3_noise_processes._allan_variance_eq2((1, 3, 2, 6), 1) == Fraction(7, 2)
    assert sj2012_sec3_noise_processes._allan_variance_eq2((1, 3, 2, 6), 2) == Fraction(2)
    # a trailing partial bin is dropped: bins (1, 3), (2, 6), [5]
    assert sj2012_sec3_noise_processes._allan_variance_eq2((1, 3, 2, 6, 5), 2) == Fraction(2)


def test_moving_average_eq8_eq9_by_hand():
    # last sample 6; mean of last two (2 + 6)/2; then the mean of all three for j ≥ k = 3
    assert sj2012_sec4_predictors._moving_average_eq8_eq9((1, 2, 6), 5) == [
        Fraction(6),
        Fraction(4),
        Fraction(3),
        Fraction(3),
        Fraction(3),
    ]


@pytest.mark.parametrize("samples_per_bin, start", [(1, 0), (2, 0), (1, 3), (2, 1)])
def test_increments_covariance_against_dense_covariance(samples_per_bin, start):
    # second way: Δ = Wx with the exact covariance matrix of x from processes.flicker_covariance
    m = samples_per_bin
    length = start + 3 * m
    covariance = [
        [Fraction(flicker_covariance(s, t, Fraction(1, 2))) for t in range(1, length + 1)]
        for s in range(1, length + 1)
    ]
    rows = [[Fraction(0)] * length for _ in range(2)]
    for t in range(m):
        rows[0][start + t] = Fraction(-1, m)
        rows[0][start + m + t] = Fraction(1, m)
        rows[1][start + m + t] = Fraction(-1, m)
        rows[1][start + 2 * m + t] = Fraction(1, m)

    def quadratic(a, b):
        return sum(a[s] * covariance[s][t] * b[t] for s in range(length) for t in range(length))

    expected = (quadratic(rows[0], rows[0]), quadratic(rows[1], rows[1]), quadratic(rows[0], rows[1]))
    assert sj2012_sec4_predictors._increments_covariance_exact(m, start) == expected


def test_first_increments_covariance_by_hand():
    # ψ = 1, 1/2, 3/8: x1 = w1, x2 = w2 + w1/2, x3 = w3 + w2/2 + 3w1/8
    # Δ1 = w2 − w1/2, Δ2 = w3 − w2/2 − w1/8: Var 5/4, 1 + 1/4 + 1/64 = 81/64, Cov −1/2 + 1/16 = −7/16
    assert sj2012_sec4_predictors._increments_covariance_exact(1, 0) == (
        Fraction(5, 4),
        Fraction(81, 64),
        Fraction(-7, 16),
    )


# --- a wrong statement is detected -----------------------------------------------------------------


def test_eq2_with_a_different_normalisation_is_refuted(monkeypatch):
    original = sj2012_sec3_noise_processes._allan_variance_eq2

    def over_two_n(record, samples_per_bin):  # 1/(2N) instead of 1/(2(N − 1))
        bins = len(record) // samples_per_bin
        return original(record, samples_per_bin) * (bins - 1) / bins

    monkeypatch.setattr(sj2012_sec3_noise_processes, "_allan_variance_eq2", over_two_n)
    assert sj2012_sec3_noise_processes._check_eq2_allan_definition().status == Status.REFUTED


def test_calibration_mean_is_not_the_moving_average(monkeypatch):
    monkeypatch.setattr(sj2012_sec4_predictors, "moving_average_forecast", calibration_mean_forecast)
    assert sj2012_sec4_predictors._check_eq8_eq9_moving_average().status == Status.REFUTED


def test_growing_allan_variance_is_not_constant(monkeypatch):
    monkeypatch.setattr(
        sj2012_sec1_introduction, "flicker_allan_variance", lambda d, taus, length: 0.1 * taus.astype(float)
    )
    assert sj2012_sec1_introduction._check_flicker_allan_constant().status == Status.REFUTED


def test_exactly_constant_allan_variance_is_not_reported_as_asymptotic(monkeypatch):
    limit = 2 * np.log(2) / np.pi
    monkeypatch.setattr(
        sj2012_sec1_introduction, "flicker_allan_variance", lambda d, taus, length: np.full(len(taus), limit)
    )
    assert sj2012_sec1_introduction._check_flicker_allan_constant().status == Status.REFUTED


def test_wrong_white_slope_is_refuted(monkeypatch):
    m = sp.Symbol("m", integer=True, positive=True)
    monkeypatch.setattr(
        sj2012_sec3_noise_processes, "WHITE_ALLAN_VARIANCE", sp.Symbol("sigma_WN^2", positive=True) / m**2
    )
    assert sj2012_sec3_noise_processes._check_white_negative_slope().status == Status.REFUTED


def test_falling_rrw_allan_variance_is_refuted(monkeypatch):
    m = sp.Symbol("m", integer=True, positive=True)
    monkeypatch.setattr(
        sj2012_sec3_noise_processes, "RRW_ALLAN_VARIANCE", sp.Symbol("sigma_q^2", positive=True) / m
    )
    assert sj2012_sec3_noise_processes._check_rrw_positive_slope().status == Status.REFUTED


def test_constant_random_walk_allan_variance_would_not_refute_eq7(monkeypatch):
    # if a random walk had constant Allan variance the two assumptions would be compatible
    m = sp.Symbol("m", integer=True, positive=True)
    constant = sp.Symbol("sigma_q^2", positive=True) / 2 + 0 * m
    monkeypatch.setattr(sj2012_sec4_predictors, "RRW_ALLAN_VARIANCE", constant)
    assert sj2012_sec4_predictors._check_eq7_assumptions_compatible().status != Status.REFUTED


def test_markov_correlations_are_not_long_memory(monkeypatch):
    monkeypatch.setattr(
        sj2012_sec3_noise_processes, "flicker_covariance", lambda s, t, d: Fraction(4, 5) ** abs(s - t)
    )
    assert sj2012_sec3_noise_processes._check_flicker_long_memory().status == Status.REFUTED


def test_uncorrelated_increments_are_detected(monkeypatch):
    monkeypatch.setattr(sj2012_sec4_predictors, "_increment_correlation", lambda samples_per_bin, start: 0.0)
    assert sj2012_sec4_predictors._check_eq7_increments_dependent().status == Status.FAILED


def test_a_wrong_fast_forecast_is_detected(monkeypatch):
    def calibration_mean(data, horizon, white_variance=0.0):
        return type("Forecast", (), {"mean": calibration_mean_forecast(data, horizon)})()

    monkeypatch.setattr(sj2012_sec4_predictors, "fast_kalman_forecast", calibration_mean)
    assert sj2012_sec4_predictors._check_kalman_cost().status == Status.FAILED


def test_vanishing_flicker_prediction_error_is_refuted(monkeypatch):
    monkeypatch.setattr(
        sj2012_sec1_introduction,
        "_prediction_error_variance",
        lambda process, calibration, lag: 1.0 / calibration,
    )
    assert sj2012_sec1_introduction._check_bias_white_calibration().status == Status.REFUTED


def test_prediction_error_variance_against_white_noise_by_hand():
    # white: Var(x_{n+k} − mean) = 1 + 1/n exactly
    assert sj2012_sec1_introduction._prediction_error_variance("white", 4, 3) == pytest.approx(
        1.25, abs=1e-15
    )
    # rrw started at t = 1, n = 1, lag 1: Var(x_2 − x_1) = 1
    assert sj2012_sec1_introduction._prediction_error_variance("rrw", 1, 1) == pytest.approx(1.0, abs=1e-15)


def test_no_minimum_without_rrw_is_refuted(monkeypatch):
    m = sp.Symbol("m", integer=True, positive=True)
    monkeypatch.setattr(
        sj2012_sec3_noise_processes, "RRW_ALLAN_VARIANCE", sp.Symbol("sigma_q^2", positive=True) / m
    )
    assert sj2012_sec3_noise_processes._check_optimal_averaging_time().status == Status.REFUTED


def test_minimum_set_by_white_noise_is_refuted(monkeypatch):
    # an Allan variance whose minimum follows the white level, not σ_w², must not pass
    monkeypatch.setattr(
        sj2012_sec3_noise_processes,
        "model_allan_variance",
        lambda model, taus, length: np.full(len(taus), model.white_variance),
    )
    assert sj2012_sec3_noise_processes._check_bias_instability_measures_flicker().status == Status.REFUTED
