"""Gyro error processes of TIM 2014 §II: bias (1), white noise, rate random walk (2) and 1/f noise
as fractional integration (3).

Every process starts at sample t = 1 (the papers number samples from 1) and is driven by unit-free
white noise of the given ``variance``:

- additive bias, eq. (1): ``b_t = b_{t−1} = b``, a random constant; ``cov(b_s, b_t) = σ_b²``;
- white noise: ``cov(e_s, e_t) = σ² [s = t]``;
- rate random walk, eq. (2): ``r_t = r_{t−1} + q_t`` with ``r_0 = 0``, so ``r_t = Σ_{i≤t} q_i`` and
  ``cov(r_s, r_t) = σ_q² min(s, t)``;
- 1/f noise, eq. (3): ``f_t = Σ_{i=1}^{t} ψ_{t−i} w_i`` with ``ψ_j = Γ(j + d) / (Γ(j + 1) Γ(d))``,
  ``0 < d < 1``, so ``cov(f_s, f_t) = σ_w² Σ_{j=0}^{min(s,t)−1} ψ_j ψ_{j+|s−t|}``.

For each process there is an exact covariance entry (a ``Fraction`` when the inputs are exact and,
for 1/f noise, ``d`` is rational, because every ψ_j is then rational), a float64 covariance matrix,
and a sampler that takes a ``numpy.random.Generator`` (there is no default generator). The 1/f
sampler applies the linear map of eq. (3) itself, through an FFT convolution in O(n log n): it is
exact in distribution, not a spectral approximation.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

import numpy as np
import scipy.fft
import sympy as sp

from carousel_theory._validation import (
    check_finite_array,
    check_fractional_order,
    check_positive_integer,
    check_positive_real,
)

__all__ = [
    "PROCESSES",
    "bias_covariance",
    "covariance_matrix",
    "flicker_covariance",
    "fractional_coefficients",
    "fractional_coefficients_exact",
    "fractionally_integrate",
    "rate_random_walk_covariance",
    "sample_bias",
    "sample_flicker",
    "sample_rate_random_walk",
    "sample_white",
    "white_covariance",
]

#: Process names accepted by :func:`covariance_matrix` and by :mod:`carousel_theory.propagation`.
PROCESSES = ("bias", "white", "rrw", "flicker")


# --- argument helpers -----------------------------------------------------------------------------


def _check_process(name: str, value: Any) -> str:
    """One of :data:`PROCESSES`."""
    if not isinstance(value, str):
        raise TypeError(f"{name}={value!r}: must be a process name, one of {PROCESSES}")
    if value not in PROCESSES:
        raise ValueError(f"{name}={value!r}: must be one of {PROCESSES}")
    return value


def _check_generator(name: str, value: Any) -> np.random.Generator:
    """A ``numpy.random.Generator``; the legacy global state and ``RandomState`` are refused so that
    every random result is reproducible from an explicit seed."""
    if not isinstance(value, np.random.Generator):
        raise TypeError(
            f"{name}={value!r}: must be a numpy.random.Generator, e.g. numpy.random.default_rng(seed)"
        )
    return value


def _exact_rational(value: Any) -> Fraction | None:
    """``value`` as a ``Fraction`` when it is an exact rational (int, Fraction, SymPy Rational), else None."""
    if isinstance(value, bool):
        return None
    if isinstance(value, Fraction):
        return value
    if isinstance(value, (int, np.integer)):
        return Fraction(int(value))
    if isinstance(value, sp.Rational):
        return Fraction(int(value.p), int(value.q))
    return None


def _check_time(name: str, value: Any) -> int:
    return check_positive_integer(name, value)


def _check_realisations(value: Any) -> int | None:
    return None if value is None else check_positive_integer("realisations", value)


def _shape(size: int, realisations: int | None) -> tuple[int, ...]:
    return (size,) if realisations is None else (realisations, size)


# --- coefficients of eq. (3) ----------------------------------------------------------------------


def fractional_coefficients(d: float, length: int) -> np.ndarray:
    """The weights ψ_j = Γ(j + d) / (Γ(j + 1) Γ(d)), j = 0 … length − 1, of TIM 2014 eq. (3).

    ``f_t = Σ_{i=1}^{t} ψ_{t−i} w_i``. Computed by the stable recursion ψ_0 = 1,
    ψ_j = ψ_{j−1} (j − 1 + d) / j, which never forms a Gamma value, so it neither overflows nor
    loses accuracy for j up to 10⁷ and beyond.
    """
    d = check_fractional_order("d", d)
    length = check_positive_integer("length", length)
    j = np.arange(1, length, dtype=np.float64)
    psi = np.empty(length, dtype=np.float64)
    psi[0] = 1.0
    psi[1:] = np.cumprod((j - 1.0 + float(d)) / j)
    return psi


def fractional_coefficients_exact(d: Any, length: int) -> list[Fraction]:
    """ψ_0 … ψ_{length−1} of TIM 2014 eq. (3) as exact ``Fraction`` values, for rational d.

    ψ_0 = 1 and ψ_j = ψ_{j−1} (j − 1 + d) / j; every factor is rational when d is.

    Raises
    ------
    TypeError
        If ``d`` is not an exact rational (int, ``Fraction`` or SymPy ``Rational``).
    """
    d = check_fractional_order("d", d)
    length = check_positive_integer("length", length)
    exact_d = _exact_rational(d)
    if exact_d is None:
        raise TypeError(
            f"d={d!r}: must be an exact rational (Fraction or sympy Rational) for exact coefficients"
        )
    psi = [Fraction(1)]
    for j in range(1, length):
        psi.append(psi[-1] * (j - 1 + exact_d) / j)
    return psi


def fractionally_integrate(innovations: Any, d: float) -> np.ndarray:
    """Apply the fractional integration of TIM 2014 eq. (3) to given white-noise innovations.

    ``f_t = Σ_{i=1}^{t} ψ_{t−i} w_i`` for t = 1 … n along the last axis of ``innovations``
    (shape ``(n,)`` or ``(realisations, n)``), computed as the first n terms of the linear
    convolution ψ * w by real FFT (``scipy.fft``, zero-padded), O(n log n). The result is the same
    linear map as the direct sum, to floating-point rounding.
    """
    d = check_fractional_order("d", d)
    array = np.asarray(innovations)
    if array.ndim not in (1, 2):
        raise ValueError(f"innovations: must be a 1- or 2-dimensional array, got shape {array.shape}")
    if array.ndim == 1:
        w = check_finite_array("innovations", array)
    else:
        w = check_finite_array("innovations", array, ndim=2)
        if w.shape[1] < 1:
            raise ValueError(f"innovations: must hold at least 1 sample per row, got shape {w.shape}")
    return _fractional_integration(w, d)


def _fractional_integration(w: np.ndarray, d: Any) -> np.ndarray:
    """The convolution of :func:`fractionally_integrate` on validated input (no copies, no checks)."""
    n = w.shape[-1]
    # zero-padding to ≥ 2n − 1 makes the circular convolution equal the linear one on t = 1 … n
    length = scipy.fft.next_fast_len(2 * n - 1, real=True)
    transfer = scipy.fft.rfft(fractional_coefficients(d, n), length)
    spectrum = scipy.fft.rfft(w, length, axis=-1)
    spectrum *= transfer  # in place: one spectrum fewer alive on a long record (the same products)
    del transfer
    return scipy.fft.irfft(spectrum, length, axis=-1, overwrite_x=True)[..., :n]


# --- exact covariance entries ---------------------------------------------------------------------


def _scale(value: Any, variance: Any) -> Any:
    exact_variance = _exact_rational(variance)
    if isinstance(value, Fraction) and exact_variance is not None:
        return value * exact_variance
    return float(value) * float(variance)


def bias_covariance(s: int, t: int, variance: Any = 1) -> Any:
    """cov(b_s, b_t) = σ_b² for the random constant of TIM 2014 eq. (1) (for all s, t ≥ 1)."""
    _check_time("s", s)
    _check_time("t", t)
    variance = check_positive_real("variance", variance, allow_zero=True)
    return _scale(Fraction(1), variance)


def white_covariance(s: int, t: int, variance: Any = 1) -> Any:
    """cov(e_s, e_t) = σ² if s = t, else 0 (white noise, TIM 2014 §II-B)."""
    s = _check_time("s", s)
    t = _check_time("t", t)
    variance = check_positive_real("variance", variance, allow_zero=True)
    return _scale(Fraction(int(s == t)), variance)


def rate_random_walk_covariance(s: int, t: int, variance: Any = 1) -> Any:
    """cov(r_s, r_t) = σ_q² min(s, t) for the rate random walk of TIM 2014 eq. (2) started at r_0 = 0."""
    s = _check_time("s", s)
    t = _check_time("t", t)
    variance = check_positive_real("variance", variance, allow_zero=True)
    return _scale(Fraction(min(s, t)), variance)


def flicker_covariance(s: int, t: int, d: Any, variance: Any = 1) -> Any:
    """cov(f_s, f_t) = σ_w² Σ_{j=0}^{min(s,t)−1} ψ_j ψ_{j+|s−t|} for the 1/f noise of TIM 2014 eq. (3).

    Exact (a ``Fraction``) when ``d`` and ``variance`` are exact rationals; float otherwise.
    """
    s = _check_time("s", s)
    t = _check_time("t", t)
    d = check_fractional_order("d", d)
    variance = check_positive_real("variance", variance, allow_zero=True)
    lag, overlap = abs(s - t), min(s, t)
    if _exact_rational(d) is not None:
        psi = fractional_coefficients_exact(d, lag + overlap)
        value: Any = sum((psi[j] * psi[j + lag] for j in range(overlap)), Fraction(0))
    else:
        psi_float = fractional_coefficients(d, lag + overlap)
        value = float(np.dot(psi_float[:overlap], psi_float[lag : lag + overlap]))
    return _scale(value, variance)


def covariance_matrix(process: str, size: int, *, d: Any = None, variance: Any = 1) -> np.ndarray:
    """The float64 covariance matrix of samples t = 1 … size of one process of TIM 2014 §II.

    ``process`` is one of :data:`PROCESSES`; ``d`` is required for ``"flicker"`` (and refused
    otherwise). For 1/f noise the matrix is F Fᵀ with F the lower-triangular Toeplitz matrix of
    ψ (TIM 2014 §III-D); it costs O(size³) and is meant for checks at moderate sizes.
    """
    process = _check_process("process", process)
    size = check_positive_integer("size", size)
    variance = float(check_positive_real("variance", variance, allow_zero=True))
    if process == "flicker":
        if d is None:
            raise ValueError("d=None: the flicker process needs its order 0 < d < 1")
        psi = fractional_coefficients(d, size)
    elif d is not None:
        raise ValueError(f"d={d!r}: only the flicker process takes an order d, not {process!r}")
    t = np.arange(1, size + 1)
    if process == "bias":
        return np.full((size, size), variance)
    if process == "white":
        return variance * np.eye(size)
    if process == "rrw":
        return variance * np.minimum.outer(t, t).astype(np.float64)
    lag = t[:, np.newaxis] - t[np.newaxis, :]
    transfer = np.where(lag >= 0, psi[np.clip(lag, 0, None)], 0.0)
    return variance * (transfer @ transfer.T)


# --- samplers -------------------------------------------------------------------------------------


def sample_bias(
    size: int, *, rng: np.random.Generator, variance: float = 1.0, realisations: int | None = None
) -> np.ndarray:
    """Samples t = 1 … size of the random-constant bias of TIM 2014 eq. (1), b ~ N(0, variance).

    Shape ``(size,)``, or ``(realisations, size)`` with one constant per row.
    """
    size = check_positive_integer("size", size)
    rng = _check_generator("rng", rng)
    variance = float(check_positive_real("variance", variance, allow_zero=True))
    realisations = _check_realisations(realisations)
    rows = 1 if realisations is None else realisations
    constants = np.sqrt(variance) * rng.standard_normal((rows, 1))
    values = np.repeat(constants, size, axis=1)
    return values[0] if realisations is None else values


def sample_white(
    size: int, *, rng: np.random.Generator, variance: float = 1.0, realisations: int | None = None
) -> np.ndarray:
    """Gaussian white noise of the given variance (TIM 2014 §II-B).

    Shape ``(size,)``, or ``(realisations, size)``.
    """
    size = check_positive_integer("size", size)
    rng = _check_generator("rng", rng)
    variance = float(check_positive_real("variance", variance, allow_zero=True))
    realisations = _check_realisations(realisations)
    noise = rng.standard_normal(_shape(size, realisations))
    if variance != 1.0:
        noise *= np.sqrt(variance)
    return noise


def sample_rate_random_walk(
    size: int, *, rng: np.random.Generator, variance: float = 1.0, realisations: int | None = None
) -> np.ndarray:
    """Rate random walk r_t = r_{t−1} + q_t, r_0 = 0, t = 1 … size (TIM 2014 eq. (2)), with
    Gaussian increments of the given variance σ_q²."""
    increments = sample_white(size, rng=rng, variance=variance, realisations=realisations)
    return np.cumsum(increments, axis=-1, out=increments)


def sample_flicker(
    size: int,
    *,
    rng: np.random.Generator,
    d: float,
    variance: float = 1.0,
    realisations: int | None = None,
) -> np.ndarray:
    """1/f noise by fractional integration, TIM 2014 eq. (3), t = 1 … size.

    Draws Gaussian innovations w of the given variance σ_w² (``rng.standard_normal`` of the output
    shape, scaled) and returns :func:`fractionally_integrate` of them: O(size log size) per row.
    """
    size = check_positive_integer("size", size)
    rng = _check_generator("rng", rng)
    d = check_fractional_order("d", d)
    variance = float(check_positive_real("variance", variance, allow_zero=True))
    realisations = _check_realisations(realisations)
    innovations = rng.standard_normal(_shape(size, realisations))
    if variance != 1.0:
        innovations *= np.sqrt(variance)
    return _fractional_integration(innovations, d)
