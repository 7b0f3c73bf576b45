"""Cholesky factorisation of the 1/f-plus-white covariance by the generalized Schur algorithm.

The calibration samples of SJ 2012 §III are x = f + v with f = L w the fractional integral of
TIM 2014 eq. (3) started at t = 1 (L the lower-triangular Toeplitz matrix of the weights ψ_j) and
v white, so

    Σ = σ_w² L Lᵀ + σ_v² I   (n × n).

Σ is not Toeplitz (the process starts at t = 1), but it has displacement rank 2: L commutes with
the down-shift Z, so L Lᵀ − Z L Lᵀ Zᵀ = ψ ψᵀ, and I − Z Zᵀ = e₁ e₁ᵀ. Hence

    Σ − Z Σ Zᵀ = G Gᵀ,   G = [σ_w ψ, σ_v e₁]   (n × 2),

with a *positive* signature. The generalized Schur algorithm (Kailath and Sayed, SIAM Review 37,
1995, §3) turns such a generator into the Cholesky factor column by column: at step k a Givens
rotation Θ_k makes row k of G equal to (δ_k, 0); the first column of GΘ_k is then column k of the
Cholesky factor (its diagonal entry δ_k), and the generator of the Schur complement is
[Z (GΘ_k)e₁, (GΘ_k)e₂]. Every transformation is orthogonal, so the recursion is as stable as the
Cholesky factorisation itself; no J-unitary (hyperbolic) rotation is ever needed.

Each step costs O(n), the whole factorisation O(n²) time, and the factor is never stored: its
columns feed, as they appear, a column-oriented forward substitution (whitened vectors L_Σ⁻¹r)
and the log-determinant 2 Σ log δ_k. Memory is O(n) per right-hand side.

Why this method and not a Whittle likelihood: the process is not stationary for d ≥ ½ (SJ 2012
uses d = ½ and 0.535), so a Whittle likelihood would be an approximation of unknown size exactly
where the model is used; the Schur recursion is exact (it reproduces the dense Cholesky factor to
rounding) and fits in O(n) memory, at the price of O(n²) time.

The same recursion gives the Kalman forecast of SJ 2012 §IV-A over any horizon h without an
n × n matrix. Extend the covariance to the samples 1 … n + h with no white noise after n:
Σ₊ = σ_w² L₊L₊ᵀ + σ_v² D, D = diag(1ₙ, 0ₕ); its generator gains a third column σ_v e_{n+1} of
negative signature that no rotation of the first n steps touches. With polynomials
A₀(z) = σ_w Σ_j ψ_j z^j, B₀(z) = σ_v and the 2 × 2 polynomial matrix
M_n(z) = Π_k Θ_k diag(z, 1), the generator after n steps is [A₀, B₀] M_n, so the Schur complement
(the covariance of f_{n+1 … n+h} given x) has diagonal Σ_{j ≤ k} (a_j² + b_j²) − σ_v², and
E[f_{n+k} | x] = coefficient n + k − 1 of A₀(z) N₀(z) with N(z) = Σ_k u_k M_k Θ_k e₁, u = L_Σ⁻¹x.
M_n and N cost O(n²) to build and O(n) to store; the products with A₀ are FFT convolutions,
O((n + h) log(n + h)).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import fft as scipy_fft
from scipy.linalg import blas

from carousel_theory._validation import (
    check_finite_array,
    check_fractional_order,
    check_positive_integer,
    check_positive_real,
)
from carousel_theory.processes import fractional_coefficients
from carousel_theory.progress import progress

__all__ = [
    "ConditionalForecast",
    "WhitenedSystem",
    "conditional_forecast",
    "whiten",
]


@dataclass(frozen=True)
class WhitenedSystem:
    """The right-hand sides r_j whitened by the Cholesky factor L_Σ of Σ = σ_w² L Lᵀ + σ_v² I.

    ``whitened`` has the shape of the right-hand sides (n, m) and holds L_Σ⁻¹ r; ``log_determinant``
    is log det Σ = 2 Σ_k log δ_k.
    """

    whitened: np.ndarray
    log_determinant: float


@dataclass(frozen=True)
class ConditionalForecast:
    """E[f_{n+k} | x] and Var[f_{n+k} | x], k = 1 … h, for each right-hand side (known zero mean).

    ``mean`` has shape (h, m), one column per right-hand side; ``variance`` shape (h,) (it does not
    depend on the data). ``whitened`` and ``log_determinant`` are those of :func:`whiten`.
    """

    mean: np.ndarray
    variance: np.ndarray
    whitened: np.ndarray
    log_determinant: float


def _check_system(d: float, driving_variance: float, white_variance: float, rhs: np.ndarray):
    d = float(check_fractional_order("d", d))
    sigma2_w = float(check_positive_real("driving_variance", driving_variance))
    sigma2_v = float(check_positive_real("white_variance", white_variance))
    values = np.asarray(rhs, dtype=np.float64)
    if values.ndim != 2:
        raise ValueError(f"right_hand_sides: must be a 2-dimensional array (n, m), got shape {values.shape}")
    check_finite_array("right_hand_sides", values.reshape(-1))
    if values.shape[0] < 1:
        raise ValueError(f"right_hand_sides: must have at least one row, got shape {values.shape}")
    return d, sigma2_w, sigma2_v, values


#: Up to this many right-hand sides the forward substitution runs column by column through BLAS
#: (Fortran order); above it, one NumPy outer-product update per step (C order) is faster.
_COLUMN_LIMIT = 16


def _working_copy(values: np.ndarray) -> np.ndarray:
    return np.array(values, order="F" if values.shape[1] <= _COLUMN_LIMIT else "C")


def _rotation(alpha: float, beta: float) -> tuple[float, float, float]:
    """Givens rotation (c, s) with (α, β)·[[c, −s], [s, c]] = (δ, 0), δ = √(α² + β²) > 0."""
    delta = math.hypot(alpha, beta)
    if not delta > 0.0:
        raise ArithmeticError("generalized Schur step: the covariance is not positive definite")
    return delta, alpha / delta, beta / delta


def _forward_step(residual: np.ndarray, column: np.ndarray, k: int, delta: float) -> np.ndarray:
    """Column-oriented forward substitution: u_k = r_k/δ_k, r_{k+1:} −= ℓ_{k+1:} u_k (in place)."""
    n = residual.shape[0]
    u = residual[k] / delta
    residual[k] = u
    if k == n - 1:
        return u
    if residual.shape[1] <= _COLUMN_LIMIT:  # contiguous columns: one BLAS axpy each, in place
        for j in range(residual.shape[1]):
            blas.daxpy(column, residual[:, j], n=n - k - 1, a=-float(u[j]), offx=1, offy=k + 1)
    else:
        residual[k + 1 :] -= column[1 : n - k, None] * u[None, :]
    return u


def whiten(
    right_hand_sides: np.ndarray,
    *,
    d: float,
    driving_variance: float,
    white_variance: float,
    label: str = "",
) -> WhitenedSystem:
    """L_Σ⁻¹ r for each column r of ``right_hand_sides`` (n, m), and log det Σ, in O(n² m) time and
    O(n m) memory (Σ = σ_w² L Lᵀ + σ_v² I, σ_v² > 0; the generalized Schur recursion of the module
    docstring). ``label`` shows progress on a terminal."""
    d, sigma2_w, sigma2_v, values = _check_system(d, driving_variance, white_variance, right_hand_sides)
    n = values.shape[0]
    first = math.sqrt(sigma2_w) * fractional_coefficients(d, n)  # a: A_k[k:] kept at positions 0 … n−k−1
    second = np.zeros(n)  # b: B_k at its global positions
    second[0] = math.sqrt(sigma2_v)
    residual = _working_copy(values)
    log_determinant = 0.0
    for k in progress(range(n), total=n, label=label, enabled=None if label else False):
        delta, c, s = _rotation(first[0], second[k])
        blas.drot(first, second, c, s, n=n - k, offy=k, overwrite_x=1, overwrite_y=1)
        log_determinant += 2.0 * math.log(delta)
        _forward_step(residual, first, k, delta)
    return WhitenedSystem(whitened=residual, log_determinant=log_determinant)


def _track_polynomials(polynomials: np.ndarray, k: int, n: int, c: float, s: float) -> None:
    """M_{k+1} = M_k Θ_k diag(z, 1): rotate the columns of both rows over degrees 0 … k.

    Column 0 of row r is kept in ``polynomials[r, 0]`` with degree i at position n − k + i, so the
    factor z costs nothing (the origin moves); column 1 in ``polynomials[r, 1]`` at position i.
    """
    for row in (0, 1):
        blas.drot(
            polynomials[row, 0],
            polynomials[row, 1],
            c,
            s,
            n=k + 1,
            offx=n - k,
            overwrite_x=1,
            overwrite_y=1,
        )


def _schur_with_polynomials(first, second, residual, label):
    """The recursion of :func:`whiten` that also builds M_n(z) and N(z) (module docstring)."""
    n = first.shape[0]
    runs = residual.shape[1]
    polynomials = np.zeros((2, 2, n + 1))  # M_k: rows (A₀, B₀), columns (generator 1, generator 2)
    polynomials[0, 0, n] = 1.0
    polynomials[1, 1, 0] = 1.0
    accumulated = np.zeros((n, runs), order="F" if runs <= _COLUMN_LIMIT else "C")  # N₀(z), per run
    log_determinant = 0.0
    for k in progress(range(n), total=n, label=label, enabled=None if label else False):
        delta, c, s = _rotation(first[0], second[k])
        blas.drot(first, second, c, s, n=n - k, offy=k, overwrite_x=1, overwrite_y=1)
        _track_polynomials(polynomials, k, n, c, s)
        log_determinant += 2.0 * math.log(delta)
        u = _forward_step(residual, first, k, delta)
        _accumulate(accumulated, polynomials[0, 0], k, n, u)
    return polynomials, accumulated, log_determinant


def _accumulate(accumulated: np.ndarray, column: np.ndarray, k: int, n: int, u: np.ndarray) -> None:
    """N₀ += u_k [M_k Θ_k]₀₀ over degrees 0 … k (the rotated column 0 before its factor z)."""
    if accumulated.shape[1] <= _COLUMN_LIMIT:
        for j in range(accumulated.shape[1]):
            blas.daxpy(column, accumulated[:, j], n=k + 1, a=float(u[j]), offx=n - k)
    else:
        accumulated[: k + 1] += column[n - k :, None] * u[None, :]


def _convolve_columns(polynomial: np.ndarray, columns: np.ndarray, start: int, stop: int) -> np.ndarray:
    """Coefficients start … stop − 1 of polynomial(z) · column_j(z) for each column (FFT)."""
    size = scipy_fft.next_fast_len(stop, real=True)
    spectrum = scipy_fft.rfft(polynomial[:stop], size)
    product = scipy_fft.irfft(scipy_fft.rfft(columns[:stop], size, axis=0) * spectrum[:, None], size, axis=0)
    return product[start:stop]


def conditional_forecast(
    right_hand_sides: np.ndarray,
    horizon: int,
    *,
    d: float,
    driving_variance: float,
    white_variance: float,
    label: str = "",
) -> ConditionalForecast:
    """E[f_{n+k} | x] and Var[f_{n+k} | x], k = 1 … ``horizon``, for x = f + v with zero mean,
    one column of ``right_hand_sides`` (n, m) per data vector.

    Exact Gaussian conditioning (the Kalman forecast of SJ 2012 §IV-A with a known bias), in
    O(n² m + (n + h) log(n + h) m) time and O((n + h) m) memory: the generalized Schur recursion of
    the module docstring, then FFT products with A₀(z) = σ_w Σ ψ_j z^j.
    """
    d, sigma2_w, sigma2_v, values = _check_system(d, driving_variance, white_variance, right_hand_sides)
    h = check_positive_integer("horizon", horizon)
    n = values.shape[0]
    total = n + h
    driving = math.sqrt(sigma2_w) * fractional_coefficients(d, total)
    first = driving[:n].copy()
    second = np.zeros(n)
    second[0] = math.sqrt(sigma2_v)
    residual = _working_copy(values)
    polynomials, accumulated, log_determinant = _schur_with_polynomials(first, second, residual, label)
    mean = _convolve_columns(driving, accumulated, n, total)
    # Generator after n steps on the future rows: [A₀, B₀] M_n with B₀ = σ_v (a constant).
    generator = _convolve_columns(driving, polynomials[0].T, n, total)
    generator[0] += math.sqrt(sigma2_v) * polynomials[1, :, n]
    variance = np.cumsum((generator**2).sum(axis=1)) - sigma2_v
    return ConditionalForecast(
        mean=mean, variance=variance, whitened=residual, log_determinant=log_determinant
    )
