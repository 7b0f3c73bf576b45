"""North-finder design: which rotation scheme, at which rate, for how long, gives what heading accuracy.

For a gyro noise model (per-sample variances of TIM 2014 §II, per gyro), every scheme of
:mod:`carousel_theory.rotation_schemes` is evaluated at the requested record durations: the exact
covariance of the horizontal Earth-rate estimate (:mod:`carousel_theory.scheme_variance`), the
error the imperfections add (:mod:`carousel_theory.imperfections`), and the heading error at
latitude L (:mod:`carousel_theory.heading`), linearised and exact. A duration is cut down to whole
cycles of a periodic scheme (whole turns of an integer carousel, whole indexing cycles); a carousel
with a non-integer number of samples a turn uses every sample.

The noise model comes from explicit per-sample variances or from the JSON of ``carousel-theory fit
--json`` through :func:`noise_models_from_fit_json`, the one place that reads that layout.
"""

from __future__ import annotations

import json
import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from carousel_theory._validation import check_positive_real, check_real
from carousel_theory.fitting import NoiseModel
from carousel_theory.heading import EARTH_RATE, check_latitude, heading_error, horizontal_earth_rate
from carousel_theory.imperfections import Imperfections, imperfection_effect
from carousel_theory.rotation_schemes import Carousel, Indexing, Static, scheme_label
from carousel_theory.scheme_variance import PROCESS_TERMS, estimate_covariances

__all__ = [
    "DesignSettings",
    "SchemeResult",
    "average_noise_models",
    "default_schemes",
    "evaluate_scheme",
    "noise_models_from_fit_json",
    "recommended",
    "record_length",
]

#: Periods (s a turn) and dwell times (s) of the built-in sweep of ``carousel-theory design``.
DEFAULT_PERIODS = (1.0, 2.0, 5.0, 10.0, 30.0, 60.0)
DEFAULT_DWELLS = (1.0, 5.0, 10.0, 30.0, 60.0)
DEFAULT_TRANSITION = 1.0


def default_schemes(sample_rate: float) -> list[Any]:
    """Static averaging, carouseling at :data:`DEFAULT_PERIODS`, 2- and 4-position indexing at
    :data:`DEFAULT_DWELLS` with a 1-s transition (dropped), at ``sample_rate`` Hz."""
    rate = float(check_positive_real("sample_rate", sample_rate))
    schemes: list[Any] = [Static()]
    schemes += [Carousel(_whole(period * rate)) for period in DEFAULT_PERIODS]
    transition = max(1, round(DEFAULT_TRANSITION * rate))
    schemes += [
        Indexing(positions, max(1, round(dwell * rate)), transition)
        for positions in (2, 4)
        for dwell in DEFAULT_DWELLS
    ]
    return schemes


def _whole(samples: float) -> float:
    return round(samples) if abs(samples - round(samples)) < 1e-9 else samples


# --- the noise model from `carousel-theory fit --json` ------------------------------------------------

_ALIASES = {
    "white_variance": ("white_variance", "white"),
    "rrw_variance": ("rrw_variance", "rrw"),
    "flicker_variance": ("flicker_variance", "flicker"),
    "flicker_d": ("flicker_d", "d"),
}


def _column_model(name: str, column: dict[str, Any], sample_rate: float | None) -> NoiseModel:
    values = column.get("model", column)
    rate = values.get("sample_rate", sample_rate)
    if rate is None:
        raise ValueError(f"noise column {name!r}: no sample_rate in the file")
    found: dict[str, float] = {}
    for key, aliases in _ALIASES.items():
        for alias in aliases:
            if values.get(alias) is not None:
                found[key] = float(values[alias])
                break
    if "white_variance" not in found:
        raise ValueError(f"noise column {name!r}: no white_variance (keys: {sorted(values)})")
    return NoiseModel(
        sample_rate=float(rate),
        white_variance=found["white_variance"],
        rrw_variance=found.get("rrw_variance", 0.0),
        flicker_variance=found.get("flicker_variance", 0.0),
        flicker_d=found.get("flicker_d", 0.5),
    )


def noise_models_from_fit_json(source: str | Path | dict[str, Any]) -> tuple[list[NoiseModel], float]:
    """Per-gyro noise models (x, y[, z]) and the sample rate from the JSON of ``carousel-theory fit --json``.

    Accepts ``{"files": [{"columns": {"wx": {"model": {...}}, ...}}, ...]}`` (several files: the
    variances are averaged per column), a single ``{"columns": ...}``, or a bare ``{column: model}``.
    Columns are taken in sorted order of their names (wx, wy, wz); model keys may be
    ``white_variance``/``white``, ``rrw_variance``/``rrw``, ``flicker_variance``/``flicker``,
    ``flicker_d``/``d``, all per-sample, plus ``sample_rate`` (Hz).
    """
    document = source if isinstance(source, dict) else json.loads(Path(source).read_text(encoding="utf-8"))
    files = document.get("files", [document])
    per_column: dict[str, list[NoiseModel]] = {}
    for entry in files:
        columns = entry.get("columns", entry)
        rate = entry.get("sample_rate")
        for name in sorted(columns):
            if isinstance(columns[name], dict):
                per_column.setdefault(name, []).append(_column_model(name, columns[name], rate))
    if not per_column:
        raise ValueError(f"noise={source!r}: holds no gyro column with a model")
    models = [average_noise_models(models) for _, models in sorted(per_column.items())]
    return models, models[0].sample_rate


