"""Argument checks name the value and the rule."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import sympy as sp

from carousel_theory import _validation as v


@pytest.mark.parametrize(
    ("call", "error", "fragment"),
    [
        pytest.param(
            lambda: v.check_positive_integer("N", 0), ValueError, "N=0: must be an integer >= 1", id="N=0"
        ),
        pytest.param(
            lambda: v.check_positive_integer("N", 2.0), TypeError, "N=2.0: must be an integer", id="N float"
        ),
        pytest.param(lambda: v.check_positive_integer("N", True), TypeError, "N=True", id="N bool"),
        pytest.param(lambda: v.check_fractional_order("d", 1), ValueError, "0 < d < 1", id="d=1"),
        pytest.param(lambda: v.check_fractional_order("d", float("nan")), ValueError, "NaN", id="d nan"),
        pytest.param(lambda: v.check_correlation("rho", 1.5), ValueError, "[-1, 1]", id="rho>1"),
        pytest.param(lambda: v.check_bin_index("k", 5, 4), ValueError, "1..4", id="bin out"),
        pytest.param(lambda: v.check_finite_array("y", [1.0, np.inf]), ValueError, "at index 1", id="inf"),
        pytest.param(lambda: v.check_finite_array("y", []), ValueError, "at least 1", id="empty"),
        pytest.param(lambda: v.check_real("x", "3"), TypeError, "x='3'", id="str"),
    ],
)
def test_invalid_arguments(call, error, fragment):
    with pytest.raises(error) as excinfo:
        call()
    assert fragment in str(excinfo.value)


def test_exact_inputs_stay_exact():
    assert v.check_real("x", Fraction(1, 3)) == Fraction(1, 3)
    assert v.check_real("x", sp.Rational(1, 3)) == sp.Rational(1, 3)
    assert v.check_positive_integer("N", np.int64(7)) == 7
    assert v.check_positive_integer("N", sp.Integer(7)) == 7
