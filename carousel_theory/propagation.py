"""Variance of linear statistics (bin means, carouselled means) of the error processes of TIM 2014 §II.

A statistic ``Σ_t w_t x_t`` of a process x started at t = 1 is a linear function of the process's
white driving noise; its variance is the squared norm of the coefficient each driving sample gets.
For the three driven processes (unit driving variance):

- white noise: ``Var = Σ_t w_t²``;
- rate random walk (TIM 2014 eq. (2)): driving sample q_i enters every r_t with t ≥ i, so
  ``Var = Σ_i (Σ_{t≥i} w_t)²`` — the general form of 1ᵀRRᵀ1 in eq. (15) and sᵀRRᵀs in eq. (17);
- 1/f noise (eq. (3)): w_i enters f_t with weight ψ_{t−i}, so ``Var = Σ_i (Σ_{t≥i} w_t ψ_{t−i})²`` —
  the general form of 1ᵀFFᵀ1 of §III-D. The inner sums are one correlation, done by FFT.

Bins. Bin k holds samples t = (k−1)N + 1 … kN and is reduced with a weight vector a_1 … a_N
(:mod:`carousel_theory.weights`). Writing j = kN − i for the driving sample i, the coefficient of w_i
in bin k is ``g_j = Σ_{u=1}^{N} a_u ψ_{u−N+j}`` (ψ of negative index is 0), **the same sequence for
every bin**; hence

    Var_k = Σ_{j=0}^{kN−1} g_j²,

and all bins k = 1 … k_max come from one cumulative sum. For plain averaging (a_u = 1/N),
``g_j = (Ψ_j − Ψ_{j−N}) / N`` with Ψ the cumulative sum of ψ. For carouseling, with z = e^{2πi/N}
and ``h_j = Σ_u z^u ψ_{u−N+j}``, the sine and cosine gyros give ``Im h_j / N`` and ``Re h_j / N``, so
the carouselled variance (two independent gyros, σ_w² = 1) is ``N⁻² Σ_{j<kN} |h_j|²``, and h obeys
the one-step recursion ``h_j = z̄ h_{j−1} + ψ_j − ψ_{j−N}``, h_{−1} = 0 (used at high precision).
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction
from typing import Any

import mpmath
import numpy as np
import scipy.signal
import sympy as sp
from scipy import fft as scipy_fft

from carousel_theory._validation import (
    check_finite_array,
    check_fractional_order,
    check_positive_integer,
)
from carousel_theory.processes import (
    _check_process,
    _exact_rational,
    fractional_coefficients,
    fractional_coefficients_exact,
)
from carousel_theory.weights import averaging_weights, carousel_weights

__all__ = [
    "BIN_METHODS",
    "flicker_averaged_bin_variance",
    "flicker_averaged_bin_variance_exact",
    "flicker_bin_variances",
    "flicker_bin_variances_high_precision",
    "flicker_carouselled_bin_variance",
    "repeated_weights_bin_variances",
    "weighted_sum_variance",
    "weighted_sums_covariance",
]

#: The two ways of reducing a bin: plain averaging (eq. (12)) and carouseling (eq. (13), two gyros).
BIN_METHODS = ("averaged", "carouselled")

#: Extra decimal digits carried by the high-precision recursions beyond the requested ``digits``.
_GUARD_DIGITS = 12


# --- argument helpers -----------------------------------------------------------------------------


def _check_order_for(process: str, d: Any) -> Any:
    if process == "flicker":
        if d is None:
            raise ValueError("d=None: the flicker process needs its order 0 < d < 1")
        return check_fractional_order("d", d)
    if d is not None:
        raise ValueError(f"d={d!r}: only the flicker process takes an order d, not {process!r}")
    return None


def _check_method(value: Any) -> str:
    if not isinstance(value, str):
        raise TypeError(f"method={value!r}: must be one of {BIN_METHODS}")
    if value not in BIN_METHODS:
        raise ValueError(f"method={value!r}: must be one of {BIN_METHODS}")
    return value


def _check_digits(value: Any) -> int | None:
    return None if value is None else check_positive_integer("digits", value)


def _exact_weights(weights: Any) -> list[Fraction]:
    if isinstance(weights, (str, bytes)) or not isinstance(weights, (Sequence, np.ndarray)):
        raise TypeError(f"weights={weights!r}: must be a sequence of exact rationals for exact=True")
    values = []
    for index, value in enumerate(weights):
        exact = _exact_rational(value)
        if exact is None:
            raise TypeError(
                f"weights[{index}]={value!r}: must be an exact rational (int, Fraction, sympy Rational) "
                "for exact=True"
            )
        values.append(exact)
    if not values:
        raise ValueError("weights: must hold at least 1 samples, got 0")
    return values


def _sum_of_squares_exact(values: Sequence[Fraction]) -> Fraction:
    return sum((value * value for value in values), Fraction(0))


# --- one linear statistic -------------------------------------------------------------------------


def weighted_sum_variance(weights: Any, process: str, d: Any = None, *, exact: bool = False) -> Any:
    """Var(Σ_{t=1}^{n} w_t x_t) for a process x of TIM 2014 §II started at t = 1, unit driving variance.

    Parameters
    ----------
    weights
        w_1 … w_n, a 1-D array of finite reals (or, with ``exact=True``, exact rationals).
    process
        ``"bias"`` ((Σ w)², eq. (1)), ``"white"`` (Σ w²), ``"rrw"`` (Σ_i (Σ_{t≥i} w_t)², eq. (2),
        O(n)) or ``"flicker"`` (Σ_i (Σ_{t≥i} w_t ψ_{t−i})², eq. (3), O(n log n) by FFT).
    d
        The order 0 < d < 1 of the 1/f noise; only for ``"flicker"``.
    exact
        Return an exact ``Fraction`` (weights and, for flicker, d must be exact rationals; the
        flicker sum then costs O(n²)).

    Returns
    -------
    float, or Fraction when ``exact``.
    """
    process = _check_process("process", process)
    d = _check_order_for(process, d)
    if not isinstance(exact, bool):
        raise TypeError(f"exact={exact!r}: must be True or False")
    if exact:
        values = _exact_weights(weights)
        if process == "flicker" and _exact_rational(d) is None:
            raise TypeError(f"d={d!r}: must be an exact rational (Fraction or sympy Rational) for exact=True")
        return _weighted_sum_variance_exact(values, process, d)
    w = check_finite_array("weights", weights)
    if process == "bias":
        return float(w.sum()) ** 2
    if process == "white":
        return float(np.dot(w, w))
    if process == "rrw":
        suffix = np.cumsum(w[::-1])  # Σ_{t≥i} w_t, in reverse order (order does not matter below)
        return float(np.dot(suffix, suffix))
    return _flicker_coefficient_norm(w, d)


def _flicker_coefficient_norm(w: np.ndarray, d: float) -> float:
    """Σ_i (Σ_{t≥i} w_t ψ_{t−i})² (TIM 2014 eq. (3)): the first n terms of the linear convolution of the
    reversed weights with ψ, by real FFT of one zero-padded length.

    The same transforms, product and inverse as :func:`~carousel_theory.long_memory.fft_convolve` (identical
    values), ordered for memory: ψ is transformed first and freed, one zero-padded buffer serves both
    transforms, and each array is released as soon as it is used, so at most three arrays of about twice
    the record length are alive (six record lengths, against seven with a padded copy per transform and
    ψ alive): this is the peak of the loop's joint warm-up refit on a record of 4·10⁷ samples."""
    n = w.shape[0]
    size = scipy_fft.next_fast_len(2 * n - 1, real=True)
    buffer = np.zeros(size, dtype=np.float64)
    buffer[:n] = fractional_coefficients(d, n)
    kernel_spectrum = scipy_fft.rfft(buffer)
    buffer[:n] = w[::-1]  # the rest of the buffer is still zero
    spectrum = scipy_fft.rfft(buffer)
    del buffer
    spectrum *= kernel_spectrum
    del kernel_spectrum
    coefficients = scipy_fft.irfft(spectrum, size, overwrite_x=True)[:n]
    del spectrum
    return float(np.dot(coefficients, coefficients))


