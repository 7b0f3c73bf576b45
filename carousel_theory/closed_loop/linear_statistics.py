"""Linear statistics of a residual under its fitted model: GLS weights, their variance, refits.

The trend detectors (warm-up, temperature, steps) use generalised least squares under white noise +
rate random walk: on first differences (which remove the bias) the noise is a tridiagonal MA(1), so the
GLS weights cost one banded solve. The variance of a linear statistic Σ w_t e_t (Σ w_t = 0) is the exact
propagation of the whole fitted model, 1/f included (TIM 2014 eqs. (2)–(3)), so the rate random walk
cannot masquerade as a trend, a step or a warm-up at the stated false-alarm rate.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import stats
from scipy.linalg import solveh_banded

from carousel_theory.closed_loop.calibration import long_tau_start
from carousel_theory.closed_loop.residual_model import (
    FittedNoise,
    ModelTerms,
    ResidualFit,
    StatisticVariance,
    bounded_noise,
    difference_covariance_bands,
    fit_residual_model,
    fit_units,
    nested_statistic,
    noise_variances,
    ranking_statistic_variance,
    statistic_variance,
    statistic_variance_error,
)
from carousel_theory.closed_loop.studentized import (
    CONFIDENCE_SHARE,
    BoundaryReference,
    block_sums,
    boundary_reference,
    expand_block_weights,
)
from carousel_theory.closed_loop.view import ResidualView

__all__ = [
    "GLS_BLOCKS",
    "RegressorTest",
    "StepScan",
    "difference_weights",
    "exponential_regressor",
    "fit_with_terms",
    "gls_block",
    "gls_difference_solve",
    "gls_weights",
    "nested_chi_square",
    "refit",
    "regressor_test",
    "step_scan",
    "studentized_test",
]

#: Long records are reduced to at most this many block means to choose the GLS weights of trend tests.
GLS_BLOCKS = 50_000


def gls_block(view: ResidualView) -> int:
    """Samples per block of the GLS trend statistics: records longer than GLS_BLOCKS samples are reduced
    to block means for the *choice* of the weights (their variance stays exact, per sample)."""
    return max(1, math.ceil(len(view.time) / GLS_BLOCKS))


def _block_means(view: ResidualView, values: np.ndarray) -> np.ndarray:
    block = gls_block(view)
    count = len(values) // block
    return values[: count * block].reshape(count, block).mean(axis=1)


def _expand(view: ResidualView, block_weights: np.ndarray) -> np.ndarray:
    """Per-sample weights: each block's weight / block on its samples, 0 on the incomplete last block
    (written into one record-length array)."""
    block = gls_block(view)
    expanded = np.zeros(len(view.time), dtype=np.float64)
    expanded[: len(block_weights) * block].reshape(len(block_weights), block)[:] = (block_weights / block)[
        :, np.newaxis
    ]
    return expanded


def _bands(view: ResidualView, noise: FittedNoise) -> np.ndarray:
    block = gls_block(view)
    return difference_covariance_bands(noise, block, len(view.time) // block - 1)


def _noise(view: ResidualView, axis: str, noise: FittedNoise | None) -> FittedNoise:
    return view.fits[axis].noise if noise is None else noise


def exponential_regressor(view: ResidualView, time_constant: float) -> np.ndarray:
    """e^{−(t − t₀)/τ_c} at the view's sample times (the warm-up's regressor), formed in one record-length
    array."""
    regressor = np.subtract(view.time, view.time[0], dtype=np.float64)
    np.divide(regressor, -time_constant, out=regressor)
    return np.exp(regressor, out=regressor)


def difference_weights(noise: FittedNoise, regressor: np.ndarray, block: int) -> np.ndarray:
    """Dᵀ Σ_Δ⁻¹ D ḡ, ḡ the means of the complete blocks of ``block`` samples of ``regressor``, D the first
    difference (which also removes the bias), Σ_Δ the tridiagonal covariance of the differenced block
    means under ``noise``: the GLS weights of the block means."""
    count = len(regressor) // block
    means = regressor[: count * block].reshape(count, block).mean(axis=1)
    bands = difference_covariance_bands(noise, block, count - 1)
    solved = solveh_banded(bands, np.diff(means), check_finite=False)
    return np.concatenate(([0.0], solved)) - np.concatenate((solved, [0.0]))


def gls_weights(
    view: ResidualView, axis: str, regressor: np.ndarray, noise: FittedNoise | None = None
) -> np.ndarray:
    """Sample weights w of the GLS projection on ``regressor``: w = Dᵀ Σ_Δ⁻¹ D g on the view's blocks
    (:func:`difference_weights`), each block's weight spread over its samples."""
    return _expand(view, difference_weights(_noise(view, axis, noise), regressor, gls_block(view)))


def gls_difference_solve(view: ResidualView, axis: str, vector: np.ndarray) -> np.ndarray:
    """Σ_Δ⁻¹ v for the tridiagonal covariance of the (block) differences under the fitted model."""
    return solveh_banded(_bands(view, view.fits[axis].noise), vector, check_finite=False)


