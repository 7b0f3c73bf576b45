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

Divide and conquer (the "superfast" Schur algorithm of Ammar and Gragg, SIAM J. Matrix Anal.
Appl. 9, 1988) lowers the time to O(n log² n): the rotations of steps k₀ … k₁ − 1 depend only on
rows k₀ … k₁ − 1 of the generator, and their joint effect is a 2 × 2 polynomial matrix
M(z) = Π_k Θ_k diag(z, 1) of degree k₁ − k₀, which carries the generator to the next window by
one FFT product, [A, B] ↦ [A, B] M; the forward substitution is carried likewise,
r ↦ r − [A, B] N with N(z) = Σ_k u_k M_k Θ_k e₁. Windows of a few hundred steps run the O(m²)
recursion directly. M(e^{iω}) is a product of rotations and of diag(e^{iω}, 1), hence unitary on
the unit circle: its coefficients are bounded, and the FFT products lose nothing beyond rounding
(the tests compare with the dense Cholesky factor to 1e-10).

Why this method and not a Whittle likelihood: the process is not stationary for d ≥ ½ (SJ 2012
uses d = ½ and 0.535), so a Whittle likelihood would be an approximation of unknown size exactly
where the model is used; the Schur recursion is exact (it reproduces the dense Cholesky factor to
rounding) and fits in O(n) memory.

The same recursion gives the Kalman forecast of SJ 2012 §IV-A over any horizon h without an
n × n matrix. Extend the covariance to the samples 1 … n + h with no white noise after n:
Σ₊ = σ_w² L₊L₊ᵀ + σ_v² D, D = diag(1ₙ, 0ₕ); its generator gains a third column σ_v e_{n+1} of
negative signature that no rotation of the first n steps touches. With polynomials
A₀(z) = σ_w Σ_j ψ_j z^j, B₀(z) = σ_v and the 2 × 2 polynomial matrix
M_n(z) = Π_k Θ_k diag(z, 1), the generator after n steps is [A₀, B₀] M_n, so the Schur complement
(the covariance of f_{n+1 … n+h} given x) has diagonal Σ_{j ≤ k} (a_j² + b_j²) − σ_v², and
E[f_{n+k} | x] = coefficient n + k − 1 of A₀(z) N₀(z) with N(z) = Σ_k u_k M_k Θ_k e₁, u = L_Σ⁻¹x.
M_n and N come out of the divide and conquer (O(n log² n), O(n) memory); the products with A₀
are FFT convolutions, O((n + h) log(n + h)).
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
) -> WhitenedSystem:
    """L_Σ⁻¹ r for each column r of ``right_hand_sides`` (n, m), and log det Σ (Σ = σ_w² L Lᵀ + σ_v² I,
    σ_v² > 0), by the generalized Schur recursion of the module docstring: O(n log² n · m) time
    (divide and conquer) and O(n m) memory."""
    d, sigma2_w, sigma2_v, values = _check_system(d, driving_variance, white_variance, right_hand_sides)
    n = values.shape[0]
    first = math.sqrt(sigma2_w) * fractional_coefficients(d, n)
    second = np.zeros(n)
    second[0] = math.sqrt(sigma2_v)
    whitened = np.empty_like(values)
    _, _, log_determinant = _solve_range(first, second, values, whitened, transfer=False)
    return WhitenedSystem(whitened=whitened, log_determinant=log_determinant)


