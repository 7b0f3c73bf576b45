"""Synthetic recordings: seeded, the same noise as a hand-written loop, every effect put in as declared."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import Z_MONTE_CARLO
from scipy.signal import lfilter

from carousel_theory.data import load_recording
from carousel_theory.simulate import (
    OUTSIDE_CATALOGUE,
    Injection,
    default_temperature_profile,
    parse_injection,
    simulate_recording,
    write_recording,
)


def _quiet(effects, samples=2000, **kwargs):
    """A recording without noise, so that the effect itself is visible exactly."""
    return simulate_recording(
        samples, 10.0, rng=np.random.default_rng(0), white_variance=0.0, effects=effects, **kwargs
    )


def test_same_seed_same_recording_and_different_seed_differs():
    first = simulate_recording(
        500, 10.0, rng=np.random.default_rng(7), rrw_variance=1e-10, effects=["spikes"]
    )
    second = simulate_recording(
        500, 10.0, rng=np.random.default_rng(7), rrw_variance=1e-10, effects=["spikes"]
    )
    third = simulate_recording(
        500, 10.0, rng=np.random.default_rng(8), rrw_variance=1e-10, effects=["spikes"]
    )
    for axis in ("wx", "wy"):
        assert np.array_equal(first.rates[axis], second.rates[axis])
        assert not np.array_equal(first.rates[axis], third.rates[axis])


def test_same_noise_as_a_hand_written_loop():
    """Bias + white + rate random walk (TIM 2014 eqs. (1)-(2)) from the same generator, drawn by hand."""
    white, walk, bias = 4e-6, 1e-9, 0.25
    recording = simulate_recording(
        300, 50.0, rng=np.random.default_rng(11), bias=bias, white_variance=white, rrw_variance=walk
    )
    rng = np.random.default_rng(11)
    for axis in ("wx", "wy"):
        w = np.sqrt(white) * rng.standard_normal(300)
        q = np.sqrt(walk) * rng.standard_normal(300)
        r = np.zeros(300)
        level = 0.0
        for t in range(300):  # r_t = r_{t-1} + q_t, r_0 = 0
            level += q[t]
            r[t] = level
        np.testing.assert_allclose(recording.rates[axis], bias + w + r, rtol=0, atol=1e-15)


def test_white_noise_variance_monte_carlo():
    variance = 2.5e-5
    samples = 400_000
    recording = simulate_recording(
        samples, 100.0, rng=np.random.default_rng(3), white_variance=variance, axes=("wx",)
    )
    estimate = float(np.var(recording.rates["wx"]))
    standard_error = variance * np.sqrt(2.0 / samples)
    assert 0.02 * variance > Z_MONTE_CARLO * standard_error  # a 2 % error would fail
    assert abs(estimate - variance) <= Z_MONTE_CARLO * standard_error


def test_warmup_is_the_declared_exponential():
    recording = _quiet(["warmup:amplitude=0.5,time_constant=20"])
    t = recording.time
    np.testing.assert_allclose(recording.rates["wx"], 0.5 * np.exp(-t / 20.0), rtol=0, atol=1e-15)


def test_temperature_effect_is_linear_in_the_column():
    recording = _quiet(["temperature:coefficient=0.02"])
    expected = 0.02 * (recording.temperature - recording.temperature[0])
    np.testing.assert_allclose(recording.rates["wy"], expected, rtol=0, atol=1e-15)
    np.testing.assert_array_equal(recording.temperature, default_temperature_profile(recording.time))


def test_sinusoid_step_and_sawtooth():
    recording = _quiet(["sinusoid:amplitude=0.1,frequency=0.7,phase=0.2"])
    np.testing.assert_allclose(
        recording.rates["wx"], 0.1 * np.sin(2 * np.pi * 0.7 * recording.time + 0.2), rtol=0, atol=1e-15
    )
    recording = _quiet(["steps:size=0.3,time=0.25"])
    at = recording.time[0] + 0.25 * (recording.time[-1] - recording.time[0])
    np.testing.assert_array_equal(recording.rates["wx"], np.where(recording.time >= at, 0.3, 0.0))
    recording = _quiet(["sawtooth:amplitude=2,period=10"])
    phase = np.mod(recording.time / 10.0, 1.0)
    np.testing.assert_allclose(recording.rates["wx"], 2 * (phase - 0.5), rtol=0, atol=1e-15)
    assert "sawtooth" in OUTSIDE_CATALOGUE


def test_spikes_count_and_size():
    recording = _quiet(["spikes:amplitude=3,rate=0.01"])
    values = recording.rates["wx"]
    assert np.count_nonzero(values) == 20
    assert set(np.abs(values[values != 0])) == {3.0}


def test_colored_noise_is_the_first_order_filter_of_the_white_noise():
    recording = simulate_recording(
        400, 10.0, rng=np.random.default_rng(5), white_variance=1.0, effects=["colored_noise:coefficient=0.6"]
    )
    rng = np.random.default_rng(5)
    white = rng.standard_normal(400)
    expected = np.zeros(400)
    previous = 0.0
    for t in range(400):  # x_t = 0.6 x_{t-1} + w_t
        previous = 0.6 * previous + white[t]
        expected[t] = previous
    np.testing.assert_allclose(recording.rates["wx"], expected, rtol=0, atol=1e-12)
    np.testing.assert_allclose(expected, lfilter([1.0], [1.0, -0.6], white), atol=1e-12)


def test_quantization_rounds_to_the_step():
    recording = simulate_recording(
        1000, 10.0, rng=np.random.default_rng(2), white_variance=1.0, effects=["quantization:step=0.25"]
    )
    multiples = recording.rates["wx"] / 0.25
    np.testing.assert_allclose(multiples, np.round(multiples), atol=1e-12)


def test_phi_column_of_a_uniform_rotation():
    recording = _quiet([], samples=40, samples_per_revolution=8)
    expected = 2 * np.pi * (np.arange(1, 41) % 8) / 8
    np.testing.assert_allclose(recording.angle, expected)


@pytest.mark.parametrize("suffix", [".csv", ".npz"])
def test_written_file_reads_back_identically(tmp_path, suffix):
    recording = simulate_recording(
        300,
        100.0,
        rng=np.random.default_rng(4),
        rrw_variance=1e-9,
        effects=["warmup"],
        samples_per_revolution=20,
    )
    path = write_recording(recording, tmp_path / f"recording{suffix}")
    loaded = load_recording(path)
    np.testing.assert_array_equal(loaded.time, recording.time)
    for axis in ("wx", "wy"):
        np.testing.assert_array_equal(loaded.rates[axis], recording.rates[axis])
    np.testing.assert_array_equal(loaded.temperature, recording.temperature)
    np.testing.assert_array_equal(loaded.angle, recording.angle)


def test_parse_injection():
    assert parse_injection("warmup") == Injection("warmup", {})
    assert parse_injection(" sinusoid:amplitude=2, frequency=0.5 ") == Injection(
        "sinusoid", {"amplitude": 2.0, "frequency": 0.5}
    )


RNG = np.random.default_rng(0)
INVALID = [
    pytest.param(lambda: simulate_recording(1, 10.0, rng=RNG), ValueError, id="one-sample"),
    pytest.param(lambda: simulate_recording(10.5, 10.0, rng=RNG), TypeError, id="samples-float"),
    pytest.param(lambda: simulate_recording(10, 0.0, rng=RNG), ValueError, id="rate-zero"),
    pytest.param(lambda: simulate_recording(10, 10.0, rng=None), TypeError, id="rng-none"),
    pytest.param(
        lambda: simulate_recording(10, 10.0, rng=RNG, white_variance=-1.0), ValueError, id="negative-white"
    ),
    pytest.param(
        lambda: simulate_recording(10, 10.0, rng=RNG, rrw_variance=np.nan), ValueError, id="nan-rrw"
    ),
    pytest.param(lambda: simulate_recording(10, 10.0, rng=RNG, axes="wx"), TypeError, id="axes-string"),
    pytest.param(
        lambda: simulate_recording(10, 10.0, rng=RNG, axes=("wx", "wx")), ValueError, id="axes-repeated"
    ),
    pytest.param(
        lambda: simulate_recording(10, 10.0, rng=RNG, bias={"wx": 1.0}), ValueError, id="bias-missing-axis"
    ),
    pytest.param(
        lambda: simulate_recording(10, 10.0, rng=RNG, effects=["wobble"]), ValueError, id="unknown-effect"
    ),
    pytest.param(
        lambda: simulate_recording(10, 10.0, rng=RNG, effects=["none"]), ValueError, id="effect-none"
    ),
    pytest.param(
        lambda: simulate_recording(10, 10.0, rng=RNG, effects=["warmup:speed=3"]),
        ValueError,
        id="unknown-parameter",
    ),
    pytest.param(
        lambda: simulate_recording(10, 10.0, rng=RNG, effects=["temperature"], temperature=None),
        ValueError,
        id="temperature-effect-without-column",
    ),
    pytest.param(
        lambda: simulate_recording(10, 10.0, rng=RNG, effects=["colored_noise:coefficient=1.5"]),
        ValueError,
        id="unstable-filter",
    ),
    pytest.param(
        lambda: simulate_recording(10, 10.0, rng=RNG, temperature=np.ones(3)),
        ValueError,
        id="temperature-length",
    ),
    pytest.param(
        lambda: simulate_recording(10, 10.0, rng=RNG, samples_per_revolution=2),
        ValueError,
        id="revolution-too-short",
    ),
    pytest.param(lambda: parse_injection("warmup:amplitude"), ValueError, id="parse-no-equals"),
    pytest.param(lambda: parse_injection("warmup:amplitude=big"), ValueError, id="parse-not-a-number"),
    pytest.param(lambda: parse_injection(""), ValueError, id="parse-empty"),
    pytest.param(lambda: write_recording("not a recording", "x.csv"), TypeError, id="write-not-recording"),
    pytest.param(
        lambda: write_recording(simulate_recording(10, 10.0, rng=RNG), "x.txt"),
        ValueError,
        id="write-extension",
    ),
]


@pytest.mark.parametrize(("call", "error"), INVALID)
def test_invalid_calls(call, error):
    with pytest.raises(error):
        call()
