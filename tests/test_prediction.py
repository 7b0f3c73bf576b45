"""The three predictors of SJ 2012 §IV, the metrics of §V, and the exact population values of the
batch test (Table I) against seeded Monte Carlo."""

from __future__ import annotations

import math

import numpy as np
import pytest
from conftest import Z_MONTE_CARLO

from carousel_theory import evaluation_cost
from carousel_theory.evaluation_cost import EvaluationBudgetError
from carousel_theory.fast_prediction import Forecast
from carousel_theory.prediction import (
    METHODS,
    BiasModel,
    batch_metrics,
    calibration_mean_forecast,
    integrated_error,
    kalman_forecast,
    moving_average_forecast,
    population_metrics,
    predict,
    prediction_weights,
    root_sum_squared_error,
    simulate_sections,
    summarize_metrics,
)


def test_moving_average_is_the_mean_of_the_last_k_samples_then_of_all():
    y = np.array([3.0, -1.0, 4.0, 1.0, 5.0])
    expected = [5.0, 3.0, 10.0 / 3.0, 2.25, 2.4, 2.4, 2.4]  # eq. (8) for k < 5, eq. (9) after
    np.testing.assert_allclose(moving_average_forecast(y, 7), expected, rtol=1e-15)


def test_moving_average_matches_a_loop_on_random_rows():
    rng = np.random.default_rng(1)
    block = rng.standard_normal((3, 30))
    got = moving_average_forecast(block, 45)
    for row in range(3):
        for k in range(1, 46):
            assert got[row, k - 1] == pytest.approx(block[row, -min(k, 30) :].mean(), rel=1e-12)


def test_calibration_mean_repeats_the_mean():
    np.testing.assert_array_equal(calibration_mean_forecast(np.array([1.0, 2.0, 6.0]), 4), [3.0] * 4)


def test_metrics_are_the_sum_and_the_root_sum_of_squares():
    data = np.array([1.0, 2.0, 3.0])
    prediction = np.array([0.0, 4.0, 1.0])  # errors 1, −2, 2
    assert integrated_error(data, prediction) == 1.0
    assert root_sum_squared_error(data, prediction) == 3.0


@pytest.mark.parametrize("prior", ["diffuse", "calibration-mean"])
@pytest.mark.parametrize("white", [0.0, 0.4])
def test_every_predictor_is_linear_with_rows_summing_to_one(prior, white):
    # Forecasts do not depend on the bias: adding a constant to the data adds it to every forecast.
    model = BiasModel(d=0.5, white_variance=white, bias_prior=prior)
    for method in METHODS:
        weights = prediction_weights(30, 20, method, model)
        np.testing.assert_allclose(weights.sum(axis=1), 1.0, rtol=1e-10)
        rng = np.random.default_rng(2)
        y = rng.standard_normal(30)
        result = predict(y, 20, method, model)
        forecast = result.mean if isinstance(result, Forecast) else result
        np.testing.assert_allclose(forecast, weights @ y, rtol=1e-10, atol=1e-12)


def test_calibration_mean_prior_centres_the_kalman_filter_on_the_mean():
    rng = np.random.default_rng(4)
    y = rng.standard_normal(40) + 3.0
    forecast = predict(y, 5000, "KF", BiasModel(bias_prior="calibration-mean"))
    # ψ_j → 0, so the forecast of the 1/f part decays and the forecast tends to the calibration mean.
    assert abs(forecast.mean[-1] - y.mean()) < 0.05 * abs(forecast.mean[0] - y.mean()) + 1e-3


def test_kalman_filter_has_the_smallest_mean_square_error():
    # The KF forecast is the conditional mean, so E RSSE² (= tr C_e) is smallest for it.
    model = BiasModel()
    squares = {method: population_metrics(60, 60, method, model)[1] for method in METHODS}
    assert squares["KF"] < squares["MA"] and squares["KF"] < squares["CM"]


