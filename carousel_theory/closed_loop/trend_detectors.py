"""Detectors of slow deterministic effects: a warm-up transient, a temperature-driven bias, bias steps.

Each is a GLS regression statistic (:mod:`carousel_theory.closed_loop.linear_statistics`), exactly
Gaussian under the model given the noise variances, Bonferroni over its scan and the axes.
The warm-up and temperature statistics are computed jointly with the stochastic term that could absorb
them: the noise model is refitted on the residual without the regressor, with
a 1/f term for the warm-up (a transient and 1/f noise share the low frequencies) and with the random walk
for the temperature (a ramp and a random walk share them), so the weaker effect is not hidden by the
inflated stochastic term fitted with it still in the data. Their z is studentized by that refit and
referred to a parametric bootstrap from it that refits every replicate, with the walk and 1/f variances
that the record cannot tell from 0 searched over their confidence interval
(:func:`~carousel_theory.closed_loop.studentized.boundary_reference`, whose size and power on whole
records are measured in docs/trend_reference_size.md). The step scan is referred to the normal
distribution at an upper confidence bound of its variance with the bound's non-coverage added to the
p-value (Berger & Boos 1994, :func:`~carousel_theory.closed_loop.detection.bounded_two_sided`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from carousel_theory.closed_loop.detection import (
    Detection,
    bounded_standard_deviation,
    bounded_threshold,
    bounded_two_sided,
    threshold_two_sided,
    untestable,
)
from carousel_theory.closed_loop.linear_statistics import (
    COMPETING_TERM_LEVEL,
    RegressorTest,
    exponential_regressor,
    gls_block,
    gls_difference_solve,
    gls_weights,
    ranking_noise,
    regressor_test,
    step_scan,
)
from carousel_theory.closed_loop.residual_model import (
    ModelTerms,
    StatisticVariance,
    statistic_variance_error,
)
from carousel_theory.closed_loop.view import FittedEffect, ResidualView

__all__ = ["StepsDetector", "TemperatureDetector", "WarmupDetector"]


@dataclass(frozen=True)
class _AxisResult:
    axis: str
    z: float
    log10_p: float
    details: dict[str, float]
    threshold: float = math.inf


def _bounded(axis: str, result: RegressorTest, tests: int, alpha: float, details: dict) -> _AxisResult:
    """The axis's result from a full :func:`regressor_test`: z studentized by the refitted model and p
    from its bootstrap reference (a joint test), else z and p at the variance's upper bound."""
    if result.reference is not None:
        reference = result.reference
        found = {**details, "reference_models": float(len(reference.references))}
        threshold = reference.threshold(alpha, tests)
        return _AxisResult(axis, result.z, reference.log10_p(result.z, tests), found, threshold)
    if result.spread is None:
        return _AxisResult(axis, 0.0, 0.0, details, bounded_threshold(alpha, tests))
    spread = result.spread
    z, log10_p = bounded_two_sided(result.projection, spread.variance, spread.standard_error, tests, alpha)
    found = {**details, "variance_relative_error": spread.relative_error}
    return _AxisResult(axis, z, log10_p, found, bounded_threshold(alpha, tests))


def _best(results: list[_AxisResult], alpha: float) -> tuple[_AxisResult, tuple[str, ...]]:
    significant = tuple(r.axis for r in results if r.log10_p < math.log10(alpha))
    return min(results, key=lambda r: r.log10_p), significant


