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
        whose Allan variance is 3Q²/τ². Datasheets give Q in µrad or arcsec (1″ = π/(180·3600) rad).

Datasheet figures to per-sample variances (the inverse conversions)
    Each ``*_from_*`` function below is the exact algebraic inverse of its forward conversion:
    σ² = (N·f_s) N with N = ARW·(π/180)/60; σ_q,sample² = K²/f_s with K = RRW·(π/180)/(3600·60);
    and for the 1/f term of eq. (3) at d = 1/2, σ_w² = B² (rate independent): the discrete model's
    Allan variance tends to (2 ln 2/π)·σ_w² at long τ, which is IEEE Std 952's (2 ln 2/π)·B².

Unit names
    JSON documents and printed output name units with the ASCII strings of :data:`UNIT_NAMES`
    ("deg/sqrt(h)", "(rad/s)^2", ...); :func:`display_unit` gives the printed form (°/√h, (rad/s)²).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = [
    "ARCSECOND",
    "BIAS_INSTABILITY_FACTOR",
    "DEGREE",
    "HOUR",
    "MICRORADIAN",
    "RATE_UNITS",
    "UNIT_NAMES",
    "angle_random_walk_from_white_variance",
    "bias_instability_from_allan_minimum",
    "bias_instability_from_flicker_variance",
    "deg_per_h_to_rad_per_s",
    "display_unit",
    "flicker_variance_from_bias_instability",
    "from_arcseconds",
    "from_deg_per_hour_per_sqrt_hour",
    "from_deg_per_sqrt_hour",
    "from_microradians",
    "from_rad_per_s",
    "rad_per_s_to_deg_per_h",
    "rate_random_walk_from_increment_variance",
    "rate_to_rad_per_s",
    "rrw_variance_from_rate_random_walk",
    "square_unit",
    "to_arcseconds",
    "to_deg_per_hour_per_sqrt_hour",
    "to_deg_per_sqrt_hour",
    "to_microradians",
    "white_variance_from_angle_random_walk",
]

#: One degree in radians.
DEGREE = math.pi / 180.0
#: One hour in seconds.
HOUR = 3600.0
#: The flat Allan deviation of 1/f noise is BIAS_INSTABILITY_FACTOR · B: √(2 ln 2 / π) ≈ 0.6643.
BIAS_INSTABILITY_FACTOR = math.sqrt(2.0 * math.log(2.0) / math.pi)

#: One arcsecond in radians.
ARCSECOND = DEGREE / 3600.0
#: One microradian in radians.
MICRORADIAN = 1e-6

#: Rate units accepted when reading data (``--units``) and when printing (``--output-units``), with their
#: size in rad/s.
RATE_UNITS: dict[str, float] = {"rad/s": 1.0, "deg/s": DEGREE, "deg/h": DEGREE / HOUR}

#: Every unit name a JSON document or a printed figure uses (ASCII) → its printed form.
UNIT_NAMES: dict[str, str] = {
    "s": "s",
    "Hz": "Hz",
    "rad": "rad",
    "rad^2": "rad²",
    "urad": "µrad",
    "arcsec": "arcsec",
    "rad/s": "rad/s",
    "deg/s": "°/s",
    "deg/h": "°/h",
    "(rad/s)^2": "(rad/s)²",
    "(deg/s)^2": "(°/s)²",
    "(deg/h)^2": "(°/h)²",
    "(rad/s)^2/s": "(rad/s)²/s",
    "rad/sqrt(s)": "rad/√s",
    "rad/s/sqrt(s)": "rad/s/√s",
    "deg/sqrt(h)": "°/√h",
    "deg/h/sqrt(h)": "°/h/√h",
    "rad/s*sample": "rad/s·sample",
    "deg/s*sample": "°/s·sample",
    "deg/h*sample": "°/h·sample",
    "deg": "°",
    "degC": "°C",
    "rad/s/degC": "rad/s/°C",
}


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
    return _finite("value", value) / DEGREE * HOUR


