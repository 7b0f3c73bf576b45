"""The 1/f Allan variance of a record, summed block by block, equals the one-pass running sum exactly."""

from __future__ import annotations

import numpy as np
import pytest

import carousel_theory.allan as allan
from carousel_theory.processes import fractional_coefficients


def _one_pass(d: float, sizes: np.ndarray, length: int, estimator: str) -> np.ndarray:
    """The expected estimate written directly: G(u) = Ψ_u − 2Ψ_{u−m} + Ψ_{u−2m} over the whole record,
    one running sum of G², averaged at the last index of each difference used."""
    psi_sum = np.cumsum(fractional_coefficients(d, length))
    result = []
    for m in sizes:
        G = psi_sum.copy()
        G[m:] -= 2.0 * psi_sum[:-m]
        if 2 * m < length:
            G[2 * m :] += psi_sum[: -2 * m]
        cumulative = np.cumsum(G**2)
        if estimator == "non-overlapping":
            last = np.arange(2, length // m + 1) * m - 1
        else:
            last = np.arange(2 * m - 1, length)
        result.append(cumulative[last].mean() / (2.0 * m * m))
    return np.array(result)


@pytest.mark.parametrize("estimator", ["non-overlapping", "overlapping"])
@pytest.mark.parametrize("block", [1, 7, 64, 1 << 20])
@pytest.mark.parametrize(("d", "length"), [(0.5, 200), (0.3, 1001), (0.8, 97)])
def test_blocks_give_the_one_pass_values_exactly(monkeypatch, estimator, block, d, length):
    monkeypatch.setattr(allan, "_SQUARE_BLOCK", block)
    sizes = np.array([1, 2, 3, 5, length // 3])
    got = allan.flicker_allan_variance(d, sizes, length, estimator)
    assert np.array_equal(got, _one_pass(d, sizes, length, estimator))
