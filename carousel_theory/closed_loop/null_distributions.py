"""Finite-sample null distributions of the spectral detectors, from the order statistics of Exp(1).

Under the fitted model each Hann-windowed periodogram ordinate divided by the model spectrum is, for
Gaussian data away from 0 and f_s/2, an Exp(1) variable (χ²₂/2; to O(1/n) for a smooth spectrum). The
spectral detectors divide ordinates by a *median* of such variables, so their null distributions are
those of ratios to exponential order statistics. These are exact, not asymptotic, by Rényi's
representation (Rényi 1953; David & Nagaraja, *Order Statistics*, 3rd ed., §2.5): the k-th smallest of
M independent Exp(1) variables is

    E_(k) = Σ_{i=1}^{k} Z_i / (M − i + 1),  Z_i independent Exp(1),

so a sample median is a positive linear combination of independent exponentials, whose Laplace transform
and cumulant generating function are finite products and sums.

- :func:`median_coefficients` gives those coefficients (NumPy's median of an even count averages the two
  middle order statistics: E_(r) + Z_{r+1} / (2(M − r))).
- :func:`exponential_over_median_log_sf`: log P(X > u M / ln 2) for X ~ Exp(1) independent of the
  median M of M' Exp(1) values, = E[e^{−(u/ln 2) M}] = Π_i 1/(1 + c_i u/ln 2), exact.
- :func:`median_ratio_log_sf`: log P(M₁ / M₂ ≥ q) for independent medians, by the Lugannani–Rice
  saddlepoint approximation to the exact cumulant generating function of M₁ − q M₂ (Lugannani & Rice
  1980; Butler, *Saddlepoint Approximations with Applications*, 2007, §1.2): relative error O(1/M)
  uniformly in the tail, i.e. about 10⁻³ for the thousands of ordinates the detector uses.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import optimize, stats

__all__ = ["exponential_over_median_log_sf", "median_coefficients", "median_ratio_log_sf"]


def median_coefficients(count: int) -> np.ndarray:
    """c with median of ``count`` iid Exp(1) = Σ c_i Z_i, Z_i iid Exp(1) (Rényi's representation)."""
    if count < 1:
        raise ValueError(f"count={count!r}: must be at least 1")
    half = count // 2
    if count % 2:  # E_(half + 1)
        return 1.0 / (count - np.arange(half + 1, dtype=np.float64))
    # (E_(half) + E_(half + 1)) / 2 = E_(half) + Z_{half+1} / (2 (count − half))
    lower = 1.0 / (count - np.arange(half, dtype=np.float64))
    return np.concatenate((lower, [0.5 / (count - half)]))


def exponential_over_median_log_sf(u: float, count: int) -> float:
    """log P(X > u · M / ln 2), X ~ Exp(1) independent of M, the median of ``count`` Exp(1) values.

    Given M the probability is e^{−uM/ln 2}; its mean is the Laplace transform of M at s = u/ln 2,
    Π_i 1/(1 + s c_i) with the c_i of :func:`median_coefficients` — exact. For count → ∞ it tends to
    e^{−u}, the Exp(1) tail of a ratio to the true median level ln 2.
    """
    s = max(float(u), 0.0) / math.log(2.0)
    return -float(np.sum(np.log1p(s * median_coefficients(count))))


def _cumulants(s: float, positive: np.ndarray, negative: np.ndarray) -> tuple[float, float, float]:
    """K, K′, K″ at s of Σ a_i Z_i − Σ b_j Z′_j (a, b > 0, Z iid Exp(1)):
    K = −Σ log(1 − s a) − Σ log(1 + s b)."""
    p, q = 1.0 - s * positive, 1.0 + s * negative
    value = -float(np.sum(np.log(p)) + np.sum(np.log(q)))
    first = float(np.sum(positive / p) - np.sum(negative / q))
    second = float(np.sum((positive / p) ** 2) + np.sum((negative / q) ** 2))
    return value, first, second


def median_ratio_log_sf(ratio: float, numerator_count: int, denominator_count: int) -> float:
    """log P(M₁ / M₂ ≥ ``ratio``) for independent medians of ``numerator_count`` and ``denominator_count``
    Exp(1) values: P(D ≥ 0), D = M₁ − ratio · M₂, by the Lugannani–Rice formula on D's exact cumulant
    generating function K: ŝ solves K′(ŝ) = 0, w = sign(ŝ)√(−2K(ŝ)), v = ŝ√K″(ŝ),
    P(D ≥ 0) ≈ Φ̄(w) + φ(w)(1/v − 1/w), evaluated in logs (the Mills ratio φ/Φ̄ from log densities) so
    that a tail of 10⁻¹⁰⁰⁰ does not underflow."""
    positive = median_coefficients(numerator_count)
    negative = float(ratio) * median_coefficients(denominator_count)
    mean = float(positive.sum() - negative.sum())
    _, _, variance = _cumulants(0.0, positive, negative)
    if abs(mean) < 1e-6 * math.sqrt(variance):  # at the mean: the normal limit (the formula is 0/0)
        return float(stats.norm.logsf(-mean / math.sqrt(variance)))
    low, high = -1.0 / negative.max(), 1.0 / positive.max()
    margin = 1e-12 * min(-low, high)
    root = optimize.brentq(lambda s: _cumulants(s, positive, negative)[1], low + margin, high - margin)
    value, _, second = _cumulants(root, positive, negative)
    w = math.copysign(math.sqrt(max(-2.0 * value, 0.0)), root)
    v = root * math.sqrt(second)
    log_normal_tail = float(stats.norm.logsf(w))
    mills = math.exp(float(stats.norm.logpdf(w)) - log_normal_tail)
    correction = 1.0 + mills * (1.0 / v - 1.0 / w)
    return min(0.0, log_normal_tail + math.log(max(correction, 1e-300)))
