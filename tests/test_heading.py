"""Heading error: linearised, exact (projected-normal quadrature) and through atan2."""

from __future__ import annotations

import math

import numpy as np
import pytest

from carousel_theory import heading
from carousel_theory.heading import (
    EARTH_RATE,
    check_latitude,
    heading_error,
    heading_monte_carlo,
    horizontal_earth_rate,
    linearisation_ratio,
)
from tests.conftest import Z_MONTE_CARLO, public_functions


def test_horizontal_earth_rate_points_north_with_magnitude_omega_cos_latitude():
    rate = horizontal_earth_rate(60.0, 90.0)
    np.testing.assert_allclose(rate, [0.0, -EARTH_RATE / 2], atol=1e-20)
    assert math.isclose(math.atan2(-rate[1], rate[0]), math.radians(90.0))


def test_linearised_sigma_is_the_cross_track_standard_deviation_over_the_magnitude():
    covariance = np.array([[4.0, 1.0], [1.0, 9.0]]) * 1e-14
    result = heading_error(covariance, 30.0, 0.0)
    magnitude = EARTH_RATE * math.cos(math.radians(30.0))
    assert math.isclose(result.linearised_sigma, math.sqrt(9e-14) / magnitude, rel_tol=1e-12)


@pytest.mark.parametrize("relative", [1e-3, 1e-2])
def test_exact_rms_tends_to_the_linearised_sigma(relative):
    """For small σ/|E| the exact RMS is σ_lin (1 + O((σ/|E|)²))."""
    assert abs(linearisation_ratio(relative) - 1) <= relative**2


def test_the_exact_law_is_a_probability_density():
    magnitude = EARTH_RATE * math.cos(math.radians(45.0))
    for relative in (0.05, 0.5, 3.0):
        covariance = np.diag([1.0, 2.0]) * (relative * magnitude) ** 2
        mean = horizontal_earth_rate(45.0, 20.0) * np.array([1, -1])
        theta = np.linspace(-math.pi, math.pi, 200_001)
        density = heading._angle_density(theta, mean, covariance)
        assert abs(np.trapezoid(density, theta) - 1) < 1e-6


@pytest.mark.parametrize(("relative", "bias"), [(0.05, 0.0), (0.35, 0.1), (1.2, -0.3)])
def test_exact_rms_and_mean_against_seeded_atan2_monte_carlo(relative, bias):
    magnitude = EARTH_RATE * math.cos(math.radians(61.5))
    covariance = np.array([[1.0, 0.3], [0.3, 0.6]]) * (relative * magnitude) ** 2
    offset = np.array([bias, -bias / 2]) * magnitude
    exact = heading_error(covariance, 61.5, 40.0, offset)
    errors = heading_monte_carlo(
        covariance, 61.5, rng=np.random.default_rng(5), replicates=300_000, heading_deg=40.0, bias=offset
    )
    squares = errors**2
    standard_error = squares.std(ddof=1) / math.sqrt(squares.shape[0])
    assert Z_MONTE_CARLO * standard_error < 0.02 * exact.exact_rms**2
    assert abs(squares.mean() - exact.exact_rms**2) <= Z_MONTE_CARLO * standard_error
    assert abs(errors.mean() - exact.exact_mean) <= Z_MONTE_CARLO * errors.std(ddof=1) / math.sqrt(
        errors.shape[0]
    )


def test_linearisation_fails_beyond_a_third_of_the_earth_rate():
    """Within 1 % up to σ/|E| = 0.13, off by more than 10 % from σ/|E| = 0.35 to 1 (heavier tails), then
    below (wrapping)."""
    assert abs(linearisation_ratio(0.13) - 1) < 0.01
    assert linearisation_ratio(0.35) > 1.1
    assert linearisation_ratio(0.99) > 1.1
    assert linearisation_ratio(5.0) < 0.5  # the exact RMS saturates near π/√3 while σ_lin grows


@pytest.mark.parametrize(
    ("call", "error", "message"),
    [
        (lambda: check_latitude(91.0), ValueError, r"latitude=91.0: must lie in \[-90, 90\]"),
        (lambda: check_latitude(-90.0), ValueError, "latitude=-90.0: must be strictly between -90 and 90"),
        (lambda: check_latitude(90), ValueError, "heading is undefined"),
        (lambda: check_latitude(math.nan), ValueError, "latitude=nan"),
        (lambda: heading_error(np.eye(3), 10.0), ValueError, "2×2"),
        (lambda: heading_error(np.zeros((2, 2)), 10.0), ValueError, "positive definite"),
        (lambda: heading_error(np.eye(2), 10.0, bias=(1.0,)), ValueError, "must hold 2 components"),
        (lambda: heading_monte_carlo(np.eye(2), 10.0, rng=1, replicates=5), TypeError, "rng=1"),
        (
            lambda: heading_monte_carlo(np.eye(2), 10.0, rng=np.random.default_rng(0), replicates=0),
            ValueError,
            "replicates=0",
        ),
        (lambda: linearisation_ratio(0.0), ValueError, "relative_sigma=0.0: must be > 0"),
    ],
    ids=[
        "beyond-90",
        "pole-south",
        "pole-north",
        "nan",
        "shape",
        "singular",
        "bias-shape",
        "rng",
        "replicates",
        "ratio",
    ],
)
def test_invalid_calls(call, error, message):
    with pytest.raises(error, match=message):
        call()


def test_all_is_honest():
    assert public_functions(heading) <= set(heading.__all__)
