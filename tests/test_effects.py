"""The effect catalogue and the loop's detectors: stable names, calibrated null distributions, each
detector finds its own effect — through the public contract (``DETECTORS[name].detect(view, alpha)`` on a
view made by ``build_view``)."""

from __future__ import annotations

import json

import numpy as np
import pytest
from conftest import Z_MONTE_CARLO
from scipy import ndimage, stats

from carousel_theory.closed_loop.detectors import DETECTORS, REMEDIES, TESTED_EFFECTS
from carousel_theory.closed_loop.signal_detectors import hann_periodogram, residual_periodogram, robust_z
from carousel_theory.closed_loop.view import ModelSpec, build_view
from carousel_theory.effects import CATALOGUE, check_effect_parameters, detect_quantization
from carousel_theory.simulate import simulate_recording

REQUIRED = {"flicker", "warmup", "temperature", "spikes", "sinusoid", "colored_noise", "none"}
WHITE, WALK = 3.6e-5, 1e-11
ALPHA = 0.01


def _view(effects=(), samples=30_000, seed=1):
    recording = simulate_recording(
        samples,
        100.0,
        rng=np.random.default_rng(seed),
        bias=0.01,
        white_variance=WHITE,
        rrw_variance=WALK,
        effects=effects,
    )
    return build_view(recording, ("wx", "wy"), ModelSpec())


def test_catalogue_has_the_stable_names_and_says_how():
    assert REQUIRED | {"steps", "quantization"} == set(CATALOGUE)
    for name, effect in CATALOGUE.items():
        assert effect.name == name
        if name != "none":
            description = effect.describe()
            assert all(description[key] for key in ("summary", "detection", "enters_model", "removal"))
    assert set(TESTED_EFFECTS) == set(CATALOGUE) - {"none", "quantization"}


def test_quantization_lattice():
    rng = np.random.default_rng(0)
    values = np.round(rng.normal(0, 6e-3, 10_000) / 8.7e-4) * 8.7e-4
    found = detect_quantization(values)
    assert found["quantized"]
    assert found["step"] == pytest.approx(8.7e-4, rel=1e-9)
    assert not detect_quantization(rng.normal(0, 6e-3, 10_000))["quantized"]


def test_hann_periodogram_of_white_noise_has_mean_sigma_squared():
    rng = np.random.default_rng(3)
    variance = 4.0
    _, power = hann_periodogram(np.sqrt(variance) * rng.standard_normal(440_000), 100.0)
    inner = power[10:-10:2]  # every second ordinate: nearly independent under the Hann window
    standard_error = variance / np.sqrt(len(inner))  # each ordinate ~ σ² Exp(1)
    assert 0.02 * variance > Z_MONTE_CARLO * standard_error
    assert abs(inner.mean() - variance) <= Z_MONTE_CARLO * standard_error


@pytest.mark.parametrize("length", [1, 3, 1000, 4097])
def test_hann_periodogram_equals_its_definition_bit_for_bit(length):
    # |Σ h_t (x_t − x̄) e^{−iωt}|² / Σ h_t², written as one expression (the function works in place).
    values = np.random.default_rng(length).standard_normal(length).cumsum()
    window = np.hanning(length)
    spectrum = np.fft.rfft((values - values.mean()) * window)
    expected = (spectrum.real**2 + spectrum.imag**2) / float(np.dot(window, window))
    frequencies, power = hann_periodogram(values, 50.0)
    np.testing.assert_array_equal(power, expected)
    np.testing.assert_array_equal(frequencies, np.fft.rfftfreq(length, d=1.0 / 50.0))


def test_residual_periodogram_is_the_periodogram_of_the_residual_bit_for_bit():
    view = _view(("sinusoid:amplitude=5e-4,frequency=3.3",), samples=4_097)
    for axis in view.axes:
        expected = hann_periodogram(view.residuals[axis], view.sample_rate)
        got = residual_periodogram(view, axis)
        np.testing.assert_array_equal(got[0], expected[0])
        np.testing.assert_array_equal(got[1], expected[1])
        assert not view.residuals[axis].flags.writeable  # the view's residual is left as it was


def _robust_z_as_written(x, window=15):
    """The statistic of robust_z as plain expressions (no array reused), the reference for its
    in-place arithmetic."""
    half = window // 2
    centred = ndimage.median_filter(x, size=half, mode="nearest")
    shift = half // 2 + 1
    padded = np.pad(centred, shift, mode="edge")
    deviation = x - 0.5 * (padded[: len(x)] + padded[2 * shift :])
    low, high = np.quantile(deviation, (0.005, 0.995))
    central = deviation[(deviation >= low) & (deviation <= high)]
    cut = float(stats.norm.isf(0.005))
    trimmed_factor = 1.0 - 2.0 * cut * float(stats.norm.pdf(cut)) / 0.99
    scale = np.sqrt(float(np.var(central)) / trimmed_factor) if len(central) > 1 else 0.0
    if scale > 0:
        scale = float(np.std(deviation[np.abs(deviation - np.median(deviation)) < 4.5 * scale]))
    return deviation / (scale or float(np.std(deviation)) or 1.0)


@pytest.mark.parametrize(
    "values",
    [
        np.random.default_rng(8).standard_normal(100_003),
        np.round(np.random.default_rng(9).standard_normal(5_000) * 3.0) / 3.0,  # a coarse lattice
        np.zeros(50),  # no scale at all
        np.r_[np.zeros(40), 1.0, np.zeros(40)],  # one spike on a constant
    ],
    ids=["gaussian", "lattice", "constant", "lone-spike"],
)
def test_robust_z_equals_its_plain_expressions_bit_for_bit(values):
    values.setflags(write=False)
    np.testing.assert_array_equal(robust_z(values), _robust_z_as_written(values))


