"""Predictions of the fitted model and the residual metrics of one iteration.

- **Averaged bins**: bin means of N samples minus the mean of the whole bins, with their exact predicted
  variances (TIM 2014 eq. (15) generalised).
- **Carouselled bins**: virtual carouseling of the two axes (TIM 2014 eq. (6), weights eq. (13)) with N
  samples per revolution, or one bin per measured revolution when the recording has angles; variances
  from eqs. (9), (17)–(18).
- **Allan variance**: each τ as a z-value of its χ² distribution.
- **Tails**: the excess kurtosis of the sample-to-sample differences.
- **Headline error** ``standardized_misfit``: the root mean square of the z-values of the Allan variance at
  each τ and axis, of the carouselled-bin variance ratio, of the tails and of every detector's p-value:
  about 1 when the model is right, large when it is not.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy import stats
from scipy.interpolate import CubicSpline

from carousel_theory.closed_loop.detection import Detection
from carousel_theory.closed_loop.detectors import DETECTORS, TESTED_EFFECTS
from carousel_theory.closed_loop.residual_model import (
    allan_z_values,
    revolution_bin_variance,
    statistic_variance,
    uniform_bin_variances,
)
from carousel_theory.closed_loop.view import ResidualView
from carousel_theory.weights import carousel_weights, carousel_weights_from_angles

__all__ = [
    "BAND_EXPECTED_EXCEEDANCE",
    "BAND_SIGMA",
    "HEADLINE_METRIC",
    "BinSeries",
    "Evaluation",
    "averaged_bins",
    "carouselled_bins",
    "evaluate",
]

#: Name of the headline error measure reported as ``error_before`` / ``error_after``.
HEADLINE_METRIC = "standardized_misfit"
#: Two-sided 2σ band, as in TIM 2014 §V-C (95.45 % inside for a Gaussian).
BAND_SIGMA = 2.0
BAND_EXPECTED_EXCEEDANCE = float(2.0 * stats.norm.sf(BAND_SIGMA))
#: Fewest bins the virtual carouseling needs.
MINIMUM_BINS = 10
#: Averaged-bin variances are computed exactly at this many bins and interpolated between them.
AVERAGED_BIN_GRID = 9
#: z-values are clipped here (exp(log p) underflows beyond; the exact size no longer matters).
Z_CLIP = 38.0


@dataclass(frozen=True)
class BinSeries:
    """Bin values, their predicted variances under the model, bin centre times (s), and how they were made."""

    values: np.ndarray
    variance: np.ndarray
    time: np.ndarray
    mode: str = ""

    def standardized(self) -> np.ndarray:
        return self.values / np.sqrt(self.variance)


@dataclass(frozen=True)
class Evaluation:
    """One model's residual: the view, its metrics (the JSON payload), headline error, bins, detections."""

    view: ResidualView
    metrics: dict[str, Any]
    headline: float
    averaged: dict[str, BinSeries]
    carouselled: BinSeries | None
    detections: dict[str, Detection]


def _virtual_carousel(view: ResidualView, N: int) -> BinSeries:
    x_axis, y_axis = view.axes[0], view.axes[1]
    x, y = view.residuals[x_axis], view.residuals[y_axis]
    count = len(x) // N
    s, c = carousel_weights(N)  # TIM 2014 eq. (13)
    values = -x[: count * N].reshape(count, N) @ s + y[: count * N].reshape(count, N) @ c  # eq. (6)
    variance = uniform_bin_variances(view.fits[x_axis].noise, s, count)
    variance = variance + uniform_bin_variances(view.fits[y_axis].noise, c, count)
    centres = (np.arange(count) + 0.5) * N / view.sample_rate
    return BinSeries(values, variance, centres, f"virtual, N = {N}")


def _measured_carousel(view: ResidualView, angle: np.ndarray) -> BinSeries:
    x_axis, y_axis = view.axes[0], view.axes[1]
    x, y = view.residuals[x_axis], view.residuals[y_axis]
    turns = np.floor((np.unwrap(angle) - angle[0]) / (2.0 * np.pi)).astype(np.int64)
    turns = turns if turns[-1] >= 0 else -turns
    edges = np.flatnonzero(np.diff(turns)) + 1
    starts, stops = np.concatenate(([0], edges))[:-1], edges
    if len(starts) == 0:
        empty = np.array([])
        return BinSeries(empty, empty, empty, "measured angles (no complete revolution)")
    values, variances, centres = [], [], []
    for start, stop in zip(starts, stops, strict=True):
        s, c = carousel_weights_from_angles(angle[start:stop])
        values.append(-float(np.dot(s, x[start:stop])) + float(np.dot(c, y[start:stop])))
        variances.append(
            revolution_bin_variance(view.fits[x_axis].noise, s, int(start))
            + revolution_bin_variance(view.fits[y_axis].noise, c, int(start))
        )
        centres.append(0.5 * float(view.time[start] + view.time[stop - 1]))
    mode = "measured angles, one bin per revolution"
    return BinSeries(np.array(values), np.array(variances), np.array(centres), mode)


def carouselled_bins(view: ResidualView, N: int, angle: np.ndarray | None) -> BinSeries | None:
    """Carouselled bins of the first two axes with predicted variances (None for one axis)."""
    if len(view.axes) < 2:
        return None
    return _virtual_carousel(view, N) if angle is None else _measured_carousel(view, angle)


