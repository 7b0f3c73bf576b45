"""The residual model of the closed loop: an adapter over the package's one noise model and one fitter.

This is the only room of the loop that knows how a noise model is stored and fitted. The rest of the
loop calls the functions listed in ``__all__`` and reads the fields of :class:`ResidualFit`; the noise
it passes around is a :class:`FittedNoise`, which it hands back to these functions without reading it.

The model is :class:`carousel_theory.noise_model.NoiseModel` (TIM 2014 §II, per-sample discrete terms):
bias + short noise (white, or for the ``colored_noise`` effect an autoregressive process
x_t = Σ a_j x_{t−j} + e_t in place of the white noise) + rate random walk (eq. (2)) + an optional 1/f
term of order d = 1/2 (eq. (3)). The fit is :func:`carousel_theory.fitting.fit_observed`: generalised
least squares on the non-overlapping Allan variance at octave τ (eq. (20)) with the model-based
covariance across τ, AR coefficients by :func:`carousel_theory.autoregression.yule_walker`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from scipy import stats

from carousel_theory import units
from carousel_theory.autoregression import yule_walker
from carousel_theory.closed_loop.flicker_blocks import flicker_block_sums
from carousel_theory.fitting import FitOptions, FitResult, fit_observed, observe_allan
from carousel_theory.noise_model import (
    NoiseModel,
    ar_autocovariance,
    ar_long_run_variance,
    term_allan_variance,
)
from carousel_theory.processes import fractionally_integrate, sample_flicker
from carousel_theory.propagation import repeated_weights_bin_variances, weighted_sum_variance

__all__ = [
    "VARIANCE_NAMES",
    "FittedNoise",
    "ModelTerms",
    "NoiseVariances",
    "ResidualFit",
    "StatisticUnits",
    "StatisticVariance",
    "allan_z_values",
    "bounded_noise",
    "chi_square_z",
    "covariance_product",
    "describe_noise",
    "difference_covariance_bands",
    "fit_residual_model",
    "fit_units",
    "model_curve_error",
    "nested_statistic",
    "noise_growth",
    "noise_variances",
    "ranking_statistic_variance",
    "revolution_bin_variance",
    "simulate_block_sum_draws",
    "simulate_block_sums",
    "spectral_density",
    "statistic_units",
    "statistic_variance",
    "statistic_variance_error",
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


#: The variances the loop's tests use, as :class:`FittedNoise` names them.
VARIANCE_NAMES = ("long_run_white_variance", "rrw_variance", "flicker_variance")
#: Which fitter parameter each of them is (the AR innovation variance is scaled to its long-run value).
_FITTER_PARAMETER = {
    "white_variance": "long_run_white_variance",
    "ar_variance": "long_run_white_variance",
    "rrw_variance": "rrw_variance",
    "flicker_variance": "flicker_variance",
}


@dataclass(frozen=True)
class FittedNoise:
    """A fitted :class:`~carousel_theory.noise_model.NoiseModel` and the covariance of its variance
    estimates that the loop's tests use: the fitter's GLS covariance (JᵀC⁻¹J)⁻¹
    (:func:`carousel_theory.fitting.fit_observed`, C the model-based covariance of the Allan-variance
    estimates across τ) of ``names`` (a subset of VARIANCE_NAMES, in that order); the short noise as
    long averages see it (``long_run_white_variance``), the walk and, when fitted, the 1/f variance.
    Without ``names`` (a model given rather than fitted) every variance counts as uncertain by its own
    size."""

    model: NoiseModel
    names: tuple[str, ...] = ()
    covariance: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))

    @property
    def standard_errors(self) -> dict[str, float]:
        """The square roots of the diagonal of ``covariance``, by name."""
        diagonal = np.diag(self.covariance)
        return {name: math.sqrt(max(float(diagonal[i]), 0.0)) for i, name in enumerate(self.names)}


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


def _fitted_noise(result: FitResult) -> FittedNoise:
    """The fit as a :class:`FittedNoise`: the rows of the fitter's GLS covariance that are variances the
    loop uses, the AR innovation variance scaled by 1/(1 − Σ a_j)² to the long-run variance (the AR
    coefficients themselves are held fixed, as the fit holds them)."""
    model = result.model
    gain = ar_long_run_variance(1.0, tuple(model.ar_coefficients))
    rows = [i for i, name in enumerate(result.parameters) if name in _FITTER_PARAMETER]
    names = tuple(_FITTER_PARAMETER[result.parameters[i]] for i in rows)
    scale = np.array([gain if result.parameters[i] == "ar_variance" else 1.0 for i in rows])
    covariance = np.asarray(result.covariance)[np.ix_(rows, rows)] * np.outer(scale, scale)
    order = sorted(range(len(names)), key=lambda i: VARIANCE_NAMES.index(names[i]))
    return FittedNoise(model, tuple(names[i] for i in order), covariance[np.ix_(order, order)])


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
    # Three covariance evaluations, always: the loop's false-alarm rates were measured with them.
    options = FitOptions(
        components,
        flicker_d=FLICKER_D,
        ar_coefficients=ar or None,
        minimum_clusters=MINIMUM_CLUSTERS,
        tolerance=None,
    )
    observed = observe_allan(x, sample_rate, estimator="non-overlapping")
    fixed = reference.result.tau_covariance if reference is not None else None
    result = fit_observed(observed, options, fixed_covariance=fixed)
    used = result.used
    allan = result.allan
    return ResidualFit(
        noise=_fitted_noise(result),
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


def nested_statistic(reduced_chi_square: float, full_chi_square: float, dof: int) -> float:
    """Δχ² / max(1, χ²/ν) of two nested GLS Allan-variance fits under one covariance across τ: the
    reduction of χ² when a term is added (never negative: a non-negative fit with one more column cannot
    fit worse), scaled by the fuller fit's over-dispersion when it has any (ν ≥ 1 degrees of freedom)."""
    dof = max(int(dof), 1)
    return max(0.0, reduced_chi_square - full_chi_square) / max(1.0, full_chi_square / dof)


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


