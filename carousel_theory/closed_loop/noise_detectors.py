"""Detectors of stochastic terms the model lacks: short-correlated (colored) noise and 1/f noise."""

from __future__ import annotations

import math

import numpy as np
from scipy import optimize, stats

from carousel_theory.closed_loop.detection import Detection, untestable
from carousel_theory.closed_loop.linear_statistics import nested_chi_square
from carousel_theory.closed_loop.null_distributions import median_ratio_log_sf
from carousel_theory.closed_loop.residual_model import ModelTerms, spectral_density
from carousel_theory.closed_loop.signal_detectors import hann_periodogram
from carousel_theory.closed_loop.view import FittedEffect, ResidualView

__all__ = ["ColoredNoiseDetector", "FlickerDetector", "FlickerGoodnessOfFit"]

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
        frequencies, power = hann_periodogram(view.residuals[axis], view.sample_rate)
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


class FlickerDetector:
    """Δχ² / max(1, χ²/ν) of the GLS Allan-variance fit when a 1/f (d = 1/2) term is added.

    The fits share the model-based covariance across τ (:mod:`carousel_theory.fitting`), so Δχ² is χ²₁
    under the model; when the larger fit misfits (χ²/ν > 1) its dispersion scales Δχ², which is then
    referred to F(1, ν) (an estimated scale)."""

    name = "flicker"
    stochastic = True

    def detect(self, view: ResidualView, alpha: float) -> Detection:
        tests = len(view.axes)
        best_log10_p, best_statistic, best_axis, best_dof, axes = 1.0, 0.0, "", 1, []
        for axis in view.axes:
            without, _ = nested_chi_square(view, axis, flicker=False)
            with_flicker, dof = nested_chi_square(view, axis, flicker=True)
            dof = max(dof, 1)
            # The gain over the residual dispersion of the larger fit (at least 1), so that a model
            # slightly off elsewhere does not pass for 1/f noise.
            dispersion = with_flicker / dof
            statistic = max(0.0, without - with_flicker) / max(1.0, dispersion)
            log_sf = stats.f.logsf(statistic, 1, dof) if dispersion > 1.0 else stats.chi2.logsf(statistic, 1)
            log10_p = min(0.0, math.log10(tests) + float(log_sf) / math.log(10.0))
            if log10_p < math.log10(alpha):
                axes.append(axis)
            if log10_p < best_log10_p:
                best_log10_p, best_statistic, best_axis, best_dof = log10_p, statistic, axis, dof
        return Detection(
            self.name,
            best_statistic,
            "Δχ² of the Allan-variance fit with a 1/f term (over its dispersion when above 1)",
            float(stats.chi2.isf(alpha / tests, 1)),
            min(0.0, best_log10_p),
            bool(axes),
            tuple(axes),
            {"axis": best_axis, "residual_degrees_of_freedom": best_dof},
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
