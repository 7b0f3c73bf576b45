"""Fractional integration and differencing of a sequence started at t = 1, and estimation of the
memory parameter d.

The 1/f model of both papers is the fractional integral of white noise, TIM 2014 eq. (3),

    f_t = Σ_{i=1}^{t} ψ_{t−i} w_i,   ψ_j = Γ(j + d) / (Γ(j + 1) Γ(d)),

i.e. f = (1 − B)^{−d} w for a sequence that is zero before t = 1 (B is the backshift). Its
inverse, the fractional difference of SJ 2012 eq. (3) as corrected in ``paper_check.md``, is

    ∇^d x_t = Σ_{i=1}^{t} φ_{t−i} x_i,   φ_j = Γ(j − d) / (Γ(j + 1) Γ(−d)),

the coefficients of (1 − z)^d. Because (1 − z)^d (1 − z)^{−d} = 1 as formal power series,
``fractional_difference(fractional_integral(w, d), d) == w`` exactly for every d, not only for the
stationary range |d| < ½: the finite sums never meet the convergence question of the infinite past.
The autoregressive weights of SJ 2012 eq. (6) are π_j = −φ_j (j ≥ 1).

The memory parameter is estimated by the exact local Whittle estimator of Shimotsu and Phillips
(Ann. Stat. 33(4), 2005), the estimator SJ 2012 §V cites for its d = 0.535.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import fft as scipy_fft

from carousel_theory._validation import (
    check_finite_array,
    check_positive_integer,
    check_real,
)
from carousel_theory.processes import fractional_coefficients

__all__ = [
    "VarianceEstimate",
    "WhittleEstimate",
    "autoregressive_coefficients",
    "estimate_noise_variances",
    "exact_local_whittle",
    "fft_convolve",
    "fractional_difference",
    "fractional_difference_coefficients",
    "fractional_integral",
]

# Above this length the O(n²) direct sums give way to FFT convolution (relative error ~1e-15·log n).
_DIRECT_LIMIT = 256


def _check_order(name: str, value: object, low: float, high: float) -> float:
    result = float(check_real(name, value))
    if not (low < result < high):
        raise ValueError(f"{name}={value!r}: must satisfy {low} < {name} < {high}")
    return result


def fractional_difference_coefficients(d: float, length: int) -> np.ndarray:
    """φ_j = Γ(j − d) / (Γ(j + 1) Γ(−d)), j = 0 … length − 1: the coefficients of (1 − z)^d.

    Computed by the recursion φ_0 = 1, φ_j = φ_{j−1} (j − 1 − d) / j (no Gamma values, so no
    overflow). Any real d in (−1, 2) is accepted; for d = 0 all φ_j with j ≥ 1 vanish.
    """
    d = _check_order("d", d, -1.0, 2.0)
    length = check_positive_integer("length", length)
    j = np.arange(1, length, dtype=np.float64)
    phi = np.empty(length, dtype=np.float64)
    phi[0] = 1.0
    phi[1:] = np.cumprod((j - 1.0 - d) / j)
    return phi


def autoregressive_coefficients(d: float, length: int) -> np.ndarray:
    """π_j = −Γ(j − d) / (Γ(j + 1) Γ(−d)) for j = 1 … length: the weights of SJ 2012 eq. (6).

    ``f_t = Σ_{j=1}^{t−1} π_j f_{t−j} + w_t`` holds exactly for the process of TIM 2014 eq. (3);
    element ``[f_t]_i`` of SJ 2012 eq. (6) is ``π_{t−i}``. Returned as an array of length ``length``
    whose entry ``j − 1`` is π_j.
    """
    length = check_positive_integer("length", length)
    return -fractional_difference_coefficients(d, length + 1)[1:]


def fft_convolve(values: np.ndarray, kernel: np.ndarray) -> np.ndarray:
    """Full linear convolution along the last axis (broadcasting over leading axes), by real FFT."""
    length = values.shape[-1] + kernel.shape[-1] - 1
    size = scipy_fft.next_fast_len(length, real=True)
    product = scipy_fft.rfft(values, size, axis=-1) * scipy_fft.rfft(kernel, size, axis=-1)
    return scipy_fft.irfft(product, size, axis=-1)[..., :length]


def _causal_filter(coefficients: np.ndarray, values: np.ndarray) -> np.ndarray:
    """y_t = Σ_{i ≤ t} c_{t−i} x_i along the last axis (the sequence is zero before its start)."""
    n = values.shape[-1]
    if n <= _DIRECT_LIMIT:
        out = np.zeros(values.shape, dtype=np.float64)
        for lag in range(n):
            out[..., lag:] += coefficients[lag] * values[..., : n - lag]
        return out
    return fft_convolve(values, coefficients[:n])[..., :n]


def fractional_integral(white: np.ndarray, d: float) -> np.ndarray:
    """f_t = Σ_{i=1}^{t} ψ_{t−i} w_i (TIM 2014 eq. (3)) along the last axis of ``white``.

    Accepts one sequence or a 2-D array of sequences (one per row).
    """
    d = _check_order("d", d, 0.0, 1.0)
    values = np.asarray(white, dtype=np.float64)
    if values.ndim not in (1, 2):
        raise ValueError(f"white: must be a 1- or 2-dimensional array, got shape {values.shape}")
    check_finite_array("white", values.reshape(-1))
    return _causal_filter(fractional_coefficients(d, values.shape[-1]), values)


def fractional_difference(values: np.ndarray, d: float) -> np.ndarray:
    """∇^d x_t = Σ_{i=1}^{t} φ_{t−i} x_i, the d-th difference of SJ 2012 eq. (3) in its corrected form.

    Along the last axis; the inverse of :func:`fractional_integral` for the same d.
    """
    d = _check_order("d", d, -1.0, 2.0)
    array = np.asarray(values, dtype=np.float64)
    if array.ndim not in (1, 2):
        raise ValueError(f"values: must be a 1- or 2-dimensional array, got shape {array.shape}")
    check_finite_array("values", array.reshape(-1))
    return _causal_filter(fractional_difference_coefficients(d, array.shape[-1]), array)


@dataclass(frozen=True)
class WhittleEstimate:
    """An exact local Whittle estimate: ``d``, its asymptotic standard error 1/(2√m), the number of
    Fourier frequencies ``frequencies`` (m) and the sample length ``length``."""

    d: float
    standard_error: float
    frequencies: int
    length: int


def _mean_estimate(values: np.ndarray, d: float) -> float:
    # Shimotsu (2010, Econometric Theory 26) two-step rule: the sample mean for d ≤ ½, the first
    # observation for d ≥ ¾, a smooth cosine blend in between.
    if d <= 0.5:
        weight = 1.0
    elif d >= 0.75:
        weight = 0.0
    else:
        weight = 0.5 * (1.0 + np.cos(4.0 * np.pi * d))
    return float(weight * values.mean() + (1.0 - weight) * values[0])


def _whittle_objective(values: np.ndarray, d: float, m: int) -> float:
    n = values.shape[0]
    centred = values - _mean_estimate(values, d)
    differenced = _causal_filter(fractional_difference_coefficients(d, n), centred)
    transform = np.fft.rfft(differenced)[1 : m + 1]
    periodogram = np.abs(transform) ** 2 / (2.0 * np.pi * n)
    frequencies = 2.0 * np.pi * np.arange(1, m + 1) / n
    return float(np.log(periodogram.mean()) - 2.0 * d * np.mean(np.log(frequencies)))


def exact_local_whittle(
    values: np.ndarray,
    frequencies: int | None = None,
    bounds: tuple[float, float] = (-0.5, 1.5),
) -> WhittleEstimate:
    """The exact local Whittle estimate of d (Shimotsu and Phillips 2005, eq. (2.3)–(2.4)).

    Minimises R(d) = log Ĝ(d) − 2d · (1/m) Σ_{j=1}^{m} log λ_j, with Ĝ(d) = (1/m) Σ I_{∇^d x}(λ_j),
    λ_j = 2πj/n, where ∇^d x is the fractional difference of the series after subtracting the mean
    estimate of Shimotsu (2010). ``frequencies`` is the bandwidth m (default ⌊n^0.65⌋, the choice
    of the Shimotsu–Phillips simulations).
    """
    array = check_finite_array("values", values, min_length=16)
    n = array.shape[0]
    if frequencies is None:
        frequencies = int(n**0.65)
    m = check_positive_integer("frequencies", frequencies, minimum=2)
    if m > n // 2:
        raise ValueError(f"frequencies={frequencies!r}: must be at most n/2 = {n // 2}")
    low = _check_order("bounds[0]", bounds[0], -1.0, 2.0)
    high = _check_order("bounds[1]", bounds[1], -1.0, 2.0)
    if not low < high:
        raise ValueError(f"bounds={bounds!r}: must be increasing")
    from scipy.optimize import minimize_scalar  # imported here: slow to import, needed only here

    result = minimize_scalar(
        lambda order: _whittle_objective(array, order, m),
        bounds=(low, high),
        method="bounded",
        options={"xatol": 1e-6},
    )
    return WhittleEstimate(
        d=float(result.x), standard_error=1.0 / (2.0 * np.sqrt(m)), frequencies=m, length=n
    )


@dataclass(frozen=True)
class VarianceEstimate:
    """Restricted maximum-likelihood variances of the model y = b + f + v (f of TIM 2014 eq. (3)):
    ``driving_variance`` σ_w², ``white_variance`` σ_v², from ``sections`` independent sections of
    ``length`` samples each, at the fixed order ``d``."""

    driving_variance: float
    white_variance: float
    d: float
    sections: int
    length: int
    log_likelihood: float


def estimate_noise_variances(
    sections: np.ndarray, d: float = 0.5, ratio_bounds: tuple[float, float] = (1e-4, 1e4)
) -> VarianceEstimate:
    """REML estimates of σ_w² and σ_v² from independent sections (rows), each with its own unknown
    constant bias, at a fixed d.

    Each section is y = b1 + x with Cov x = σ_w² (Γ + ρ I), Γ the covariance of eq. (3) for unit
    driving variance and ρ = σ_v²/σ_w². With A = Γ + ρI and P_A = A⁻¹ − A⁻¹11ᵀA⁻¹/(1ᵀA⁻¹1), the
    restricted log-likelihood of K sections of length n is, up to a constant,
    −½ [K(n − 1) log σ_w² + K log|A| + K log(1ᵀA⁻¹1) + Σ_k y_kᵀ P_A y_k / σ_w²]; σ_w² is profiled out
    (σ̂_w² = Σ_k y_kᵀP_A y_k / (K(n − 1))) and log ρ maximised over ``ratio_bounds`` (a ratio at the
    bound means one component is not identified).
    """
    from scipy.linalg import cho_factor, cho_solve
    from scipy.optimize import minimize_scalar

    from carousel_theory.fast_prediction import fractional_covariance_rows

    data = np.asarray(sections, dtype=np.float64)
    if data.ndim != 2:
        raise ValueError(
            f"sections: must be a 2-dimensional array (sections, samples), got shape {data.shape}"
        )
    check_finite_array("sections", data.reshape(-1))
    count, n = data.shape
    if n < 3:
        raise ValueError(f"sections: must hold at least 3 samples each, got {n}")
    d = _check_order("d", d, 0.0, 1.0)
    low, high = (float(check_real("ratio_bounds", b)) for b in ratio_bounds)
    if not 0 < low < high:
        raise ValueError(f"ratio_bounds={ratio_bounds!r}: must satisfy 0 < low < high")
    gamma = fractional_covariance_rows(d, n, n)
    ones = np.ones(n)

    def profile(log_ratio: float) -> tuple[float, float]:
        matrix = gamma + np.exp(log_ratio) * np.eye(n)
        factor = cho_factor(matrix, lower=True, check_finite=False)
        log_det = 2.0 * float(np.log(np.diag(factor[0])).sum())
        solved_ones = cho_solve(factor, ones, check_finite=False)
        total_ones = float(ones @ solved_ones)
        solved = cho_solve(factor, data.T, check_finite=False)
        quadratic = (
            float(np.einsum("ij,ji->", data, solved)) - float(((data @ solved_ones) ** 2).sum()) / total_ones
        )
        scale = quadratic / (count * (n - 1))
        log_likelihood = -0.5 * (
            count * (n - 1) * (np.log(scale) + 1.0) + count * (log_det + np.log(total_ones))
        )
        return float(log_likelihood), scale

    result = minimize_scalar(
        lambda value: -profile(value)[0],
        bounds=(np.log(low), np.log(high)),
        method="bounded",
        options={"xatol": 1e-5},
    )
    log_likelihood, scale = profile(float(result.x))
    return VarianceEstimate(
        driving_variance=scale,
        white_variance=scale * float(np.exp(result.x)),
        d=d,
        sections=count,
        length=n,
        log_likelihood=log_likelihood,
    )
