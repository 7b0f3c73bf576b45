"""Averaging and carouseling weight vectors of TIM 2014 eq. (12)–(13), and weights from measured angles."""

from __future__ import annotations

import mpmath
import numpy as np
import pytest
from conftest import functions_called_in, public_functions
from hypothesis import example, given
from hypothesis import strategies as st

from carousel_theory import weights
from carousel_theory.weights import (
    averaging_weights,
    carousel_weights,
    carousel_weights_from_angles,
    unit_circle_points,
)


def test_averaging_weights_eq12():
    np.testing.assert_array_equal(averaging_weights(4), [0.25] * 4)
    assert averaging_weights(1).tolist() == [1.0]


@pytest.mark.parametrize("N", [1, 2, 3, 4, 5, 7, 8, 12, 200, 301])
def test_carousel_weights_match_sine_and_cosine_at_40_digits(N):
    s, c = carousel_weights(N)
    with mpmath.workdps(40):
        for i in range(1, N + 1):
            assert (
                abs(s[i - 1] - float(mpmath.sinpi(mpmath.mpf(2 * i) / N) / N)) <= 4.5e-16 / N
            )  # two units in the last place of 1, scaled
            assert (
                abs(c[i - 1] - float(mpmath.cospi(mpmath.mpf(2 * i) / N) / N)) <= 4.5e-16 / N
            )  # two units in the last place of 1, scaled


@given(N=st.integers(1, 5000))
@example(N=1)
@example(N=2)
@example(N=4)
def test_symmetries_hold_exactly_in_floating_point(N):
    sine, cosine = unit_circle_points(N)
    assert sine[-1] == 0.0 and cosine[-1] == 1.0  # i = N is angle 2π
    if N % 2 == 0:  # TIM 2014 §III-D: N/2 pairs of opposite numbers
        half = N // 2
        np.testing.assert_array_equal(sine[:half], -sine[half:])
        np.testing.assert_array_equal(cosine[:half], -cosine[half:])
    if N % 4 == 0:
        assert sine[N // 4 - 1] == 1.0 and cosine[N // 4 - 1] == 0.0
    # sums vanish (eq. (8)) to rounding for N > 1, and s² + c² sums to 1/N (eq. (9))
    s, c = carousel_weights(N)
    if N > 1:
        assert abs(s.sum()) <= 4e-16 and abs(c.sum()) <= 4e-16
    assert abs(np.sum(s * s + c * c) - 1.0 / N) <= 1e-15 / N


def test_weights_from_uniform_angles_agree_with_eq13():
    N = 200
    s, c = carousel_weights(N)
    phi = 2 * np.pi * np.arange(1, N + 1) / N
    s_phi, c_phi = carousel_weights_from_angles(phi)
    assert np.max(np.abs(s_phi - s)) <= 1e-15 / N * 10
    assert np.max(np.abs(c_phi - c)) <= 1e-15 / N * 10


def test_weights_from_nonuniform_angles():
    phi = np.array([0.0, np.pi / 2, np.pi])
    s, c = carousel_weights_from_angles(phi)
    np.testing.assert_allclose(s, [0.0, 1 / 3, 0.0], atol=1e-16)
    np.testing.assert_allclose(c, [1 / 3, 0.0, -1 / 3], atol=1e-16)


INVALID_CALLS = [
    ("averaging N=0", lambda: averaging_weights(0), ValueError, "N=0"),
    ("averaging N float", lambda: averaging_weights(2.0), TypeError, "N=2.0"),
    ("carousel N=-3", lambda: carousel_weights(-3), ValueError, "N=-3"),
    ("carousel N bool", lambda: carousel_weights(True), TypeError, "N=True"),
    ("circle N=0", lambda: unit_circle_points(0), ValueError, "N=0"),
    ("angles nan", lambda: carousel_weights_from_angles([0.0, float("nan")]), ValueError, "index 1"),
    ("angles empty", lambda: carousel_weights_from_angles([]), ValueError, "at least 1"),
    ("angles 2-D", lambda: carousel_weights_from_angles([[0.0]]), ValueError, "1-dimensional"),
    ("angles text", lambda: carousel_weights_from_angles("abc"), TypeError, "phi"),
]


@pytest.mark.parametrize(
    ("call", "error", "fragment"), [c[1:] for c in INVALID_CALLS], ids=[c[0] for c in INVALID_CALLS]
)
def test_invalid_calls(call, error, fragment):
    with pytest.raises(error) as excinfo:
        call()
    assert fragment in str(excinfo.value)


def test_every_public_function_is_exported_and_covered_by_the_invalid_call_table():
    public = public_functions(weights)
    assert public == set(weights.__all__)
    assert public <= functions_called_in(INVALID_CALLS)
