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
(Ann. Stat. 33(4), 2005), the estimator SJ 2012 §V cites for its d = 0.535. The variances σ_w², σ_v²
of the prediction model are estimated in :mod:`carousel_theory.restricted_likelihood`.
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
    "WhittleEstimate",
    "autoregressive_coefficients",
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
    """Full linear convolution along the last axis (broadcasting over leading axes), by real FFT.

    The product is formed in place, so at most two spectra are alive at a time (two arrays of about
    twice the input length each, not the three of a separate product): this bounds the memory the
    1/f variance of a linear statistic needs on a record of 4·10⁷ samples."""
    length = values.shape[-1] + kernel.shape[-1] - 1
    size = scipy_fft.next_fast_len(length, real=True)
    spectrum = scipy_fft.rfft(values, size, axis=-1)
    kernel_spectrum = scipy_fft.rfft(kernel, size, axis=-1)
    if np.broadcast_shapes(spectrum.shape, kernel_spectrum.shape) == spectrum.shape:
        spectrum *= kernel_spectrum
    else:
        spectrum = spectrum * kernel_spectrum
    del kernel_spectrum
    return scipy_fft.irfft(spectrum, size, axis=-1, overwrite_x=True)[..., :length]


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