class WarmupDetector:
    """max over time constants τ_c of |z| of the GLS amplitude of e^{−t/τ_c}, jointly with a 1/f term."""

    name = "warmup"
    stochastic = False
    grid_size = 8

    def _grid(self, view: ResidualView) -> np.ndarray:
        span = float(view.time[-1] - view.time[0])
        low = max(span / 500.0, 5.0 / view.sample_rate)
        return np.geomspace(low, span / 4.0, self.grid_size)

    def _axis(self, view: ResidualView, axis: str, tests: int, alpha: float) -> _AxisResult:
        noise = ranking_noise(view, axis)
        ranked = max(
            (
                (
                    regressor_test(view, axis, exponential_regressor(view, tc), quick=True, ranking=noise).z,
                    float(tc),
                )
                for tc in self._grid(view)
            ),
            key=lambda pair: abs(pair[0]),
        )
        joint = ModelTerms(view.spec.terms.ar_order, flicker=True)
        regressor = exponential_regressor(view, ranked[1])
        result = regressor_test(view, axis, regressor, refit_terms=joint, level=alpha / tests)
        details = {
            "time_constant_s": ranked[1],
            "amplitude": result.amplitude,
            "competing_flicker_p": result.competing_p,
        }
        return _bounded(axis, result, tests, alpha, details)

    def detect(self, view: ResidualView, alpha: float) -> Detection:
        tests = self.grid_size * len(view.axes)
        best, axes = _best([self._axis(view, axis, tests, alpha) for axis in view.axes], alpha)
        return Detection(
            self.name,
            abs(best.z),
            "max abs z of an exponential transient (studentized by the joint refit)",
            best.threshold,
            best.log10_p,
            bool(axes),
            axes,
            {"axis": best.axis, **best.details},
        )

    def fit(self, view: ResidualView, detection: Detection, alpha: float) -> FittedEffect:
        """The time constant maximising the GLS fit (the detector's own criterion) on a fine grid around
        the detected one; the amplitude by GLS."""
        grid = self._grid(view)
        centre = float(detection.details.get("time_constant_s") or grid[0])
        fine = np.geomspace(max(centre / 4.0, grid[0] / 2.0), min(centre * 4.0, grid[-1] * 2.0), 13)
        signals, fitted = {}, {}
        for axis in view.axes:
            best = (-1.0, centre, 0.0)
            for time_constant in fine:
                regressor = exponential_regressor(view, time_constant)
                weights = gls_weights(view, axis, regressor)
                information = float(np.dot(weights, regressor))
                projection = float(np.dot(weights, view.residuals[axis]))
                if information > 0 and projection**2 / information > best[0]:
                    best = (projection**2 / information, float(time_constant), projection / information)
            _, time_constant, amplitude = best
            curve = exponential_regressor(view, time_constant)
            curve *= amplitude
            curve -= curve.mean()
            signals[axis] = curve
            fitted[axis] = {"amplitude": amplitude, "time_constant_s": time_constant}
        # Detected jointly with a 1/f term whose own test (on the residual without the warm-up) is
        # significant at the loop's rate: the two enter the model together and the 1/f term is named
        # (control._joint_term). A 1/f term that only entered the joint statistic (p below
        # COMPETING_TERM_LEVEL, not below ``alpha``) stays out of the model rather than entering it unnamed:
        # its own detector tests it on the residual without the warm-up (control._companion adds the two
        # together when it is significant there; otherwise the next iteration tests it again).
        joint = float(detection.details.get("competing_flicker_p", 1.0)) < min(alpha, COMPETING_TERM_LEVEL)
        terms = ModelTerms(flicker=True) if joint else None
        return FittedEffect(self.name, fitted, signals=signals, terms=terms)


class TemperatureDetector:
    """|z| of the GLS coefficient of the temperature column, jointly with the rate random walk."""

    name = "temperature"
    stochastic = False
    statistic_name = "abs z of the temperature regression (studentized by the joint refit)"

    def detect(self, view: ResidualView, alpha: float) -> Detection:
        tests = len(view.axes)
        if view.temperature is None:
            note = "no temperature column: a temperature effect cannot be tested"
            return untestable(self.name, self.statistic_name, threshold_two_sided(alpha, tests), note)
        if float(np.ptp(view.temperature)) == 0.0:
            note = "the temperature column is constant: no temperature effect can be tested"
            return untestable(self.name, self.statistic_name, threshold_two_sided(alpha, tests), note)
        results = []
        for axis in view.axes:
            result = regressor_test(
                view, axis, view.temperature, refit_terms=view.spec.terms, level=alpha / tests
            )
            found = {"coefficient_rad_s_per_degC": result.amplitude}
            results.append(_bounded(axis, result, tests, alpha, found))
        best, axes = _best(results, alpha)
        details: dict[str, Any] = {
            "axis": best.axis,
            **best.details,
            "temperature_range_degC": float(np.ptp(view.temperature)),
        }
        return Detection(
            self.name,
            abs(best.z),
            self.statistic_name,
            best.threshold,
            best.log10_p,
            bool(axes),
            axes,
            details,
        )

    def fit(self, view: ResidualView, detection: Detection, alpha: float) -> FittedEffect:
        """k by GLS on each axis (the detector's own estimate); k (T − T̄) subtracted."""
        assert view.temperature is not None
        centred = view.temperature - view.temperature.mean()
        signals, fitted = {}, {}
        for axis in view.axes:
            weights = gls_weights(view, axis, view.temperature)
            coefficient = float(np.dot(weights, view.residuals[axis]) / np.dot(weights, view.temperature))
            signals[axis] = coefficient * centred
            fitted[axis] = {"coefficient_rad_s_per_degC": coefficient}
        return FittedEffect(self.name, fitted, signals=signals)


