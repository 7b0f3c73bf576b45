"""Measured noise, virtually rotated: the spread of a scheme's estimates against the predicted one.

A static recording of two horizontal gyros holds their noise and a constant (bias plus the Earth-rate
projection). Demodulating it with a scheme's weights
(:func:`carousel_theory.rotation_schemes.demodulation_weights`) segment by segment gives the
estimates the scheme would have produced had the unit turned, under the
assumption that the noise does not depend on the rotation (the check TIM 2014 §V-C makes for
carouseling, here for every scheme). Over whole cycles the constant cancels exactly, so each segment
estimate is noise only; its exact variance under a noise model is, for segment m = 1 … M, the bin
variance of :func:`carousel_theory.propagation.repeated_weights_bin_variances` (the same weights in
every segment; RRW and 1/f noise from the first sample of the record).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from carousel_theory._validation import check_finite_array, check_positive_integer
from carousel_theory.fitting import NoiseModel
from carousel_theory.propagation import repeated_weights_bin_variances
from carousel_theory.rotation_schemes import demodulation_weights

__all__ = ["VirtualRotationCheck", "virtual_rotation_check"]


@dataclass(frozen=True)
class VirtualRotationCheck:
    """Segment estimates of both horizontal components, pooled.

    ``measured_mean_square`` is the mean of Ê² over segments and components (their mean is zero
    exactly), ``predicted_variance`` the mean of their exact variances, ``standardized`` the mean of
    Ê²/Var (1 when the model is right), ``exceedance`` the fraction with |Ê| > 2 σ (0.0455 for Gaussian
    estimates).
    """

    segment_samples: int
    estimates: int
    measured_mean_square: float
    predicted_variance: float
    standardized: float
    exceedance: float


def _predicted_variances(weights: np.ndarray, models: Sequence[NoiseModel], segments: int) -> np.ndarray:
    """Var of each component's estimate in segments 1 … M, shape (components, M)."""
    result = np.zeros((weights.shape[0], segments))
    for component in range(weights.shape[0]):
        for gyro, model in enumerate(models):
            row = weights[component, gyro]
            if not np.any(row):
                continue
            result[component] += model.white_variance * repeated_weights_bin_variances(row, "white", segments)
            result[component] += model.rrw_variance * repeated_weights_bin_variances(row, "rrw", segments)
            if model.flicker_variance > 0:
                result[component] += model.flicker_variance * repeated_weights_bin_variances(
                    row, "flicker", segments, d=model.flicker_d
                )
    return result


def virtual_rotation_check(
    rates: Any, scheme: Any, segment_samples: int, models: Sequence[NoiseModel]
) -> VirtualRotationCheck:
    """Demodulate a static two-gyro recording (``rates``: shape (2, n), x and y in rad/s) with ``scheme``
    in consecutive segments of ``segment_samples`` and compare the spread with the prediction from
    ``models`` (one per gyro).

    The segment must hold whole cycles of the scheme, so that the recording's constant cancels.
    """
    values = check_finite_array("rates", rates, ndim=2)
    if values.shape[0] != 2:
        raise ValueError(f"rates: must hold the x and y gyro (2 rows), got shape {values.shape}")
    length = check_positive_integer("segment_samples", segment_samples)
    cycle = scheme.cycle_length()
    if cycle is None or length % cycle:
        raise ValueError(
            f"segment_samples={segment_samples!r}: must be a whole number of cycles ({cycle}) of the scheme"
        )
    segments = values.shape[1] // length
    if segments < 2:
        raise ValueError(f"segment_samples={segment_samples!r}: the recording holds fewer than 2 segments")
    weights = demodulation_weights(scheme.pattern(length))[:, :2, :]
    blocks = values[:, : segments * length].reshape(2, segments, length)
    estimates = np.einsum("jgt,gmt->jm", weights, blocks)
    variances = _predicted_variances(weights, list(models), segments)
    ratios = estimates**2 / variances
    return VirtualRotationCheck(
        segment_samples=length,
        estimates=int(estimates.size),
        measured_mean_square=float(np.mean(estimates**2)),
        predicted_variance=float(np.mean(variances)),
        standardized=float(np.mean(ratios)),
        exceedance=float(np.mean(ratios > 4.0)),
    )
