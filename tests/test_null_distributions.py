"""The finite-sample null distributions of the spectral detectors: exact against an independent exact
sum for small sizes, and the saddlepoint tail of a ratio of medians against a seeded Monte Carlo."""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest
from conftest import Z_MONTE_CARLO

from carousel_theory.closed_loop.null_distributions import (
    exponential_over_median_log_sf,
    median_coefficients,
    median_ratio_log_sf,
)


def _order_statistic_laplace(count: int, rank: int, s: int) -> Fraction:
    """E[e^{−s E_(rank)}] for the rank-th of ``count`` Exp(1) values, from the order-statistic density
    n!/((k−1)!(n−k)!) F^{k−1} (1−F)^{n−k} f with F = 1 − e^{−x}, expanded binomially and integrated
    term by term: C Σ_j C(k−1, j) (−1)^j / (s + n − k + 1 + j) — exact in rationals."""
    constant = Fraction(math.factorial(count), math.factorial(rank - 1) * math.factorial(count - rank))
    total = sum(Fraction(math.comb(rank - 1, j) * (-1) ** j, s + count - rank + 1 + j) for j in range(rank))
    return constant * total


@pytest.mark.parametrize("count", [1, 3, 5, 9])
@pytest.mark.parametrize("s", [1, 2, 7])
def test_exponential_over_median_matches_the_order_statistic_density(count, s):
    """For odd sizes the median is E_((n+1)/2); the product formula equals the exact integral."""
    u = s * math.log(2.0)  # the function's argument is u = s ln 2
    expected = _order_statistic_laplace(count, (count + 1) // 2, s)
    assert math.exp(exponential_over_median_log_sf(u, count)) == pytest.approx(float(expected), rel=1e-12)


def test_median_coefficients_of_an_even_count_average_the_middle_pair():
    """Rényi: E_(k) = Σ_{i≤k} Z_i/(n − i + 1); for n = 4, (E_(2) + E_(3))/2 = Z₁/4 + Z₂/3 + Z₃/4."""
    assert median_coefficients(4).tolist() == pytest.approx([1 / 4, 1 / 3, 1 / 4], rel=1e-15)
    with pytest.raises(ValueError, match="count=0"):
        median_coefficients(0)


@pytest.mark.parametrize(
    ("numerator", "denominator", "ratio"), [(31, 40, 1.2), (40, 31, 0.9), (64, 64, 1.15)]
)
def test_median_ratio_tail_against_monte_carlo(numerator, denominator, ratio):
    """P(M₁/M₂ ≥ q) by the saddlepoint against 200,000 seeded draws; the tail probabilities here (0.1–0.4)
    are resolved to better than 2 % at Z_MONTE_CARLO."""
    rng = np.random.default_rng(17)
    draws = 200_000
    first = np.median(rng.exponential(size=(draws, numerator)), axis=1)
    second = np.median(rng.exponential(size=(draws, denominator)), axis=1)
    observed = float(np.mean(first / second >= ratio))
    expected = math.exp(median_ratio_log_sf(ratio, numerator, denominator))
    standard_error = math.sqrt(expected * (1 - expected) / draws)
    assert Z_MONTE_CARLO * standard_error < 0.02 * expected
    assert abs(observed - expected) <= Z_MONTE_CARLO * standard_error


def test_exponential_over_median_of_an_even_count_against_monte_carlo():
    rng = np.random.default_rng(19)
    draws, count, u = 400_000, 16, 2.0
    level = np.median(rng.exponential(size=(draws, count)), axis=1) / math.log(2.0)
    observed = float(np.mean(rng.exponential(size=draws) > u * level))
    expected = math.exp(exponential_over_median_log_sf(u, count))
    standard_error = math.sqrt(expected * (1 - expected) / draws)
    assert Z_MONTE_CARLO * standard_error < 0.02 * expected
    assert abs(observed - expected) <= Z_MONTE_CARLO * standard_error
