"""Virtual rotation of static recordings: exact predicted variances, a seeded simulation, measured runs."""

from __future__ import annotations

import math

import numpy as np
import pytest

from carousel_theory.fitting import NoiseModel
from carousel_theory.processes import covariance_matrix, sample_rate_random_walk, sample_white
from carousel_theory.rotation_schemes import Carousel, Indexing, demodulation_weights
from carousel_theory.virtual_rotation import _predicted_variances, virtual_rotation_check
from tests.conftest import Z_MONTE_CARLO


@pytest.mark.parametrize("scheme", [Carousel(5), Indexing(2, 2, 1), Indexing(4, 1, 1, use_transitions=True)])
def test_segment_variances_against_dense_covariance_matrices(scheme):
    """Segment m of length L sits at samples (m−1)L … mL − 1 of a record started at t = 1."""
    length, segments, d = 2 * scheme.cycle_length(), 4, 0.3
    model = NoiseModel(100.0, white_variance=2.0, rrw_variance=0.5, flicker_variance=0.7, flicker_d=d)
    weights = demodulation_weights(scheme.pattern(length))[:, :2, :]
    predicted = _predicted_variances(weights, [model, model], segments)
    total = segments * length
    covariance = sum(
        variance * covariance_matrix(process, total, d=d if process == "flicker" else None)
        for process, variance in (("white", 2.0), ("rrw", 0.5), ("flicker", 0.7))
    )
    for segment in range(segments):
        for component in range(2):
            expected = 0.0
            for gyro in range(2):
                row = np.zeros(total)
                row[segment * length : (segment + 1) * length] = weights[component, gyro]
                expected += row @ covariance @ row
            assert math.isclose(predicted[component, segment], expected, rel_tol=1e-10)


def test_simulated_static_recording_with_constant_offsets():
    """White + RRW + a large constant per gyro; 2 × 60 000 segment estimates: a 2 % error would fail."""
    rng = np.random.default_rng(2024)
    scheme, length = Carousel(4), 8
    segments = 60_000
    n = segments * length
    white, rrw = 1.0, 0.01
    rates = np.stack(
        [
            sample_white(n, rng=rng, variance=white)
            + sample_rate_random_walk(n, rng=rng, variance=rrw)
            + offset
            for offset in (150.0, -75.0)
        ]
    )
    model = NoiseModel(100.0, white_variance=white, rrw_variance=rrw)
    check = virtual_rotation_check(rates, scheme, length, [model, model])
    standard_error = math.sqrt(2 / check.estimates)  # segments of whole cycles are uncorrelated here
    assert Z_MONTE_CARLO * standard_error < 0.02
    assert abs(check.standardized - 1) <= Z_MONTE_CARLO * standard_error


@pytest.mark.slow
def test_measured_adis16405_run_is_consistent_with_its_fitted_model(shared_data):
    """One measured run (wx, wy), fitted with white + RRW + 1/f, carouselled virtually at 2 s a turn in
    100-s segments: the mean of Ê²/Var lies within ±25 % of 1 (200 estimates: ±20 % is the 95 % range)."""
    from carousel_theory.data import load_recording
    from carousel_theory.fitting import fit_noise_model

    recording = load_recording(shared_data / "adis16405_static" / "adis16405_run2.npz")
    rates = np.stack([recording.rates["wx"], recording.rates["wy"]])
    models = [
        fit_noise_model(row, 100.0, ("white", "rrw", "flicker"), tau_range=(0.1, 1e9), iterations=2).model
        for row in rates
    ]
    check = virtual_rotation_check(rates, Carousel(200), 10_000, models)
    assert check.estimates == 200
    assert abs(check.standardized - 1) < 0.25


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: virtual_rotation_check(np.zeros((3, 100)), Carousel(4), 8, []), "2 rows"),
        (lambda: virtual_rotation_check(np.zeros((2, 100)), Carousel(4), 10, []), "whole number of cycles"),
        (lambda: virtual_rotation_check(np.zeros((2, 100)), Carousel(4.5), 9, []), "whole number of cycles"),
        (lambda: virtual_rotation_check(np.zeros((2, 100)), Carousel(4), 52, []), "fewer than 2 segments"),
        (lambda: virtual_rotation_check(np.zeros((2, 100)), Carousel(4), 0, []), "segment_samples=0"),
    ],
    ids=["rows", "partial-cycle", "no-cycle", "one-segment", "zero"],
)
def test_invalid_calls(call, message):
    with pytest.raises(ValueError, match=message):
        call()
