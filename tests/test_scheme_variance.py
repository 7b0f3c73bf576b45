"""Covariance of the Earth-rate estimate of every scheme: against dense matrices, exact sums, the registry."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import example, given
from hypothesis import strategies as st

from carousel_theory.fitting import NoiseModel
from carousel_theory.formulas import formula
from carousel_theory.processes import covariance_matrix
from carousel_theory.rotation_schemes import (
    Carousel,
    Indexing,
    MeasuredProfile,
    Static,
    TwoAxisCarousel,
    demodulation_weights,
)
from carousel_theory.scheme_variance import estimate_covariances, unit_covariances

SCHEMES = [
    Static(),
    Carousel(6),
    Carousel(5.5),
    Indexing(2, 3, 1),
    Indexing(4, 2, 1, use_transitions=True),
    MeasuredProfile.from_array([0.1, 0.9, 2.0, 3.3, 4.1, 5.9, 6.0]),
    TwoAxisCarousel(4),
]
D = 0.35


@pytest.mark.parametrize("scheme", SCHEMES, ids=lambda s: type(s).__name__)
@pytest.mark.parametrize("gyro", [0, 1, 2])
def test_every_length_against_dense_covariance_matrices(scheme, gyro):
    """W C Wᵀ with the (n×n) covariance matrix of each process, for every prefix length up to 36."""
    lengths = list(range(1, 37))
    pattern = scheme.pattern(36)
    if not np.any(pattern.used[:1]):
        lengths = lengths[1:]
    result = unit_covariances(pattern, lengths, gyro, d=D)
    for index, n in enumerate(lengths):
        W = demodulation_weights(scheme.pattern(n))[:, gyro, :]
        for process in ("bias", "white", "rrw", "flicker"):
            dense = W @ covariance_matrix(process, n, d=D if process == "flicker" else None) @ W.T
            np.testing.assert_allclose(result[process][index], dense, rtol=1e-11, atol=1e-14, err_msg=process)


def _exact_indexing_weights(positions, dwell, gap, cycles):
    """Exact weights of component 1 (x, y gyro), 2 or 4 positions: cos φ and −sin φ at φ = 2πp/P."""
    cosine = {2: [1, -1], 4: [1, 0, -1, 0]}[positions]
    sine = {2: [0, 0], 4: [0, 1, 0, -1]}[positions]
    step = Fraction(1, positions * dwell * cycles)
    x, y = [], []
    for _ in range(cycles):
        for p in range(positions):
            x += [step * cosine[p]] * dwell + [Fraction(0)] * gap
            y += [-step * sine[p]] * dwell + [Fraction(0)] * gap
    return x, y


def _suffix_squares(weights):
    total, suffix = Fraction(0), Fraction(0)
    for value in reversed(weights):
        suffix += value
        total += suffix * suffix
    return total


@pytest.mark.parametrize("positions", [2, 4])
def test_registry_closed_forms_against_exact_sums(positions):
    for dwell in range(1, 5):
        for gap in range(3):
            for cycles in range(1, 4):
                x, y = _exact_indexing_weights(positions, dwell, gap, cycles)
                rrw = _suffix_squares(x) + _suffix_squares(y)
                white = sum(w * w for w in x + y)
                bias = sum(x) ** 2 + sum(y) ** 2
                name = f"indexing{positions}"
                assert formula(f"{name}_rrw_var").exact(N=dwell, k=cycles, g=gap) == rrw
                assert formula(f"{name}_white_var").exact(N=dwell, k=cycles) == white
                assert formula(f"{name}_bias_var").exact(N=dwell, k=cycles) == bias == 0


@given(
    positions=st.sampled_from([2, 4]),
    dwell=st.integers(1, 40),
    gap=st.integers(0, 12),
    cycles=st.integers(1, 6),
)
@example(positions=2, dwell=1, gap=0, cycles=1)
@example(positions=4, dwell=40, gap=12, cycles=6)
def test_registry_closed_forms_against_the_propagation(positions, dwell, gap, cycles):
    scheme = Indexing(positions, dwell, gap)
    n = cycles * scheme.cycle_length()
    pattern = scheme.pattern(n)
    total = {
        p: sum(unit_covariances(pattern, [n], g)[p][0] for g in (0, 1)) for p in ("bias", "white", "rrw")
    }
    name = f"indexing{positions}"
    rrw = formula(f"{name}_rrw_var").numeric(N=dwell, k=cycles, g=gap)
    white = formula(f"{name}_white_var").numeric(N=dwell, k=cycles)
    np.testing.assert_allclose(np.diag(total["rrw"]), [rrw, rrw], rtol=1e-12)
    np.testing.assert_allclose(np.diag(total["white"]), [white, white], rtol=1e-12)
    assert abs(total["rrw"][0, 1]) <= 1e-12 * rrw
    np.testing.assert_allclose(total["bias"], 0, atol=1e-28)


def test_carousel_matches_tim2014_closed_forms():
    """Integer N, k turns: RRW csc²(π/N)/(2Nk) (TIM 2014 eq. (17)-(18), bins uncorrelated), white 1/(kN)."""
    N, turns = 12, 5
    pattern = Carousel(N).pattern(N * turns)
    total = {
        p: sum(unit_covariances(pattern, [N * turns], g)[p][0] for g in (0, 1)) for p in ("white", "rrw")
    }
    expected_rrw = formula("rrw_carousel_var").numeric(N=N) / turns
    np.testing.assert_allclose(np.diag(total["rrw"]), expected_rrw, rtol=1e-12)
    np.testing.assert_allclose(np.diag(total["white"]), 1 / (N * turns), rtol=1e-12)


def test_estimate_covariances_scales_each_process_by_its_gyro_variance():
    pattern = Carousel(6).pattern(24)
    x = NoiseModel(100.0, white_variance=2.0, rrw_variance=0.5, flicker_variance=0.25, flicker_d=D)
    y = NoiseModel(100.0, white_variance=3.0, rrw_variance=0.0)
    result = estimate_covariances(pattern, [12, 24], [x, y], bias_variance=4.0)[1]
    unit_x, unit_y = unit_covariances(pattern, [24], 0, d=D), unit_covariances(pattern, [24], 1)
    np.testing.assert_allclose(result.white, 2 * unit_x["white"][0] + 3 * unit_y["white"][0])
    np.testing.assert_allclose(result.rrw, 0.5 * unit_x["rrw"][0])
    np.testing.assert_allclose(result.flicker, 0.25 * unit_x["flicker"][0])
    np.testing.assert_allclose(result.bias, 4 * (unit_x["bias"][0] + unit_y["bias"][0]), atol=1e-30)
    assert result.length == 24 and result.used == 24


@pytest.mark.parametrize(
    ("call", "error", "message"),
    [
        (lambda: unit_covariances(Static().pattern(5), [6], 0), ValueError, "must not exceed"),
        (lambda: unit_covariances(Static().pattern(5), [0], 0), ValueError, "length=0"),
        (
            lambda: unit_covariances(
                MeasuredProfile.from_array([0.0, 1.0], [False, True]).pattern(4), [1, 3], 0
            ),
            ValueError,
            "at least one sample",
        ),
        (lambda: estimate_covariances(Static().pattern(5), [5], []), TypeError, "noise="),
        (
            lambda: estimate_covariances(Static().pattern(5), [5], [NoiseModel(1.0)], bias_variance=-1),
            ValueError,
            "bias_variance=-1",
        ),
    ],
    ids=["too-long", "zero", "only-dropped", "no-noise", "negative-bias"],
)
def test_invalid_calls(call, error, message):
    with pytest.raises(error, match=message):
        call()


@pytest.mark.parametrize("scheme", SCHEMES, ids=lambda s: type(s).__name__)
def test_the_y_gyro_shortcut_equals_its_own_propagation(scheme):
    """About the vertical the y gyro's covariances are J C Jᵀ of the x gyro's; checked against gyro 1."""
    model = NoiseModel(100.0, white_variance=2.0, rrw_variance=0.5, flicker_variance=0.25, flicker_d=D)
    pattern = scheme.pattern(30)
    lengths = [7, 30]
    result = estimate_covariances(pattern, lengths, [model], bias_variance=3.0)
    gyros = (0, 1) if pattern.components == 2 else (0, 1, 2)
    units = [unit_covariances(pattern, lengths, gyro, d=D) for gyro in gyros]
    for index in range(2):
        for name, variance in (("bias", 3.0), ("white", 2.0), ("rrw", 0.5), ("flicker", 0.25)):
            expected = variance * sum(unit[name][index] for unit in units)
            np.testing.assert_allclose(getattr(result[index], name), expected, rtol=1e-12, atol=1e-15)
