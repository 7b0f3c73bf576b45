"""The exact fast form of the Kalman bias predictor of SJ 2012 §IV-A.

Model (SJ 2012 §III–IV, process of TIM 2014 eq. (3)) for the calibration samples t = 1 … n and the
forecast samples t = n + 1 … n + h:

    y_t = b + f_t + v_t,   f = Ψ w (f_t = Σ_{i=1}^{t} ψ_{t−i} w_i),   w_i ~ N(0, σ_w²),   v_t ~ N(0, σ_v²),

b ~ N(b₀, P_b) independent (P_b = ∞: a diffuse, unknown constant). The Kalman filter of
:mod:`carousel_theory.prediction` computes E[b + f_{n+k} | y_{1..n}] and its variance exactly;
here the same two numbers come from generalised least squares instead of a growing state.

Write x = y − b₀1 and let W be any matrix with WᵀW = C⁻¹, C = Cov(f + v) on the calibration
samples. With u = Wx, c = W1, g_k = W Cov(f_{1..n}, f_{n+k}), s = cᵀc, r = cᵀu, q_k = cᵀg_k,
V_k = Var f_{n+k} (Sherman–Morrison on C + P_b 11ᵀ):

    mean_k     = b₀ + g_kᵀu + r (1 − q_k) · P_b / (1 + P_b s)
    variance_k = V_k − ‖g_k‖² + (1 − q_k)² · P_b / (1 + P_b s)

(the diffuse limit replaces P_b/(1 + P_b s) by 1/s: b̂ = r/s is the GLS mean).

* No white noise (σ_v = 0, the simulated columns of SJ 2012 Table I): W = Φ/σ_w is the fractional
  difference (SJ 2012 eq. (3), corrected), g_k = σ_w (ψ_{n+k−1}, …, ψ_k), V_k − ‖g_k‖² =
  σ_w² Σ_{j<k} ψ_j², so every quantity is a convolution: O((n + h) log(n + h)).
* With white noise: W = L_C⁻¹ for the Cholesky factor of C, applied by the generalized Schur
  recursion of :mod:`carousel_theory.generalized_schur` without forming C (C − ZCZᵀ has rank 2):
  g_kᵀu, q_k and V_k − ‖g_k‖² are conditional means and variances of f_{n+k} given the data (and
  given 1), O(n log² n (runs + 1)) time and O((n + h)(runs + 1)) memory, any horizon.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from carousel_theory._validation import (
    check_finite_array,
    check_fractional_order,
    check_positive_integer,
    check_positive_real,
    check_real,
)
from carousel_theory.generalized_schur import conditional_forecast
from carousel_theory.long_memory import fft_convolve, fractional_difference_coefficients
from carousel_theory.processes import fractional_coefficients

__all__ = ["Forecast", "fast_kalman_forecast", "fractional_covariance_rows"]


@dataclass(frozen=True)
class Forecast:
    """A bias forecast for the samples n + 1 … n + h after a calibration of n samples.

    ``mean`` is the predicted bias (b + 1/f noise); ``bias_variance`` the variance of its error;
    ``observation_variance`` adds the white-noise variance, so that ``mean ± 2·√observation_variance``
    is the ±2σ interval of the measured signal (SJ 2012 Fig. 3). Arrays have shape (h,) or, for a
    batch of calibrations, (runs, h).
    """

    mean: np.ndarray
    bias_variance: np.ndarray
    observation_variance: np.ndarray

    def interval(self, width: float = 2.0) -> tuple[np.ndarray, np.ndarray]:
        """``mean ∓ width·σ`` of the measured signal (σ² = ``observation_variance``)."""
        width = float(check_positive_real("width", width))
        half = width * np.sqrt(self.observation_variance)
        return self.mean - half, self.mean + half


def fractional_covariance_rows(d: float, rows: int, columns: int) -> np.ndarray:
    """Γ_{s,t} = Cov(f_s, f_t) for σ_w² = 1, s = 1 … rows, t = 1 … columns (TIM 2014 eq. (3)).

    Γ_{s,t} = Σ_{m=0}^{min(s,t)−1} ψ_{s−1−m} ψ_{t−1−m}, built by the displacement recursion
    Γ_{s,t} = Γ_{s−1,t−1} + ψ_{s−1} ψ_{t−1} in O(rows · columns).
    """
    d = check_fractional_order("d", d)
    rows = check_positive_integer("rows", rows)
    columns = check_positive_integer("columns", columns)
    psi = fractional_coefficients(d, max(rows, columns))
    gamma = np.empty((rows, columns), dtype=np.float64)
    gamma[0] = psi[0] * psi[:columns]
    for s in range(1, rows):
        gamma[s, 0] = psi[s] * psi[0]
        gamma[s, 1:] = gamma[s - 1, :-1] + psi[s] * psi[1:columns]
    return gamma


def _check_bias_prior(bias_mean: float | None, bias_variance: float) -> tuple[float, float]:
    """(b₀, P_b) of the bias prior; P_b = +inf (diffuse) is allowed, b₀ is then unused."""
    if isinstance(bias_variance, float) and bias_variance == math.inf:
        return 0.0, math.inf
    bias_variance = float(check_positive_real("bias_variance", bias_variance, allow_zero=True))
    if bias_mean is None:
        raise ValueError(f"bias_mean={bias_mean!r}: must be given when bias_variance is finite")
    return float(check_real("bias_mean", bias_mean)), bias_variance


def _prior_weight(bias_variance: float, s: float) -> float:
    """P_b / (1 + P_b s), with its diffuse limit 1/s."""
    return 1.0 / s if math.isinf(bias_variance) else bias_variance / (1.0 + bias_variance * s)


def fast_kalman_forecast(
    calibration: np.ndarray,
    horizon: int,
    *,
    d: float = 0.5,
    driving_variance: float = 1.0,
    white_variance: float = 0.0,
    bias_mean: float | None = None,
    bias_variance: float = math.inf,
) -> Forecast:
    """Forecast b + f_{n+k}, k = 1 … horizon, from the calibration samples, exactly as the Kalman
    filter of SJ 2012 §IV-A (eq. (5)–(6) with a bias state and white measurement noise) does.

    Parameters
    ----------
    calibration
        y_1 … y_n (n ≥ 2), or a 2-D array with one calibration per row.
    horizon
        h ≥ 1 forecast samples.
    d
        Fractional order, 0 < d < 1 (TIM 2014 eq. (3)).
    driving_variance, white_variance
        σ_w² > 0 of the 1/f driving noise and σ_v² ≥ 0 of the white measurement noise.
    bias_mean, bias_variance
        Prior N(b₀, P_b) of the constant bias; ``bias_variance=inf`` (default) is the diffuse prior
        (b₀ is then not used), ``bias_variance=0`` a known bias b₀.
    """
    data = np.asarray(calibration, dtype=np.float64)
    if data.ndim not in (1, 2):
        raise ValueError(f"calibration: must be a 1- or 2-dimensional array, got shape {data.shape}")
    check_finite_array("calibration", data.reshape(-1))
    n = data.shape[-1]
    if n < 2:
        raise ValueError(f"calibration: must hold at least 2 samples, got {n}")
    h = check_positive_integer("horizon", horizon)
    d = float(check_fractional_order("d", d))
    sigma2_w = float(check_positive_real("driving_variance", driving_variance))
    sigma2_v = float(check_positive_real("white_variance", white_variance, allow_zero=True))
    b0, prior = _check_bias_prior(bias_mean, bias_variance)

    x = data - b0
    if sigma2_v == 0.0:
        mean_part, q, s, r, variance_part = _whitened_by_fractional_difference(x, n, h, d, sigma2_w)
    else:
        mean_part, q, s, r, variance_part = _whitened_by_schur(x, n, h, d, sigma2_w, sigma2_v)
    weight = _prior_weight(prior, s)
    r = np.asarray(r)[..., None]
    mean = b0 + mean_part + r * (1.0 - q) * weight
    bias_var = variance_part + (1.0 - q) ** 2 * weight
    bias_var = np.broadcast_to(bias_var, mean.shape).copy()
    return Forecast(mean=mean, bias_variance=bias_var, observation_variance=bias_var + sigma2_v)


def _whitened_by_fractional_difference(x: np.ndarray, n: int, h: int, d: float, sigma2_w: float):
    # W = Φ/σ_w; the σ_w factors cancel in g_kᵀu and q_k, so work with unit scale.
    psi = fractional_coefficients(d, n + h)
    phi = fractional_difference_coefficients(d, n)
    whitened_ones = np.cumsum(phi)  # Φ1: partial sums of φ
    differenced = fft_convolve(x, phi)[..., :n]  # Φx = ŵ
    # g_kᵀu = Σ_i ψ_{n+k−i} ŵ_i: entries n … n+h−1 (0-based) of the full convolution ψ * ŵ.
    mean_part = fft_convolve(differenced, psi)[..., n : n + h]
    q = fft_convolve(whitened_ones, psi)[n : n + h]
    s = float(whitened_ones @ whitened_ones) / sigma2_w
    r = differenced @ whitened_ones / sigma2_w
    variance_part = sigma2_w * np.cumsum(psi[:h] ** 2)  # σ_w² Σ_{j<k} ψ_j²
    return mean_part, q, s, r, variance_part


def _whitened_by_schur(x: np.ndarray, n: int, h: int, d: float, sigma2_w: float, sigma2_v: float):
    # W = L_Σ⁻¹ through the generalized Schur recursion: the ones vector and every calibration are
    # right-hand sides of one pass; g_kᵀu and q_k = g_kᵀc are the conditional means of f_{n+k}.
    runs = x.reshape(-1, n)
    right_hand_sides = np.empty((n, runs.shape[0] + 1))
    right_hand_sides[:, 0] = 1.0
    right_hand_sides[:, 1:] = runs.T
    result = conditional_forecast(
        right_hand_sides, h, d=d, driving_variance=sigma2_w, white_variance=sigma2_v
    )
    whitened_ones = result.whitened[:, 0]
    q = result.mean[:, 0]
    s = float(whitened_ones @ whitened_ones)
    r = whitened_ones @ result.whitened[:, 1:]
    mean_part = result.mean[:, 1:].T
    if x.ndim == 1:
        mean_part, r = mean_part[0], float(r[0])
    return mean_part, q, s, r, result.variance