def _leaf(first: np.ndarray, second: np.ndarray, residual: np.ndarray, whitened: np.ndarray):
    """The O(m²) recursion on a window of m steps: writes u = L⁻¹r into ``whitened`` and returns
    the transfer matrix M(z) (2, 2, m + 1), the accumulated N(z) (2, m, runs) and Σ 2 log δ_k.

    ``first`` holds A_k[k:] at positions 0 … m−k−1 (the factor z moves nothing), ``second`` holds
    B_k at its window positions; both are overwritten. Column 0 of M_k is kept degree-major with
    the rows (A, B) interleaved, degree i at positions 2(m − k + i) and 2(m − k + i) + 1, so one
    BLAS rotation turns both rows and the factor z only moves the origin; column 1 likewise from
    position 0. The rotations do not depend on the data: the window's Cholesky columns and the
    rotated columns M_k Θ_k e₁ are stored, and u and N = Σ_k u_k M_k Θ_k e₁ follow from one
    triangular solve and one matrix product.
    """
    m = first.shape[0]
    column_zero = np.zeros(2 * (m + 1))
    column_zero[2 * m] = 1.0  # M₀ = I: entry (A, column 0) at degree 0
    column_one = np.zeros(2 * (m + 1))
    column_one[1] = 1.0  # entry (B, column 1) at degree 0
    factor_transposed = np.zeros((m, m))  # row k: Cholesky column k on rows k … m−1
    rotated = np.zeros((m, 2 * m))  # row k: M_k Θ_k e₁, degrees 0 … k, rows interleaved
    # Flat views: the rows are filled by BLAS copies with offsets, one call per row instead of the
    # two views and the copy of a NumPy slice assignment (the loop's cost is per call, not per flop).
    flat_factor, flat_rotated = factor_transposed.reshape(-1), rotated.reshape(-1)
    rotate, copy = blas.drot, blas.dcopy
    for k in range(m):  # the hot loop: the rotation of _rotation, written out
        alpha, beta = first.item(0), second.item(k)
        delta = math.hypot(alpha, beta)
        if not delta > 0.0:
            raise ArithmeticError("generalized Schur step: the covariance is not positive definite")
        c, s = alpha / delta, beta / delta
        rotate(first, second, c, s, m - k, 0, 1, k, 1, 1, 1)
        rotate(column_zero, column_one, c, s, 2 * (k + 1), 2 * (m - k), 1, 0, 1, 1, 1)
        copy(first, flat_factor, m - k, 0, 1, k * (m + 1), 1)  # factor_transposed[k, k:] = first[: m − k]
        copy(column_zero, flat_rotated, 2 * (k + 1), 2 * (m - k), 1, 2 * m * k, 1)  # rotated[k, : 2(k + 1)]
    log_determinant = 2.0 * float(np.log(np.diagonal(factor_transposed)).sum())
    # Lower factor = factor_transposedᵀ, Fortran-contiguous: BLAS trsm directly (scipy's
    # solve_triangular takes a path that a multithreaded OpenBLAS makes 20× slower at this size).
    whitened[...] = blas.dtrsm(1.0, factor_transposed.T, residual, side=0, lower=1)
    accumulated = (rotated.T @ whitened).reshape(m, 2, -1).transpose(1, 0, 2)
    transfer_matrix = np.stack([column_zero.reshape(m + 1, 2).T, column_one.reshape(m + 1, 2).T], axis=1)
    return transfer_matrix, accumulated, log_determinant


def _quadratic(first: np.ndarray, second: np.ndarray, residual: np.ndarray, whitened: np.ndarray) -> float:
    """The O(m²) recursion without M and N (the last window needs no transfer): column-oriented
    forward substitution as the Cholesky columns appear; returns Σ 2 log δ_k."""
    m = first.shape[0]
    work = _working_copy(residual)
    log_determinant = 0.0
    for k in range(m):
        delta, c, s = _rotation(first[0], second[k])
        blas.drot(first, second, c, s, n=m - k, offy=k, overwrite_x=1, overwrite_y=1)
        log_determinant += 2.0 * math.log(delta)
        _forward_step(work, first, k, delta)
    whitened[...] = work
    return log_determinant


#: Windows of at most this many steps run the O(m²) recursion; longer ones are split in two.
_LEAF = 256
#: A last window (no transfer needed) this short runs the plain O(m²) loop, which makes fewer
#: calls per step than the divide and conquer.
_QUADRATIC_LIMIT = 4096


def _spectra(polynomials: np.ndarray, size: int) -> np.ndarray:
    """Real FFT of size ``size`` along axis 1 of polynomials laid out (entries, degree, ...)."""
    return scipy_fft.rfft(polynomials, size, axis=1)


def _stacked(transfer_matrix: np.ndarray, accumulated: np.ndarray) -> np.ndarray:
    """[Mᵀ | N] coefficient by coefficient, zero-filled where N is shorter than M: (2, coefficients of M,
    2 + columns), so that one FFT product carries the generator and the residual correction together."""
    stacked = np.zeros((2, transfer_matrix.shape[2], 2 + accumulated.shape[2]))
    stacked[:, :, :2] = transfer_matrix.transpose(0, 2, 1)
    stacked[:, : accumulated.shape[1], 2:] = accumulated
    return stacked