@dataclass(frozen=True)
class StatisticVariance:
    """Var(Σ w_t e_t) under the fitted model and the standard error of that estimate."""

    variance: float
    standard_error: float

    @property
    def relative_error(self) -> float:
        """se(V̂) / V̂."""
        return self.standard_error / self.variance if self.variance > 0 else math.inf


def statistic_variance_error(noise: FittedNoise, weights: np.ndarray) -> StatisticVariance:
    """Var(Σ w_t e_t) and its standard error.

    The variance V = Σ_i θ_i u_i(w) (:func:`statistic_units`, θ the fitted variances, u_i the variance of
    the statistic per unit of each); its standard error √(uᵀ Σ_θ u) by the delta method,
    Σ_θ the fitter's GLS covariance of the variances (:class:`FittedNoise`; the white, walk and 1/f
    estimates are correlated through the Allan variance they share, which the quadratic form keeps).
    The walk's share counts even at a fitted σ_q² of 0: its standard error still says how large it could
    be. A variance without a covariance row counts as uncertain by its own size."""
    model = noise.model
    flicker = bool(model.flicker_variance) or "flicker_variance" in noise.names
    per_unit, theta = statistic_units(weights, model.flicker_d, flicker=flicker), noise_variances(noise)
    parts = {
        "long_run_white_variance": (theta.long_run_white, per_unit.long_run_white),
        "rrw_variance": (theta.rrw, per_unit.rrw),
    }
    if flicker:
        parts["flicker_variance"] = (theta.flicker, per_unit.flicker)
    variance = sum(value * unit for value, unit in parts.values())
    rows = [i for i, name in enumerate(noise.names) if name in parts]
    units = np.array([parts[noise.names[i]][1] for i in rows])
    spread = float(units @ noise.covariance[np.ix_(rows, rows)] @ units) if rows else 0.0
    spread += sum((unit * value) ** 2 for name, (value, unit) in parts.items() if name not in noise.names)
    return StatisticVariance(variance, math.sqrt(max(spread, 0.0)))


@dataclass(frozen=True)
class NoiseVariances:
    """The variances the loop's tests use (VARIANCE_NAMES): the short noise's long-run variance, the walk
    and the 1/f variance (0 when the model has none)."""

    long_run_white: float
    rrw: float
    flicker: float


def noise_variances(noise: FittedNoise) -> NoiseVariances:
    """θ of ``noise`` as :class:`NoiseVariances`."""
    model = noise.model
    return NoiseVariances(_long_run_variance(model), float(model.rrw_variance), float(model.flicker_variance))


@dataclass(frozen=True)
class StatisticUnits:
    """u_i(w), the variance of Σ w_t e_t per unit of each variance of :class:`NoiseVariances`:
    Σ w² for the short noise, TIM 2014 eq. (2) for the walk, eq. (3) of order ``flicker_d`` for the 1/f
    term; V(θ) = Σ_i θ_i u_i(w)."""

    long_run_white: float
    rrw: float
    flicker: float

    def variance(self, theta: NoiseVariances) -> float:
        """V(θ) = Σ_i θ_i u_i."""
        return (
            theta.long_run_white * self.long_run_white + theta.rrw * self.rrw + theta.flicker * self.flicker
        )

    def of_parameter(self, parameter: str) -> float:
        """u of a fitter parameter (``white_variance``, ``ar_variance`` — both the short noise's long-run
        variance per unit —, ``rrw_variance``, ``flicker_variance``)."""
        name = _FITTER_PARAMETER[parameter]
        return {"long_run_white_variance": self.long_run_white, "rrw_variance": self.rrw}.get(
            name, self.flicker
        )


