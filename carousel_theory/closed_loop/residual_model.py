"""The residual model of the closed loop: an adapter over the package's one noise model and one fitter.

This is the only room of the loop that knows how a noise model is stored and fitted. The rest of the
loop calls the functions listed in ``__all__`` and reads the fields of :class:`ResidualFit`; the noise
it passes around is a :class:`FittedNoise`, which it hands back to these functions without reading it.

The model is :class:`carousel_theory.noise_model.NoiseModel` (TIM 2014 §II, per-sample discrete terms):
bias + short noise (white, or for the ``colored_noise`` effect an autoregressive process
x_t = Σ a_j x_{t−j} + e_t in place of the white noise) + rate random walk (eq. (2)) + an optional 1/f
term of order d = 1/2 (eq. (3)). The fit is :func:`carousel_theory.fitting.fit_observed`: generalised
least squares on the non-overlapping Allan variance at octave τ (eq. (20)) with the model-based
covariance across τ, AR coefficients by :func:`carousel_theory.fitting.yule_walker`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from scipy import stats

from carousel_theory import units
from carousel_theory.fitting import FitOptions, FitResult, fit_observed, observe_allan, yule_walker
from carousel_theory.noise_model import NoiseModel, ar_autocovariance, term_allan_variance
from carousel_theory.processes import sample_flicker
from carousel_theory.propagation import repeated_weights_bin_variances, weighted_sum_variance

__all__ = [
    "FittedNoise",
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
    "simulate_block_sums",
    "spectral_density",
    "statistic_variance",
    "statistic_variance_dof",
    "uniform_bin_variances",
]

#: Autocovariance lags kept for the autoregressive short noise in bin variances.
AR_LAGS = 256
#: Fewest clusters an Allan-variance point needs to enter the fit (τ ≤ T/8).
MINIMUM_CLUSTERS = 8
#: Order of the loop's 1/f term (TIM 2014 eq. (3) with d = 1/2).
FLICKER_D = 0.5


@dataclass(frozen=True)
class ModelTerms:
    """The stochastic terms a fit may use besides white noise and the rate random walk."""

    ar_order: int = 0
    flicker: bool = False


@dataclass(frozen=True)
class FittedNoise:
    """A fitted :class:`~carousel_theory.noise_model.NoiseModel` and the standard errors the loop's tests
    use: ``long_run_white_variance`` (the short noise as long averages see it), ``rrw_variance`` and, when
    fitted, ``flicker_variance``."""

    model: NoiseModel
    standard_errors: Mapping[str, float]


def _long_run_variance(model: NoiseModel) -> float:
    """σ² of the short noise as long averages see it: white, or the AR term's σ_e²/(1 − Σ a_j)²."""
    return float(model.white_variance) + (model.long_run_ar_variance if model.ar_variance else 0.0)


@dataclass(frozen=True)
class ResidualFit:
    """One axis's fit: the noise model and the Allan-variance points it was fitted to.

    ``observed``, ``model`` and ``edf`` are the measured and fitted Allan variances and the equivalent
    degrees of freedom at ``tau`` (``sizes`` samples per cluster), the τ that entered the fit;
    ``chi_square`` on ``dof`` degrees of freedom is the GLS misfit, which nested fits compare (they share
    the covariance across τ through ``reference``); ``result`` is the fitter's whole answer.
    """

    noise: FittedNoise
    tau: np.ndarray
    sizes: np.ndarray
    observed: np.ndarray
    model: np.ndarray
    edf: np.ndarray
    chi_square: float
    dof: int
    result: FitResult

    @property
    def bias(self) -> float:
        """The fitted constant bias (rad/s), TIM 2014 eq. (1)."""
        return float(self.noise.model.bias)


# --- the fit --------------------------------------------------------------------------------------------


def _ar_coefficients(
    x: np.ndarray, sample_rate: float, terms: ModelTerms, reference: ResidualFit | None
) -> tuple[float, ...]:
    """The reference's AR coefficients when it has some (a refit subtracts a slow signal, which leaves the
    fast part's autocovariance as it was), else Yule–Walker on ``x``; () without an AR term."""
    if not terms.ar_order:
        return ()
    reused = reference.noise.model.ar_coefficients if reference is not None else ()
    return reused or yule_walker(x, sample_rate, terms.ar_order)


