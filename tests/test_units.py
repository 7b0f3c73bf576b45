"""Unit conversions of carousel_theory.units, checked against values worked out by hand."""

from __future__ import annotations

import math

import numpy as np
import pytest

from carousel_theory import units


def test_rate_conversions_round_trip_and_known_values():
    assert units.rate_to_rad_per_s([180.0], "deg/s")[0] == pytest.approx(math.pi, rel=1e-15)
    assert units.rate_to_rad_per_s([3600.0 * 180.0], "deg/h")[0] == pytest.approx(math.pi, rel=1e-15)
    values = np.array([0.5, -2.0, 7.25])
    for unit in units.RATE_UNITS:
        np.testing.assert_allclose(units.from_rad_per_s(units.rate_to_rad_per_s(values, unit), unit), values)


def test_bias_instability_factor_is_sqrt_two_ln_two_over_pi():
    # IEEE Std 952: flat Allan variance of 1/f noise is (2 ln 2 / π) B², so the factor is 0.6643 to 4 digits.
    assert round(units.BIAS_INSTABILITY_FACTOR, 4) == 0.6643
    assert units.bias_instability_from_allan_minimum(0.6643) == pytest.approx(1.0, rel=1e-4)


def test_noise_density_conversions():
    # White per-sample variance 1e-4 (rad/s)² at 100 Hz: N = √(1e-6) = 1e-3 rad/√s = 1e-3·(180/π)·60 °/√h.
    arw = units.angle_random_walk_from_white_variance(1e-4, 100.0)
    assert arw == pytest.approx(1e-3, rel=1e-15)
    assert units.to_deg_per_sqrt_hour(arw) == pytest.approx(1e-3 * 180 / math.pi * 60, rel=1e-15)
    # RRW per-sample increment variance 1e-12 at 100 Hz: K² = 1e-10 (rad/s)²/s, K = 1e-5 rad/s/√s.
    rrw = units.rate_random_walk_from_increment_variance(1e-12, 100.0)
    assert rrw == pytest.approx(1e-5, rel=1e-15)
    assert units.to_deg_per_hour_per_sqrt_hour(rrw) == pytest.approx(
        1e-5 * 180 / math.pi * 3600 * 60, rel=1e-15
    )
    assert units.rad_per_s_to_deg_per_h(math.pi / 180) == pytest.approx(3600.0, rel=1e-15)


@pytest.mark.parametrize(
    ("call", "error"),
    [
        pytest.param(lambda: units.rate_to_rad_per_s([1.0], "rpm"), ValueError, id="unknown-unit"),
        pytest.param(lambda: units.rate_to_rad_per_s([1.0], 1.0), TypeError, id="unit-not-string"),
        pytest.param(lambda: units.from_rad_per_s([1.0], "deg/min"), ValueError, id="unknown-unit-back"),
    ],
)
def test_invalid_calls(call, error):
    with pytest.raises(error, match="units="):
        call()
