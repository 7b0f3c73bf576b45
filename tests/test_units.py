"""Unit conversions of carousel_theory.units, checked against values worked out by hand."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import example, given
from hypothesis import strategies as st

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


# --- datasheet figures → per-sample variances: each the inverse of the forward conversion -------------

_figures = st.floats(min_value=1e-6, max_value=1e6, allow_nan=False, allow_infinity=False)
_rates = st.floats(min_value=1e-2, max_value=1e5, allow_nan=False, allow_infinity=False)
#: Relative tolerance of a float round trip through a handful of multiplications and a square root.
_ROUND_TRIP = 1e-13


@given(arw=_figures, sample_rate=_rates)
@example(arw=0.2, sample_rate=100.0)
def test_angle_random_walk_round_trip(arw, sample_rate):
    variance = units.white_variance_from_angle_random_walk(arw, sample_rate)
    back = units.to_deg_per_sqrt_hour(units.angle_random_walk_from_white_variance(variance, sample_rate))
    assert math.isclose(back, arw, rel_tol=_ROUND_TRIP)


@given(rrw=_figures, sample_rate=_rates)
@example(rrw=5.0, sample_rate=100.0)
def test_rate_random_walk_round_trip(rrw, sample_rate):
    variance = units.rrw_variance_from_rate_random_walk(rrw, sample_rate)
    back = units.to_deg_per_hour_per_sqrt_hour(
        units.rate_random_walk_from_increment_variance(variance, sample_rate)
    )
    assert math.isclose(back, rrw, rel_tol=_ROUND_TRIP)


@given(bias_instability=_figures)
@example(bias_instability=3.0)
def test_bias_instability_round_trip(bias_instability):
    variance = units.flicker_variance_from_bias_instability(bias_instability)
    back = units.rad_per_s_to_deg_per_h(units.bias_instability_from_flicker_variance(variance))
    assert math.isclose(back, bias_instability, rel_tol=_ROUND_TRIP)


@given(angle=_figures)
def test_quantization_round_trips(angle):
    assert math.isclose(units.to_microradians(units.from_microradians(angle)), angle, rel_tol=_ROUND_TRIP)
    assert math.isclose(units.to_arcseconds(units.from_arcseconds(angle)), angle, rel_tol=_ROUND_TRIP)
    assert math.isclose(units.from_deg_per_sqrt_hour(units.to_deg_per_sqrt_hour(angle)), angle, rel_tol=1e-13)


def test_datasheet_conversions_known_values():
    # 0.2 °/√h = 0.2·(π/180)/60 rad/√s; at 100 Hz σ² = N²·100 (worked by hand, not through the module).
    n = 0.2 * math.pi / 180 / 60
    assert units.white_variance_from_angle_random_walk(0.2, 100.0) == pytest.approx(n * n * 100, rel=1e-15)
    # 5 °/h/√h = 5·(π/180)/(3600·60) rad/s/√s; σ_q,sample² = K²/100.
    k = 5 * math.pi / 180 / 3600 / 60
    assert units.rrw_variance_from_rate_random_walk(5.0, 100.0) == pytest.approx(k * k / 100, rel=1e-15)
    # 3 °/h = 3·π/(180·3600) rad/s; σ_w² = B², whatever the rate.
    b = 3 * math.pi / 180 / 3600
    assert units.flicker_variance_from_bias_instability(3.0) == pytest.approx(b * b, rel=1e-15)
    # 1″ = 4.8481368… µrad.
    assert units.to_microradians(units.from_arcseconds(1.0)) == pytest.approx(math.pi / 0.648, rel=1e-15)


def test_flicker_plateau_is_the_bias_instability_convention():
    """σ_w² = B² rests on the discrete 1/f model's long-τ Allan variance (2 ln 2/π)·σ_w² at d = 1/2;
    the exact variogram sum of noise_model reaches it to 1e-7 at m = 10⁵ samples."""
    from carousel_theory.noise_model import term_allan_variance

    plateau = float(term_allan_variance("flicker", [100_000], 0.5)[0])
    assert plateau == pytest.approx(units.BIAS_INSTABILITY_FACTOR**2, rel=1e-7)


def test_unit_names():
    assert units.square_unit("deg/h") == "(deg/h)^2"
    assert units.display_unit("deg/sqrt(h)") == "°/√h"
    assert all(units.square_unit(unit) in units.UNIT_NAMES for unit in units.RATE_UNITS)


@pytest.mark.parametrize(
    ("call", "error", "match"),
    [
        pytest.param(
            lambda: units.white_variance_from_angle_random_walk(-0.1, 100.0), ValueError, "arw", id="arw<0"
        ),
        pytest.param(
            lambda: units.white_variance_from_angle_random_walk(0.1, 0.0),
            ValueError,
            "sample_rate",
            id="fs=0",
        ),
        pytest.param(
            lambda: units.rrw_variance_from_rate_random_walk(math.nan, 1.0), ValueError, "rrw", id="rrw-nan"
        ),
        pytest.param(
            lambda: units.flicker_variance_from_bias_instability("3"),
            TypeError,
            "bias_instability",
            id="bi-str",
        ),
        pytest.param(lambda: units.display_unit("furlong"), ValueError, "unit=", id="unknown-unit-name"),
        pytest.param(lambda: units.square_unit("rpm"), ValueError, "units=", id="unknown-square"),
    ],
)
def test_invalid_datasheet_calls(call, error, match):
    with pytest.raises(error, match=match):
        call()


def test_all_is_honest():
    from conftest import public_functions

    from carousel_theory import noise_parameters

    for module in (units, noise_parameters):
        assert public_functions(module) <= set(module.__all__)
        assert all(hasattr(module, name) for name in module.__all__)


BAD_CONVERSIONS = [
    (
        "arw-rate-zero",
        lambda: units.angle_random_walk_from_white_variance(1.0, 0.0),
        ValueError,
        "sample_rate",
    ),
    (
        "arw-negative",
        lambda: units.angle_random_walk_from_white_variance(-1.0, 1.0),
        ValueError,
        "variance=-1",
    ),
    ("rrw-rate-zero", lambda: units.rate_random_walk_from_increment_variance(1.0, 0.0), ValueError, "rate=0"),
    ("to-arw-nan", lambda: units.to_deg_per_sqrt_hour(math.nan), ValueError, "must be finite"),
    ("to-rrw-inf", lambda: units.to_deg_per_hour_per_sqrt_hour(math.inf), ValueError, "must be finite"),
    ("rate-string", lambda: units.rad_per_s_to_deg_per_h("1"), TypeError, "value='1'"),
    ("rate-bool", lambda: units.rad_per_s_to_deg_per_h(True), TypeError, "value=True"),
    ("back-nan", lambda: units.deg_per_h_to_rad_per_s(math.nan), ValueError, "value=nan"),
    ("minimum-negative", lambda: units.bias_instability_from_allan_minimum(-1.0), ValueError, ">= 0"),
    ("urad-none", lambda: units.to_microradians(None), TypeError, "radians=None"),
    ("arcsec-nan", lambda: units.from_arcseconds(math.nan), ValueError, "arcseconds=nan"),
]


@pytest.mark.parametrize(
    ("call", "error", "message"), [b[1:] for b in BAD_CONVERSIONS], ids=[b[0] for b in BAD_CONVERSIONS]
)
def test_conversions_refuse_what_is_not_a_finite_number_by_name(call, error, message):
    with pytest.raises(error, match=message):
        call()


def test_signed_rates_and_numpy_scalars_still_convert():
    assert units.rad_per_s_to_deg_per_h(np.float64(-1.0)) == pytest.approx(-180.0 / math.pi * 3600.0)
    assert units.deg_per_h_to_rad_per_s(np.array(3600.0)) == pytest.approx(math.pi / 180.0)
