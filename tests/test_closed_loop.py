"""The closed loop on recordings with undeclared effects: it names each catalogue effect and the error
drops; a clean recording gives "none"; an effect outside the catalogue gives "unexplained"."""

from __future__ import annotations

import json

import numpy as np
import pytest
from conftest import Z_MONTE_CARLO

from carousel_theory.closed_loop import (
    BAND_EXPECTED_EXCEEDANCE,
    HEADLINE_METRIC,
    run_loop,
    uniform_resample,
)
from carousel_theory.closed_loop.residual_model import AxisNoise, short_noise_allan
from carousel_theory.data import recording_from_arrays
from carousel_theory.effects import CATALOGUE
from carousel_theory.simulate import simulate_recording

SAMPLES, RATE, WHITE, WALK = 30_000, 100.0, 3.6e-5, 1e-11


def _recording(effects=(), seed=2, samples=SAMPLES, **kwargs):
    return simulate_recording(
        samples,
        RATE,
        rng=np.random.default_rng(seed),
        bias=0.01,
        white_variance=WHITE,
        rrw_variance=WALK,
        effects=effects,
        **kwargs,
    )


def test_clean_recording_gives_none():
    result = run_loop(_recording())
    assert result.effects == ["none"]
    assert result.error_after == result.error_before
    assert result.metric == HEADLINE_METRIC
    assert result.error_before < 2.0  # about 1 when the model is right
    assert all(not step.trials for step in result.steps)
    json.dumps(result.as_dict())


@pytest.mark.parametrize(
    ("injection", "name"),
    [
        pytest.param("warmup:amplitude=8e-3,time_constant=30", "warmup", id="warmup"),
        pytest.param("temperature:coefficient=3e-3", "temperature", id="temperature"),
        pytest.param("spikes", "spikes", id="spikes"),
        pytest.param("sinusoid:amplitude=5e-4,frequency=3.3", "sinusoid", id="sinusoid"),
        pytest.param("colored_noise:coefficient=0.4", "colored_noise", id="colored_noise"),
        pytest.param("flicker:variance=1e-6", "flicker", id="flicker"),
        pytest.param("steps:size=3e-3", "steps", id="steps"),
    ],
)
def test_each_catalogue_effect_is_named_and_the_error_drops(injection, name):
    result = run_loop(_recording([injection]))
    assert result.effects == [name], result.steps
    assert result.error_after < result.error_before
    assert result.error_after < 2.0
    # the same metrics before and after
    assert result.metrics_before.keys() == result.metrics_after.keys()


def test_outside_the_catalogue_is_unexplained_never_a_wrong_name():
    result = run_loop(_recording(["sawtooth:amplitude=3e-3,period=20"]))
    assert result.effects == ["unexplained"], result.steps
    tried = [trial for step in result.steps for trial in step.trials]
    assert tried  # candidates were tried and every one was rejected with its reason
    assert all(trial.decision.startswith("rejected") and not trial.accepted for trial in tried)


def test_fine_quantization_is_an_observation_not_an_effect():
    result = run_loop(_recording(["quantization:step=3e-3"]))
    assert result.effects == ["none"]
    assert any(note.startswith("quantization on wx") for note in result.observations)


def test_deterministic_for_a_seed():
    first = run_loop(_recording(["spikes"], seed=5, samples=10_000)).as_dict()
    second = run_loop(_recording(["spikes"], seed=5, samples=10_000)).as_dict()
    assert first == second


def test_carouselled_bins_match_the_predicted_variance_on_the_declared_model():
    """Under the fitted declared model the carouselled bins are uncorrelated (TIM 2014 eq. (17)) with the
    predicted variance: their mean squared z is 1 within Monte Carlo error (K = 300 bins).

    An end-to-end check of the loop's bookkeeping (fit, weights, bands): 300 bins resolve the variance to
    about 8 % only. The 2 %-sensitive Monte Carlo of the same carouselled-bin prediction is
    tests/test_monte_carlo_figures.py."""
    result = run_loop(_recording(seed=7, samples=60_000))
    carouselled = result.metrics_after["carouselled_bins"]
    assert carouselled["bins"] == 300
    assert abs(carouselled["mean_square_z"] - 1.0) <= Z_MONTE_CARLO * np.sqrt(2.0 / 300)
    assert abs(carouselled["exceedance_2sigma"] - BAND_EXPECTED_EXCEEDANCE) <= Z_MONTE_CARLO * np.sqrt(
        BAND_EXPECTED_EXCEEDANCE * (1 - BAND_EXPECTED_EXCEEDANCE) / 300
    )


