"""Seeded Monte Carlo of the whole chain: gyro outputs with Earth rate, noise, rotation and imperfections →
demodulated estimate → heading, against the exact covariance, systematic error and heading error.

Bounds: |estimate − theory| ≤ Z·SE with Z = 4.5 for the suite, and each test asserts that Z·SE is below
2 % of the theoretical value, so a 2 % error in the theory would fail it.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from carousel_theory.fitting import NoiseModel
from carousel_theory.heading import EARTH_RATE, heading_error, horizontal_earth_rate
from carousel_theory.imperfections import Imperfections, imperfection_effect
from carousel_theory.rotation_schemes import Carousel, Indexing
from carousel_theory.scheme_variance import estimate_covariances
from tests.conftest import Z_MONTE_CARLO

LATITUDE, HEADING = 61.5, 35.0
SAMPLE_RATE = 10.0


def _angles(pattern):
    return np.unwrap(np.arctan2(pattern.rotations[:, 1, 0], pattern.rotations[:, 0, 0]))


def _simulate_estimates(pattern, earth, rng, replicates, white, rrw, bias_sigma, encoder_noise=0.0):
    """Ω̂ for ``replicates`` independent records: two gyros, ω = R(φ)ᵀE + b + white + RRW, demodulated at
    φ + encoder noise. Written from the model, not from the package's weights."""
    phi = _angles(pattern)
    used = pattern.used
    n = phi.shape[0]
    out = np.empty((replicates, 2))
    batch = 10_000
    for start in range(0, replicates, batch):
        size = min(batch, replicates - start)
        noise = math.sqrt(white) * rng.standard_normal((2, size, n))
        noise += np.cumsum(math.sqrt(rrw) * rng.standard_normal((2, size, n)), axis=2)
        noise += bias_sigma * rng.standard_normal((2, size, 1))
        x = np.cos(phi) * earth[0] + np.sin(phi) * earth[1] + noise[0]
        y = -np.sin(phi) * earth[0] + np.cos(phi) * earth[1] + noise[1]
        demodulation = phi + encoder_noise * rng.standard_normal((size, n))
        c, s = np.cos(demodulation), np.sin(demodulation)
        out[start : start + size, 0] = ((c * x - s * y)[:, used]).mean(axis=1)
        out[start : start + size, 1] = ((s * x + c * y)[:, used]).mean(axis=1)
    return out


def _assert_variance(samples, expected):
    standard_error = expected * math.sqrt(2 / (samples.shape[0] - 1))
    assert Z_MONTE_CARLO * standard_error < 0.02 * expected  # power: a 2 % error would fail
    assert abs(samples.var(ddof=1) - expected) <= Z_MONTE_CARLO * standard_error


@pytest.mark.parametrize(
    "scheme",
    [Carousel(9.5), Indexing(2, 5, 2, use_transitions=True), Indexing(4, 3, 2)],
    ids=["carousel-9.5", "indexing2-transitions-used", "indexing4"],
)
def test_estimate_covariance_and_heading_against_the_simulated_chain(scheme):
    rng = np.random.default_rng(20261123)
    length = 4 * scheme.cycle_length() if scheme.cycle_length() else 95
    pattern = scheme.pattern(length)
    earth = horizontal_earth_rate(LATITUDE, HEADING)
    magnitude = float(np.linalg.norm(earth))
    white, rrw, bias = (0.6 * magnitude) ** 2, (0.02 * magnitude) ** 2, 0.3 * magnitude
    noise = [NoiseModel(SAMPLE_RATE, white_variance=white, rrw_variance=rrw)]
    covariance = estimate_covariances(pattern, [length], noise, bias**2)[0].total()[:2, :2]
    estimates = _simulate_estimates(pattern, earth, rng, 220_000, white, rrw, bias)
    across = np.array([earth[1], -earth[0]]) / magnitude
    along = earth / magnitude
    for direction in (across, along):
        _assert_variance((estimates - earth) @ direction, float(direction @ covariance @ direction))
    # the heading through atan2 against the exact projected-normal RMS (σ/|E| ≈ 0.2: mildly nonlinear)
    errors = np.angle(np.exp(1j * (np.arctan2(-estimates[:, 1], estimates[:, 0]) - math.radians(HEADING))))
    exact = heading_error(covariance, LATITUDE, HEADING)
    squares = errors**2
    standard_error = squares.std(ddof=1) / math.sqrt(squares.shape[0])
    assert Z_MONTE_CARLO * standard_error < 0.02 * exact.exact_rms**2
    assert abs(squares.mean() - exact.exact_rms**2) <= Z_MONTE_CARLO * standard_error