def angle_random_walk_from_white_variance(white_variance: float, sample_rate: float) -> float:
    """Angle random walk N = √(σ² Δt) in rad/√s from the per-sample white variance σ² ((rad/s)²)."""
    return math.sqrt(
        _check_datasheet_value("white_variance", white_variance) / _check_sample_rate(sample_rate)
    )


def rate_random_walk_from_increment_variance(rrw_variance: float, sample_rate: float) -> float:
    """Rate random walk K = √(σ_q,sample² / Δt) in rad/s/√s from the per-sample increment variance."""
    return math.sqrt(_check_datasheet_value("rrw_variance", rrw_variance) * _check_sample_rate(sample_rate))


def to_deg_per_sqrt_hour(rad_per_sqrt_second: float) -> float:
    """rad/√s → °/√h: multiply by (180/π)·√3600."""
    return _finite("rad_per_sqrt_second", rad_per_sqrt_second) / DEGREE * math.sqrt(HOUR)


def to_deg_per_hour_per_sqrt_hour(rad_per_second_per_sqrt_second: float) -> float:
    """rad/s/√s → °/h/√h: multiply by (180/π)·3600·√3600."""
    value = _finite("rad_per_second_per_sqrt_second", rad_per_second_per_sqrt_second)
    return value / DEGREE * HOUR * math.sqrt(HOUR)


def bias_instability_from_allan_minimum(minimum_allan_deviation: float) -> float:
    """Bias instability B = σ_A,min / √(2 ln 2/π) (the 0.664 convention of IEEE Std 952)."""
    return (
        _check_datasheet_value("minimum_allan_deviation", minimum_allan_deviation) / BIAS_INSTABILITY_FACTOR
    )


def deg_per_h_to_rad_per_s(value: float) -> float:
    """A rate (or a bias instability) in °/h expressed in rad/s; the inverse of
    :func:`rad_per_s_to_deg_per_h`."""
    return _finite("value", value) * DEGREE / HOUR


def from_deg_per_sqrt_hour(deg_per_sqrt_hour: float) -> float:
    """°/√h → rad/√s: divide by (180/π)·√3600; the inverse of :func:`to_deg_per_sqrt_hour`."""
    return _finite("deg_per_sqrt_hour", deg_per_sqrt_hour) * DEGREE / math.sqrt(HOUR)


def from_deg_per_hour_per_sqrt_hour(deg_per_hour_per_sqrt_hour: float) -> float:
    """°/h/√h → rad/s/√s; the inverse of :func:`to_deg_per_hour_per_sqrt_hour`."""
    return (
        _finite("deg_per_hour_per_sqrt_hour", deg_per_hour_per_sqrt_hour) * DEGREE / (HOUR * math.sqrt(HOUR))
    )


def _finite(name: str, value: Any) -> float:
    """``value`` as a float after checking it: a real number (not a bool or a string), finite."""
    if isinstance(value, (bool, str, bytes)):
        raise TypeError(f"{name}={value!r}: must be a real number")
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise TypeError(f"{name}={value!r}: must be a real number") from None
    if not math.isfinite(number):
        raise ValueError(f"{name}={value!r}: must be finite")
    return number