def _weighted_sum_variance_exact(values: list[Fraction], process: str, d: Any) -> Fraction:
    n = len(values)
    if process == "bias":
        total = sum(values, Fraction(0))
        return total * total
    if process == "white":
        return _sum_of_squares_exact(values)
    if process == "rrw":
        suffix, squares = Fraction(0), Fraction(0)
        for value in reversed(values):
            suffix += value
            squares += suffix * suffix
        return squares
    psi = fractional_coefficients_exact(d, n)
    coefficients = [sum((values[t] * psi[t - i] for t in range(i, n)), Fraction(0)) for i in range(n)]
    return _sum_of_squares_exact(coefficients)


def weighted_sums_covariance(weights: Any, process: str, d: Any = None) -> np.ndarray:
    """Covariance matrix of several linear statistics Σ_t W[m, t] x_t of one realisation of a process.

    ``weights`` has shape (statistics, n): row m weights samples t = 1 … n of a process of TIM 2014 §II
    started at t = 1 (unit driving variance). Each row is turned into the coefficients of the
    driving noise (as in :func:`weighted_sum_variance`: the row itself for white noise, its suffix
    sums for rate random walk, its FFT correlation with ψ for 1/f noise, its total for bias), and
    the covariance is C Cᵀ: O(m n log n + m² n), never an n×n matrix. Bins of unequal length or with
    measured, non-uniform rotation angles (:func:`carousel_theory.weights.carousel_weights_from_angles`)
    are rows with their weights placed at their own samples.
    """
    process = _check_process("process", process)
    d = _check_order_for(process, d)
    W = check_finite_array("weights", weights, ndim=2)
    n = W.shape[1]
    if n < 1:
        raise ValueError(f"weights: must hold at least 1 sample per row, got shape {W.shape}")
    if process == "bias":
        coefficients = W.sum(axis=1, keepdims=True)
    elif process == "white":
        coefficients = W
    elif process == "rrw":
        coefficients = np.cumsum(W[:, ::-1], axis=1)
    else:
        coefficients = scipy.signal.fftconvolve(
            W[:, ::-1], fractional_coefficients(d, n)[np.newaxis, :], axes=1
        )[:, :n]
    return coefficients @ coefficients.T


