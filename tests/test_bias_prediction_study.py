"""The SJ 2012 §V studies as library functions: one recording's forecast, the simulated and the
measured Table I, and their Markdown report."""

from __future__ import annotations

import math

import numpy as np
import pytest

from carousel_theory.bias_prediction_study import (
    PAPER_TABLE1_SIMULATED,
    MeasuredTable1,
    SimulatedTable1,
    forecast_recording,
    measured_table1,
    simulated_table1,
    table1_markdown,
)
from carousel_theory.fast_prediction import fast_kalman_forecast
from carousel_theory.long_memory import fractional_integral
from carousel_theory.prediction import (
    METHODS,
    BiasModel,
    batch_metrics,
    population_metrics,
    simulate_sections,
)
from carousel_theory.restricted_likelihood import estimate_noise_variances


@pytest.fixture
def rates():
    rng = np.random.default_rng(5)
    return 2e-3 + 1e-4 * fractional_integral(rng.standard_normal(700), 0.5) + 3e-4 * rng.standard_normal(700)


def test_forecast_with_given_variances_is_the_kalman_forecast_of_the_segment(rates):
    result = forecast_recording(
        rates,
        start=50,
        calibration_length=200,
        horizon=100,
        driving_variance=1e-8,
        white_variance=9e-8,
        bias_prior="diffuse",
    )
    expected = fast_kalman_forecast(rates[50:250], 100, driving_variance=1e-8, white_variance=9e-8)
    np.testing.assert_allclose(result.kalman.mean, expected.mean, rtol=1e-13)
    assert not result.variances_estimated
    assert result.calibration_mean == pytest.approx(float(rates[50:250].mean()), rel=1e-15)
    np.testing.assert_array_equal(result.measured, rates[250:350])
    errors = result.errors()
    assert errors is not None and set(errors) == set(METHODS)
    integrated, root_sum = errors["CM"]
    assert integrated == pytest.approx(float((rates[250:350] - rates[50:250].mean()).sum()), rel=1e-12)
    assert root_sum > 0


def test_forecast_estimates_missing_variances_by_reml_and_marks_samples_past_the_end(rates):
    result = forecast_recording(rates, start=400, calibration_length=250, horizon=100)
    estimate = estimate_noise_variances(rates[None, 400:650], 0.5)
    assert result.variances_estimated
    assert result.model.driving_variance == pytest.approx(estimate.driving_variance, rel=1e-12)
    assert result.model.white_variance == pytest.approx(estimate.white_variance, rel=1e-12)
    assert np.isnan(result.measured[50:]).all() and np.isfinite(result.measured[:50]).all()
    assert result.errors() is None


def test_forecast_with_estimated_order_uses_the_joint_reml_estimate(rates):
    result = forecast_recording(rates, start=0, calibration_length=300, horizon=50, estimate_d=True)
    estimate = estimate_noise_variances(rates[None, :300], 0.5, estimate_d=True)
    assert result.estimated_d and result.variances_estimated
    assert result.model.d == estimate.d != 0.5
    assert result.model.white_variance == pytest.approx(estimate.white_variance, rel=1e-12)


def test_simulated_table1_repeats_the_batch_metrics_and_the_population_values():
    model = BiasModel()
    table = simulated_table1(30, 40, 20, model, seed=4, chunk=7)
    rng = np.random.default_rng(4)
    pieces = [simulate_sections(min(7, 30 - start), 60, model, rng=rng) for start in range(0, 30, 7)]
    for column in table.columns:
        integrated = np.concatenate([batch_metrics(piece, 40, column.method, model)[0] for piece in pieces])
        assert column.observed.mean_ie == pytest.approx(float(integrated.mean()), rel=1e-12)
        population, mean_square = population_metrics(40, 20, column.method, model)
        assert column.population == population and column.mean_square_rsse == mean_square
        assert column.paper == PAPER_TABLE1_SIMULATED[column.method]
    assert [column.method for column in table.columns] == list(METHODS)
    payload = table.as_dict()
    assert payload["settings"]["runs"] == 30 and payload["KF"]["population"]["mean_ie"] == 0.0
    text = table1_markdown(table, "carousel-theory predict --table1")
    assert text.startswith("<!-- generated") and "| mean RSSE |" in text and text.endswith("|\n")


def test_measured_table1_on_a_directory(tmp_path):
    rng = np.random.default_rng(9)
    for index in range(2):
        values = 1e-3 * fractional_integral(rng.standard_normal(1300), 0.5) + 2e-3 * rng.standard_normal(1300)
        np.savez(tmp_path / f"run{index}.npz", t=np.arange(1300) / 20.0, wx=values, fs=20.0)
    table = measured_table1(tmp_path, 100, 30, average=2)
    assert isinstance(table, MeasuredTable1)
    assert table.sample_rate_hz == 10.0 and table.files == ("run0.npz", "run1.npz")
    (axis,) = table.axes
    assert axis.axis == "wx" and axis.sections == 2 * (650 // 130)
    assert axis.variances.sections == math.ceil(axis.sections / 10)
    for column in axis.columns:
        assert math.isfinite(column.observed.std_ie) and column.population is None
    text = table1_markdown(table, "command")
    assert "## wx: 10 sections" in text


def test_simulated_table_is_a_frozen_record():
    table = simulated_table1(4, 10, 5, BiasModel(), seed=1)
    assert isinstance(table, SimulatedTable1)
    with pytest.raises(AttributeError):
        table.runs = 5  # type: ignore[misc]


INVALID = [
    ("runs_one", lambda: simulated_table1(1, 10, 5, BiasModel(), seed=1), ValueError),
    ("seed_negative", lambda: simulated_table1(4, 10, 5, BiasModel(), seed=-1), ValueError),
    ("model_not_bias_model", lambda: simulated_table1(4, 10, 5, "KF", seed=1), TypeError),  # type: ignore[arg-type]
    ("directory_missing", lambda: measured_table1("/nonexistent/recordings", 10, 5), ValueError),  # type: ignore[arg-type]
    (
        "prior_unknown",
        lambda: forecast_recording(np.ones(50), start=0, calibration_length=10, horizon=5, bias_prior="x"),
        ValueError,
    ),
    (
        "calibration_too_long",
        lambda: forecast_recording(np.ones(50), start=45, calibration_length=10, horizon=5),
        ValueError,
    ),
    (
        "start_negative",
        lambda: forecast_recording(np.ones(50), start=-1, calibration_length=10, horizon=5),
        ValueError,
    ),
    (
        "white_negative",
        lambda: forecast_recording(
            np.ones(50), start=0, calibration_length=10, horizon=5, driving_variance=1.0, white_variance=-1.0
        ),
        ValueError,
    ),
]


@pytest.mark.parametrize(("call", "error"), [(c, e) for _, c, e in INVALID], ids=[i for i, _, _ in INVALID])
def test_invalid_arguments_are_refused(call, error):
    with pytest.raises(error):
        call()