@dataclass(frozen=True)
class _Scan:
    """u_j, the GLS statistic of a step after block j; the variance of a step's statistic with its error;
    the information of a step; and the standard deviation at the variance's upper bound."""

    statistics: np.ndarray
    spread: StatisticVariance
    information: float
    sd: float


class StepsDetector:
    """max over t₀ of |z| of the GLS estimate of a bias step after sample t₀, Bonferroni over positions."""

    name = "steps"
    stochastic = False
    maximum_steps = 5

    def _scan(self, view: ResidualView, axis: str, alpha: float) -> _Scan:
        """u of a step after every block under the fit (no refit: a refit without the largest increment
        of the random walk lowers σ_q² enough to make the scan's maximum anticonservative); the variance
        of a step in the middle and its standard error carry the uncertainty of the fitted σ_q²."""
        scan = step_scan(view, axis)
        spread = statistic_variance_error(view.fits[axis].noise, scan.middle_weights)
        sd = bounded_standard_deviation(spread.variance, spread.standard_error, alpha)
        return _Scan(scan.statistics, spread, scan.information, sd)

    def _tests(self, view: ResidualView) -> int:
        return (len(view.time) // gls_block(view) - 1) * len(view.axes)

    def detect(self, view: ResidualView, alpha: float) -> Detection:
        n, tests = len(view.time), self._tests(view)
        results = []
        for axis in view.axes:
            scan = self._scan(view, axis, alpha)
            index = int(np.argmax(np.abs(scan.statistics)))
            u = float(scan.statistics[index])
            z, log10_p = bounded_two_sided(u, scan.spread.variance, scan.spread.standard_error, tests, alpha)
            at = min((index + 1) * gls_block(view), n - 1)
            details = {
                "time_s": float(view.time[at]),
                "height": u / scan.information,
                "variance_relative_error": scan.spread.relative_error,
            }
            results.append(_AxisResult(axis, z, log10_p, details))
        best, axes = _best(results, alpha)
        return Detection(
            self.name,
            abs(best.z),
            "max abs z of a bias step (GLS, variance at its upper bound)",
            bounded_threshold(alpha, tests),
            best.log10_p,
            bool(axes),
            axes,
            {"axis": best.axis, **best.details},
        )

    def _jumps(self, view: ResidualView, axis: str, threshold: float, scan: _Scan) -> tuple[np.ndarray, list]:
        n, block = len(view.time), gls_block(view)
        statistic = scan.statistics  # u_t
        total, jumps = np.zeros(n), []
        for _ in range(self.maximum_steps):
            index = int(np.argmax(np.abs(statistic)))
            if abs(statistic[index]) / scan.sd <= threshold:
                break
            height = float(statistic[index] / scan.information)
            at = (index + 1) * block
            # Remove this jump from the scan: u changes by height · Σ_Δ⁻¹ e_index.
            impulse = np.zeros(len(statistic))
            impulse[index] = 1.0
            statistic = statistic - height * gls_difference_solve(view, axis, impulse)
            step = height * (np.arange(n) >= at)
            total += step - step.mean()
            jumps.append({"time_s": float(view.time[at]), "height": height})
        return total, jumps

    def fit(self, view: ResidualView, detection: Detection, alpha: float) -> FittedEffect:
        """Each jump at the maximum |z|, its height by GLS, removed from the scan; up to 5 jumps."""
        signals, fitted = {}, {}
        for axis in view.axes:
            scan = self._scan(view, axis, alpha)
            threshold = bounded_threshold(alpha, self._tests(view))
            signals[axis], jumps = self._jumps(view, axis, threshold, scan)
            fitted[axis] = {"jumps": jumps}
        return FittedEffect(self.name, fitted, signals=signals)