# --- the same weights in every bin ----------------------------------------------------------------


def repeated_weights_bin_variances(weights: Any, process: str, k_max: int, d: Any = None) -> np.ndarray:
    """Var of bin k = 1 … k_max when every bin of N = len(weights) samples is reduced with the same weights.

    Bin k is ``Σ_{u=1}^{N} a_u x_{(k−1)N+u}`` for a process x of TIM 2014 §II started at t = 1 (unit
    driving variance). Without any (kN)×(kN) matrix:

    - bias: (Σ a)²; white: Σ a² (the same for every k);
    - rate random walk: ``(k−1) N (Σ a)² + Σ_u (Σ_{v≥u} a_v)²`` (the driving samples before the bin
      enter every sample of it);
    - 1/f noise: ``Σ_{j<kN} g_j²`` with ``g_j = Σ_u a_u ψ_{u−N+j}`` (module docstring), one FFT
      convolution and one cumulative sum for all k, O(k_max N log(k_max N)).

    Returns
    -------
    numpy.ndarray of shape (k_max,), float64.
    """
    process = _check_process("process", process)
    d = _check_order_for(process, d)
    a = check_finite_array("weights", weights)
    k_max = check_positive_integer("k_max", k_max)
    N = a.shape[0]
    if process == "bias":
        return np.full(k_max, float(a.sum()) ** 2)
    if process == "white":
        return np.full(k_max, float(np.dot(a, a)))
    if process == "rrw":
        suffix = np.cumsum(a[::-1])
        within = float(np.dot(suffix, suffix))
        return (np.arange(k_max) * N) * float(a.sum()) ** 2 + within
    g = _bin_coefficients(a, d, k_max * N)
    return np.cumsum(g * g)[N - 1 :: N]


