"""Exact scaling of float64 arrays by powers of two.

``values · 2ᵏ`` is exact in binary while the result stays a normal number, and rounded once (to nearest)
where it falls below: the same result as :func:`numpy.ldexp`. When 2ᵏ is itself a normal float64
(−1022 ≤ k ≤ 1023) one multiplication by it gives that single rounding, more than ten times faster than
``ldexp`` on long arrays (a long recording is scaled this way on every Allan variance and noise check).
Beyond that range the scaling falls back to ``ldexp``.
"""

from __future__ import annotations

import numpy as np

__all__ = ["binary_exponent", "scaled_by_power_of_two"]

#: Exponents k for which 2ᵏ is a normal float64.
_NORMAL_EXPONENTS = range(-1022, 1024)


def binary_exponent(values: np.ndarray) -> int:
    """e with the largest magnitude of ``values`` in [2^(e−1), 2^e) (0 when every value is 0): scaling by
    2^(−e) brings it into [1/2, 1)."""
    return int(np.frexp(np.max(np.abs(values)))[1])


def scaled_by_power_of_two(values: np.ndarray, exponent: int, out: np.ndarray | None = None) -> np.ndarray:
    """``values · 2^exponent`` as :func:`numpy.ldexp` gives it, into ``out`` when given."""
    if exponent in _NORMAL_EXPONENTS:
        return np.multiply(values, 2.0**exponent, out=out)
    return np.ldexp(values, exponent, out=out)
