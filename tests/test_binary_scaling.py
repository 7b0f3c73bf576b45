"""Scaling by powers of two: the same bits as numpy.ldexp, also where results fall below the normal range
and where 2ᵏ itself is not a normal number (the fallback)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from carousel_theory.binary_scaling import binary_exponent, scaled_by_power_of_two


@given(
    st.lists(st.floats(allow_nan=False, allow_infinity=False, width=64), min_size=1, max_size=50),
    st.integers(-1100, 1100),
)
def test_same_bits_as_ldexp(values: list[float], exponent: int) -> None:
    array = np.array(values)
    with np.errstate(over="ignore", under="ignore"):
        expected = np.ldexp(array, exponent)
        got = scaled_by_power_of_two(array, exponent)
    np.testing.assert_array_equal(got.view(np.int64), expected.view(np.int64))


@pytest.mark.parametrize("exponent", [-1075, -1074, -1023, -1022, -60, 0, 1, 1023, 1024, 1074])
def test_edges_of_the_normal_range(exponent: int) -> None:
    tiny, huge = np.nextafter(0.0, 1.0), np.finfo(np.float64).max
    array = np.array(
        [tiny, 3 * tiny, 2.0**-1022, 1.5 * 2.0**-1000, 0.75, -0.75, 2.0**1000, huge, -huge, -0.0]
    )
    with np.errstate(over="ignore", under="ignore"):
        expected = np.ldexp(array, exponent)
        got = scaled_by_power_of_two(array, exponent)
    np.testing.assert_array_equal(got.view(np.int64), expected.view(np.int64))


def test_in_place() -> None:
    array = np.array([1.0, -3.0, 0.5])
    result = scaled_by_power_of_two(array, -2, out=array)
    assert result is array
    np.testing.assert_array_equal(array, [0.25, -0.75, 0.125])


@pytest.mark.parametrize(
    ("values", "expected"),
    [([0.5], 0), ([0.75, -0.25], 0), ([1.0], 1), ([-3.0, 2.0], 2), ([0.0, 0.0], 0), ([2.0**-1074], -1073)],
)
def test_binary_exponent(values: list[float], expected: int) -> None:
    """The largest magnitude lies in [2^(e−1), 2^e), so that scaling by 2^(−e) brings it into [1/2, 1)."""
    assert binary_exponent(np.array(values)) == expected