def _bin_coefficients(a: np.ndarray, d: Any, length: int) -> np.ndarray:
    """g_j = Σ_{u=1}^{N} a_u ψ_{u−N+j}, j = 0 … length − 1: the convolution of reversed a with ψ."""
    return scipy.signal.fftconvolve(a[::-1], fractional_coefficients(d, length))[:length]


# --- 1/f noise bins, TIM 2014 §III-D --------------------------------------------------------------


def flicker_bin_variances(d: Any, N: int, k_max: int, method: str = "averaged") -> np.ndarray:
    """Variances of bins k = 1 … k_max of 1/f noise (TIM 2014 eq. (3), σ_w² = 1), float64.

    ``method="averaged"``: one gyro, bin mean with the weights 1 of eq. (12), i.e. the diagonal of
    1ᵀFFᵀ1 generalised to bin k. ``method="carouselled"``: the carouselled estimate of eq. (6),
    sine gyro plus cosine gyro with independent driving noise, sᵀFFᵀs + cᵀFFᵀc generalised to bin k.
    O(k_max N log(k_max N)); no (kN)×(kN) matrix is formed.
    """
    d = check_fractional_order("d", d)
    N = check_positive_integer("N", N)
    k_max = check_positive_integer("k_max", k_max)
    method = _check_method(method)
    if method == "averaged":
        return repeated_weights_bin_variances(averaging_weights(N), "flicker", k_max, d=d)
    sine, cosine = carousel_weights(N)
    return repeated_weights_bin_variances(sine, "flicker", k_max, d=d) + repeated_weights_bin_variances(
        cosine, "flicker", k_max, d=d
    )


def _mp_order(d: Any) -> mpmath.mpf:
    exact = _exact_rational(d)
    if exact is not None:
        return mpmath.mpf(exact.numerator) / exact.denominator
    if isinstance(d, sp.Basic):
        return mpmath.mpf(sp.Float(d, mpmath.mp.dps)._mpf_)
    return mpmath.mpf(d)  # a float is taken at its exact binary value


def _flicker_bin_variances_mp(d: Any, N: int, k_max: int, digits: int, carouselled: bool) -> list[mpmath.mpf]:
    """Bins k = 1 … k_max: N⁻² Σ_{j<kN} |h_j|² with h_j = z̄ h_{j−1} + ψ_j − ψ_{j−N} (z = e^{2πi/N},
    or z = 1 when averaged, where h_j = Ψ_j − Ψ_{j−N}).

    The recursion multiplies by |z̄| = 1, so rounding errors add up and are never amplified; the
    guard digits cover the log10(kN) digits of accumulated rounding, and the cancellation in
    Ψ_j − Ψ_{j−N}, with a wide margin.
    """
    length = k_max * N
    guard = _GUARD_DIGITS + len(str(length))
    bins: list[mpmath.mpf] = []
    with mpmath.workdps(digits + guard):
        order = _mp_order(d)
        psi = [mpmath.mpf(1)]
        for j in range(1, length):
            psi.append(psi[-1] * (j - 1 + order) / j)  # TIM 2014 eq. (3): ψ_j = ψ_{j−1}(j − 1 + d)/j
        zero = mpmath.mpf(0)
        total = zero
        scale = mpmath.mpf(N) ** 2
        if carouselled:
            rotate_cos, rotate_sin = mpmath.cospi(mpmath.mpf(2) / N), mpmath.sinpi(mpmath.mpf(2) / N)
        real, imaginary = zero, zero
        for j in range(length):
            step = psi[j] - (psi[j - N] if j >= N else zero)
            if carouselled:
                real, imaginary = (
                    rotate_cos * real + rotate_sin * imaginary + step,
                    rotate_cos * imaginary - rotate_sin * real,
                )
                total += real * real + imaginary * imaginary
            else:
                real += step  # Ψ_j − Ψ_{j−N}
                total += real * real
            if (j + 1) % N == 0:
                bins.append(total / scale)
    with mpmath.workdps(digits):
        return [+value for value in bins]