def _check_datasheet_value(name: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
        raise TypeError(f"{name}={value!r}: must be a real number")
    number = float(value)
    if not (math.isfinite(number) and number >= 0.0):
        raise ValueError(f"{name}={value!r}: must be a finite number >= 0")
    return number


def _check_sample_rate(sample_rate: Any) -> float:
    rate = _check_datasheet_value("sample_rate", sample_rate)
    if rate == 0.0:
        raise ValueError(f"sample_rate={sample_rate!r}: must be > 0 Hz")
    return rate


def white_variance_from_angle_random_walk(arw_deg_per_sqrt_hour: float, sample_rate: float) -> float:
    """Per-sample white variance σ² ((rad/s)²) of a datasheet angle random walk in °/√h at ``sample_rate``.

    σ² = N²·f_s with N = ARW·(π/180)/60 rad/√s: the inverse of :func:`to_deg_per_sqrt_hour` ∘
    :func:`angle_random_walk_from_white_variance` (IEEE Std 952, Annex C: σ_A²(τ) = N²/τ).
    """
    arw = _check_datasheet_value("arw_deg_per_sqrt_hour", arw_deg_per_sqrt_hour)
    rate = _check_sample_rate(sample_rate)
    return from_deg_per_sqrt_hour(arw) ** 2 * rate


def rrw_variance_from_rate_random_walk(rrw_deg_per_hour_per_sqrt_hour: float, sample_rate: float) -> float:
    """Per-sample rate-random-walk increment variance σ_q,sample² ((rad/s)², TIM 2014 eq. (2)) of a
    datasheet RRW in °/h/√h: σ_q,sample² = K²/f_s with K = RRW·(π/180)/(3600·60) rad/s/√s.

    The inverse of :func:`to_deg_per_hour_per_sqrt_hour` ∘ :func:`rate_random_walk_from_increment_variance`
    (IEEE Std 952: σ_A²(τ) = K² τ/3).
    """
    rrw = _check_datasheet_value("rrw_deg_per_hour_per_sqrt_hour", rrw_deg_per_hour_per_sqrt_hour)
    rate = _check_sample_rate(sample_rate)
    return from_deg_per_hour_per_sqrt_hour(rrw) ** 2 / rate


def bias_instability_from_flicker_variance(flicker_variance: float) -> float:
    """Bias instability B (rad/s) of the 1/f term of TIM 2014 eq. (3) at d = 1/2: B = σ_w.

    The discrete model's Allan variance tends to (2 ln 2/π)·σ_w² at long τ, IEEE Std 952's flat level
    (2 ln 2/π)·B² (Annex C), whatever the sample rate.
    """
    return math.sqrt(_check_datasheet_value("flicker_variance", flicker_variance))


def flicker_variance_from_bias_instability(bias_instability_deg_per_hour: float) -> float:
    """Per-sample 1/f driving variance σ_w² ((rad/s)², eq. (3) at d = 1/2) of a datasheet bias instability
    in °/h: σ_w² = B² with B in rad/s; the inverse of :func:`bias_instability_from_flicker_variance`."""
    bias_instability = _check_datasheet_value("bias_instability_deg_per_hour", bias_instability_deg_per_hour)
    return deg_per_h_to_rad_per_s(bias_instability) ** 2


def to_microradians(radians: float) -> float:
    """An angle (the quantization Q) in µrad."""
    return _finite("radians", radians) / MICRORADIAN


def from_microradians(microradians: float) -> float:
    """An angle in µrad → rad; the inverse of :func:`to_microradians`."""
    return _finite("microradians", microradians) * MICRORADIAN


def to_arcseconds(radians: float) -> float:
    """An angle (the quantization Q) in arcseconds."""
    return _finite("radians", radians) / ARCSECOND


def from_arcseconds(arcseconds: float) -> float:
    """An angle in arcseconds → rad; the inverse of :func:`to_arcseconds`."""
    return _finite("arcseconds", arcseconds) * ARCSECOND


def square_unit(unit: str) -> str:
    """The unit of a variance of a quantity in ``unit``: ``"deg/h"`` → ``"(deg/h)^2"``."""
    _check_unit(unit)
    return f"({unit})^2"


def display_unit(unit: str) -> str:
    """The printed form of a unit name of :data:`UNIT_NAMES` (``"deg/sqrt(h)"`` → ``"°/√h"``)."""
    if unit not in UNIT_NAMES:
        raise ValueError(f"unit={unit!r}: must be one of {sorted(UNIT_NAMES)}")
    return UNIT_NAMES[unit]