def test_spike_statistic_is_gaussian_in_the_tail():
    """The deviation from the neighbours' median, over its scale, exceeds 3 as often as N(0, 1) does."""
    rng = np.random.default_rng(5)
    z = robust_z(rng.standard_normal(1_000_000))
    expected = 2 * stats.norm.sf(3.0)
    observed = float(np.mean(np.abs(z) > 3.0))
    standard_error = np.sqrt(expected * (1 - expected) / len(z)) * 3  # ×3: 15-sample windows overlap
    assert abs(observed - expected) <= Z_MONTE_CARLO * standard_error
    assert abs(observed - expected) < 0.1 * expected


def test_clean_recording_triggers_no_detector():
    view = _view()
    for name in TESTED_EFFECTS:
        detection = DETECTORS[name].detect(view, ALPHA)
        assert not detection.significant, (name, detection)
        json.dumps(detection.as_dict())


@pytest.mark.parametrize(
    ("injection", "name", "check"),
    [
        pytest.param(
            "warmup:amplitude=5e-3,time_constant=30",
            "warmup",
            lambda d: 5 <= d.details["time_constant_s"] <= 150,
            id="warmup",
        ),
        pytest.param(
            "temperature:coefficient=2e-3",
            "temperature",
            lambda d: d.details["coefficient_rad_s_per_degC"] > 0,
            id="temperature",
        ),
        pytest.param(
            "steps:size=3e-3,time=0.4",
            "steps",
            lambda d: abs(d.details["time_s"] - 0.4 * 299.99) < 2.0,
            id="steps",
        ),
        pytest.param(
            "spikes:amplitude=0.06,rate=1e-4",
            "spikes",
            lambda d: d.details["samples_beyond_threshold"] >= 1,
            id="spikes",
        ),
        pytest.param(
            "sinusoid:amplitude=5e-4,frequency=3.3",
            "sinusoid",
            lambda d: abs(d.details["frequency_hz"] - 3.3) <= 2 * 100.0 / 30_000,
            id="sinusoid",
        ),
        pytest.param(
            "colored_noise:coefficient=0.3",
            "colored_noise",
            lambda d: d.details["signed_log_ratio"] > 0,
            id="colored_noise",
        ),
        pytest.param("flicker:variance=1e-6", "flicker", lambda d: d.statistic > 0, id="flicker"),
    ],
)
def test_each_detector_finds_its_effect(injection, name, check):
    view = _view([injection])
    detection = DETECTORS[name].detect(view, ALPHA)
    assert detection.significant, detection
    assert check(detection), detection


def test_fitted_sinusoid_and_step_recover_the_parameters():
    view = _view(["sinusoid:amplitude=5e-4,frequency=3.3,phase=0.4"])
    detection = DETECTORS["sinusoid"].detect(view, ALPHA)
    fitted = REMEDIES["sinusoid"].fit(view, detection, ALPHA)
    assert fitted.parameters["wx"]["frequency_hz"] == pytest.approx(3.3, abs=1e-3)
    assert fitted.parameters["wx"]["amplitude"] == pytest.approx(5e-4, rel=0.15)
    view = _view(["steps:size=3e-3,time=0.5"])
    fitted = REMEDIES["steps"].fit(view, DETECTORS["steps"].detect(view, ALPHA), ALPHA)
    jumps = fitted.parameters["wx"]["jumps"]
    assert len(jumps) == 1
    assert jumps[0]["height"] == pytest.approx(3e-3, rel=0.3)


def test_temperature_not_testable_when_absent_or_constant():
    recording = simulate_recording(
        3000, 100.0, rng=np.random.default_rng(0), white_variance=WHITE, temperature=np.full(3000, 25.0)
    )
    view = build_view(recording, ("wx", "wy"), ModelSpec())
    detection = DETECTORS["temperature"].detect(view, ALPHA)
    assert not detection.testable and not detection.significant
    assert "constant" in detection.note
    recording = simulate_recording(
        3000, 100.0, rng=np.random.default_rng(0), white_variance=WHITE, temperature=None
    )
    view = build_view(recording, ("wx", "wy"), ModelSpec())
    assert "no temperature column" in DETECTORS["temperature"].detect(view, ALPHA).note


@pytest.mark.parametrize(
    ("call", "error"),
    [
        pytest.param(lambda: check_effect_parameters("wobble", {}), ValueError, id="unknown-effect"),
        pytest.param(lambda: check_effect_parameters("none", {}), ValueError, id="none-has-no-parameters"),
        pytest.param(
            lambda: check_effect_parameters("warmup", {"speed": 1.0}), ValueError, id="unknown-parameter"
        ),
        pytest.param(
            lambda: check_effect_parameters("warmup", {"amplitude": np.inf}), ValueError, id="infinite"
        ),
        pytest.param(
            lambda: check_effect_parameters("warmup", {"amplitude": "big"}), TypeError, id="not-a-number"
        ),
        pytest.param(
            lambda: check_effect_parameters("warmup", [("amplitude", 1.0)]), TypeError, id="not-a-mapping"
        ),
        pytest.param(
            lambda: CATALOGUE["quantization"].inject(np.zeros(3), np.arange(3.0), None, None, {"step": 0.0}),
            ValueError,
            id="quantization-step-zero",
        ),
        pytest.param(
            lambda: CATALOGUE["temperature"].inject(
                np.zeros(3), np.arange(3.0), None, None, {"coefficient": 1.0}
            ),
            ValueError,
            id="temperature-without-column",
        ),
    ],
)
def test_invalid_calls(call, error):
    with pytest.raises(error):
        call()
