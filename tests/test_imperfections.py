"""Imperfections: exact systematic errors against their leading-order SymPy forms and derivatives."""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp
from hypothesis import example, given
from hypothesis import strategies as st

from carousel_theory import imperfections as module
from carousel_theory.heading import EARTH_RATE, horizontal_earth_rate
from carousel_theory.imperfections import LEADING_ORDER, Imperfections, imperfection_effect, sensitivity
from carousel_theory.rotation_schemes import Carousel, Indexing, Static, TwoAxisCarousel
from tests.conftest import public_functions

LATITUDE, HEADING, RATE = 61.5, 30.0, 100.0


def _heading_shift(effect):
    earth = horizontal_earth_rate(LATITUDE, HEADING)
    x, y = earth + effect.bias
    return math.atan2(-y, x) - math.radians(HEADING)


def _value(name, **values):
    expression = LEADING_ORDER[name][0]
    symbols = {s.name: s for s in expression.free_symbols}
    values.setdefault("Omega", EARTH_RATE)
    return float(expression.subs({symbols[k]: v for k, v in values.items() if k in symbols}))


@pytest.mark.parametrize("scheme", [Static(), Carousel(200), Carousel(173.5), Indexing(4, 50, 10)])
def test_an_encoder_offset_moves_the_heading_by_minus_beta_exactly(scheme):
    effect = imperfection_effect(
        scheme.pattern(2000), Imperfections(angle_bias=0.02), LATITUDE, HEADING, RATE
    )
    assert math.isclose(_heading_shift(effect), _value("angle_bias", beta=0.02), rel_tol=1e-10)


@pytest.mark.parametrize("size", [1e-4, 1e-3, 1e-2])
def test_scale_mismatch_static_and_2_position_against_leading_order(size):
    imperfections = Imperfections(scale_factor_x=size, scale_factor_y=-size)
    leading = _value("scale_mismatch", k_x=size, k_y=-size, psi=math.radians(HEADING))
    for scheme, length in ((Static(), 100), (Indexing(2, 10, 2), 240)):
        shift = _heading_shift(
            imperfection_effect(scheme.pattern(length), imperfections, LATITUDE, HEADING, RATE)
        )
        assert abs(shift - leading) <= 2 * size * abs(leading)  # second order in the size
    for scheme, length in ((Carousel(20), 200), (Indexing(4, 10, 2), 240)):
        shift = _heading_shift(
            imperfection_effect(scheme.pattern(length), imperfections, LATITUDE, HEADING, RATE)
        )
        assert abs(shift) < 1e-12


@pytest.mark.parametrize(("tilt", "wobble"), [(1e-4, 0.001), (1e-3, 0.01)])
def test_misalignment_with_open_loop_wobble_against_leading_order(tilt, wobble):
    pattern = Carousel(200).pattern(20_000)
    reference = imperfection_effect(
        pattern, Imperfections(measured_angles=False, rate_wobble=wobble), LATITUDE, HEADING, RATE
    )
    effect = imperfection_effect(
        pattern,
        Imperfections(measured_angles=False, rate_wobble=wobble, misalignment_x=tilt),
        LATITUDE,
        HEADING,
        RATE,
    )
    omega = 2 * math.pi * RATE / 200
    magnitude = EARTH_RATE * math.cos(math.radians(LATITUDE))
    coupling = np.linalg.norm(effect.bias - reference.bias) / magnitude
    latitude = math.radians(LATITUDE)
    leading = _value("misalignment_wobble", epsilon=tilt, wobble=wobble, omega_r=omega, L=latitude)
    assert abs(coupling - leading) <= 0.02 * leading


def test_measured_angles_cancel_the_rate_coupling_to_discretisation_order():
    pattern = Carousel(200).pattern(20_000)
    base = Imperfections(rate_wobble=0.01)
    tilted = Imperfections(rate_wobble=0.01, misalignment_x=1e-3)
    difference = (
        imperfection_effect(pattern, tilted, LATITUDE, HEADING, RATE).bias
        - imperfection_effect(pattern, base, LATITUDE, HEADING, RATE).bias
    )
    latitude = math.radians(LATITUDE)
    open_loop = _value("misalignment_wobble", epsilon=1e-3, wobble=0.01, omega_r=math.pi, L=latitude)
    assert np.linalg.norm(difference) / (EARTH_RATE * math.cos(math.radians(LATITUDE))) < 1e-3 * open_loop


def test_encoder_noise_heading_variance_is_exact_and_its_derivative_is_the_sympy_one():
    pattern = Carousel(100).pattern(1000)
    for sigma in (0.01, 0.3):
        effect = imperfection_effect(pattern, Imperfections(angle_noise=sigma), LATITUDE, HEADING, RATE)
        earth = horizontal_earth_rate(LATITUDE, HEADING)
        across = np.array([earth[1], -earth[0]]) / np.linalg.norm(earth)
        variance = across @ effect.covariance @ across / float(earth @ earth)
        assert math.isclose(variance, _value("angle_noise", sigma_e=sigma, n=1000), rel_tol=1e-12)
        step = 1e-6
        numeric = (
            imperfection_effect(
                pattern, Imperfections(angle_noise=sigma + step), LATITUDE, HEADING, RATE
            ).covariance
            - imperfection_effect(
                pattern, Imperfections(angle_noise=sigma - step), LATITUDE, HEADING, RATE
            ).covariance
        ) / (2 * step)
        symbols = {s.name: s for s in LEADING_ORDER["angle_noise"][0].free_symbols}
        derivative = float(
            sensitivity("angle_noise", "sigma_e").subs({symbols["sigma_e"]: sigma, symbols["n"]: 1000})
        )
        assert math.isclose(across @ numeric @ across / float(earth @ earth), derivative, rel_tol=1e-6)