def _loop_standard_errors(result: FitResult, terms: ModelTerms) -> dict[str, float]:
    """Standard errors of the long-run white, walk and 1/f variances for the loop's Satterthwaite degrees
    of freedom: from the normal equations with diagonal weights Var(σ̂_A²) = 2 σ_A⁴/ν at the used τ (ν
    the fitted model's equivalent degrees of freedom), as the loop's tests were calibrated with. They are
    smaller than the fitter's GLS standard errors, which include the correlation across τ."""
    model = result.model
    used = result.used
    sizes = np.asarray(result.allan.samples_per_cluster, dtype=np.int64)[used]
    short = "ar" if model.ar_variance or model.ar_coefficients else "white"
    names = (short, "rrw", *(("flicker",) if terms.flicker else ()))
    columns = [term_allan_variance(name, sizes, model.flicker_d, model.ar_coefficients) for name in names]
    if short == "ar":  # the column of the long-run variance σ_e²/(1 − Σ a_j)²
        columns[0] = columns[0] * (1.0 - sum(model.ar_coefficients)) ** 2
    sigma = np.maximum(result.model_avar[used], 1e-300) * np.sqrt(2.0 / result.edf[used])
    weighted = np.column_stack(columns) / sigma[:, None]
    try:
        covariance = np.linalg.inv(weighted.T @ weighted)
    except np.linalg.LinAlgError:
        covariance = np.full((len(names), len(names)), math.nan)
    labels = ("long_run_white_variance", "rrw_variance", "flicker_variance")
    return {labels[i]: float(math.sqrt(max(covariance[i, i], 0.0))) for i in range(len(names))}


def fit_residual_model(
    values: np.ndarray, sample_rate: float, terms: ModelTerms, *, reference: ResidualFit | None = None
) -> ResidualFit:
    """Fit bias + short noise + rate random walk (+ 1/f of order 1/2) to one axis.

    :func:`carousel_theory.fitting.fit_observed` on the non-overlapping octave Allan variance, the τ with
    at least MINIMUM_CLUSTERS clusters. ``reference``, a fit of the same axis and length, fixes the
    covariance across τ (a refit, or a nested fit whose χ² is compared with the reference's) and lends
    its autoregressive coefficients.
    """
    x = np.asarray(values, dtype=np.float64)
    ar = _ar_coefficients(x, sample_rate, terms, reference)
    components = ("ar" if ar else "white", "rrw", *(("flicker",) if terms.flicker else ()))
    options = FitOptions(
        components, flicker_d=FLICKER_D, ar_coefficients=ar or None, minimum_clusters=MINIMUM_CLUSTERS
    )
    observed = observe_allan(x, sample_rate, estimator="non-overlapping")
    fixed = reference.result.tau_covariance if reference is not None else None
    result = fit_observed(observed, options, fixed_covariance=fixed)
    used = result.used
    allan = result.allan
    return ResidualFit(
        noise=FittedNoise(result.model, _loop_standard_errors(result, terms)),
        tau=np.asarray(allan.tau)[used],
        sizes=np.asarray(allan.samples_per_cluster, dtype=np.int64)[used],
        observed=np.asarray(allan.avar)[used],
        model=result.model_avar[used],
        edf=result.edf[used].astype(np.float64),
        chi_square=float(result.chi_square),
        dof=int(result.degrees_of_freedom),
        result=result,
    )


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


def statistic_variance(noise: FittedNoise, weights: np.ndarray, include_flicker: bool = True) -> float:
    """Var(Σ w_t e_t) under the model: short noise as its long-run variance times Σw² (exact for white;
    for the autoregressive noise exact up to O(correlation length / scale of w), the weights used here
    varying slowly), the walk and the 1/f term by :func:`~carousel_theory.propagation.weighted_sum_variance`
    (TIM 2014 eqs. (2)–(3))."""
    model = noise.model
    total = _long_run_variance(model) * float(np.dot(weights, weights))
    if model.rrw_variance:
        total += model.rrw_variance * weighted_sum_variance(weights, "rrw")
    if model.flicker_variance and include_flicker:
        total += model.flicker_variance * weighted_sum_variance(weights, "flicker", d=model.flicker_d)
    return total


def ranking_statistic_variance(noise: FittedNoise, weights: np.ndarray, block: int) -> float:
    """Var(Σ w_t e_t) for weights constant over blocks of ``block`` samples, the 1/f part approximated at
    block level (block means of 1/f noise of order d are, at low frequency, 1/f noise of driving variance
    σ_f² b^{2d−1}, so the part is σ_f² b^{2d+1} Σ_i (Σ_{B≥i} w_B ψ_{B−i})² over the n/b block weights).
    Only to rank the points of a scan, whose chosen point is then tested exactly: O(n/b log(n/b))."""
    model = noise.model
    total = statistic_variance(noise, weights, include_flicker=False)
    if model.flicker_variance:
        count = len(weights) // block
        block_weights = weights[: count * block : block]
        unit = weighted_sum_variance(block_weights, "flicker", d=model.flicker_d)
        total += model.flicker_variance * block ** (2 * model.flicker_d + 1) * unit
    return total


