"""The residual model of the closed loop: the noise model of one axis, its fit, and what it predicts.

This is the only room of the loop that knows how a noise model is stored and fitted. The rest of the
loop calls the functions listed in ``__all__`` and reads the fields of :class:`ResidualFit`; it never
reads an attribute of :class:`AxisNoise` itself. Replacing the model and the fitter by the package's
common ones therefore touches this module only.

The model (TIM 2014 §II, per-sample discrete terms): bias + short noise (white, or an autoregressive
process x_t = Σ a_j x_{t−j} + e_t for the ``colored_noise`` effect) + rate random walk (eq. (2)) + an
optional 1/f term of order d = 1/2 (eq. (3)). The fit is weighted least squares on the non-overlapping
Allan variance at octave τ (eq. (20)), weights from the equivalent degrees of freedom of the fitted
model (:func:`carousel_theory.allan.equivalent_degrees_of_freedom`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from scipy import optimize, stats
from scipy.linalg import solve_toeplitz

from carousel_theory.allan import (
    allan_variance,
    equivalent_degrees_of_freedom,
    flicker_allan_variance,
    model_allan_variance,
)
from carousel_theory.fitting import NoiseModel
from carousel_theory.processes import sample_flicker
from carousel_theory.propagation import repeated_weights_bin_variances, weighted_sum_variance

__all__ = [
    "AxisNoise",
    "ModelTerms",
    "ResidualFit",
    "allan_z_values",
    "bounded_noise",
    "chi_square_z",
    "describe_noise",
    "difference_covariance_bands",
    "fit_residual_model",
    "noise_growth",
    "ranking_statistic_variance",
    "revolution_bin_variance",
    "short_noise_allan",
    "simulate_block_sums",
    "spectral_density",
    "statistic_variance",
    "statistic_variance_dof",
    "uniform_bin_variances",
]

#: Autocovariance lags kept for the autoregressive short noise (its correlation dies out long before).
AR_LAGS = 256
#: Fewest clusters an Allan-variance point needs to enter the fit (τ ≤ T/8).
MINIMUM_CLUSTERS = 8


@dataclass(frozen=True)
class ModelTerms:
    """The stochastic terms a fit may use besides white noise and the rate random walk."""

    ar_order: int = 0
    flicker: bool = False


@dataclass(frozen=True)
class AxisNoise:
    """The fitted noise model of one axis in per-sample discrete terms (TIM 2014 §II).

    ``white_variance`` is the innovation variance of the short noise: white when ``ar_coefficients`` is
    empty, otherwise of the autoregressive process. Its long-run variance σ_e²/(1 − Σ a_j)² is what
    averaging over many samples sees.
    """

    sample_rate: float
    bias: float
    white_variance: float
    rrw_variance: float = 0.0
    flicker_variance: float = 0.0
    flicker_d: float = 0.5
    ar_coefficients: tuple[float, ...] = ()
    standard_errors: dict[str, float] = field(default_factory=dict)

    @property
    def long_run_variance(self) -> float:
        return self.white_variance / (1.0 - sum(self.ar_coefficients)) ** 2

    def short_autocovariance(self, lags: int = AR_LAGS) -> np.ndarray:
        """γ_h, h = 0 … lags − 1, of the short noise (white: σ² at lag 0 only)."""
        gamma = np.zeros(lags)
        if not self.ar_coefficients:
            gamma[0] = self.white_variance
            return gamma
        from scipy.signal import lfilter

        # Impulse response of 1/(1 − Σ a_j z^j), long enough for |roots| < 1 to have died out.
        length = lags + 4096
        impulse = np.zeros(length)
        impulse[0] = 1.0
        response = lfilter([1.0], np.concatenate(([1.0], -np.asarray(self.ar_coefficients))), impulse)
        spectrum = np.fft.rfft(response, 2 * length)
        autocorrelation = np.fft.irfft(spectrum * np.conj(spectrum), 2 * length)[:lags]
        return self.white_variance * autocorrelation

    def white_and_walk(self) -> NoiseModel:
        """The :class:`~carousel_theory.fitting.NoiseModel` of the white (long-run) and random-walk parts."""
        return NoiseModel(
            sample_rate=self.sample_rate,
            bias=self.bias,
            white_variance=self.long_run_variance,
            rrw_variance=self.rrw_variance,
        )


@dataclass(frozen=True)
class ResidualFit:
    """One axis's fit: the noise model and the Allan-variance points it was fitted to.

    ``observed``, ``model`` and ``edf`` are the measured and fitted Allan variances and the equivalent
    degrees of freedom at ``tau`` (``sizes`` samples per cluster); ``chi_square`` on ``dof`` degrees of
    freedom is the weighted misfit, which nested fits compare.
    """

    noise: AxisNoise
    tau: np.ndarray
    sizes: np.ndarray
    observed: np.ndarray
    model: np.ndarray
    edf: np.ndarray
    chi_square: float
    dof: int

    @property
    def bias(self) -> float:
        """The fitted constant bias (rad/s), TIM 2014 eq. (1)."""
        return self.noise.bias


# --- the Allan variance of the model and its fit -----------------------------------------------------


def short_noise_allan(noise: AxisNoise, sizes: np.ndarray) -> np.ndarray:
    """Exact Allan variance of the stationary short noise from its autocovariance:
    σ_A²(m) = Var(x̄_m) − Cov(x̄_m⁽¹⁾, x̄_m⁽²⁾), both finite sums of γ_h (γ_h = 0 beyond AR_LAGS)."""
    if not noise.ar_coefficients:
        return noise.white_variance / sizes.astype(np.float64)
    gamma = noise.short_autocovariance()
    h = np.arange(len(gamma), dtype=np.float64)
    result = np.empty(len(sizes))
    for i, m in enumerate(sizes.astype(np.float64)):
        inside = (h >= 1) & (h < m)
        variance = (gamma[0] * m + 2.0 * np.sum((m - h[inside]) * gamma[inside])) / m**2
        near = (h >= 1) & (h < 2 * m)
        covariance = np.sum(np.minimum(h[near], 2 * m - h[near]) * gamma[near]) / m**2
        result[i] = variance - covariance
    return result


def _unit_walk_allan(sample_rate: float, sizes: np.ndarray) -> np.ndarray:
    """Allan variance of a unit rate random walk: the closed form allan.RRW_ALLAN_VARIANCE."""
    unit = NoiseModel(sample_rate=sample_rate, bias=0.0, white_variance=0.0, rrw_variance=1.0)
    return model_allan_variance(unit, sizes)


_FLICKER_CACHE: dict[tuple[int, tuple[int, ...]], np.ndarray] = {}


def _unit_flicker_allan(sizes: np.ndarray, length: int) -> np.ndarray:
    """The unit 1/f Allan-variance curve, cached per record length (it costs one pass per τ)."""
    key = (length, tuple(int(m) for m in sizes))
    if key not in _FLICKER_CACHE:
        if len(_FLICKER_CACHE) > 64:
            _FLICKER_CACHE.clear()
        _FLICKER_CACHE[key] = flicker_allan_variance(0.5, sizes, length, "non-overlapping")
    return _FLICKER_CACHE[key]


def yule_walker(x: np.ndarray, sample_rate: float, maximum_order: int) -> tuple[float, ...]:
    """AR coefficients by Yule–Walker on the residual with its slow part (rate random walk, 1/f, trends)
    removed by a centred 10-s moving average (a shorter one biases the lag covariances by about
    −(long-run variance)/window); the order is the largest p ≤ maximum_order whose partial
    autocorrelation exceeds 4/√n (Levinson–Durbin)."""
    from scipy.ndimage import uniform_filter1d

    window = max(1001, round(10 * sample_rate) | 1)
    fast = x - uniform_filter1d(x, window, mode="nearest")
    n = len(fast)
    spectrum = np.fft.rfft(fast, 2 * n)
    autocovariance = np.fft.irfft(spectrum * np.conj(spectrum), 2 * n)[: maximum_order + 1] / n
    order = 0
    for p in range(1, maximum_order + 1):
        coefficients = solve_toeplitz(autocovariance[:p], autocovariance[1 : p + 1])
        if abs(coefficients[-1]) > 4.0 / math.sqrt(n):  # the last coefficient is the partial autocorrelation
            order = p
    if order == 0:
        return ()
    coefficients = solve_toeplitz(autocovariance[:order], autocovariance[1 : order + 1])
    return tuple(float(c) for c in coefficients)


@dataclass(frozen=True)
class _Design:
    sizes: np.ndarray
    tau: np.ndarray
    observed: np.ndarray
    matrix: np.ndarray
    names: tuple[str, ...]
    edf: np.ndarray
    ar: tuple[float, ...]


def _design(x: np.ndarray, sample_rate: float, terms: ModelTerms, reference: ResidualFit | None) -> _Design:
    """Allan-variance points with at least MINIMUM_CLUSTERS clusters and the unit curve of each term.

    Beyond T/8 an estimate rests on 2–6 squared differences, and a single one would decide whether the
    fit "needs" a 1/f or a random-walk term."""
    n = len(x)
    ar: tuple[float, ...] = ()
    if terms.ar_order:
        reused = reference.noise.ar_coefficients if reference is not None else ()
        ar = reused or yule_walker(x, sample_rate, terms.ar_order)
    allan = allan_variance(x, sample_rate, "octave", estimator="non-overlapping", noise="white")
    assert allan.samples_per_cluster is not None and allan.edf is not None
    keep = allan.samples_per_cluster * MINIMUM_CLUSTERS <= n
    sizes = allan.samples_per_cluster[keep].astype(np.int64)
    unit_short = AxisNoise(sample_rate, 0.0, (1.0 - sum(ar)) ** 2, ar_coefficients=ar)
    columns = [short_noise_allan(unit_short, sizes), _unit_walk_allan(sample_rate, sizes)]
    names: tuple[str, ...] = ("short", "rrw")
    if terms.flicker:
        columns.append(_unit_flicker_allan(sizes, n))
        names = (*names, "flicker")
    edf = allan.edf[keep].astype(np.float64) if reference is None else reference.edf
    return _Design(sizes, allan.tau[keep], allan.avar[keep], np.column_stack(columns), names, edf, ar)


def _model_edf(design: _Design, theta: np.ndarray, sample_rate: float, n: int) -> np.ndarray:
    """Equivalent degrees of freedom of each non-overlapping estimate (M − 1 differences, eq. (20))
    under the white + random-walk part of the current fit."""
    trial = AxisNoise(
        sample_rate, 0.0, theta[0] * (1.0 - sum(design.ar)) ** 2, float(theta[1]), ar_coefficients=design.ar
    )
    model = trial.white_and_walk()
    if model.white_variance + model.rrw_variance <= 0:
        return design.edf
    return np.array(
        [
            equivalent_degrees_of_freedom(model, int(m), int(n // m - 1), int(m), n, sample_rate)
            for m in design.sizes
        ]
    )


def _standard_errors(design: _Design, sigma: np.ndarray) -> dict[str, float]:
    """Standard errors from the weighted normal equations (NaN when they are singular)."""
    weighted = design.matrix / sigma[:, None]
    try:
        covariance = np.linalg.inv(weighted.T @ weighted)
    except np.linalg.LinAlgError:
        return {}
    labels = {"short": "long_run_white_variance", "rrw": "rrw_variance", "flicker": "flicker_variance"}
    return {labels[name]: float(math.sqrt(max(covariance[i, i], 0.0))) for i, name in enumerate(design.names)}


def fit_residual_model(
    values: np.ndarray, sample_rate: float, terms: ModelTerms, *, reference: ResidualFit | None = None
) -> ResidualFit:
    """Fit bias + short noise + rate random walk (+ 1/f) to one axis.

    Weighted non-negative least squares on the Allan variance: Var(σ̂_A²) = 2 σ_A⁴/ν with ν the
    equivalent degrees of freedom of the current fit, iterated. ``reference``, a fit of the same axis,
    fixes ν (a refit, or a nested fit that must share its weights with the fit it is compared to) and
    lends its autoregressive coefficients (a refit subtracts a slow signal, which leaves the fast part's
    autocovariance as it was).
    """
    x = np.asarray(values, dtype=np.float64)
    design = _design(x, sample_rate, terms, reference)
    edf, weights_base = design.edf, design.observed
    theta = np.zeros(len(design.names))
    for iteration in range(3 if reference is None else 2):
        sigma = np.maximum(weights_base, 1e-300) * np.sqrt(2.0 / edf)
        theta, _ = optimize.nnls(design.matrix / sigma[:, None], design.observed / sigma)
        weights_base = np.maximum(design.matrix @ theta, 1e-300)
        if reference is None and iteration < 2:
            edf = _model_edf(design, theta, sample_rate, len(x))
    fitted = design.matrix @ theta
    sigma = np.maximum(fitted, 1e-300) * np.sqrt(2.0 / edf)
    errors = _standard_errors(design, sigma)
    noise = AxisNoise(
        sample_rate=sample_rate,
        bias=float(x.mean()),
        white_variance=float(theta[0]) * (1.0 - sum(design.ar)) ** 2,
        rrw_variance=float(theta[1]),
        flicker_variance=float(theta[2]) if terms.flicker else 0.0,
        ar_coefficients=design.ar,
        standard_errors={
            "long_run_white_variance": errors.get("long_run_white_variance", math.nan),
            "rrw_variance": errors.get("rrw_variance", math.nan),
            **({"flicker_variance": errors.get("flicker_variance", math.nan)} if terms.flicker else {}),
        },
    )
    chi_square = float(np.sum(((design.observed - fitted) / sigma) ** 2))
    dof = len(design.sizes) - len(design.names)
    return ResidualFit(noise, design.tau, design.sizes, design.observed, fitted, edf, chi_square, dof)


def allan_z_values(fit: ResidualFit) -> np.ndarray:
    """z-value of each Allan-variance estimate of ``fit`` (:func:`chi_square_z`)."""
    return chi_square_z(fit.observed, fit.model, fit.edf)


def chi_square_z(observed: np.ndarray, expected: np.ndarray, edf: np.ndarray) -> np.ndarray:
    """z-value of Allan-variance estimates: ν σ̂²/σ² ~ χ²_ν under the model, mapped through its cdf (a
    standardisation; at long τ the loop's misfit test takes its null distribution from a bootstrap)."""
    statistic = edf * observed / np.maximum(expected, 1e-300)
    lower = stats.chi2.logcdf(statistic, edf)
    upper = stats.chi2.logsf(statistic, edf)
    z = np.where(lower < upper, stats.norm.ppf(np.exp(lower)), -stats.norm.ppf(np.exp(upper)))
    # exp(log p) underflows past z ≈ 38; beyond that the exact size no longer matters.
    z = np.where(np.isfinite(z), z, np.where(lower < upper, -38.0, 38.0))
    return np.clip(z, -38.0, 38.0)


# --- what the fitted model predicts --------------------------------------------------------------------


def statistic_variance(noise: AxisNoise, weights: np.ndarray, include_flicker: bool = True) -> float:
    """Var(Σ w_t e_t) under the model: short noise as its long-run variance times Σw² (exact for white;
    for the autoregressive noise exact up to O(correlation length / scale of w), the weights used here
    varying slowly), the walk and the 1/f term by :func:`~carousel_theory.propagation.weighted_sum_variance`
    (TIM 2014 eqs. (2)–(3))."""
    total = noise.long_run_variance * float(np.dot(weights, weights))
    if noise.rrw_variance:
        total += noise.rrw_variance * weighted_sum_variance(weights, "rrw")
    if noise.flicker_variance and include_flicker:
        total += noise.flicker_variance * weighted_sum_variance(weights, "flicker", d=noise.flicker_d)
    return total


def ranking_statistic_variance(noise: AxisNoise, weights: np.ndarray, block: int) -> float:
    """Var(Σ w_t e_t) for weights constant over blocks of ``block`` samples, the 1/f part approximated at
    block level (block means of 1/f noise of order d are, at low frequency, 1/f noise of driving variance
    σ_f² b^{2d−1}, so the part is σ_f² b^{2d+1} Σ_i (Σ_{B≥i} w_B ψ_{B−i})² over the n/b block weights).
    Only to rank the points of a scan, whose chosen point is then tested exactly: O(n/b log(n/b))."""
    total = statistic_variance(noise, weights, include_flicker=False)
    if noise.flicker_variance:
        count = len(weights) // block
        block_weights = weights[: count * block : block]
        unit = weighted_sum_variance(block_weights, "flicker", d=noise.flicker_d)
        total += noise.flicker_variance * block ** (2 * noise.flicker_d + 1) * unit
    return total


def statistic_variance_dof(noise: AxisNoise, weights: np.ndarray) -> tuple[float, float]:
    """(variance, effective degrees of freedom) of Σ w_t e_t: the variance as :func:`statistic_variance`,
    and ν = 2 V² / Var(V̂) from the standard errors of the fitted variances (Satterthwaite), so that a z
    built on it is referred to Student's t with ν degrees of freedom: a rate random walk estimated from a
    few long-τ Allan points is uncertain, and a normal reference would then be anticonservative."""
    parts = {"long_run_white_variance": (noise.long_run_variance, float(np.dot(weights, weights)))}
    # The walk's share counts even at a fitted σ_q² of 0: its standard error still says how large it could be.
    parts["rrw_variance"] = (noise.rrw_variance, weighted_sum_variance(weights, "rrw"))
    if noise.flicker_variance or math.isfinite(noise.standard_errors.get("flicker_variance", math.nan)):
        flicker_unit = weighted_sum_variance(weights, "flicker", d=noise.flicker_d)
        parts["flicker_variance"] = (noise.flicker_variance, flicker_unit)
    variance = sum(value * unit for value, unit in parts.values())
    spread = 0.0
    for name, (value, unit) in parts.items():
        error = noise.standard_errors.get(name, math.nan)
        spread += (unit * (error if math.isfinite(error) else value)) ** 2
    dof = 2.0 * variance**2 / spread if spread > 0 else math.inf
    return variance, max(dof, 1.0)


def bounded_noise(current: AxisNoise, candidate: AxisNoise, *, keep_flicker_floor: bool = True) -> AxisNoise:
    """``candidate`` with each variance raised to at least ``current``'s value minus 2 standard errors.

    ``keep_flicker_floor=False`` leaves the 1/f variance as fitted: the joint fit of a regressor with the
    1/f term is exactly the case where the null fit's 1/f variance holds the regressor's signal."""
    errors = current.standard_errors

    def floor(name: str, value: float, reference: float) -> float:
        error = errors.get(name, math.nan)
        limit = reference - 2.0 * error if math.isfinite(error) else reference
        return max(value, limit, 0.0)

    flicker = candidate.flicker_variance
    if keep_flicker_floor and (candidate.flicker_variance or current.flicker_variance):
        flicker = floor("flicker_variance", candidate.flicker_variance, current.flicker_variance)
    lower_walk = candidate.rrw_variance < current.rrw_variance
    return replace(
        candidate,
        rrw_variance=floor("rrw_variance", candidate.rrw_variance, current.rrw_variance),
        flicker_variance=flicker,
        standard_errors=dict(current.standard_errors) if lower_walk else candidate.standard_errors,
    )


def difference_covariance_bands(noise: AxisNoise, block: int, size: int) -> np.ndarray:
    """Upper banded form of the covariance of first differences of ``block``-sample means.

    Differences Δx_t = q_t + w_t − w_{t−1} of white + rate random walk: MA(1) with γ₀ = σ_q² + 2σ²,
    γ₁ = −σ²; on block means of b samples white σ²/b, walk increments ≈ σ_q² b. A floor on σ_q² keeps the
    tridiagonal system well conditioned when no walk is fitted."""
    white = noise.long_run_variance / block
    walk = max(noise.rrw_variance * block, 1e-8 * white)
    bands = np.empty((2, size))
    bands[0, :] = -white
    bands[0, 0] = 0.0
    bands[1, :] = walk + 2.0 * white
    return bands


def spectral_density(noise: AxisNoise, frequencies: np.ndarray) -> np.ndarray:
    """Discrete spectral density (per-sample variance units: white σ² is flat at σ²)."""
    omega = 2.0 * np.pi * np.asarray(frequencies) / noise.sample_rate
    short = np.full_like(omega, noise.white_variance, dtype=np.float64)
    if noise.ar_coefficients:
        # 1 − Σ a_j z^j at z = e^{−iω}, by Horner's rule
        z = np.exp(-1j * omega)
        transfer = np.zeros_like(z)
        for coefficient in reversed(noise.ar_coefficients):
            transfer = (transfer + coefficient) * z
        short = noise.white_variance / np.abs(1.0 - transfer) ** 2
    difference = np.maximum(4.0 * np.sin(omega / 2.0) ** 2, 1e-300)  # |1 − e^{−iω}|²
    with np.errstate(over="ignore"):  # at ω = 0 the walk's density is unbounded: +inf is its value
        total = short + noise.rrw_variance / difference  # TIM 2014 eq. (2): r = q / (1 − B)
        if noise.flicker_variance:
            total = total + noise.flicker_variance / difference**noise.flicker_d  # eq. (3): (1 − B)^{−d}
    return total


def uniform_bin_variances(noise: AxisNoise, weights: np.ndarray, count: int) -> np.ndarray:
    """Var of each of ``count`` consecutive bins reduced with the same ``weights``: wᵀΓw of the short
    noise (TIM 2014 eq. (9) for white) plus the walk and 1/f terms of eqs. (17)–(18), exact per bin."""
    length = len(weights)
    gamma = noise.short_autocovariance(min(AR_LAGS, length))
    lagged = np.array([np.dot(weights[: length - h], weights[h:]) for h in range(len(gamma))])
    variance = np.full(count, gamma[0] * lagged[0] + 2.0 * np.dot(gamma[1:], lagged[1:]))
    if noise.rrw_variance:
        variance += noise.rrw_variance * repeated_weights_bin_variances(weights, "rrw", count)
    if noise.flicker_variance:
        variance += noise.flicker_variance * repeated_weights_bin_variances(
            weights, "flicker", count, d=noise.flicker_d
        )
    return variance


def revolution_bin_variance(noise: AxisNoise, weights: np.ndarray, start: int) -> float:
    """Var of Σ w_u x_{start+u} for one bin starting at sample ``start`` (short noise as its long-run
    variance; the walk at the bin start enters every sample: t₀ (Σw)² plus the walk within the bin)."""
    total = noise.long_run_variance * float(np.dot(weights, weights))
    total += noise.rrw_variance * (start * float(weights.sum()) ** 2 + weighted_sum_variance(weights, "rrw"))
    if noise.flicker_variance:
        padded = np.concatenate((np.zeros(start), weights))
        total += noise.flicker_variance * weighted_sum_variance(padded, "flicker", d=noise.flicker_d)
    return total


def noise_growth(
    before: AxisNoise, after: AxisNoise, z: float = 2.0, *, new_flicker: bool = False
) -> list[str]:
    """Noise variances that grew by more than ``z`` standard errors (and 20 %) from ``before``
    (``new_flicker``: the 1/f term is new in ``after``, its variance is not compared)."""
    grown = []
    pairs = (
        ("long_run_white_variance", before.long_run_variance, after.long_run_variance),
        ("rrw_variance", before.rrw_variance, after.rrw_variance),
        ("flicker_variance", before.flicker_variance, after.flicker_variance),
    )
    for name, value_before, value_after in pairs:
        if new_flicker and name == "flicker_variance":
            continue
        error = before.standard_errors.get(name, math.nan)
        if not math.isfinite(error) or error <= 0:
            error = 0.1 * value_before
        if value_after > value_before + z * error and value_after > 1.2 * value_before:
            grown.append(f"{name} {value_before:.3g} -> {value_after:.3g}")
    return grown


def simulate_block_sums(noise: AxisNoise, length: int, block: int, rng: np.random.Generator) -> np.ndarray:
    """Sums of ``block`` consecutive samples of one draw of the fitted model (bias 0), ``length // block``
    of them, without simulating every sample for the white and random-walk parts.

    Short noise: independent N(0, σ_LR² b) (exact for white; for the autoregressive noise the block sums
    are correlated only through O(correlation length / b) edge terms). Rate random walk (TIM 2014 eq. (2)):
    block j's sum is b R_j + W_j with R_j the walk before the block, and the pair (I_j = Σ_k q_k,
    W_j = Σ_k (b − k + 1) q_k) of the block's increments Gaussian with Var I = b σ_q²,
    Var W = σ_q² Σ_k k², Cov = σ_q² Σ_k k — exact. 1/f noise is simulated sample by sample."""
    count = length // block
    total = rng.normal(0.0, math.sqrt(noise.long_run_variance * block), count)
    if noise.rrw_variance:
        # Σ_k k and Σ_k k² over the block, exact integer sums (the weights of W are b, b − 1, …, 1)
        linear, square = sum(range(1, block + 1)), sum(k * k for k in range(1, block + 1))
        covariance = noise.rrw_variance * np.array([[block, linear], [linear, square]], dtype=np.float64)
        if block == 1:  # I = W = q₁: the covariance is singular, and Cholesky refuses it
            pairs = np.repeat(rng.normal(0.0, math.sqrt(noise.rrw_variance), (count, 1)), 2, axis=1)
        else:
            pairs = rng.multivariate_normal(np.zeros(2), covariance, count, method="cholesky")
        before = np.concatenate(([0.0], np.cumsum(pairs[:-1, 0])))
        total += block * before + pairs[:, 1]
    if noise.flicker_variance:
        flicker = sample_flicker(count * block, rng=rng, d=noise.flicker_d, variance=noise.flicker_variance)
        total += flicker.reshape(count, block).sum(axis=1)
    return total


def describe_noise(noise: AxisNoise) -> dict[str, Any]:
    """The fitted model as the loop's JSON reports it (per-sample variances and the usual IEEE units)."""
    return {
        "bias_rad_s": noise.bias,
        "white_variance_rad2_s2": noise.white_variance,
        "long_run_white_variance_rad2_s2": noise.long_run_variance,
        "rrw_variance_rad2_s2": noise.rrw_variance,
        "flicker_variance_rad2_s2": noise.flicker_variance,
        "flicker_d": noise.flicker_d if noise.flicker_variance else None,
        "ar_coefficients": list(noise.ar_coefficients),
        "angle_random_walk_deg_per_sqrt_h": math.degrees(
            math.sqrt(noise.long_run_variance / noise.sample_rate)
        )
        * 60.0,
        "rate_random_walk_deg_per_h_per_sqrt_h": math.degrees(
            math.sqrt(noise.rrw_variance * noise.sample_rate)
        )
        * 3600.0
        * 60.0,
        "standard_errors": dict(noise.standard_errors),
    }