def averaged_bins(view: ResidualView, axis: str, N: int) -> BinSeries:
    """Bin means of N samples minus the mean of the whole bins; variances exact at AVERAGED_BIN_GRID bins
    (weights 1/N on the bin minus 1/(KN) everywhere) and joined by a cubic in k (exact for white noise and
    the rate random walk, whose contributions are polynomials of degree ≤ 2 in k; smooth for 1/f)."""
    x = view.residuals[axis]
    count = len(x) // N
    total = count * N
    bins = x[:total].reshape(count, N).mean(axis=1)
    grid = np.unique(np.linspace(1, count, min(count, AVERAGED_BIN_GRID)).astype(int))
    grid_variance = np.empty(len(grid))
    for i, k in enumerate(grid):
        weights = np.full(total, -1.0 / total)
        weights[(k - 1) * N : k * N] += 1.0 / N
        grid_variance[i] = statistic_variance(view.fits[axis].noise, weights)
    k_all = np.arange(1, count + 1)
    variance = (
        CubicSpline(grid, grid_variance)(k_all) if len(grid) >= 4 else np.interp(k_all, grid, grid_variance)
    )
    variance = np.maximum(variance, grid_variance.min() * 0.5)
    return BinSeries(bins - bins.mean(), variance, (np.arange(count) + 0.5) * N / view.sample_rate)


def tail_z(x: np.ndarray) -> tuple[float, float]:
    """(excess kurtosis, z) of the sample-to-sample differences: 0 ± √(24/n) for Gaussian noise; the
    difference removes the bias and the slow processes, spikes make it large."""
    differences = np.diff(x)
    kurtosis = float(stats.kurtosis(differences, fisher=True, bias=True))
    return kurtosis, kurtosis / math.sqrt(24.0 / len(differences))


def z_from_log10_p(log10_p: float) -> float:
    """The two-sided normal z of a (family-wise) p-value given as log10 p, clipped at Z_CLIP."""
    if log10_p >= 0:
        return 0.0
    log_half = log10_p * math.log(10.0) - math.log(2.0)
    return float(min(Z_CLIP, -stats.norm.ppf(math.exp(log_half)) if log_half > -700 else Z_CLIP))


def _allan_metrics(view: ResidualView, z_values: list[float]) -> dict[str, Any]:
    metrics = {}
    for axis in view.axes:
        fit = view.fits[axis]
        z = allan_z_values(fit)
        z_values.extend(z.tolist())
        metrics[axis] = {
            "rms_z": float(np.sqrt(np.mean(z**2))),
            "max_abs_z": float(np.max(np.abs(z))),
            "fraction_outside_95": float(np.mean(np.abs(z) > 1.96)),
            "chi_square": fit.chi_square,
            "dof": fit.dof,
        }
    return metrics


def _bin_metrics(bins: BinSeries) -> dict[str, Any]:
    standardized = bins.standardized()
    return {
        "bins": len(standardized),
        "exceedance_2sigma": float(np.mean(np.abs(standardized) > BAND_SIGMA)),
        "mean_square_z": float(np.mean(standardized**2)),
    }


def _carousel_metrics(carouselled: BinSeries | None, z_values: list[float]) -> dict[str, Any] | None:
    if carouselled is None or not len(carouselled.values):
        return None
    metrics = _bin_metrics(carouselled)
    # Carouselled bins are uncorrelated under the model (TIM 2014 eq. (17)): mean z² is 1 ± √(2/K).
    ratio_z = (metrics["mean_square_z"] - 1.0) / math.sqrt(2.0 / metrics["bins"])
    z_values.append(float(np.clip(ratio_z, -Z_CLIP, Z_CLIP)) if metrics["bins"] >= MINIMUM_BINS else 0.0)
    return {**metrics, "mode": carouselled.mode, "mean_square_z_score": ratio_z}


def _tail_metrics(view: ResidualView, z_values: list[float]) -> dict[str, Any]:
    tails = {}
    for axis in view.axes:
        kurtosis, z = tail_z(view.residuals[axis])
        # Only heavy tails count against the model (light tails come from coarse quantization).
        z_values.append(min(max(z, 0.0), Z_CLIP))
        tails[axis] = {"excess_kurtosis_of_differences": kurtosis, "z": z}
    return tails


def run_detectors(view: ResidualView, alpha: float) -> dict[str, Detection]:
    """Every detector of an effect the model lacks (1/f noise, once in the model, is judged by the Allan
    variance z-values instead), each at ``alpha``."""
    return {
        name: DETECTORS[name].detect(view, alpha)
        for name in TESTED_EFFECTS
        if not (name == "flicker" and view.spec.terms.flicker)
    }


def evaluate(view: ResidualView, N: int, angle: np.ndarray | None, detector_alpha: float) -> Evaluation:
    """Predictions, metrics, headline error and detections of one model (detectors at ``detector_alpha``)."""
    z_values: list[float] = []
    allan = _allan_metrics(view, z_values)
    averaged = {axis: averaged_bins(view, axis, N) for axis in view.axes}
    carouselled = carouselled_bins(view, N, angle)
    carousel = _carousel_metrics(carouselled, z_values)
    tails = _tail_metrics(view, z_values)
    detections = run_detectors(view, detector_alpha)
    residual_tests = {}
    for name, detection in detections.items():
        if detection.testable:
            z = z_from_log10_p(detection.log10_p)
            z_values.append(z)
            residual_tests[name] = {"statistic": detection.statistic, "log10_p": detection.log10_p, "z": z}
    headline = float(np.sqrt(np.mean(np.square(z_values))))
    metrics = {
        "residual_tests": residual_tests,
        HEADLINE_METRIC: headline,
        "allan": allan,
        "averaged_bins": {axis: _bin_metrics(bins) for axis, bins in averaged.items()},
        "carouselled_bins": carousel,
        "tails": tails,
        "expected_exceedance_2sigma": BAND_EXPECTED_EXCEEDANCE,
    }
    return Evaluation(view, metrics, headline, averaged, carouselled, detections)