def statistic_units(
    weights: np.ndarray, flicker_d: float = FLICKER_D, *, flicker: bool = True
) -> StatisticUnits:
    """:class:`StatisticUnits` of ``weights`` (1/f of order ``flicker_d``; its unit left at 0 without
    ``flicker``)."""
    return StatisticUnits(
        float(np.dot(weights, weights)),
        weighted_sum_variance(weights, "rrw"),
        weighted_sum_variance(weights, "flicker", d=flicker_d) if flicker else 0.0,
    )


def fit_units(fit: ResidualFit, weights: np.ndarray) -> StatisticUnits:
    """:func:`statistic_units` of ``weights`` at the fit's 1/f order, the 1/f unit (a transform of twice
    the record's length) only when the fit has a 1/f term: without it neither V(θ̂) nor any model drawn
    with the fit's terms has a 1/f variance."""
    flicker = "flicker_variance" in fit.result.parameters
    return statistic_units(weights, fit.noise.model.flicker_d, flicker=flicker)


def covariance_product(noise: FittedNoise, weights: np.ndarray) -> np.ndarray:
    """Σ w, Σ the covariance of the model's samples (bias left out), so that Cov(e, Σ w_t e_t) = Σ w.

    Short noise: its long-run variance times w (exact for white). Walk (TIM 2014 eq. (2)), x = C q with C
    the lower-triangular matrix of ones: σ_q² C Cᵀ w by a suffix sum and a prefix sum. 1/f (eq. (3)),
    x = Ψ ε with Ψ the lower-triangular Toeplitz matrix of the ψ_j: σ_f² Ψ Ψᵀ w by two FFT convolutions."""
    model = noise.model
    product = _long_run_variance(model) * weights
    if model.rrw_variance:
        suffix = np.cumsum(weights[::-1])[::-1]
        product = product + model.rrw_variance * np.cumsum(suffix)
    if model.flicker_variance:
        transposed = fractionally_integrate(weights[::-1], model.flicker_d)[::-1]
        product = product + model.flicker_variance * fractionally_integrate(transposed, model.flicker_d)
    return product


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
    return replace(current if lower_walk else candidate, model=model)


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


#: The noise-model term of each fitter parameter the loop fits.
_TERM_OF_PARAMETER = {
    "white_variance": "white",
    "rrw_variance": "rrw",
    "flicker_variance": "flicker",
    "ar_variance": "ar",
}


def _curve_columns(fit: ResidualFit) -> tuple[list[int], np.ndarray]:
    """(rows of the fitter's covariance, design J): ∂σ_A²(τ)/∂θ at the used τ for the fitted variances."""
    result, model = fit.result, fit.noise.model
    rows = [i for i, name in enumerate(result.parameters) if name in _TERM_OF_PARAMETER]
    columns = [
        term_allan_variance(
            _TERM_OF_PARAMETER[result.parameters[i]], fit.sizes, model.flicker_d, model.ar_coefficients
        )
        for i in rows
    ]
    return rows, np.column_stack(columns)


def model_curve_error(fit: ResidualFit) -> np.ndarray:
    """Standard error of the fitted model's Allan variance at each used τ: √diag(J Σ_θ Jᵀ), Σ_θ the
    fitter's GLS covariance of the variances (TIM 2014 eq. (20) is linear in them)."""
    rows, design = _curve_columns(fit)
    covariance = np.asarray(fit.result.covariance)[np.ix_(rows, rows)]
    return np.sqrt(np.maximum(np.einsum("ij,jk,ik->i", design, covariance, design), 0.0))


#: The least relative growth of the model's Allan variance that counts as growth in :func:`noise_growth`.
#: On a long record the curve's standard error is a fraction of a percent, so the refit's reshuffling of
#: power between correlated terms alone exceeds 2 of them: without this floor the spikes of ADIS16405
#: run 4 are rejected and the loop ends ``unexplained`` (docs/real_data_loop.md). A judgement, not a
#: computed level: it only ever keeps a candidate its own test has already detected.
MATERIAL_GROWTH = 0.2


