"""Detectors of stochastic terms the model lacks: short-correlated (colored) noise and 1/f noise."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import optimize, stats
from scipy.linalg import solve_triangular

from carousel_theory.closed_loop.calibration import (
    FLICKER_STREAM,
    AllanVarianceSampler,
    bootstrap_generator,
    sequential_monte_carlo_p,
)
from carousel_theory.closed_loop.detection import Detection, untestable
from carousel_theory.closed_loop.null_distributions import median_ratio_log_sf
from carousel_theory.closed_loop.residual_model import (
    FLICKER_D,
    ModelTerms,
    ResidualFit,
    nested_statistic,
    spectral_density,
)
from carousel_theory.closed_loop.signal_detectors import residual_periodogram
from carousel_theory.closed_loop.view import FittedEffect, ResidualView
from carousel_theory.noise_model import term_allan_variance

__all__ = ["ColoredNoiseDetector", "FlickerDetector", "FlickerGoodnessOfFit", "NestedAllanStatistic"]


#: Every this many-th periodogram ordinate is used: the Hann window's DFT kernel has three taps (lags
#: −1, 0, 1), so for white Gaussian noise ordinates three bins apart are independent (to O(1/n)).
ORDINATE_STRIDE = 3


class ColoredNoiseDetector:
    """log(median whitened periodogram in 5–15 % of f_s / median in 35–50 % of f_s), two-sided.

    Under the model the whitened ordinates (periodogram / model spectrum), every ORDINATE_STRIDE-th, are
    independent Exp(1), so the ratio of the two medians has the finite-sample distribution of a ratio of
    independent exponential medians: its tails by
    :func:`~carousel_theory.closed_loop.null_distributions.median_ratio_log_sf` (exact cumulant
    generating function, saddlepoint tail; relative error O(1/M) for M ordinates, a few thousand already
    at 300 s, 100 Hz). This replaces the normal approximation of the log median (variance 1/(M ln²2),
    asymptotic) and the Hann correlation of ordinates two bins apart that it had to be inflated for."""

    name = "colored_noise"
    stochastic = True
    maximum_order = 4
    statistic_name = "abs log ratio of the median whitened periodogram, 10 % vs 42 % of f_s"

    def _statistic(self, view: ResidualView, axis: str) -> tuple[float, int, int]:
        """(log ratio of the two medians, ordinates in the low band, in the high band)."""
        frequencies, power = residual_periodogram(view, axis)
        model = np.maximum(spectral_density(view.fits[axis].noise, frequencies), 1e-300)
        stride = slice(None, None, ORDINATE_STRIDE)
        relative, whitened = (frequencies / view.sample_rate)[stride], (power / model)[stride]
        low = whitened[(relative >= 0.05) & (relative < 0.15)]
        high = whitened[(relative >= 0.35) & (relative < 0.5)]
        if len(low) < 8 or len(high) < 8:
            return 0.0, 0, 0
        return math.log(np.median(low) / np.median(high)), len(low), len(high)

    @staticmethod
    def _log_p(statistic: float, low: int, high: int) -> float:
        """log of the two-sided p-value of a log ratio ``statistic`` of medians of ``low`` and ``high``
        independent Exp(1) values: P(ratio ≥ e^{|t|}) + P(1/ratio ≥ e^{|t|})."""
        ratio = math.exp(abs(statistic))
        return float(
            np.logaddexp(median_ratio_log_sf(ratio, low, high), median_ratio_log_sf(ratio, high, low))
        )

    def _threshold(self, alpha: float, low: int, high: int) -> float:
        target = math.log(alpha)
        return float(optimize.brentq(lambda t: self._log_p(t, low, high) - target, 0.0, 5.0))

    def detect(self, view: ResidualView, alpha: float) -> Detection:
        tests = len(view.axes)
        results = {axis: self._statistic(view, axis) for axis in view.axes}
        results = {axis: result for axis, result in results.items() if result[1]}
        if not results:
            note = "the record is too short for the spectral slope"
            return untestable(self.name, self.statistic_name, math.inf, note)
        log_p = {axis: math.log(tests) + self._log_p(*result) for axis, result in results.items()}
        best_axis = min(log_p, key=lambda axis: log_p[axis])
        statistic, low, high = results[best_axis]
        return Detection(
            self.name,
            abs(statistic),
            self.statistic_name,
            self._threshold(alpha / tests, low, high),
            min(0.0, log_p[best_axis] / math.log(10.0)),
            log_p[best_axis] < math.log(alpha),
            tuple(axis for axis, value in log_p.items() if value < math.log(alpha)),
            {"axis": best_axis, "signed_log_ratio": statistic, "ordinates": low + high},
        )

    def fit(self, view: ResidualView, detection: Detection, alpha: float) -> FittedEffect:
        """The short noise becomes autoregressive of order ≤ 4 (Yule–Walker) in the refit."""
        terms = ModelTerms(ar_order=self.maximum_order)
        return FittedEffect(self.name, {"maximum_order": self.maximum_order}, terms=terms)


def _whitened_design(
    components: tuple[str, ...], sizes: np.ndarray, ar: tuple[float, ...], cholesky: np.ndarray
) -> np.ndarray:
    """The GLS design of :func:`carousel_theory.fitting.fit_observed` (the exact Allan variance of each
    term at unit variance), whitened by C = LLᵀ and with unit-norm columns (the fitter's NNLS scaling)."""
    columns = [term_allan_variance(name, sizes, FLICKER_D, ar_coefficients=ar) for name in components]
    whitened = solve_triangular(cholesky, np.column_stack(columns), lower=True)
    norms = np.linalg.norm(whitened, axis=0)
    return whitened / np.where(norms > 0, norms, 1.0)


@dataclass(frozen=True)
class NestedAllanStatistic:
    """T = max(0, χ²₀ − χ²₁) / max(1, χ²₁/ν) of the non-negative GLS fits of an Allan-variance vector
    without (χ²₀) and with (χ²₁, ν degrees of freedom) a 1/f term, both under one fixed covariance C
    across τ: the statistic of :class:`FlickerDetector`, cheap enough to recompute on every replicate.
    On the observed Allan variance it equals the Δχ² of the loop's nested fits
    (:func:`~carousel_theory.closed_loop.linear_statistics.nested_chi_square`)."""

    cholesky: np.ndarray
    reduced: np.ndarray
    full: np.ndarray
    dof: int

    @classmethod
    def from_fit(cls, fit: ResidualFit) -> NestedAllanStatistic:
        """The statistic at the τ, AR coefficients and covariance across τ of ``fit`` (a fit without 1/f)."""
        ar = fit.noise.model.ar_coefficients
        cholesky = np.linalg.cholesky(np.asarray(fit.result.tau_covariance, dtype=np.float64))
        reduced = ("ar" if ar else "white", "rrw")
        full = _whitened_design((*reduced, "flicker"), fit.sizes, ar, cholesky)
        dof = max(len(fit.sizes) - 3, 1)
        return cls(cholesky, _whitened_design(reduced, fit.sizes, ar, cholesky), full, dof)

    def __call__(self, allan: np.ndarray) -> float:
        whitened = solve_triangular(self.cholesky, allan, lower=True)
        without = optimize.nnls(self.reduced, whitened)[1] ** 2
        with_flicker = optimize.nnls(self.full, whitened)[1] ** 2
        return nested_statistic(without, with_flicker, self.dof)


class FlickerDetector:
    """Δχ² / max(1, χ²/ν) of the GLS Allan-variance fit when a 1/f (d = 1/2) term is added, referred to a
    parametric bootstrap from the fitted model without it.

    The fits share the covariance C across τ of the model's fit (:mod:`carousel_theory.fitting`). Δχ² is
    χ²₁ only asymptotically (Gaussian Allan-variance estimates, the longest τ averaging a handful of
    differences), so its null distribution is drawn instead: each replicate is an Allan-variance vector
    of the fitted model (:class:`~carousel_theory.closed_loop.calibration.AllanVarianceSampler`, the long
    τ exactly from block sums), refitted both ways under the same C (:class:`NestedAllanStatistic`), and
    p = (1 + #{T* ≥ T})/(B + 1) by the loop's sequential Monte Carlo test
    (:func:`~carousel_theory.closed_loop.calibration.sequential_monte_carlo_p`) at α over the axes
    (Bonferroni). C is held at the observed fit's (the weights are treated as fixed, as the trend
    detectors' are); the draws come from
    :func:`~carousel_theory.closed_loop.calibration.bootstrap_generator`, seeded by the observed Allan
    variances, so a recording always gets the same answer and different recordings independent replicates."""

    name = "flicker"
    stochastic = True
    statistic_name = "Δχ² of the Allan-variance fit with a 1/f term (over its dispersion when above 1)"

    def _axis_p(self, view: ResidualView, axis: str, alpha: float, rng: np.random.Generator) -> tuple:
        """(statistic, Monte Carlo p-value, replicates drawn, residual degrees of freedom) of one axis."""
        fit = view.fits[axis]
        statistic = NestedAllanStatistic.from_fit(fit)
        observed = statistic(fit.observed)
        sampler = AllanVarianceSampler.from_fit(fit, len(view.cleaned[axis]))
        p_value, drawn = sequential_monte_carlo_p(lambda: statistic(sampler.draw(rng)), observed, alpha)
        return observed, p_value, drawn, statistic.dof

    def detect(self, view: ResidualView, alpha: float) -> Detection:
        if view.spec.terms.flicker:
            note = "the model already has a 1/f term"
            return untestable(self.name, self.statistic_name, float("nan"), note)
        tests = len(view.axes)
        rng = bootstrap_generator(FLICKER_STREAM, [view.fits[axis].observed for axis in view.axes])
        results = {axis: self._axis_p(view, axis, alpha / tests, rng) for axis in view.axes}
        axes = tuple(axis for axis, result in results.items() if result[1] <= alpha / tests)
        best_axis = min(results, key=lambda axis: (results[axis][1], -results[axis][0]))
        statistic, p_value, drawn, dof = results[best_axis]
        return Detection(
            self.name,
            statistic,
            self.statistic_name,
            float("nan"),  # a Monte Carlo test has no fixed threshold
            min(0.0, math.log10(min(1.0, tests * p_value))),
            bool(axes),
            axes,
            {"axis": best_axis, "residual_degrees_of_freedom": dof, "replicates": drawn},
        )

    def fit(self, view: ResidualView, detection: Detection, alpha: float) -> FittedEffect:
        """A 1/f term σ_f² (d = 1/2) in the refit; nothing is subtracted."""
        return FittedEffect(self.name, {"d": 0.5}, terms=ModelTerms(flicker=True))


class FlickerGoodnessOfFit:
    """After adding 1/f noise: the χ² goodness of fit of the Allan variance on every axis."""

    name = "flicker"

    def detect(self, view: ResidualView, alpha: float) -> Detection:
        tests = len(view.axes)
        worst, worst_axis, worst_log_p, axes = 0.0, "", 0.0, []
        for axis in view.axes:
            fit = view.fits[axis]
            dof = max(fit.dof, 1)
            log_p = float(stats.chi2.logsf(fit.chi_square, dof)) / math.log(10.0) + math.log10(tests)
            if log_p < math.log10(alpha):
                axes.append(axis)
            if log_p <= worst_log_p:
                worst, worst_axis, worst_log_p = fit.chi_square, axis, log_p
        return Detection(
            self.name,
            worst,
            "χ² of the Allan-variance fit",
            float("nan"),
            min(0.0, worst_log_p),
            bool(axes),
            tuple(axes),
            {"axis": worst_axis},
        )
