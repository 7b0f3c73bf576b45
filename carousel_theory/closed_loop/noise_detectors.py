"""Detectors of stochastic terms the model lacks: short-correlated (colored) noise and 1/f noise."""

from __future__ import annotations

import math

import numpy as np
from scipy import stats

from carousel_theory.closed_loop.detection import Detection, log10_two_sided, threshold_two_sided
from carousel_theory.closed_loop.linear_statistics import nested_chi_square
from carousel_theory.closed_loop.residual_model import ModelTerms, spectral_density
from carousel_theory.closed_loop.signal_detectors import hann_periodogram
from carousel_theory.closed_loop.view import FittedEffect, ResidualView

__all__ = ["ColoredNoiseDetector", "FlickerDetector", "FlickerGoodnessOfFit"]

#: Asymptotic variance × M of the log of the median of M Exp(1) values: 1/ln²2.
MEDIAN_LOG_VARIANCE = 1.0 / math.log(2.0) ** 2
#: Variance inflation from the Hann window's correlation of ordinates two bins apart (|1/6|² = 1/36).
HANN_LAG_TWO_INFLATION = 1.0 + 2.0 / 36.0


class ColoredNoiseDetector:
    """z of log(median whitened periodogram in 5–15 % of f_s / median in 35–50 % of f_s).

    Under the model every second Hann ordinate of the whitened periodogram is Exp(1); the log of a median
    of M of them is asymptotically normal with variance 1/(4 M f(m)² m²) = 1/(M ln²2) = 2.08/M (m = ln 2
    the median, f(m) = 1/2 the density there). Ordinates two bins apart are not quite independent: the
    Hann window correlates the DFT values two bins apart by 1/6, their squares by 1/36, which inflates the
    variance of the median by at most 1 + 2/36 (measured on white noise of 3.6·10⁵ samples: sd of z
    1.049 ± 0.043 without the factor). M is a few thousand already at 300 s, 100 Hz."""

    name = "colored_noise"
    stochastic = True
    maximum_order = 4

    def _statistic(self, view: ResidualView, axis: str) -> tuple[float, int]:
        frequencies, power = hann_periodogram(view.residuals[axis], view.sample_rate)
        model = np.maximum(spectral_density(view.fits[axis].noise, frequencies), 1e-300)
        relative, whitened = (frequencies / view.sample_rate)[::2], (power / model)[::2]
        low = whitened[(relative >= 0.05) & (relative < 0.15)]
        high = whitened[(relative >= 0.35) & (relative < 0.5)]
        if len(low) < 8 or len(high) < 8:
            return 0.0, 0
        se = math.sqrt(MEDIAN_LOG_VARIANCE * HANN_LAG_TWO_INFLATION * (1.0 / len(low) + 1.0 / len(high)))
        return math.log(np.median(low) / np.median(high)) / se, len(low) + len(high)

    def detect(self, view: ResidualView, alpha: float) -> Detection:
        tests = len(view.axes)
        threshold = threshold_two_sided(alpha, tests)
        best, best_axis, axes = 0.0, "", []
        for axis in view.axes:
            z, ordinates = self._statistic(view, axis)
            if ordinates == 0:
                continue
            if abs(z) > threshold:
                axes.append(axis)
            if abs(z) >= abs(best):
                best, best_axis = z, axis
        return Detection(
            self.name,
            abs(best),
            "abs z of the spectral slope, 10 % vs 42 % of f_s",
            threshold,
            log10_two_sided(best, tests),
            bool(axes),
            tuple(axes),
            {"axis": best_axis, "signed_z": best},
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