def statistic_variance_dof(noise: FittedNoise, weights: np.ndarray) -> tuple[float, float]:
    """(variance, effective degrees of freedom) of Σ w_t e_t: the variance as :func:`statistic_variance`,
    and ν = 2 V² / Var(V̂) from the standard errors of the fitted variances (Satterthwaite), so that a z
    built on it is referred to Student's t with ν degrees of freedom: a rate random walk estimated from a
    few long-τ Allan points is uncertain, and a normal reference would then be anticonservative."""
    model, errors = noise.model, noise.standard_errors
    parts = {"long_run_white_variance": (_long_run_variance(model), float(np.dot(weights, weights)))}
    # The walk's share counts even at a fitted σ_q² of 0: its standard error still says how large it could be.
    parts["rrw_variance"] = (model.rrw_variance, weighted_sum_variance(weights, "rrw"))
    if model.flicker_variance or math.isfinite(errors.get("flicker_variance", math.nan)):
        flicker_unit = weighted_sum_variance(weights, "flicker", d=model.flicker_d)
        parts["flicker_variance"] = (model.flicker_variance, flicker_unit)
    variance = sum(value * unit for value, unit in parts.values())
    spread = 0.0
    for name, (value, unit) in parts.items():
        error = errors.get(name, math.nan)
        spread += (unit * (error if math.isfinite(error) else value)) ** 2
    dof = 2.0 * variance**2 / spread if spread > 0 else math.inf
    return variance, max(dof, 1.0)


def bounded_noise(
    current: FittedNoise, candidate: FittedNoise, *, keep_flicker_floor: bool = True
) -> FittedNoise:
    """``candidate`` with each variance raised to at least ``current``'s value minus 2 standard errors.

    ``keep_flicker_floor=False`` leaves the 1/f variance as fitted: the joint fit of a regressor with the
    1/f term is exactly the case where the null fit's 1/f variance holds the regressor's signal."""
    errors, now, new = current.standard_errors, current.model, candidate.model

    def floor(name: str, value: float, reference: float) -> float:
        error = errors.get(name, math.nan)
        limit = reference - 2.0 * error if math.isfinite(error) else reference
        return max(value, limit, 0.0)

    flicker = new.flicker_variance
    if keep_flicker_floor and (new.flicker_variance or now.flicker_variance):
        flicker = floor("flicker_variance", new.flicker_variance, now.flicker_variance)
    lower_walk = new.rrw_variance < now.rrw_variance
    model = replace(
        new,
        rrw_variance=floor("rrw_variance", new.rrw_variance, now.rrw_variance),
        flicker_variance=flicker,
    )
    return FittedNoise(model, dict(errors) if lower_walk else dict(candidate.standard_errors))


def difference_covariance_bands(noise: FittedNoise, block: int, size: int) -> np.ndarray:
    """Upper banded form of the covariance of first differences of ``block``-sample means.

    Differences Δx_t = q_t + w_t − w_{t−1} of white + rate random walk: MA(1) with γ₀ = σ_q² + 2σ²,
    γ₁ = −σ²; on block means of b samples white σ²/b, walk increments ≈ σ_q² b. A floor on σ_q² keeps the
    tridiagonal system well conditioned when no walk is fitted."""
    white = _long_run_variance(noise.model) / block
    walk = max(noise.model.rrw_variance * block, 1e-8 * white)
    bands = np.empty((2, size))
    bands[0, :] = -white
    bands[0, 0] = 0.0
    bands[1, :] = walk + 2.0 * white
    return bands


def spectral_density(noise: FittedNoise, frequencies: np.ndarray) -> np.ndarray:
    """Discrete spectral density (per-sample variance units: white σ² is flat at σ²) of the model,
    :meth:`~carousel_theory.noise_model.NoiseModel.spectral_density`; at f = 0 a walk or 1/f term gives
    +inf."""
    return noise.model.spectral_density(frequencies)


def _short_autocovariance(model: NoiseModel, lags: int) -> np.ndarray:
    """γ_h, h = 0 … lags − 1, of the short noise: white σ² at lag 0 plus the AR term's autocovariance."""
    gamma = np.zeros(lags)
    gamma[0] = model.white_variance
    if model.ar_variance:
        gamma += model.ar_variance * ar_autocovariance(model.ar_coefficients, lags)
    return gamma


def uniform_bin_variances(noise: FittedNoise, weights: np.ndarray, count: int) -> np.ndarray:
    """Var of each of ``count`` consecutive bins reduced with the same ``weights``: wᵀΓw of the short
    noise (TIM 2014 eq. (9) for white) plus the walk and 1/f terms of eqs. (17)–(18), exact per bin."""
    model, length = noise.model, len(weights)
    gamma = _short_autocovariance(model, min(AR_LAGS, length))
    lagged = np.array([np.dot(weights[: length - h], weights[h:]) for h in range(len(gamma))])
    variance = np.full(count, gamma[0] * lagged[0] + 2.0 * np.dot(gamma[1:], lagged[1:]))
    if model.rrw_variance:
        variance += model.rrw_variance * repeated_weights_bin_variances(weights, "rrw", count)
    if model.flicker_variance:
        variance += model.flicker_variance * repeated_weights_bin_variances(
            weights, "flicker", count, d=model.flicker_d
        )
    return variance