def test_encoder_noise_covariance_with_bias_coupling_against_the_simulated_chain():
    rng = np.random.default_rng(7)
    pattern = Carousel(8).pattern(64)
    earth = horizontal_earth_rate(LATITUDE, HEADING)
    magnitude = float(np.linalg.norm(earth))
    bias, encoder = 3 * magnitude, 0.4
    effect = imperfection_effect(
        pattern, Imperfections(angle_noise=encoder), LATITUDE, HEADING, SAMPLE_RATE, bias_sigma=bias
    )
    estimates = _simulate_estimates(pattern, earth, rng, 200_000, 0.0, 0.0, bias, encoder_noise=encoder)
    shrink = math.exp(-(encoder**2) / 2)  # E[cos e]: the systematic error of encoder noise
    np.testing.assert_allclose(effect.bias, (shrink - 1) * earth, rtol=1e-12)
    centred = estimates - (earth + effect.bias)
    for direction in (np.array([earth[1], -earth[0]]) / magnitude, earth / magnitude):
        _assert_variance(centred @ direction, float(direction @ effect.covariance @ direction))


def test_systematic_error_of_open_loop_wobble_misalignment_and_scale_factors():
    """The deterministic imperfections together, simulated sample by sample from the physical model."""
    pattern = Carousel(40).pattern(400)
    imperfections = Imperfections(
        measured_angles=False,
        rate_wobble=0.02,
        wobble_phase=0.3,
        misalignment_x=2e-3,
        misalignment_y=-1e-3,
        scale_factor_x=0.01,
        scale_factor_y=-0.004,
        angle_bias=0.005,
    )
    effect = imperfection_effect(pattern, imperfections, LATITUDE, HEADING, SAMPLE_RATE)
    # the model, integrated independently: φ(t) from φ̇ = ω(1 + a cos(φ⁰ + ϕ)) by fine Euler steps
    omega = 2 * math.pi * SAMPLE_RATE / 40
    fine = 200
    tau = np.arange(1, 400 * fine + 1) / (SAMPLE_RATE * fine)
    nominal_fine = omega * tau
    true_fine = np.cumsum(omega * (1 + 0.02 * np.cos(nominal_fine - omega / (SAMPLE_RATE * fine) + 0.3))) / (
        SAMPLE_RATE * fine
    )
    phi, rate = (
        true_fine[fine - 1 :: fine],
        (omega * (1 + 0.02 * np.cos(nominal_fine + 0.3)))[fine - 1 :: fine],
    )
    earth = horizontal_earth_rate(LATITUDE, HEADING)
    vertical = EARTH_RATE * math.sin(math.radians(LATITUDE))
    x = 1.01 * math.cos(2e-3) * (np.cos(phi) * earth[0] + np.sin(phi) * earth[1]) + math.sin(2e-3) * (
        rate + vertical
    )
    y = 0.996 * math.cos(-1e-3) * (-np.sin(phi) * earth[0] + np.cos(phi) * earth[1]) + math.sin(-1e-3) * (
        rate + vertical
    )
    nominal = omega * np.arange(1, 401) / SAMPLE_RATE + 0.005
    estimate = np.array(
        [
            np.mean(np.cos(nominal) * x - np.sin(nominal) * y),
            np.mean(np.sin(nominal) * x + np.cos(nominal) * y),
        ]
    )
    np.testing.assert_allclose(
        effect.bias, estimate - earth, rtol=2e-3, atol=1e-3 * np.linalg.norm(earth) * 1e-2
    )


def test_unmeasured_angle_random_walk_against_the_simulated_chain():
    rng = np.random.default_rng(99)
    pattern = Carousel(10).pattern(60)
    sigma = 0.08
    effect = imperfection_effect(
        pattern, Imperfections(rate_noise=sigma, measured_angles=False), LATITUDE, HEADING, SAMPLE_RATE
    )
    earth = horizontal_earth_rate(LATITUDE, HEADING)
    phi = _angles(pattern)
    walk = np.cumsum(sigma * rng.standard_normal((200_000, phi.shape[0])), axis=1)
    true = phi + walk
    x = np.cos(true) * earth[0] + np.sin(true) * earth[1]
    y = -np.sin(true) * earth[0] + np.cos(true) * earth[1]
    estimates = np.stack(
        [(np.cos(phi) * x - np.sin(phi) * y).mean(axis=1), (np.sin(phi) * x + np.cos(phi) * y).mean(axis=1)],
        axis=1,
    )
    magnitude = float(np.linalg.norm(earth))
    mean_error = (estimates - earth).mean(axis=0) - effect.bias
    assert np.all(np.abs(mean_error) <= Z_MONTE_CARLO * estimates.std(axis=0, ddof=1) / math.sqrt(200_000))
    across = np.array([earth[1], -earth[0]]) / magnitude
    _assert_variance(estimates @ across, float(across @ effect.covariance @ across))
