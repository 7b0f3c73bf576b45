"""AR coefficients of a rate record's short correlated noise (first-order Gauss–Markov, AR(p)).

Both estimators read the record high-passed by a centred moving average of max(1001, 10 s) samples (the
slow terms — rate random walk, 1/f, drift — removed; a shorter window biases the lag covariances by about
−(long-run variance)/window) through its sample autocovariance γ̂(k) = Σ_t x_t x_{t+k}/n.

:func:`yule_walker` — the AR process is the whole short noise (the closed loop's coloured noise, which
replaces the white noise): Levinson–Durbin on γ̂(0 … p); the order is the largest p ≤ the maximum whose
partial autocorrelation (the last Levinson–Durbin coefficient) exceeds 4/√n.

:func:`yule_walker_beside_white` — the short noise is white noise plus an AR(p) process (a white floor
beside a Gauss–Markov term). White noise adds its variance σ² to γ(0) alone, so Yule–Walker on γ̂(0 …)
returns the coefficients of the sum, an ARMA(p, p) process, and the AR term's Allan variance bends away
from the data's (white + AR(1) with φ = 0.8 and a white variance nine times the AR one: AR(4)
coefficients near (0.15, 0.10, 0.07, 0.05) and a GLS χ² of 700–800 on 14 degrees of freedom at 10⁶
samples). The high-order (modified) Yule–Walker equations γ(k) = Σ_{i≤p} φ_i γ(k − i), k = p + 1 … p + L,
use only lags ≥ 1, which white noise does not reach, and hold exactly for the sum; they are solved by
least squares over L = 4·(maximum order) equations. Order: none when no |γ̂(k)|, k = 1 … L, exceeds
4 γ̂(0)/√n (the standard deviation of a sample autocovariance of white noise); otherwise the smallest p
whose equations' residuals all lie within 4 √(1 + Σ φ_i²) s, s² = Σ_{|j|≤J} γ̂(j)²/n the large-sample
variance of a sample autocovariance (Bartlett's formula, lags to J = 2·(maximum order) + L).

:func:`short_noise_coefficients` — for a model with both white noise and an AR term, which of the two
describes the record: the short noise of a sensor behind a short internal filter is the filtered white
noise as a whole, correlated over a lag or two (the ADIS16405: γ̂(2)/γ̂(1) ≈ 0, so the high-order
equations see no AR process and white + AR cannot reproduce γ̂(1); plain Yule–Walker's AR(3) fits its
Allan variance with χ² = 30 on 14 degrees of freedom against 1.2·10⁴), while white noise beside a
Gauss–Markov term needs the high-order equations. Both candidates are scored on the record's own
autocovariance at lags 0 … J by the model both stand for, γ(k) = v g_φ(k) + σ² [k = 0] (g_φ the AR
autocovariance at unit innovation variance, v and σ² ≥ 0 by non-negative least squares), and the
closer one is kept; candidates that are not stationary are dropped. The high-pass lowers every γ̂(k),
k ≪ W, by about the long-run variance over W (W the moving average's length; the boxcar's mean of γ
around k): for a Gauss–Markov term of correlation time τ_c that is 2τ_c/W of γ(0), enough to bias φ
(φ = 0.95 at 10⁶ samples: 0.941, χ² = 70 on 16 degrees of freedom). The offset is added back from the
chosen white + AR model's long-run variance σ² + v/(1 − Σφ)² and the choice redone (OFFSET_ROUNDS times).
Measured over 12 records of 10⁶ samples at 100 Hz, white variance 3.6·10⁻⁵, AR long-run variance 10⁻⁴:
for φ = 0.5, 0.8, 0.9, 0.95 the mean is within one standard deviation (0.0015–0.0028) of φ (at φ = 0.5
the high-order AR(1) is chosen on 9 records, plain Yule–Walker's AR(4) on 3; elsewhere always AR(1));
at φ = 0.99
(τ_c = 1 s against W = 10 s, where the first-order correction no longer suffices) the mean is 0.977 and
the spread 0.013. :func:`correlation_is_long` says where that bias begins; the noise-model fit refines
such an AR(1) coefficient by its χ² on the Allan variance (:mod:`carousel_theory.fitting`).

:func:`coefficient_covariance` — the coefficients' large-sample covariance. Both estimators solve
M(γ̂) φ = b(γ̂) (least squares for the high-order one), so to first order dφ = M⁺ (db − dM φ) = G dγ̂ and
Cov φ̂ = G Cov(γ̂) Gᵀ, with Bartlett's formula for Cov(γ̂) under the white + AR autocovariance fitted to
γ̂ (Gaussian noise). The offset correction and the choice between the estimators are not in G. Measured
over 200 records of 10⁵ samples at 100 Hz (white variance 3.6·10⁻⁵, AR innovation variance 4·10⁻⁶, a
rate random walk and 1/f noise beside them): the spread of (φ̂ − φ)/error is 0.99, 1.05 and 1.13 for
φ = 0.95, 0.8 and 0.5, and 1.15 without the white noise (where the two estimators take turns).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.linalg import solve_toeplitz
from scipy.ndimage import uniform_filter1d
from scipy.optimize import nnls

from carousel_theory._validation import check_finite_array, check_positive_integer, check_positive_real
from carousel_theory.noise_model import ar_autocovariance, ar_decay_lags, ar_long_run_variance, stationary_ar

__all__ = [
    "LONG_CORRELATION_FRACTION",
    "ShortNoiseEstimate",
    "bartlett_covariance",
    "coefficient_covariance",
    "coefficient_gradient",
    "coefficients_from_autocovariance",
    "correlation_is_long",
    "high_pass_window",
    "high_passed_autocovariance",
    "lag_products",
    "short_noise_coefficients",
    "short_noise_estimate",
    "yule_walker",
    "yule_walker_beside_white",
    "yule_walker_estimate",
]

#: Equations of the high-order Yule–Walker system per unit of the maximum order.
EQUATIONS_PER_ORDER = 4
#: Rounds of adding the high-pass's offset back (module text); the coefficients settle to 4 digits in 2.
OFFSET_ROUNDS = 3
#: A high-passed record whose RMS is below this fraction of the record's is constant to rounding.
CONSTANT_LEVEL = 1e-12
#: Standard deviations a sample autocovariance or an equation's residual may reach by chance.
THRESHOLD = 4.0


def high_pass_window(sample_rate: float) -> int:
    """W = max(1001, 10 s) samples, odd: the centred moving average removed before the autocovariance."""
    return max(1001, round(10 * float(check_positive_real("sample_rate", sample_rate))) | 1)


#: An AR(1) correlation time above W/this (W the high-pass window) is where the estimate is biased low:
#: between the measured W/51, where the bias is within the spread, and W/10, where it is one spread
#: (module text; φ = 0.99 at τ_c = W/10 came out 0.977).
LONG_CORRELATION_FRACTION = 20.0


def correlation_is_long(
    coefficients: tuple[float, ...], sample_rate: float, fraction: float = LONG_CORRELATION_FRACTION
) -> bool:
    """Is ``coefficients`` an AR(1) with 0 < φ < 1 whose correlation time −1/ln φ samples exceeds
    W/``fraction`` (by default where this module's estimate of it is biased low)?"""
    if len(coefficients) != 1 or not 0.0 < coefficients[0] < 1.0:
        return False
    return -1.0 / math.log(coefficients[0]) > high_pass_window(sample_rate) / fraction


def high_passed_autocovariance(x: Any, sample_rate: float, lags: int) -> tuple[np.ndarray, int]:
    """(γ̂(0 … lags) of ``x`` less its centred moving average of max(1001, 10 s) samples, n); lags the
    record does not reach are 0, and all are 0 for a record constant to rounding."""
    samples = check_finite_array("x", x, min_length=3)
    fast = uniform_filter1d(samples, high_pass_window(sample_rate), mode="nearest")
    np.subtract(samples, fast, out=fast)  # the record less its moving average, in the average's array
    n = len(fast)
    autocovariance = lag_products(fast, min(lags, n - 1)) / n
    if autocovariance[0] <= CONSTANT_LEVEL**2 * float(np.einsum("i,i->", samples, samples)) / n:
        autocovariance[:] = 0.0  # constant to rounding: the high-pass leaves only its own rounding
    return np.concatenate((autocovariance, np.zeros(lags + 1 - len(autocovariance)))), n


#: Multiply-adds of one Gram block's product in :func:`lag_products` (B × rows × B): OpenBLAS runs a
#: product below 2¹⁸ of them on one thread. One product over the whole record is threaded and, measured
#: at 10⁶ samples on 2 cores, costs 1.6 times the CPU time of the blocks (its threads wait by spinning).
_GRAM_BLOCK_PRODUCTS = 1 << 18


def lag_products(x: np.ndarray, lags: int) -> np.ndarray:
    """Σ_i x_i x_{i+k} for k = 0 … ``lags`` (< len(x)), by Gram matrices rather than one pass per lag.

    x is cut into rows of B = max(32, lags + 1) samples, X[r, j] = x_{rB+j}. A product at lag k < B joins
    column j of row r to column j + k of the same row (j + k < B: the k-th superdiagonal of G = XᵀX) or to
    column j + k − B of row r + 1 (the diagonal of Y = X[:−1]ᵀX[1:] from row B − k): the lag-k sum is
    tr_k(G) + Σ_{t<k} Y[B − k + t, t]. The products that reach past the last whole row are added directly.
    The same products as one dot per lag, added in another order (equal within rounding; a test holds
    them to exact integer sums).
    """
    n = len(x)
    width = max(32, lags + 1)
    rows = n // width
    table = x[: rows * width].reshape(rows, width)
    gram, across = np.zeros((width, width)), np.zeros((width, width))
    step = max(1, _GRAM_BLOCK_PRODUCTS // (width * width))
    for first in range(0, rows, step):
        block = table[first : first + step]
        gram += block.T @ block
        following = table[first + 1 : first + step + 1]
        across += block[: len(following)].T @ following
    result = np.empty(lags + 1)
    whole = rows * width
    for k in range(lags + 1):
        start = max(whole - k, 0)  # products whose later sample lies past the last whole row
        rest = float(np.dot(x[start : n - k], x[start + k :])) if start < n - k else 0.0
        result[k] = np.trace(gram, offset=k) + np.trace(across[width - k :, :k]) + rest
    return result


#: The two estimators, as :attr:`ShortNoiseEstimate.estimator` names them.
PLAIN, HIGH_ORDER = "Yule–Walker", "high-order Yule–Walker"


@dataclass(frozen=True)
class ShortNoiseEstimate:
    """AR coefficients of a record's short noise, the estimator that gave them (:data:`PLAIN`,
    :data:`HIGH_ORDER`, or "" when none was found) and their large-sample covariance
    (:func:`coefficient_covariance`; 0 × 0 without coefficients)."""

    coefficients: tuple[float, ...]
    estimator: str
    covariance: np.ndarray


def yule_walker(x: Any, sample_rate: float, maximum_order: int) -> tuple[float, ...]:
    """AR coefficients by Yule–Walker on ``x`` with its slow part removed (module text); () for order 0."""
    check_positive_integer("maximum_order", maximum_order)
    autocovariance, n = high_passed_autocovariance(x, sample_rate, maximum_order)
    _check_order(n, maximum_order)
    return _plain(autocovariance, n, maximum_order)


def yule_walker_estimate(x: Any, sample_rate: float, maximum_order: int) -> ShortNoiseEstimate:
    """:func:`yule_walker` with the coefficients' covariance (:func:`coefficient_covariance`)."""
    check_positive_integer("maximum_order", maximum_order)
    autocovariance, n = high_passed_autocovariance(x, sample_rate, maximum_order)
    _check_order(n, maximum_order)
    coefficients = _plain(autocovariance, n, maximum_order)
    return _estimate(autocovariance, n, coefficients, PLAIN if coefficients else "", maximum_order)


def _check_order(n: int, maximum_order: int) -> None:
    """Refuse AR orders a record of n samples cannot carry: at most n/4 (each of the p lags the estimate
    reads must be averaged over many samples)."""
    if maximum_order > n // 4:
        raise ValueError(
            f"maximum_order={maximum_order}: a record of {n} samples carries AR orders up to n/4 = {n // 4}"
        )


def _plain(autocovariance: np.ndarray, n: int, maximum_order: int) -> tuple[float, ...]:
    if not autocovariance[0] > 0:  # a constant record: nothing to correlate
        return ()
    order = 0
    for p in range(1, maximum_order + 1):
        coefficients = solve_toeplitz(autocovariance[:p], autocovariance[1 : p + 1])
        if abs(coefficients[-1]) > THRESHOLD / math.sqrt(n):
            order = p
    if order == 0:
        return ()
    coefficients = solve_toeplitz(autocovariance[:order], autocovariance[1 : order + 1])
    return tuple(float(c) for c in coefficients)


def yule_walker_beside_white(x: Any, sample_rate: float, maximum_order: int) -> tuple[float, ...]:
    """AR coefficients of the AR part of white + AR(p) noise in ``x`` by the high-order Yule–Walker
    equations (module text); () when the lags ≥ 1 show no correlation."""
    check_positive_integer("maximum_order", maximum_order)
    lags = _beside_white_lags(maximum_order)
    return _beside_white(*high_passed_autocovariance(x, sample_rate, lags), maximum_order)


def _beside_white_lags(maximum_order: int) -> int:
    """J: the largest lag the high-order equations read."""
    return 2 * maximum_order + EQUATIONS_PER_ORDER * maximum_order


def _beside_white(autocovariance: np.ndarray, n: int, maximum_order: int) -> tuple[float, ...]:
    equations = EQUATIONS_PER_ORDER * maximum_order
    if not autocovariance[0] > 0:
        return ()
    if np.max(np.abs(autocovariance[1 : equations + 1])) <= THRESHOLD * autocovariance[0] / math.sqrt(n):
        return ()
    spread = math.sqrt((autocovariance[0] ** 2 + 2.0 * np.sum(autocovariance[1:] ** 2)) / n)
    coefficients = np.zeros(0)
    for p in range(1, maximum_order + 1):
        rows = np.arange(p + 1, p + equations + 1)
        design = autocovariance[rows[:, None] - np.arange(1, p + 1)]
        coefficients = np.linalg.lstsq(design, autocovariance[rows], rcond=None)[0]
        residual = autocovariance[rows] - design @ coefficients
        allowed = THRESHOLD * math.sqrt(1.0 + float(coefficients @ coefficients)) * spread
        if np.max(np.abs(residual)) <= allowed:
            break
    return tuple(float(c) for c in coefficients)


def short_noise_coefficients(x: Any, sample_rate: float, maximum_order: int) -> tuple[float, ...]:
    """AR coefficients for a model with white + AR short noise (module text): of :func:`yule_walker` and
    :func:`yule_walker_beside_white`, those whose white + AR autocovariance v g_φ(k) + σ² [k = 0] (v, σ² ≥ 0
    by non-negative least squares) is closer to the record's at lags 0 … J, with the high-pass's offset
    added back; () when neither finds any."""
    return short_noise_estimate(x, sample_rate, maximum_order).coefficients


def short_noise_estimate(x: Any, sample_rate: float, maximum_order: int) -> ShortNoiseEstimate:
    """:func:`short_noise_coefficients` with the estimator chosen and the coefficients' covariance."""
    check_positive_integer("maximum_order", maximum_order)
    autocovariance, n = high_passed_autocovariance(x, sample_rate, _beside_white_lags(maximum_order))
    _check_order(n, maximum_order)
    corrected = autocovariance
    coefficients, estimator = _closer(autocovariance, n, maximum_order)
    for _ in range(OFFSET_ROUNDS):
        if not coefficients:
            break
        _, long_run = _white_and_ar_fit(autocovariance, coefficients)
        corrected = autocovariance + long_run / high_pass_window(sample_rate)
        coefficients, estimator = _closer(corrected, n, maximum_order)
    return _estimate(corrected, n, coefficients, estimator, maximum_order)


def _closer(autocovariance: np.ndarray, n: int, maximum_order: int) -> tuple[tuple[float, ...], str]:
    """Of the plain and the high-order coefficients, those whose white + AR model is closer, and which."""
    found = (
        (_plain(autocovariance, n, maximum_order), PLAIN),
        (_beside_white(autocovariance, n, maximum_order), HIGH_ORDER),
    )
    candidates = [(c, name) for c, name in found if c and stationary_ar(c)]
    if len(candidates) < 2:
        return candidates[0] if candidates else ((), "")
    misfit = [_white_and_ar_fit(autocovariance, coefficients)[0] for coefficients, _ in candidates]
    return candidates[1] if misfit[1] < misfit[0] else candidates[0]


def _white_and_ar_fit(autocovariance: np.ndarray, coefficients: tuple[float, ...]) -> tuple[float, float]:
    """(residual norm, long-run variance σ² + v/(1 − Σφ)²) of :func:`_white_and_ar_parts`."""
    residual, innovation, white = _white_and_ar_parts(autocovariance, coefficients)
    return residual, float(white + ar_long_run_variance(innovation, coefficients))


def _white_and_ar_parts(
    autocovariance: np.ndarray, coefficients: tuple[float, ...]
) -> tuple[float, float, float]:
    """(residual norm, v, σ²) of γ̂(k) ≈ v g_φ(k) + σ² [k = 0], v, σ² ≥ 0 by non-negative least squares,
    g_φ the AR autocovariance at unit innovation variance."""
    design = np.zeros((len(autocovariance), 2))
    design[:, 0] = ar_autocovariance(coefficients, len(autocovariance))
    design[0, 1] = 1.0
    scale = np.linalg.norm(design, axis=0)
    solution, residual = nnls(design / scale, autocovariance)
    innovation, white = solution / scale
    return float(residual), float(innovation), float(white)


# --- the coefficients' covariance -------------------------------------------------------------------


def coefficients_from_autocovariance(
    autocovariance: np.ndarray, n: int, estimator: str, maximum_order: int
) -> tuple[float, ...]:
    """The coefficients ``estimator`` (:data:`PLAIN` or :data:`HIGH_ORDER`) finds in a sample
    autocovariance γ̂(0 … J) of n samples (the map that :func:`coefficient_gradient` linearizes)."""
    if estimator == PLAIN:
        return _plain(autocovariance, n, maximum_order)
    if estimator == HIGH_ORDER:
        return _beside_white(autocovariance, n, maximum_order)
    raise ValueError(f"estimator={estimator!r}: must be {PLAIN!r} or {HIGH_ORDER!r}")


def _estimate(
    autocovariance: np.ndarray, n: int, coefficients: tuple[float, ...], estimator: str, maximum_order: int
) -> ShortNoiseEstimate:
    if not coefficients:
        return ShortNoiseEstimate((), "", np.zeros((0, 0)))
    covariance = coefficient_covariance(autocovariance, n, coefficients, estimator, maximum_order)
    return ShortNoiseEstimate(coefficients, estimator, covariance)


def coefficient_covariance(
    autocovariance: np.ndarray, n: int, coefficients: tuple[float, ...], estimator: str, maximum_order: int
) -> np.ndarray:
    """Large-sample covariance of AR ``coefficients`` found by ``estimator`` (:data:`PLAIN` or
    :data:`HIGH_ORDER`, at ``maximum_order``) from the sample autocovariance γ̂(0 … J) of n samples.

    Both estimators solve equations M(γ̂) φ = b(γ̂) (least squares when there are more equations than
    coefficients), so to first order dφ = M⁺ (db − dM φ) = G dγ̂; Cov φ̂ = G Cov(γ̂) Gᵀ with Bartlett's
    formula Cov(γ̂(h), γ̂(k)) = (1/n) Σ_j [γ(j) γ(j + k − h) + γ(j + k) γ(j − h)] (Gaussian noise), γ the
    white + AR autocovariance v g_φ(k) + σ² [k = 0] fitted to γ̂ (:func:`short_noise_coefficients`)."""
    lags = len(autocovariance) - 1
    _, innovation, white = _white_and_ar_parts(autocovariance, coefficients)
    reach = len(coefficients) + 2 + ar_decay_lags(coefficients) + 2 * lags + 1
    model = innovation * np.array(ar_autocovariance(coefficients, reach))
    model[0] += white
    gradient = coefficient_gradient(autocovariance, coefficients, estimator, maximum_order)
    return gradient @ bartlett_covariance(model, lags, n) @ gradient.T


def coefficient_gradient(
    autocovariance: np.ndarray, coefficients: tuple[float, ...], estimator: str, maximum_order: int
) -> np.ndarray:
    """G (p × (J + 1)) with dφ = G dγ̂: M⁺ (db − dM φ), M and b read from γ̂ at the estimator's lags."""
    p, phi = len(coefficients), np.asarray(coefficients, dtype=np.float64)
    if estimator == PLAIN:
        rows = np.arange(p)
        matrix_lags, right_lags = np.abs(rows[:, None] - rows[None, :]), rows + 1
    elif estimator == HIGH_ORDER:
        rows = np.arange(p + 1, p + EQUATIONS_PER_ORDER * maximum_order + 1)
        matrix_lags, right_lags = rows[:, None] - np.arange(1, p + 1), rows
    else:
        raise ValueError(f"estimator={estimator!r}: must be {PLAIN!r} or {HIGH_ORDER!r}")
    lag_axis = np.arange(len(autocovariance))
    derivative = (right_lags[:, None] == lag_axis).astype(np.float64)
    derivative -= np.einsum("rcl,c->rl", (matrix_lags[:, :, None] == lag_axis).astype(np.float64), phi)
    return np.linalg.pinv(autocovariance[matrix_lags]) @ derivative


def bartlett_covariance(model: np.ndarray, lags: int, n: int) -> np.ndarray:
    """Bartlett's Cov(γ̂(h), γ̂(k)), h, k = 0 … ``lags``, for the autocovariance ``model`` (γ(0), γ(1), …;
    zero beyond) and n samples: (A(|k − h|) + A(h + k))/n with A(s) = Σ_j γ(j) γ(j + s)."""
    symmetric = np.concatenate((model[:0:-1], model))
    size = len(symmetric)
    products = lag_products(symmetric, min(2 * lags, size - 1))
    products = np.concatenate((products, np.zeros(2 * lags + 1 - len(products))))
    h = np.arange(lags + 1)
    return (products[np.abs(h[:, None] - h[None, :])] + products[h[:, None] + h[None, :]]) / n