def test_rate_noise_heading_variance_tends_to_the_rrw_average_form():
    pattern = Carousel(50).pattern(500)
    sigma = 1e-4
    effect = imperfection_effect(
        pattern, Imperfections(rate_noise=sigma, measured_angles=False), LATITUDE, 0.0, RATE
    )
    earth = horizontal_earth_rate(LATITUDE, 0.0)
    across = np.array([earth[1], -earth[0]]) / np.linalg.norm(earth)
    variance = across @ effect.covariance @ across / float(earth @ earth)
    assert math.isclose(variance, _value("rate_noise", sigma_nu=sigma, n=500), rel_tol=1e-4)


def test_sensitivities_are_derivatives():
    assert sensitivity("angle_bias", "beta") == -1
    epsilon = sp.Symbol("epsilon", real=True)
    assert (
        sp.simplify(
            sensitivity("misalignment_wobble", "epsilon")
            - sp.diff(LEADING_ORDER["misalignment_wobble"][0], epsilon)
        )
        == 0
    )


def test_ideal_set_up_adds_nothing():
    effect = imperfection_effect(Carousel(20).pattern(200), Imperfections(), LATITUDE, HEADING, RATE)
    np.testing.assert_allclose(effect.bias, 0, atol=1e-12 * EARTH_RATE)  # rounding of the sums only
    np.testing.assert_array_equal(effect.covariance, 0)


@pytest.mark.parametrize(
    ("call", "error", "message"),
    [
        (lambda: Imperfections(angle_noise=-1.0), ValueError, "angle_noise=-1.0: must be >= 0"),
        (lambda: Imperfections(rate_wobble=math.inf), ValueError, "rate_wobble=inf"),
        (lambda: Imperfections(wobble_harmonic=0), ValueError, "wobble_harmonic=0"),
        (lambda: Imperfections(measured_angles="yes"), TypeError, "measured_angles='yes'"),
        (lambda: Imperfections(misalignment_x="1"), TypeError, "misalignment_x='1'"),
        (
            lambda: imperfection_effect(TwoAxisCarousel(4).pattern(8), Imperfections(), 10.0),
            ValueError,
            "rotations about the vertical",
        ),
        (lambda: imperfection_effect(Static().pattern(8), None, 10.0), TypeError, "imperfections=None"),
        (
            lambda: imperfection_effect(Static().pattern(8), Imperfections(), 95.0),
            ValueError,
            "latitude=95.0",
        ),
        (lambda: sensitivity("wind", "x"), ValueError, "name='wind'"),
        (lambda: sensitivity("angle_bias", "x"), ValueError, "parameter='x'"),
    ],
    ids=[
        "negative",
        "infinite",
        "harmonic",
        "flag",
        "text",
        "two-axis",
        "none",
        "latitude",
        "name",
        "parameter",
    ],
)
def test_invalid_calls(call, error, message):
    with pytest.raises(error, match=message):
        call()


def test_all_is_honest():
    assert public_functions(module) <= set(module.__all__)


@given(
    sigma=st.floats(0.0, 1.5),
    turns=st.integers(1, 5),
    per_turn=st.integers(3, 40),
    heading=st.floats(-180.0, 180.0),
)
@example(sigma=0.0, turns=1, per_turn=3, heading=0.0)
def test_registry_encoder_noise_form_is_the_exact_cross_track_variance(sigma, turns, per_turn, heading):
    from carousel_theory.formulas import formula

    length = turns * per_turn
    effect = imperfection_effect(
        Carousel(per_turn).pattern(length), Imperfections(angle_noise=sigma), LATITUDE, heading, RATE
    )
    earth = horizontal_earth_rate(LATITUDE, heading)
    across = np.array([earth[1], -earth[0]]) / np.linalg.norm(earth)
    variance = across @ effect.covariance @ across / float(earth @ earth)
    expected = formula("heading_encoder_noise_var").numeric(sigma_e=sigma, n=length)
    assert math.isclose(variance, expected, rel_tol=1e-9, abs_tol=1e-300)


@given(beta=st.floats(-0.5, 0.5), heading=st.floats(-180.0, 180.0), per_turn=st.floats(3.0, 50.0))
def test_registry_angle_bias_form_is_exact_for_any_carousel(beta, heading, per_turn):
    from carousel_theory.formulas import formula

    effect = imperfection_effect(
        Carousel(per_turn).pattern(97), Imperfections(angle_bias=beta), LATITUDE, heading, RATE
    )
    earth = horizontal_earth_rate(LATITUDE, heading)
    x, y = earth + effect.bias
    shift = math.remainder(math.atan2(-y, x) - math.radians(heading), 2 * math.pi)
    assert abs(shift - formula("heading_angle_bias").numeric(beta=beta)) < 1e-9
