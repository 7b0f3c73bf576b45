"""Unit conventions for angular rates and gyro noise parameters, written out.

Internally every rate is in rad/s and every time in s. The conversions below are the only place where
degrees and hours enter.

Rates
    1 deg/s = π/180 rad/s;   1 deg/h = π/(180·3600) rad/s.

Noise parameters (discrete model of TIM 2014 §II, sample interval Δt = 1/f_s)
    white noise
        per-sample variance σ² ((rad/s)²). Its continuous-time density (the angle random walk
        coefficient N of IEEE Std 952) is N = σ·√Δt in rad/√s, because the average of white noise over
        τ seconds has variance σ²Δt/τ = N²/τ. In the field's unit, °/√h = (180/π)·60·(rad/√s)
        (√3600 = 60). TIM 2014 Table III reports "σ_WN² (τ = 1 s)", the variance of a 1-s average,
        which equals N² numerically (in (rad/s)²).
    rate random walk
        per-sample increment variance σ_q,sample² ((rad/s)²) of eq. (2). Its continuous density is
        K² = σ_q,sample²/Δt ((rad/s)²/s), so that after t seconds the walk has variance K²·t; TIM 2014
        Table III's σ_q² in (rad/s)²/s is this K². The field's unit is °/h/√h = (180/π)·3600·60·(rad/s/√s).
    bias instability
        for continuous 1/f noise of PSD B²/(2πf) the Allan deviation is flat at
        √(2 ln 2/π)·B = 0.6643·B (IEEE Std 952, Annex C), so B = min ADEV / 0.6643. The "0.664
        factor" is this √(2 ln 2/π). In °/h: (180/π)·3600·(rad/s).
    quantization
        angle quantization Q (rad): a white angle error of variance Q² differenced into the rate,
        whose Allan variance is 3Q²/τ².
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = [
    "BIAS_INSTABILITY_FACTOR",
    "DEGREE",
    "HOUR",
    "RATE_UNITS",
    "angle_random_walk_from_white_variance",
    "bias_instability_from_allan_minimum",
    "from_rad_per_s",
    "rad_per_s_to_deg_per_h",
    "rate_random_walk_from_increment_variance",
    "rate_to_rad_per_s",
    "to_deg_per_hour_per_sqrt_hour",
    "to_deg_per_sqrt_hour",
]

#: One degree in radians.
DEGREE = math.pi / 180.0
#: One hour in seconds.
HOUR = 3600.0
#: The flat Allan deviation of 1/f noise is BIAS_INSTABILITY_FACTOR · B: √(2 ln 2 / π) ≈ 0.6643.
BIAS_INSTABILITY_FACTOR = math.sqrt(2.0 * math.log(2.0) / math.pi)

#: Rate units accepted when reading data, with their size in rad/s.
RATE_UNITS: dict[str, float] = {"rad/s": 1.0, "deg/s": DEGREE, "deg/h": DEGREE / HOUR}


def _check_unit(units: Any) -> float:
    if not isinstance(units, str):
        raise TypeError(f"units={units!r}: must be a string, one of {sorted(RATE_UNITS)}")
    if units not in RATE_UNITS:
        raise ValueError(f"units={units!r}: must be one of {sorted(RATE_UNITS)}")
    return RATE_UNITS[units]


def rate_to_rad_per_s(values: Any, units: str) -> np.ndarray:
    """Convert angular rates given in ``units`` ("rad/s", "deg/s" or "deg/h") to rad/s (a new array)."""
    factor = _check_unit(units)
    return np.asarray(values, dtype=np.float64) * factor


def from_rad_per_s(values: Any, units: str) -> np.ndarray:
    """Convert angular rates in rad/s to ``units`` (a new array)."""
    factor = _check_unit(units)
    return np.asarray(values, dtype=np.float64) / factor


def rad_per_s_to_deg_per_h(value: float) -> float:
    """A rate (or a bias, or a bias instability) in rad/s expressed in °/h."""
    return float(value) / DEGREE * HOUR


def angle_random_walk_from_white_variance(white_variance: float, sample_rate: float) -> float:
    """Angle random walk N = √(σ² Δt) in rad/√s from the per-sample white variance σ² ((rad/s)²)."""
    return math.sqrt(float(white_variance) / float(sample_rate))


def rate_random_walk_from_increment_variance(rrw_variance: float, sample_rate: float) -> float:
    """Rate random walk K = √(σ_q,sample² / Δt) in rad/s/√s from the per-sample increment variance."""
    return math.sqrt(float(rrw_variance) * float(sample_rate))


def to_deg_per_sqrt_hour(rad_per_sqrt_second: float) -> float:
    """rad/√s → °/√h: multiply by (180/π)·√3600."""
    return float(rad_per_sqrt_second) / DEGREE * math.sqrt(HOUR)


def to_deg_per_hour_per_sqrt_hour(rad_per_second_per_sqrt_second: float) -> float:
    """rad/s/√s → °/h/√h: multiply by (180/π)·3600·√3600."""
    return float(rad_per_second_per_sqrt_second) / DEGREE * HOUR * math.sqrt(HOUR)


def bias_instability_from_allan_minimum(minimum_allan_deviation: float) -> float:
    """Bias instability B = σ_A,min / √(2 ln 2/π) (the 0.664 convention of IEEE Std 952)."""
    return float(minimum_allan_deviation) / BIAS_INSTABILITY_FACTOR
