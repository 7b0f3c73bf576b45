"""The one check that a column can carry a noise model: a table of refused signals, and the bounds."""

from __future__ import annotations

import numpy as np
import pytest

from carousel_theory.fitting import fit_noise_model
from carousel_theory.signal_checks import (
    LARGEST_RATE,
    SMALLEST_SPREAD,
    UnusableSignalError,
    check_noise_signal,
)

_NOISE = np.random.default_rng(7).standard_normal(64)

INVALID = [
    ("two-samples", [1.0, 2.0], "2 sample(s); a noise model needs at least 3"),
    ("two-dimensional", np.ones((4, 4)), "16 sample(s)"),
    ("nan", [1.0, float("nan"), 2.0], "sample 1 is nan"),
    ("constant", np.full(10, -2.5), "constant (every sample is -2.5)"),
    ("all-zero", np.zeros(10), "constant (every sample is 0.0)"),
    ("too-large", _NOISE * 1e61, "within ±1e+60"),
    ("offset-too-large", 2e60 + np.arange(10.0) * 1e50, "within ±1e+60"),
    ("spread-too-small", _NOISE * 1e-61, "at least 1e-60"),
    ("subnormal", np.array([0.0, 5e-324, 0.0, 1e-323]), "at least 1e-60"),
]


@pytest.mark.parametrize(
    ("values", "fragment"), [case[1:] for case in INVALID], ids=[case[0] for case in INVALID]
)
def test_refused_signals_name_the_column_and_the_rule(values, fragment) -> None:
    with pytest.raises(UnusableSignalError, match=r"^run\.csv: column 'wx': ") as caught:
        check_noise_signal(values, "run.csv: column 'wx'")
    assert fragment in str(caught.value)
    assert isinstance(caught.value, ValueError)


def test_the_bounds_themselves_are_accepted() -> None:
    at_top = _NOISE * (LARGEST_RATE / np.max(np.abs(_NOISE)))
    at_bottom = _NOISE * (SMALLEST_SPREAD / np.std(_NOISE)) * (1 + 1e-12)
    np.testing.assert_array_equal(check_noise_signal(at_top, "x"), at_top)
    np.testing.assert_array_equal(check_noise_signal(at_bottom, "x"), at_bottom)


def test_fit_noise_model_refuses_a_constant_signal_by_name() -> None:
    with pytest.raises(UnusableSignalError, match="y: constant"):
        fit_noise_model(np.full(1000, 3.0), 100.0)