@dataclass(frozen=True)
class StepScan:
    """u_j = (Σ_Δ⁻¹ Δx)_j, the GLS statistic of a bias step after block j, for every j; the sample
    weights of a step in the middle and its information (Σ_Δ⁻¹)_mm."""

    statistics: np.ndarray
    middle_weights: np.ndarray
    information: float


def step_scan(view: ResidualView, axis: str) -> StepScan:
    """The GLS statistic of a bias step at every block boundary, from one tridiagonal solve."""
    bands = _bands(view, view.fits[axis].noise)
    u = solveh_banded(bands, np.diff(_block_means(view, view.residuals[axis])), check_finite=False)
    impulse = np.zeros(len(u))
    impulse[len(u) // 2] = 1.0
    solved = solveh_banded(bands, impulse, check_finite=False)
    weights = _expand(view, np.concatenate(([0.0], solved)) - np.concatenate((solved, [0.0])))
    return StepScan(u, weights, float(solved[len(u) // 2]))


def refit(view: ResidualView, axis: str, signal: np.ndarray, terms: ModelTerms | None = None) -> FittedNoise:
    """The noise model of the axis refitted on its residual minus ``signal`` (the view's terms, or
    ``terms``), with the same Allan-variance weights as the view's fit."""
    fit = fit_residual_model(
        view.cleaned[axis] - signal,
        view.sample_rate,
        view.spec.terms if terms is None else terms,
        reference=view.fits[axis],
    )
    return fit.noise


def fit_with_terms(view: ResidualView, axis: str, terms: ModelTerms) -> ResidualFit:
    """The axis's residual fitted with ``terms`` and the view's weights (made once per view and terms)."""
    key = (axis, terms)
    if key not in view.other_fits:
        view.other_fits[key] = fit_residual_model(
            view.cleaned[axis], view.sample_rate, terms, reference=view.fits[axis]
        )
    return view.other_fits[key]


def nested_chi_square(view: ResidualView, axis: str, *, flicker: bool) -> tuple[float, int]:
    """χ² and its degrees of freedom of the Allan-variance fit with (or without) a 1/f term, weights
    shared with the view's fit so that the two χ² are comparable."""
    if flicker == view.spec.terms.flicker:
        fit = view.fits[axis]
        return fit.chi_square, fit.dof
    fit = fit_with_terms(view, axis, ModelTerms(view.spec.terms.ar_order, flicker))
    return fit.chi_square, fit.dof


#: Pre-test level at which a competing 1/f term enters a joint refit (liberal: including it when it is
#: absent only widens the statistic's variance; leaving it out when present lets it hide the regressor).
COMPETING_TERM_LEVEL = 0.05


def _competing_terms(
    view: ResidualView, axis: str, signal: np.ndarray, terms: ModelTerms
) -> tuple[ModelTerms, float]:
    """``terms``, keeping a 1/f term only when the model already has one or when, on the residual without
    ``signal``, the F test of the nested Allan-variance fits asks for it at COMPETING_TERM_LEVEL; and the
    p-value of that F test (1 when none was made)."""
    if not terms.flicker or view.spec.terms.flicker:
        return terms, 1.0
    if not np.any(signal):
        without = fit_with_terms(view, axis, ModelTerms(terms.ar_order, False))
        joint = fit_with_terms(view, axis, terms)
    else:
        values, rate, reference = view.cleaned[axis] - signal, view.sample_rate, view.fits[axis]
        without = fit_residual_model(values, rate, ModelTerms(terms.ar_order, False), reference=reference)
        joint = fit_residual_model(values, rate, terms, reference=reference)
    statistic = nested_statistic(without.chi_square, joint.chi_square, joint.dof)
    p_value = float(stats.f.sf(statistic, 1, max(joint.dof, 1)))
    return (terms if p_value < COMPETING_TERM_LEVEL else ModelTerms(terms.ar_order)), p_value


def ranking_noise(view: ResidualView, axis: str) -> FittedNoise:
    """The noise model under which the points of a scan are ranked: the view's, or, when a 1/f term the
    model lacks is asked for by the residual itself (:func:`_competing_terms`), the fit with it."""
    terms = ModelTerms(view.spec.terms.ar_order, flicker=True)
    chosen, _ = _competing_terms(view, axis, np.zeros(len(view.time)), terms)
    if chosen.flicker and not view.spec.terms.flicker:
        return fit_with_terms(view, axis, chosen).noise
    return view.fits[axis].noise


@dataclass(frozen=True)
class RegressorTest:
    """A regressor's GLS statistic L = Σ w_t e_t in the residual: ``z`` = L/√V̂ under the fitted model (the
    ranking value), the amplitude, L, its variance and that variance's standard error
    (:class:`~carousel_theory.closed_loop.residual_model.StatisticVariance`, None when only ranked), the
    p-value of a competing 1/f term on the residual without the regressor (1 when none was tested), and,
    for a joint test, the bootstrap reference of z (:func:`studentized_test`)."""

    z: float
    amplitude: float
    projection: float = 0.0
    spread: StatisticVariance | None = None
    competing_p: float = 1.0
    reference: BoundaryReference | None = None


def studentized_test(
    view: ResidualView, axis: str, regressor: np.ndarray, terms: ModelTerms, noise: FittedNoise, level: float
) -> tuple[float, float, BoundaryReference]:
    """(z, L, reference) of the joint test of ``regressor`` with the stochastic ``terms``: the GLS weights
    under ``noise`` on blocks of the first long τ (constant over them, as the reference needs), L = Σ w_t e_t,
    the noise refitted by the fitter on r = e − (L/I)(g − ḡ) (no floor: the boundary is the reference's
    business), z = L/√V(θ̂), and the confidence-set reference of z
    (:func:`~carousel_theory.closed_loop.studentized.boundary_reference`) at the per-test ``level``, γ =
    CONFIDENCE_SHARE · level."""
    length, fit = len(view.time), view.fits[axis]
    first = long_tau_start(fit, length)
    if first >= len(fit.sizes):
        raise ValueError(f"{axis!r}: {length!r} samples give no long τ to refer a trend statistic to")
    block = int(fit.sizes[first])
    block_weights = difference_weights(noise, regressor, block) / block
    sums = block_sums(np.asarray(regressor, dtype=np.float64), block)
    projection = float(np.dot(block_weights, block_sums(view.residuals[axis], block)))
    information = float(np.dot(block_weights, sums))
    signal = regressor - regressor.mean()
    signal *= projection / information
    refitted = fit_residual_model(view.cleaned[axis] - signal, view.sample_rate, terms, reference=fit)
    del signal
    weights = expand_block_weights(block_weights, block, length)
    units = fit_units(refitted, weights)
    del weights  # the reference expands its own; one record-length array less at its peak
    z = projection / math.sqrt(max(units.variance(noise_variances(refitted.noise)), 1e-300))
    share = CONFIDENCE_SHARE * level
    reference = boundary_reference(refitted, length, block_weights, projection, share, sums, units=units)
    return z, projection, reference


def regressor_test(
    view: ResidualView,
    axis: str,
    regressor: np.ndarray,
    *,
    quick: bool = False,
    refit_terms: ModelTerms | None = None,
    ranking: FittedNoise | None = None,
    level: float = 0.0,
) -> RegressorTest:
    """The GLS statistic Σ w_t e_t of ``regressor``, its z under the fitted model and its variance.

    ``quick`` ranks points of a scan (no refit; under ``ranking`` when given, else under the view's fit
    without its 1/f term). With ``refit_terms`` the noise model is
    refitted jointly with the regressor (a Wald test under the alternative) with those stochastic terms:
    a competing term that could absorb the regressor (1/f noise under a warm-up) is fitted on the
    residual *without* the regressor, so it cannot hide it; a 1/f term the model lacks enters only when
    that residual asks for it (:func:`_competing_terms`). With a per-test ``level`` the joint test is
    studentized by the refitted model and referred to its bootstrap (:func:`studentized_test`; the weights
    chosen under the refit below). Without ``level`` the refit may not go below the lower
    2-standard-error limit for the walk of the null fit with the same terms (a smooth regressor absorbs
    a stretch of the random walk, and σ_q² → 0 would make the normal reference anticonservative; a null
    fit without the 1/f term would count the 1/f power twice, once in its walk). Without ``refit_terms``:
    the view's fit.
    """
    weights = gls_weights(view, axis, regressor)
    information = float(np.dot(weights, regressor))
    if information <= 0.0:
        return RegressorTest(0.0, 0.0)
    amplitude = float(np.dot(weights, view.residuals[axis])) / information
    noise = view.fits[axis].noise
    if quick:
        if ranking is None:
            variance = statistic_variance(noise, weights, include_flicker=False)
        else:
            variance = ranking_statistic_variance(ranking, weights, max(gls_block(view), 16))
        return RegressorTest(float(np.dot(weights, view.residuals[axis])) / math.sqrt(variance), amplitude)
    competing_p = 1.0
    if refit_terms is not None:
        del weights  # made anew under the refitted noise; one record-length array less meanwhile
        signal = regressor - regressor.mean()
        signal *= amplitude
        terms, competing_p = _competing_terms(view, axis, signal, refit_terms)
        refitted = refit(view, axis, signal, terms)
        del signal  # not held through the variance below, the peak of the joint refit
        # The floor comes from the null fit with the same stochastic terms: without its 1/f term the
        # null fit's walk holds the 1/f power too, and a floor from it would count that power twice.
        floor = fit_with_terms(view, axis, terms).noise if terms != view.spec.terms else noise
        noise = bounded_noise(floor, refitted, keep_flicker_floor=not terms.flicker)
        if level:
            z, projection, reference = studentized_test(view, axis, regressor, terms, noise, level)
            return RegressorTest(z, amplitude, projection, None, competing_p, reference)
        weights = gls_weights(view, axis, regressor, noise)
    spread = statistic_variance_error(noise, weights)
    projection = float(np.dot(weights, view.residuals[axis]))
    z = projection / math.sqrt(max(spread.variance, 1e-300))
    return RegressorTest(z, amplitude, projection, spread, competing_p)
