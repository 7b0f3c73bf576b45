"""The long-memory lag sums of :mod:`carousel_theory.tau_covariance` (non-overlapping estimator, and the
every-lag sums of short records): the in-place moving sums against their definition, block boundaries
that do not change a value, and the windowed lag sums against dense Toeplitz algebra."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from test_tau_covariance import _dense_toeplitz

from carousel_theory import symbols, tau_covariance
from carousel_theory.increment_sums import FLICKER_INCREMENT_AUTOCOVARIANCE
from carousel_theory.noise_model import NoiseModel, unit_flicker_increment_autocovariance
from carousel_theory.tau_covariance import (
    _moving_sum_in_place,
    _twice_moving_sum,
    allan_estimate_covariance,
    allan_estimate_variance,
)

MODELS = {
    "flicker+white": NoiseModel(sample_rate=1.0, flicker_variance=1.0, flicker_d=0.5, white_variance=0.5),
    "flicker-0.3+rrw": NoiseModel(sample_rate=1.0, flicker_variance=1.0, flicker_d=0.3, rrw_variance=0.01),
    "ar2+rrw": NoiseModel(sample_rate=1.0, ar_variance=1.0, ar_coefficients=(0.6, -0.2), rrw_variance=0.01),
    "white+rrw": NoiseModel(sample_rate=1.0, white_variance=2.0, rrw_variance=0.01),
}


@pytest.mark.parametrize("block", [1, 2, 3, 7, 1 << 18])
@pytest.mark.parametrize("m", [1, 2, 3, 5, 16])
def test_moving_sum_in_place_is_the_moving_sum(m, block, monkeypatch):
    # Integers: every sum is exact, so the in-place result must equal the definition exactly.
    monkeypatch.setattr(tau_covariance, "_MOVING_BLOCK", block)
    values = np.random.default_rng(5).integers(-1000, 1000, size=41).astype(np.float64)
    expected = np.array([values[k : k + m].sum() for k in range(len(values) - m + 1)])
    buffer = np.concatenate(([np.nan], values))  # the free slot
    result = _moving_sum_in_place(buffer, m)
    np.testing.assert_array_equal(result[1:], expected)
    assert np.shares_memory(result, buffer)


@pytest.mark.parametrize("m", [1, 2, 4, 9])
def test_twice_moving_sum_is_the_triangle(m, monkeypatch):
    monkeypatch.setattr(tau_covariance, "_MOVING_BLOCK", 3)
    values = np.random.default_rng(6).integers(-50, 50, size=60).astype(np.float64)
    triangle = np.convolve(np.ones(m), np.ones(m))  # g_m = B_m ⋆ B_m
    expected = np.convolve(values, triangle[::-1], mode="valid")
    buffer = np.concatenate(([0.0], values))
    np.testing.assert_array_equal(_twice_moving_sum(buffer, m)[1:], expected)


@pytest.mark.parametrize("block", [2, 5, 1 << 18])
@pytest.mark.parametrize("name", sorted(MODELS))
def test_non_overlapping_against_dense_toeplitz(name, block, monkeypatch):
    # Blocks of 2 and 5 cut every lag sum and every moving difference into many pieces.
    monkeypatch.setattr(tau_covariance, "_MOVING_BLOCK", block)
    sizes = np.array([1, 2, 4, 8, 16, 32])
    length = 200
    result = allan_estimate_covariance(MODELS[name], sizes, length, estimator="non-overlapping")
    dense = _dense_toeplitz(MODELS[name], sizes, length, "non-overlapping")
    assert np.all(np.abs(result.covariance - dense) <= result.truncation_bound + 1e-11 * np.abs(dense))
    if "flicker" not in name:
        assert np.all(result.truncation_bound == 0)
    variance = allan_estimate_variance(MODELS[name], sizes, length, estimator="non-overlapping")
    np.testing.assert_allclose(variance, np.diag(result.covariance), rtol=1e-13)


@pytest.mark.parametrize("name", sorted(MODELS))
def test_every_lag_sums_of_a_short_record_against_dense_toeplitz(name, monkeypatch):
    monkeypatch.setattr(tau_covariance, "_MOVING_BLOCK", 4)
    sizes = np.array([1, 3, 9])
    length = 150
    result = allan_estimate_covariance(MODELS[name], sizes, length, estimator="overlapping")
    dense = _dense_toeplitz(MODELS[name], sizes, length, "overlapping")
    np.testing.assert_allclose(result.covariance, dense, rtol=1e-11)


@pytest.mark.parametrize("d", ["1/5", "1/2", "4/5"])
def test_flicker_tail_bound_uses_the_increment_autocovariance(d):
    # The bound's γ_z(V) against FLICKER_INCREMENT_AUTOCOVARIANCE at 30 digits, and the bound against the
    # tail it bounds.
    d = sp.Rational(d)
    lag = 5000
    model = NoiseModel(sample_rate=1.0, flicker_variance=1.0, flicker_d=float(d))
    memory = tau_covariance._LongMemory(model, [(4, 4, 100, 100)], "non-overlapping", 100)
    bound = tau_covariance._flicker_tail_bound(memory, 1, 1, lag, 1)
    at_lag = {symbol: lag for symbol in FLICKER_INCREMENT_AUTOCOVARIANCE.free_symbols if symbol.name == "x"}
    gamma = float(FLICKER_INCREMENT_AUTOCOVARIANCE.subs({symbols.d: d, **at_lag}).evalf(30))
    expected = 2.0 * gamma**2 * (1.0 + (lag + 2.0 - float(d)) / (5.0 - 4.0 * float(d)))
    assert abs(bound - expected) <= 1e-12 * expected
    # And it bounds what it stands for: 2 Σ_{k≥V} γ_z(k)² (m_i = m_j = K = 1), here its first 10⁶ terms.
    tail = unit_flicker_increment_autocovariance(float(d), lag + 1_000_000)[lag:]
    assert bound >= 2.0 * float(np.dot(tail, tail))


@pytest.mark.parametrize(
    "model",
    [
        *MODELS.values(),
        NoiseModel(
            sample_rate=2.0,
            flicker_variance=0.7,
            flicker_d=0.6,
            white_variance=1.5,
            rrw_variance=0.01,
            quantization=0.05,
            ar_variance=0.4,
            ar_coefficients=(0.9, -0.1),
        ),
    ],
    ids=[*MODELS, "every-term"],
)
def test_held_increment_autocovariance_is_the_models(model):
    # Built term by term to spare record-length temporaries; the values must be the model's, bit for bit.
    length = 3000
    memory = tau_covariance._LongMemory(model, [(8, 8, 374, 374)], "non-overlapping", length)
    held = len(memory.gamma)
    expected = model.increment_autocovariance(max(held, length))
    assert np.all(expected[held:] == 0)  # what is not held is zero
    # Every window (a lag at each sign, both ends of what is held, and beyond it) holds the model's γ_z(|x|).
    reach = held + 5
    lags = np.abs(np.arange(-reach, reach + 1))
    window = memory._window(-reach, reach)
    assert window[0] == 0  # the free slot
    np.testing.assert_array_equal(
        window[1:], np.where(lags < held, expected[np.minimum(lags, held - 1)], 0.0)
    )
