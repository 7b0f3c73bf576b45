"""Noise-model identification from a gyro recording, with standard errors.

Method: generalized least squares on the overlapping Allan variance at octave τ (a GMWM-like
estimator: the Haar wavelet variance is half the overlapping Allan variance).
The model Allan variance is linear in the noise variances for a fixed 1/f order d,
σ_A²(m) = σ_WN²·a_WN(m) + σ_q²·a_RRW(m) + Q²·a_Q(m) + σ_w²·a_f(m; d), with the exact discrete curves of
:mod:`carousel_theory.allan`. The estimate minimises (â − Aθ)ᵀ C⁻¹ (â − Aθ), where C is the covariance of
the Allan variance estimates *across* τ, computed exactly for Gaussian noise from the fitted model
(Cov(Σd², Σd'²) = 2 ΣΣ cov(d, d')², the same filters as the confidence intervals), iterated from an
ordinary fit. With a model-based C the weights do not depend on the noise in each point, which avoids
the downward bias of weighting with the observed Allan variance. Standard errors are the square roots
of the diagonal of (AᵀC⁻¹A)⁻¹; the order d, when fitted, is profiled (the GLS objective is minimised
over d, and its standard error comes from the curvature of the profile, where the objective behaves
as a χ² statistic). A bound (a variance at zero) is reported rather than hidden.

Why this and not a likelihood: the exact Gaussian likelihood of white + rate random walk + 1/f noise
is cheap only under a stationary spectral (Whittle) approximation, and real recordings are not white at
the sample rate (internal filters, spectral lines); a fit on the Allan variance lets the user choose the
τ range that the model should explain and reports the same quantities as the field's Allan plot.

Units: the model is stored in per-sample discrete terms (TIM 2014 §II) with its sample rate; see
:mod:`carousel_theory.units` for the conversions (0.664 factor, continuous vs discrete densities).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from carousel_theory import units
from carousel_theory._validation import check_fractional_order, check_positive_real, check_real

__all__ = ["NoiseModel"]


@dataclass(frozen=True)
class NoiseModel:
    """A gyro noise model in the per-sample discrete terms of TIM 2014 §II.

    Attributes
    ----------
    sample_rate : float
        Samples per second f_s (Δt = 1/f_s).
    bias : float
        Constant bias b (rad/s), eq. (1).
    white_variance : float
        Per-sample white-noise variance σ_WN² ((rad/s)²).
    rrw_variance : float
        Per-sample increment variance σ_q² of the rate random walk, eq. (2) ((rad/s)²).
    flicker_variance : float
        Driving variance σ_w² of the fractionally integrated 1/f noise, eq. (3) ((rad/s)²).
    flicker_d : float
        Order 0 < d < 1 of the fractional integration (ignored when ``flicker_variance`` is 0).
    quantization : float
        Angle quantization Q (rad): Allan variance 3Q²/τ².
    """

    sample_rate: float
    bias: float = 0.0
    white_variance: float = 0.0
    rrw_variance: float = 0.0
    flicker_variance: float = 0.0
    flicker_d: float = 0.5
    quantization: float = 0.0
    extra: dict[str, Any] = field(default_factory=dict, compare=False, repr=False)

    def __post_init__(self) -> None:
        check_positive_real("sample_rate", self.sample_rate)
        check_real("bias", self.bias)
        for name in ("white_variance", "rrw_variance", "flicker_variance", "quantization"):
            check_positive_real(name, getattr(self, name), allow_zero=True)
        check_fractional_order("flicker_d", self.flicker_d)

    # --- the field's units (IEEE Std 952) -------------------------------------------------------
    def angle_random_walk(self) -> float:
        """N = √(σ_WN²/f_s) in rad/√s."""
        return units.angle_random_walk_from_white_variance(self.white_variance, self.sample_rate)

    def angle_random_walk_deg_per_sqrt_hour(self) -> float:
        """Angle random walk in °/√h."""
        return units.to_deg_per_sqrt_hour(self.angle_random_walk())

    def rate_random_walk(self) -> float:
        """K = √(σ_q² f_s) in rad/s/√s."""
        return units.rate_random_walk_from_increment_variance(self.rrw_variance, self.sample_rate)

    def rate_random_walk_deg_per_hour_per_sqrt_hour(self) -> float:
        """Rate random walk in °/h/√h."""
        return units.to_deg_per_hour_per_sqrt_hour(self.rate_random_walk())

    def bias_deg_per_hour(self) -> float:
        """The bias in °/h."""
        return units.rad_per_s_to_deg_per_h(self.bias)

    # --- the paper's units (TIM 2014 Table III) -------------------------------------------------
    def white_variance_at_one_second(self) -> float:
        """σ_WN² (τ = 1 s) of TIM 2014 Table III: the variance of a 1-s average, σ_WN²/f_s ((rad/s)²)."""
        return self.white_variance / self.sample_rate

    def rrw_variance_per_second(self) -> float:
        """σ_q² of TIM 2014 Table III in (rad/s)²/s: the increment variance per second, σ_q² f_s."""
        return self.rrw_variance * self.sample_rate

    def minimum_allan_deviation(self, length: int) -> tuple[float, float]:
        """(min σ_A, τ at the minimum) of this model over octave τ of a record of ``length`` samples."""
        from carousel_theory.allan import model_allan_variance, octave_cluster_sizes

        sizes = octave_cluster_sizes(length)
        # Refine between octaves: the minimum of a smooth curve is found on a dense log grid.
        grid = np.unique(np.rint(np.geomspace(1, sizes[-1], 200)).astype(np.int64))
        values = model_allan_variance(self, grid, length=length)
        best = int(np.argmin(values))
        return math.sqrt(float(values[best])), float(grid[best] / self.sample_rate)

    def bias_instability(self, length: int) -> float:
        """Bias instability B = min σ_A / 0.664 (rad/s) of the model's Allan curve (IEEE Std 952)."""
        return units.bias_instability_from_allan_minimum(self.minimum_allan_deviation(length)[0])