def noise_growth(
    before: ResidualFit, after: ResidualFit, z: float = 2.0, *, new_flicker: bool = False
) -> list[str]:
    """The τ at which the fitted model's Allan variance grew by more than ``z`` of its standard errors
    (:func:`model_curve_error` of ``before``) and by more than :data:`MATERIAL_GROWTH`, from ``before``
    to ``after`` (``new_flicker``: the 1/f term is new in ``after``; its own share is not counted as growth).

    Removing a deterministic effect s that is really there lowers the expected Allan variance at every τ
    by the effect's own, E σ̂_A²(e + s) = E σ̂_A²(e) + σ_A²(s) for s independent of e; what a wrongly
    fitted effect leaves behind adds power that the refitted model must absorb. The comparison is of the
    curve, not of the single variances: the white, walk and 1/f estimates are correlated across τ, and
    removing a slow effect moves power between the walk and the 1/f term by about their GLS standard
    errors without adding any. This check can only reject a candidate, never name one, so it does not
    enter the false-alarm rate of a clean record."""
    grown_after = after.model
    if new_flicker:
        model = after.noise.model
        grown_after = grown_after - model.flicker_variance * term_allan_variance(
            "flicker", after.sizes, model.flicker_d
        )
    limit = before.model + z * model_curve_error(before)
    grown = np.flatnonzero((grown_after > limit) & (grown_after > (1.0 + MATERIAL_GROWTH) * before.model))
    return [
        f"Allan variance at τ = {before.tau[i]:.4g} s {before.model[i]:.3g} -> {grown_after[i]:.3g}"
        for i in grown
    ]


def _walk_block_sums(
    variance: float, block: int, shape: tuple[int, ...], rng: np.random.Generator
) -> np.ndarray:
    """Block sums of a rate random walk (TIM 2014 eq. (2), r_0 = 0) along the last axis of ``shape``:
    block j's sum is b R_j + W_j, R_j the walk before the block and
    (I_j = Σ_k q_k, W_j = Σ_k (b − k + 1) q_k) Gaussian with Var I = b σ_q², Var W = σ_q² Σ_k k²,
    Cov = σ_q² Σ_k k — exact."""
    # Σ_k k and Σ_k k² over the block, exact integer sums (the weights of W are b, b − 1, …, 1)
    linear, square = sum(range(1, block + 1)), sum(k * k for k in range(1, block + 1))
    covariance = variance * np.array([[block, linear], [linear, square]], dtype=np.float64)
    if block == 1:  # I = W = q₁: the covariance is singular, and Cholesky refuses it
        pairs = np.repeat(rng.normal(0.0, math.sqrt(variance), (*shape, 1)), 2, axis=-1)
    else:
        pairs = rng.multivariate_normal(np.zeros(2), covariance, shape, method="cholesky")
    before = np.zeros(shape)
    before[..., 1:] = np.cumsum(pairs[..., :-1, 0], axis=-1)
    return block * before + pairs[..., 1]


def simulate_block_sums(noise: FittedNoise, length: int, block: int, rng: np.random.Generator) -> np.ndarray:
    """Sums of ``block`` consecutive samples of one draw of the fitted model (bias 0), ``length // block``
    of them, without simulating every sample for the white and random-walk parts.

    Short noise: independent N(0, σ_LR² b) (exact for white; for the autoregressive noise the block sums
    are correlated only through O(correlation length / b) edge terms). Rate random walk: exact
    (:func:`_walk_block_sums`). 1/f noise is simulated sample by sample."""
    model, count = noise.model, length // block
    total = rng.normal(0.0, math.sqrt(_long_run_variance(model) * block), count)
    if model.rrw_variance:
        total += _walk_block_sums(model.rrw_variance, block, (count,), rng)
    if model.flicker_variance:
        flicker = sample_flicker(count * block, rng=rng, d=model.flicker_d, variance=model.flicker_variance)
        total += flicker.reshape(count, block).sum(axis=1)
    return total


def simulate_block_sum_draws(
    noise: FittedNoise, length: int, block: int, replicates: int, rng: np.random.Generator
) -> np.ndarray:
    """``replicates`` independent draws of :func:`simulate_block_sums` as the rows of one array, the 1/f
    block sums from their low-rank factor
    (:func:`~carousel_theory.closed_loop.flicker_blocks.flicker_block_sums`, exact covariance to
    FLICKER_RANK_TOLERANCE) instead of sample by sample."""
    model, count = noise.model, length // block
    total = rng.normal(0.0, math.sqrt(_long_run_variance(model) * block), (replicates, count))
    if model.rrw_variance:
        total += _walk_block_sums(model.rrw_variance, block, (replicates, count), rng)
    if model.flicker_variance:
        total += flicker_block_sums(model.flicker_variance, model.flicker_d, block, count, rng, replicates)
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
