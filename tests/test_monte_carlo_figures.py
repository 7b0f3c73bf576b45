"""Monte Carlo at the settings of TIM 2014 Fig. 4 (rate random walk) and Fig. 5 (1/f noise, d = 1/2):
N = 200 samples per bin, seeded generators, against the exact bin variances.

Each test pools several bins per realisation, (1/K) Σ_k x_k² / Var_k, so that the standard error,
estimated from the spread over realisations, accounts for the correlation between bins; and each
asserts that 2 % of the theory exceeds Z · SE, i.e. that a 2 % error in the prediction would fail.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest
import sympy as sp
from conftest import Z_MONTE_CARLO

from carousel_theory.formulas import formula
from carousel_theory.processes import sample_flicker, sample_rate_random_walk
from carousel_theory.propagation import flicker_bin_variances, weighted_sum_variance
from carousel_theory.weights import carousel_weights

N = 200


def assert_pooled_ratio_is_one(per_realisation: np.ndarray) -> None:
    mean = float(per_realisation.mean())
    standard_error = float(per_realisation.std(ddof=1) / math.sqrt(per_realisation.shape[0]))
    assert Z_MONTE_CARLO * standard_error < 0.02, "too few realisations to detect a 2 % error"
    assert abs(mean - 1) <= Z_MONTE_CARLO * standard_error, (mean, standard_error)


def averaged_bins(samples: np.ndarray) -> np.ndarray:
    realisations, length = samples.shape
    return samples.reshape(realisations, length // N, N).mean(axis=2)


def carouselled_bins(x_gyro: np.ndarray, y_gyro: np.ndarray) -> np.ndarray:
    """TIM 2014 eq. (6): −Σ_i ω_x sin(2πi/N)/N + Σ_i ω_y cos(2πi/N)/N per revolution."""
    sine, cosine = carousel_weights(N)
    shape = (x_gyro.shape[0], x_gyro.shape[1] // N, N)
    return -(x_gyro.reshape(shape) @ sine) + y_gyro.reshape(shape) @ cosine


def test_registry_rrw_average_equals_exact_propagation():
    """The closed form of the registry against the exact cumulative-sum propagation, N ≤ 12, k ≤ 4."""
    closed_form = formula("rrw_average_var")
    for size in range(1, 13):
        for bin_number in range(1, 5):
            weights = [Fraction(0)] * ((bin_number - 1) * size) + [Fraction(1, size)] * size
            exact = weighted_sum_variance(weights, "rrw", exact=True)
            assert closed_form.exact(N=size, k=bin_number) == sp.Rational(exact.numerator, exact.denominator)


def test_fig4_rate_random_walk_averaged_bins():
    """Bins 3–4 of the N-mean of RRW (σ_q² = 1), 100 000 realisations, against (k−1)N + (2N³+3N²+N)/(6N²)."""
    rng = np.random.default_rng(4)
    theory = np.array([formula("rrw_average_var").numeric(N=N, k=bin_number) for bin_number in (3, 4)])
    pooled = []
    for _ in range(10):
        means = averaged_bins(sample_rate_random_walk(4 * N, rng=rng, realisations=10_000))[:, 2:]
        pooled.append(np.mean(means**2 / theory, axis=1))
    assert_pooled_ratio_is_one(np.concatenate(pooled))


def test_fig4_rate_random_walk_carouselled_bins():
    """Carouselled RRW bins 1–110 (uncorrelated, TIM 2014 eq. (17)), 1000 realisations of both gyros."""
    rng = np.random.default_rng(41)
    bins = 110
    theory = formula("rrw_carousel_var").numeric(N=N)
    pooled = []
    for _ in range(4):
        x_gyro = sample_rate_random_walk(bins * N, rng=rng, realisations=250)
        y_gyro = sample_rate_random_walk(bins * N, rng=rng, realisations=250)
        pooled.append(np.mean(carouselled_bins(x_gyro, y_gyro) ** 2 / theory, axis=1))
    assert_pooled_ratio_is_one(np.concatenate(pooled))


def test_fig5_flicker_averaged_bins():
    """Bins 1–3 of the N-mean of 1/f noise (d = 1/2, σ_w² = 1), 80 000 realisations."""
    rng = np.random.default_rng(5)
    theory = flicker_bin_variances(0.5, N, 3, "averaged")
    pooled = []
    for _ in range(8):
        means = averaged_bins(sample_flicker(3 * N, rng=rng, d=0.5, realisations=10_000))
        pooled.append(np.mean(means**2 / theory, axis=1))
    assert_pooled_ratio_is_one(np.concatenate(pooled))


@pytest.mark.slow
def test_fig5_flicker_carouselled_bins():
    """Carouselled 1/f bins 1–25 (d = 1/2), 5000 realisations of both gyros."""
    rng = np.random.default_rng(51)
    bins = 25
    theory = flicker_bin_variances(0.5, N, bins, "carouselled")
    pooled = []
    for _ in range(5):
        x_gyro = sample_flicker(bins * N, rng=rng, d=0.5, realisations=1000)
        y_gyro = sample_flicker(bins * N, rng=rng, d=0.5, realisations=1000)
        pooled.append(np.mean(carouselled_bins(x_gyro, y_gyro) ** 2 / theory, axis=1))
    assert_pooled_ratio_is_one(np.concatenate(pooled))
