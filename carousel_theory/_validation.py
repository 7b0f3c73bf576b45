"""Argument checks at the public boundary.

Every public function validates its arguments once, here, before any work, and raises a
``TypeError`` (wrong kind of value) or ``ValueError`` (right kind, outside the rule) whose
message has the form ``name=value!r: must be ...``.
"""

from __future__ import annotations

import math
import numbers
from fractions import Fraction
from typing import Any

import numpy as np
import sympy as sp

__all__ = [
    "check_bin_index",
    "check_boolean",
    "check_correlation",
    "check_finite_array",
    "check_fractional_order",
    "check_integer",
    "check_positive_integer",
    "check_positive_real",
    "check_real",
]


def _is_integer_value(value: Any) -> bool:
    if isinstance(value, bool):
        return False
    if isinstance(value, numbers.Integral):
        return True
    return isinstance(value, sp.Integer)


def check_integer(name: str, value: Any) -> int:
    """Return ``value`` as a Python ``int``; reject bools, floats and anything non-integral."""
    if not _is_integer_value(value):
        raise TypeError(f"{name}={value!r}: must be an integer (int, numpy integer or sympy Integer)")
    return int(value)


def check_boolean(name: str, value: Any) -> bool:
    """Return ``value`` after checking that it is ``True`` or ``False`` (not 0, 1 or a string)."""
    if not isinstance(value, bool):
        raise TypeError(f"{name}={value!r}: must be True or False")
    return value


def check_positive_integer(name: str, value: Any, minimum: int = 1) -> int:
    """Return ``value`` as an ``int`` after checking that it is an integer ≥ ``minimum``."""
    result = check_integer(name, value)
    if result < minimum:
        raise ValueError(f"{name}={value!r}: must be an integer >= {minimum}")
    return result


def check_real(name: str, value: Any) -> Any:
    """Accept a finite real number: int, float, Fraction, numpy scalar or real SymPy number.

    Exact inputs are returned unchanged (so that exact evaluation stays exact); floats are
    checked for NaN and infinity.
    """
    if isinstance(value, bool):
        raise TypeError(f"{name}={value!r}: must be a real number, not a bool")
    if isinstance(value, sp.Basic):
        if not (value.is_number and value.is_real):
            raise TypeError(f"{name}={value!r}: must be a real number")
        if not value.is_finite:
            raise ValueError(f"{name}={value!r}: must be finite")
        return value
    if isinstance(value, (numbers.Integral, Fraction)):
        return value
    if isinstance(value, numbers.Real):
        if math.isnan(float(value)):
            raise ValueError(f"{name}={value!r}: must be a number, not NaN")
        if math.isinf(float(value)):
            raise ValueError(f"{name}={value!r}: must be finite")
        return value
    try:  # mpmath mpf and friends
        import mpmath

        if isinstance(value, mpmath.mpf):
            if mpmath.isnan(value) or mpmath.isinf(value):
                raise ValueError(f"{name}={value!r}: must be a finite number")
            return value
    except ImportError:  # pragma: no cover - mpmath is a core dependency
        pass
    raise TypeError(f"{name}={value!r}: must be a real number")


def check_positive_real(name: str, value: Any, allow_zero: bool = False) -> Any:
    """A finite real number > 0 (or ≥ 0 with ``allow_zero``)."""
    result = check_real(name, value)
    if allow_zero and not result >= 0:
        raise ValueError(f"{name}={value!r}: must be >= 0")
    if not allow_zero and not result > 0:
        raise ValueError(f"{name}={value!r}: must be > 0")
    return result


def check_probability(name: str, value: Any) -> float:
    """A level or confidence strictly inside (0, 1)."""
    result = float(check_positive_real(name, value))
    if not result < 1:
        raise ValueError(f"{name}={value!r}: must be in (0, 1)")
    return result


def check_fractional_order(name: str, value: Any, low: Any = 0, high: Any = 1) -> Any:
    """The degree of fractional integration d, strictly inside (low, high).

    TIM 2014 eq. (3) uses 0 < d < 1.
    """
    result = check_real(name, value)
    if not (low < result < high):
        raise ValueError(f"{name}={value!r}: must satisfy {low} < {name} < {high}")
    return result


def check_correlation(name: str, value: Any) -> Any:
    """A correlation coefficient in [-1, 1]."""
    result = check_real(name, value)
    if not (-1 <= result <= 1):
        raise ValueError(f"{name}={value!r}: must lie in [-1, 1]")
    return result


def check_bin_index(name: str, value: Any, number_of_bins: int) -> int:
    """A bin number in 1 … number_of_bins (bins are numbered from 1, as in the papers)."""
    result = check_integer(name, value)
    if not (1 <= result <= number_of_bins):
        raise ValueError(f"{name}={value!r}: must be a bin number in 1..{number_of_bins}")
    return result


def check_not_complex(name: str, values: Any) -> None:
    """Refuse complex values: a cast to float64 would drop their imaginary parts with only a warning."""
    if np.iscomplexobj(values):
        raise TypeError(f"{name}: must be an array of real numbers, got complex values")


def check_finite_array(name: str, values: Any, ndim: int = 1, min_length: int = 1) -> np.ndarray:
    """Return ``values`` as a float64 array, refusing NaN/inf (with the first bad index), wrong
    dimension and too few samples."""
    check_not_complex(name, values)
    try:
        array = np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError) as error:
        raise TypeError(f"{name}: must be an array of real numbers ({error})") from None
    if array.ndim != ndim:
        raise ValueError(f"{name}: must be a {ndim}-dimensional array, got shape {array.shape}")
    if array.shape[0] < min_length:
        raise ValueError(f"{name}: must hold at least {min_length} samples, got {array.shape[0]}")
    bad = ~np.isfinite(array)
    if bad.any():
        index = tuple(int(i) for i in np.argwhere(bad)[0])
        where = index[0] if len(index) == 1 else index
        raise ValueError(f"{name}: must be finite, found {array[index]!r} at index {where}")
    return array