def test_short_noise_allan_variance_against_the_definition():
    """Allan variance of an AR(1) short noise from its autocovariance, against the quadratic form of the
    cluster-mean difference with the exact Toeplitz covariance (dense, small m)."""
    noise = AxisNoise(1.0, 0.0, 2.0, ar_coefficients=(0.5,))
    gamma = noise.short_autocovariance()
    for m in (1, 2, 3, 7):
        weights = np.concatenate((-np.ones(m), np.ones(m))) / m
        lags = np.abs(np.subtract.outer(np.arange(2 * m), np.arange(2 * m)))
        covariance = gamma[lags]
        expected = 0.5 * weights @ covariance @ weights
        assert short_noise_allan(noise, np.array([m]))[0] == pytest.approx(expected, rel=1e-12)
    # AR(1) autocovariance: σ² φ^h / (1 − φ²)
    assert gamma[:4] == pytest.approx(2.0 * 0.5 ** np.arange(4) / 0.75, rel=1e-12)


def test_one_axis_is_averaging_only():
    result = run_loop(_recording(axes=("wx",)))
    assert result.metrics_after["carouselled_bins"] is None
    assert any("averaging analysis only" in note for note in result.observations)


def test_constant_temperature_is_said():
    result = run_loop(_recording(temperature=np.full(SAMPLES, 24.0)))
    assert any("constant" in note for note in result.observations)
    assert result.effects == ["none"]


def test_measured_angles_give_one_bin_per_revolution():
    result = run_loop(_recording(samples_per_revolution=250))
    carouselled = result.metrics_after["carouselled_bins"]
    assert carouselled["mode"].startswith("measured angles")
    assert carouselled["bins"] == SAMPLES // 250 - 1  # complete revolutions between the first wraps


def test_irregular_timestamps_are_resampled_and_said():
    rng = np.random.default_rng(0)
    time = np.cumsum(rng.choice([0.002, 0.002, 0.03], size=40_000))
    recording = recording_from_arrays(
        {"wx": rng.normal(0, 6e-3, 40_000), "wy": rng.normal(0, 6e-3, 40_000)}, time=time, irregular="keep"
    )
    resampled, note = uniform_resample(recording)
    assert resampled.uniform and "bin-averaged" in note
    result = run_loop(recording, samples_per_revolution=50)
    assert any("irregular timestamps" in note for note in result.observations)


def test_catalogue_effects_each_have_a_detector_in_the_loop():
    result = run_loop(_recording())
    names = {d.effect for d in result.steps[0].detections}
    assert names == set(CATALOGUE) - {"none", "quantization"}


RECORDING = _recording(samples=3000)
INVALID = [
    pytest.param(lambda: run_loop("recording.csv"), TypeError, id="not-a-recording"),
    pytest.param(lambda: run_loop(RECORDING, samples_per_revolution=2), ValueError, id="N-too-small"),
    pytest.param(lambda: run_loop(RECORDING, samples_per_revolution=200.0), TypeError, id="N-float"),
    pytest.param(lambda: run_loop(RECORDING, samples_per_revolution=400), ValueError, id="too-short-for-N"),
    pytest.param(lambda: run_loop(RECORDING, alpha=0.7), ValueError, id="alpha-too-large"),
    pytest.param(lambda: run_loop(RECORDING, alpha=0.0), ValueError, id="alpha-zero"),
    pytest.param(lambda: run_loop(RECORDING, axes=("wz",)), ValueError, id="axis-missing"),
    pytest.param(lambda: run_loop(RECORDING, maximum_iterations=0), ValueError, id="no-iterations"),
    pytest.param(lambda: run_loop(RECORDING, declared=("white",)), ValueError, id="declared-without-rrw"),
    pytest.param(
        lambda: run_loop(RECORDING, declared=("white", "rrw", "drift")), ValueError, id="declared-unknown"
    ),
]


@pytest.mark.parametrize(("call", "error"), INVALID)
def test_invalid_calls(call, error):
    with pytest.raises(error):
        call()


@pytest.mark.data
@pytest.mark.slow
def test_measured_mpu6050_recording_runs_end_to_end(shared_data):
    """The bursty MPU6050 recording: resampled (said), temperature testable, a valid result."""
    from carousel_theory.data import load_recording

    recording = load_recording(
        shared_data / "mpu6050_static_10min" / "mpu6050_static_10min.npz", irregular="keep"
    )
    result = run_loop(recording)
    assert any("irregular timestamps" in note for note in result.observations)
    assert any(note.startswith("quantization on wx") for note in result.observations)
    assert result.effects and all(name in set(CATALOGUE) | {"unexplained"} for name in result.effects)
    assert np.isfinite(result.error_before) and np.isfinite(result.error_after)
    json.dumps(result.as_dict())