def average_noise_models(models: Sequence[NoiseModel]) -> NoiseModel:
    """The mean of several noise models' variances and 1/f orders (at the first one's sample rate)."""

    def mean(name: str) -> float:
        return float(np.mean([getattr(model, name) for model in models]))

    return NoiseModel(
        sample_rate=models[0].sample_rate,
        white_variance=mean("white_variance"),
        rrw_variance=mean("rrw_variance"),
        flicker_variance=mean("flicker_variance"),
        flicker_d=mean("flicker_d"),
    )


# --- evaluation ------------------------------------------------------------------------------------


@dataclass(frozen=True)
class DesignSettings:
    """Everything but the scheme and the duration: noise per gyro, site, and imperfections."""

    noise: Sequence[NoiseModel]
    sample_rate: float
    latitude: float
    heading: float = 0.0
    bias_sigma: float = 0.0
    imperfections: Imperfections = field(default_factory=Imperfections)
    exact: bool = True

    def __post_init__(self) -> None:
        check_positive_real("sample_rate", self.sample_rate)
        check_latitude(self.latitude)
        check_real("heading", self.heading)
        check_positive_real("bias_sigma", self.bias_sigma, allow_zero=True)


@dataclass(frozen=True)
class SchemeResult:
    """One scheme at one duration. Rates in rad/s, angles in degrees.

    ``rate_covariance`` is the covariance of (Ω̂_x, Ω̂_y) and ``rate_bias`` its systematic error from
    the imperfections; ``rate_variance`` is the variance of the estimate's component across the true
    horizontal Earth rate (the one that moves the heading); ``rate_variance_by_process`` splits it by
    error process.
    """

    scheme: str
    duration: float
    samples: int
    used_samples: int
    rate_variance: float
    rate_variance_by_process: dict[str, float]
    rate_covariance: list[list[float]]
    rate_bias: list[float]
    heading_sigma_deg: float
    heading_bias_deg: float
    heading_rms_deg: float | None
    dominant_process: str


def record_length(scheme: Any, duration: Any, sample_rate: float) -> int:
    """Samples of a record of ``duration`` s, cut down to whole cycles of a periodic scheme."""
    seconds = float(check_real("duration", duration))
    if seconds <= 0:
        raise ValueError(f"duration={duration!r}: must be > 0 seconds")
    samples = math.floor(seconds * sample_rate + 1e-9)
    cycle = scheme.cycle_length()
    if cycle is not None:
        samples -= samples % cycle
    if samples < 1:
        raise ValueError(
            f"duration={duration!r}: shorter than one cycle ({cycle} samples at {sample_rate!r} Hz) "
            f"of scheme {scheme_label(scheme, sample_rate)!r}"
        )
    return samples


def _across(latitude: float, heading: float) -> np.ndarray:
    truth = horizontal_earth_rate(latitude, heading)
    return np.array([truth[1], -truth[0]]) / float(np.linalg.norm(truth))


def evaluate_scheme(scheme: Any, durations: Sequence[float], settings: DesignSettings) -> list[SchemeResult]:
    """The rate variance and heading error of ``scheme`` after each of ``durations`` seconds."""
    lengths = [record_length(scheme, duration, settings.sample_rate) for duration in durations]
    pattern = scheme.pattern(max(lengths))
    covariances = estimate_covariances(pattern, lengths, settings.noise, settings.bias_sigma**2)
    across = _across(settings.latitude, settings.heading)
    magnitude = EARTH_RATE * math.cos(math.radians(settings.latitude))
    label = scheme_label(scheme, settings.sample_rate)
    results = []
    for duration, length, covariance in zip(durations, lengths, covariances, strict=True):
        matrix = covariance.total()[:2, :2]
        bias = np.zeros(2)
        if not settings.imperfections.is_ideal():
            effect = imperfection_effect(
                scheme.pattern(length),
                settings.imperfections,
                settings.latitude,
                settings.heading,
                settings.sample_rate,
                settings.bias_sigma,
            )
            matrix, bias = matrix + effect.covariance, effect.bias
        split = {name: float(across @ getattr(covariance, name)[:2, :2] @ across) for name in PROCESS_TERMS}
        rate_variance = float(across @ matrix @ across)
        exact = heading_error(matrix, settings.latitude, settings.heading, bias) if settings.exact else None
        results.append(
            SchemeResult(
                scheme=label,
                duration=float(duration),
                samples=length,
                used_samples=covariance.used,
                rate_variance=rate_variance,
                rate_variance_by_process=split,
                rate_covariance=matrix.tolist(),
                rate_bias=bias.tolist(),
                heading_sigma_deg=math.degrees(math.sqrt(rate_variance) / magnitude),
                heading_bias_deg=math.degrees(float(across @ bias) / magnitude),
                heading_rms_deg=None if exact is None else math.degrees(exact.exact_rms),
                dominant_process=max(split, key=lambda name: split[name]),
            )
        )
    return results


def recommended(results: Sequence[SchemeResult]) -> str:
    """The scheme with the smallest heading error at the longest duration (exact RMS when computed)."""
    if not results:
        raise ValueError("results: must hold at least one scheme")
    longest = max(result.duration for result in results)
    final = [result for result in results if result.duration == longest]

    def error(result: SchemeResult) -> float:
        if result.heading_rms_deg is not None:
            return result.heading_rms_deg
        return math.hypot(result.heading_sigma_deg, result.heading_bias_deg)

    return min(final, key=error).scheme