def revolution_bin_variance(noise: FittedNoise, weights: np.ndarray, start: int) -> float:
    """Var of Σ w_u x_{start+u} for one bin starting at sample ``start`` (short noise as its long-run
    variance; the walk at the bin start enters every sample: t₀ (Σw)² plus the walk within the bin)."""
    model = noise.model
    total = _long_run_variance(model) * float(np.dot(weights, weights))
    total += model.rrw_variance * (start * float(weights.sum()) ** 2 + weighted_sum_variance(weights, "rrw"))
    if model.flicker_variance:
        padded = np.concatenate((np.zeros(start), weights))
        total += model.flicker_variance * weighted_sum_variance(padded, "flicker", d=model.flicker_d)
    return total


def noise_growth(
    before: FittedNoise, after: FittedNoise, z: float = 2.0, *, new_flicker: bool = False
) -> list[str]:
    """Noise variances that grew by more than ``z`` standard errors (and 20 %) from ``before``
    (``new_flicker``: the 1/f term is new in ``after``, its variance is not compared)."""
    grown = []
    pairs = (
        ("long_run_white_variance", _long_run_variance(before.model), _long_run_variance(after.model)),
        ("rrw_variance", before.model.rrw_variance, after.model.rrw_variance),
        ("flicker_variance", before.model.flicker_variance, after.model.flicker_variance),
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


def simulate_block_sums(noise: FittedNoise, length: int, block: int, rng: np.random.Generator) -> np.ndarray:
    """Sums of ``block`` consecutive samples of one draw of the fitted model (bias 0), ``length // block``
    of them, without simulating every sample for the white and random-walk parts.

    Short noise: independent N(0, σ_LR² b) (exact for white; for the autoregressive noise the block sums
    are correlated only through O(correlation length / b) edge terms). Rate random walk (TIM 2014 eq. (2)):
    block j's sum is b R_j + W_j with R_j the walk before the block, and the pair (I_j = Σ_k q_k,
    W_j = Σ_k (b − k + 1) q_k) of the block's increments Gaussian with Var I = b σ_q²,
    Var W = σ_q² Σ_k k², Cov = σ_q² Σ_k k — exact. 1/f noise is simulated sample by sample."""
    model, count = noise.model, length // block
    total = rng.normal(0.0, math.sqrt(_long_run_variance(model) * block), count)
    if model.rrw_variance:
        # Σ_k k and Σ_k k² over the block, exact integer sums (the weights of W are b, b − 1, …, 1)
        linear, square = sum(range(1, block + 1)), sum(k * k for k in range(1, block + 1))
        covariance = model.rrw_variance * np.array([[block, linear], [linear, square]], dtype=np.float64)
        pairs = rng.multivariate_normal(np.zeros(2), covariance, count, method="cholesky")
        before = np.concatenate(([0.0], np.cumsum(pairs[:-1, 0])))
        total += block * before + pairs[:, 1]
    if model.flicker_variance:
        flicker = sample_flicker(count * block, rng=rng, d=model.flicker_d, variance=model.flicker_variance)
        total += flicker.reshape(count, block).sum(axis=1)
    return total


def describe_noise(noise: FittedNoise) -> dict[str, Any]:
    """The fitted model as the loop's JSON reports it (per-sample variances and the usual IEEE units):
    ``white_variance_rad2_s2`` is the innovation variance of the short noise (white, or the AR term's)."""
    model = noise.model
    long_run = _long_run_variance(model)
    return {
        "bias_rad_s": float(model.bias),
        "white_variance_rad2_s2": float(model.ar_variance if model.ar_variance else model.white_variance),
        "long_run_white_variance_rad2_s2": long_run,
        "rrw_variance_rad2_s2": float(model.rrw_variance),
        "flicker_variance_rad2_s2": float(model.flicker_variance),
        "flicker_d": float(model.flicker_d) if model.flicker_variance else None,
        "ar_coefficients": list(model.ar_coefficients),
        "angle_random_walk_deg_per_sqrt_h": units.to_deg_per_sqrt_hour(
            units.angle_random_walk_from_white_variance(long_run, model.sample_rate)
        ),
        "rate_random_walk_deg_per_h_per_sqrt_h": model.rate_random_walk_deg_per_hour_per_sqrt_hour(),
        "standard_errors": dict(noise.standard_errors),
    }