def flicker_bin_variances_high_precision(
    d: Any, N: int, k_max: int, method: str = "averaged", digits: int = 50
) -> list[mpmath.mpf]:
    """:func:`flicker_bin_variances` at ``digits`` significant digits (mpmath), bins k = 1 … k_max.

    O(k_max N) operations at that precision, by the one-step recursion of the module docstring.
    """
    d = check_fractional_order("d", d)
    N = check_positive_integer("N", N)
    k_max = check_positive_integer("k_max", k_max)
    method = _check_method(method)
    digits = check_positive_integer("digits", digits)
    return _flicker_bin_variances_mp(d, N, k_max, digits, carouselled=method == "carouselled")


def flicker_averaged_bin_variance(d: Any, N: int, k: int, digits: int | None = None) -> Any:
    """Variance of the k-th N-sample mean of 1/f noise (TIM 2014 eq. (3), σ_w² = 1, §III-D).

    ``Var_k = N⁻² Σ_{j=0}^{kN−1} (Ψ_j − Ψ_{j−N})²`` with Ψ_j = ψ_0 + … + ψ_j (Ψ_{<0} = 0). For
    k = 1 this is σ_w² 1ᵀFFᵀ1 of §III-D.

    Returns a float (float64, FFT), or an ``mpmath.mpf`` with ``digits`` significant digits.
    """
    d = check_fractional_order("d", d)
    N = check_positive_integer("N", N)
    k = check_positive_integer("k", k)
    digits = _check_digits(digits)
    if digits is not None:
        return _flicker_bin_variances_mp(d, N, k, digits, carouselled=False)[-1]
    return float(flicker_bin_variances(d, N, k, "averaged")[-1])


def flicker_carouselled_bin_variance(d: Any, N: int, k: int, digits: int | None = None) -> Any:
    """Variance of the k-th carouselled estimate of 1/f noise (TIM 2014 eq. (3), (6), (13), §III-D).

    Sine gyro plus cosine gyro, independent, σ_w² = 1: ``Σ_{j<kN} (g^s_j)² + (g^c_j)²`` with
    ``g^s_j = Σ_u s_u ψ_{u−N+j}`` and likewise for c; for k = 1 this is sᵀFFᵀs + cᵀFFᵀc.

    Returns a float (float64, FFT), or an ``mpmath.mpf`` with ``digits`` significant digits.
    """
    d = check_fractional_order("d", d)
    N = check_positive_integer("N", N)
    k = check_positive_integer("k", k)
    digits = _check_digits(digits)
    if digits is not None:
        return _flicker_bin_variances_mp(d, N, k, digits, carouselled=True)[-1]
    return float(flicker_bin_variances(d, N, k, "carouselled")[-1])


def flicker_averaged_bin_variance_exact(d: Any, N: int, k: int) -> Fraction:
    """:func:`flicker_averaged_bin_variance` as an exact ``Fraction`` for rational d (O(kN) exact terms).

    Raises ``TypeError`` unless d is an exact rational (``Fraction`` or SymPy ``Rational``).
    """
    d = check_fractional_order("d", d)
    N = check_positive_integer("N", N)
    k = check_positive_integer("k", k)
    if _exact_rational(d) is None:
        raise TypeError(
            f"d={d!r}: must be an exact rational (Fraction or sympy Rational) for the exact variance"
        )
    psi = fractional_coefficients_exact(d, k * N)
    window, total = Fraction(0), Fraction(0)
    for j in range(k * N):
        window += psi[j] - (psi[j - N] if j >= N else 0)
        total += window * window
    return total / (N * N)