def _accumulate(model: BiasModel, n: int, h: int, runs: int, seed: int):
    rng = np.random.default_rng(seed)
    ie = {method: [] for method in METHODS}
    rsse = {method: [] for method in METHODS}
    for _ in range(runs // 20000):
        sections = simulate_sections(20000, n + h, model, rng=rng, bias=-4.0)
        for method in METHODS:
            errors = batch_metrics(sections, n, method, model)
            ie[method].append(errors[0])
            rsse[method].append(errors[1])
    return {m: np.concatenate(ie[m]) for m in METHODS}, {m: np.concatenate(rsse[m]) for m in METHODS}


def _assert_mean_agrees(sample: np.ndarray, theory: float, scale: float):
    standard_error = sample.std(ddof=1) / math.sqrt(sample.size)
    assert 0.02 * scale > Z_MONTE_CARLO * standard_error  # enough runs to see a 2 % error
    assert abs(sample.mean() - theory) <= Z_MONTE_CARLO * standard_error


@pytest.mark.parametrize(
    "model",
    [BiasModel(), BiasModel(d=0.3, driving_variance=2.0, white_variance=0.5, bias_prior="calibration-mean")],
    ids=["table1-setting", "white-noise-and-mean-prior"],
)
def test_population_values_agree_with_monte_carlo(model):
    n, h, runs = 20, 20, 280000
    ie, rsse = _accumulate(model, n, h, runs, seed=30)
    for method in METHODS:
        summary, mean_square = population_metrics(n, h, method, model)
        assert summary.mean_ie == 0.0
        _assert_mean_agrees(ie[method], 0.0, summary.std_ie)
        _assert_mean_agrees(ie[method] ** 2, summary.std_ie**2, summary.std_ie**2)
        _assert_mean_agrees(rsse[method], summary.mean_rsse, summary.mean_rsse)
        _assert_mean_agrees(rsse[method] ** 2, mean_square, mean_square)
        centred = (rsse[method] - summary.mean_rsse) ** 2
        _assert_mean_agrees(centred, summary.std_rsse**2, summary.std_rsse**2)


@pytest.mark.slow
def test_table1_batch_at_full_size_agrees_with_population_values():
    # SJ 2012 §V-C: 2000-sample runs, 1000 to calibrate, d = ½, no white noise; 4000 runs so that a
    # 2 % error in the mean RSSE would show.
    model = BiasModel()
    rng = np.random.default_rng(2012)
    rsse = {method: [] for method in METHODS}
    for _ in range(4):
        sections = simulate_sections(1000, 2000, model, rng=rng)
        for method in METHODS:
            rsse[method].append(batch_metrics(sections, 1000, method, model)[1])
    for method in METHODS:
        summary, _ = population_metrics(1000, 1000, method, model)
        _assert_mean_agrees(np.concatenate(rsse[method]), summary.mean_rsse, summary.mean_rsse)


def test_summary_uses_sample_statistics():
    summary = summarize_metrics(np.array([1.0, 3.0]), np.array([2.0, 2.0]))
    assert summary.as_dict() == {"mean_ie": 2.0, "std_ie": math.sqrt(2.0), "mean_rsse": 2.0, "std_rsse": 0.0}


INVALID = [
    ("model_d_one", lambda: BiasModel(d=1.0), ValueError),
    ("model_d_negative", lambda: BiasModel(d=-0.2), ValueError),
    ("model_driving_zero", lambda: BiasModel(driving_variance=0.0), ValueError),
    ("model_white_negative", lambda: BiasModel(white_variance=-0.1), ValueError),
    ("model_prior_unknown", lambda: BiasModel(bias_prior="flat"), ValueError),
    ("predict_method_unknown", lambda: predict(np.ones(5), 2, "AR"), ValueError),
    ("predict_model_wrong_type", lambda: predict(np.ones(5), 2, "KF", model=0.5), TypeError),
    ("predict_calibration_one_sample", lambda: predict(np.ones(1), 2, "MA"), ValueError),
    ("predict_calibration_nan", lambda: predict(np.array([1.0, np.nan]), 2, "CM"), ValueError),
    ("predict_horizon_zero", lambda: predict(np.ones(5), 0, "KF"), ValueError),
    ("moving_average_inf", lambda: moving_average_forecast(np.array([np.inf, 1.0]), 2), ValueError),
    ("calibration_mean_horizon_negative", lambda: calibration_mean_forecast(np.ones(3), -1), ValueError),
    ("metrics_shape_mismatch", lambda: integrated_error(np.ones(3), np.ones(4)), ValueError),
    ("metrics_nan", lambda: root_sum_squared_error(np.array([np.nan]), np.ones(1)), ValueError),
    ("batch_one_dimensional", lambda: batch_metrics(np.ones(10), 5, "CM"), ValueError),
    ("batch_calibration_too_long", lambda: batch_metrics(np.ones((2, 10)), 10, "CM"), ValueError),
    ("batch_calibration_one", lambda: batch_metrics(np.ones((2, 10)), 1, "CM"), ValueError),
    ("simulate_global_rng", lambda: simulate_sections(2, 10, BiasModel(), rng=None), TypeError),
    (
        "simulate_runs_zero",
        lambda: simulate_sections(0, 10, BiasModel(), rng=np.random.default_rng(0)),
        ValueError,
    ),
    ("weights_horizon_zero", lambda: prediction_weights(5, 0, "KF"), ValueError),
    ("population_calibration_one", lambda: population_metrics(1, 5, "KF"), ValueError),
    ("summary_one_run", lambda: summarize_metrics(np.ones(1), np.ones(1)), ValueError),
]


@pytest.mark.parametrize(("call", "error"), [(c, e) for _, c, e in INVALID], ids=[i for i, _, _ in INVALID])
def test_invalid_arguments_are_refused(call, error):
    with pytest.raises(error):
        call()


def test_public_names_exist():
    import carousel_theory.fast_prediction as fast_module
    import carousel_theory.long_memory as long_memory_module
    import carousel_theory.prediction as prediction_module

    for module in (prediction_module, fast_module, long_memory_module):
        for name in module.__all__:
            assert hasattr(module, name), f"{module.__name__}.{name}"


def test_growing_state_filter_is_refused_over_the_budget_unless_forced(monkeypatch):
    # n + h = 66 000 states: a 35 GB covariance and about 35 h (4.4·10⁻¹⁰ T³ s, measured): refused with
    # the estimate and the way out, before anything is allocated.
    calibration = np.random.default_rng(2).standard_normal(6000)
    with pytest.raises(EvaluationBudgetError, match=r"n \+ h = 66,?000 states .* refused; pass force=True"):
        kalman_forecast(calibration, 60_000)
    # Under a budget every call exceeds, force=True runs it, with the result of the unforced call.
    small = calibration[:50]
    expected = kalman_forecast(small, 20).mean
    monkeypatch.setattr(evaluation_cost, "DEFAULT_BUDGET_SECONDS", 1e-12)
    with pytest.raises(EvaluationBudgetError):
        kalman_forecast(small, 20)
    np.testing.assert_array_equal(kalman_forecast(small, 20, force=True).mean, expected)