def _carry(generator: np.ndarray, transfer_matrix: np.ndarray, accumulated: np.ndarray, start: int):
    """The generator [A, B] M and the correction [A, B] N on coefficients start … m − 1 (m the
    generator's length), in one FFT product: (m − start, 2) and (m − start, columns).

    ``generator`` is (2, m), ``transfer_matrix`` (2, 2, start + 1) and ``accumulated``
    (2, start, columns). The linear product has degree m − 1 + start; a cyclic one of size S ≥ m
    folds only coefficients ≥ S onto 0 … start − 1, so S = m leaves the wanted ones exact.
    """
    m = generator.shape[1]
    size = scipy_fft.next_fast_len(m, real=True)
    spectrum = _spectra(generator, size)[:, :, None] * _spectra(_stacked(transfer_matrix, accumulated), size)
    product = scipy_fft.irfft(spectrum.sum(axis=0), size, axis=0)[start:m]
    return product[:, :2], product[:, 2:]


def _solve_range(first, second, residual, whitened, transfer: bool):
    """Divide and conquer over the steps of one window (Ammar and Gragg's superfast Schur idea):
    the left half's rotations depend only on its own coefficients; its transfer matrix M_L and
    accumulated N_L carry the generator and the residual to the right half by FFT products,
    [A, B] ↦ [A, B] M_L and R ↦ R − [A, B] N_L; then M = M_L M_R and N = N_L + M_L N_R."""
    m = first.shape[0]
    if not transfer and m <= _QUADRATIC_LIMIT:
        return None, None, _quadratic(first.copy(), second.copy(), residual, whitened)
    if m <= _LEAF:
        return _leaf(first.copy(), second.copy(), residual, whitened)
    half = m // 2
    left_m, left_n, left_log = _solve_range(
        first[:half], second[:half], residual[:half], whitened[:half], True
    )
    moved, correction = _carry(np.stack([first, second]), left_m, left_n, half)
    right_m, right_n, right_log = _solve_range(
        np.ascontiguousarray(moved[:, 0]),
        np.ascontiguousarray(moved[:, 1]),
        residual[half:] - correction,
        whitened[half:],
        transfer,
    )
    if not transfer:
        return None, None, left_log + right_log
    transfer_matrix, accumulated = _compose(left_m, left_n, right_m, right_n, m)
    return transfer_matrix, accumulated, left_log + right_log


def _compose(left_m, left_n, right_m, right_n, m):
    """M = M_L M_R (degree ≤ m) and N = N_L + M_L N_R (degree ≤ m − 1), by one FFT product."""
    size = scipy_fft.next_fast_len(m + 1, real=True)
    right = _stacked(right_m, right_n)
    product = np.einsum(
        "rjf,jfc->rfc", scipy_fft.rfft(left_m, size, axis=2), scipy_fft.rfft(right, size, axis=1)
    )
    both = scipy_fft.irfft(product, size, axis=1)
    transfer_matrix = both[:, : m + 1, :2].transpose(0, 2, 1)
    accumulated = both[:, :m, 2:]
    accumulated[:, : left_n.shape[1]] += left_n
    return transfer_matrix, accumulated


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
) -> ConditionalForecast:
    """E[f_{n+k} | x] and Var[f_{n+k} | x], k = 1 … ``horizon``, for x = f + v with zero mean,
    one column of ``right_hand_sides`` (n, m) per data vector.

    Exact Gaussian conditioning (the Kalman forecast of SJ 2012 §IV-A with a known bias), in
    O(n log² n · m + (n + h) log(n + h) m) time and O((n + h) m) memory: the generalized Schur
    recursion of the module docstring, then FFT products with A₀(z) = σ_w Σ ψ_j z^j.
    """
    d, sigma2_w, sigma2_v, values = _check_system(d, driving_variance, white_variance, right_hand_sides)
    h = check_positive_integer("horizon", horizon)
    n = values.shape[0]
    total = n + h
    driving = math.sqrt(sigma2_w) * fractional_coefficients(d, total)
    second = np.zeros(n)
    second[0] = math.sqrt(sigma2_v)
    whitened = np.empty_like(values)
    polynomials, accumulated, log_determinant = _solve_range(
        driving[:n], second, values, whitened, transfer=True
    )
    # One FFT product gives both: the means from N and the generator after n steps on the future
    # rows, [A₀, B₀] M_n with B₀ = σ_v (a constant).
    products = _convolve_columns(driving, _stacked(polynomials, accumulated)[0], n, total)
    generator, mean = products[:, :2], np.ascontiguousarray(products[:, 2:])  # mean: its own array
    generator[0] += math.sqrt(sigma2_v) * polynomials[1, :, n]
    variance = np.cumsum((generator**2).sum(axis=1)) - sigma2_v
    return ConditionalForecast(
        mean=mean, variance=variance, whitened=whitened, log_determinant=log_determinant
    )
