"""The contract between the loop and its detectors: a :class:`Detection` result and two one-method
protocols, :class:`Detector` (``detect``) and :class:`Remedy` (``fit``), over a public
:class:`~carousel_theory.closed_loop.view.ResidualView`.

Each detector computes a test statistic whose null distribution is that of the *fitted* noise model,
and reports the base-10 logarithm of its p-value, family-wise over its own scan and the axes
(Bonferroni). The loop decides what ``alpha`` each detector gets (see
:mod:`carousel_theory.closed_loop.calibration`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Protocol

import numpy as np
from scipy import stats

from carousel_theory.closed_loop.view import FittedEffect, ResidualView

__all__ = [
    "NUISANCE_SHARE",
    "Detection",
    "Detector",
    "Remedy",
    "bounded_standard_deviation",
    "bounded_threshold",
    "bounded_two_sided",
    "json_value",
    "log10_two_sided",
    "threshold_two_sided",
    "untestable",
]


@dataclass(frozen=True)
class Detection:
    """The outcome of one detector on one residual.

    ``log10_p`` is the base-10 logarithm of the family-wise p-value (Bonferroni over the scan and the
    axes); ``significant`` is ``p < alpha``. ``testable`` is False when the data cannot show the effect
    at all (no temperature column, a constant one, a record too short); ``note`` then says why.
    """

    effect: str
    statistic: float
    statistic_name: str
    threshold: float
    log10_p: float
    significant: bool
    axes: tuple[str, ...] = ()
    details: dict[str, Any] = field(default_factory=dict)
    testable: bool = True
    note: str = ""

    def as_dict(self) -> dict[str, Any]:
        return {
            "effect": self.effect,
            "statistic": json_value(self.statistic),
            "statistic_name": self.statistic_name,
            "threshold": json_value(self.threshold),
            "log10_p": json_value(self.log10_p),
            "significant": self.significant,
            "axes": list(self.axes),
            "details": {k: json_value(v) for k, v in self.details.items()},
            "testable": self.testable,
            "note": self.note,
        }


class Detector(Protocol):
    """Tests a residual for one effect."""

    name: str

    def detect(self, view: ResidualView, alpha: float) -> Detection: ...


class Remedy(Protocol):
    """Fits one effect that a detection found; ``stochastic`` effects change the noise model only."""

    name: str
    stochastic: bool

    def fit(self, view: ResidualView, detection: Detection, alpha: float) -> FittedEffect: ...


def untestable(name: str, statistic_name: str, threshold: float, note: str) -> Detection:
    """A detection that the data cannot make, with the reason."""
    return Detection(name, 0.0, statistic_name, threshold, 0.0, False, testable=False, note=note)


def json_value(value: Any) -> Any:
    """``value`` with NumPy scalars as Python numbers and non-finite floats as strings (valid JSON)."""
    if isinstance(value, (float, np.floating)):
        number = float(value)
        return number if math.isfinite(number) else str(number)
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, np.bool_):
        return bool(value)
    if isinstance(value, (list, tuple, np.ndarray)):
        return [json_value(v) for v in value]
    if isinstance(value, dict):
        return {str(k): json_value(v) for k, v in value.items()}
    return value


def log10_two_sided(z: float, tests: int) -> float:
    """log10 of min(1, tests · 2 Φ̄(|z|)) computed in logs, so that z = 200 does not underflow."""
    log_p = math.log(2.0 * max(tests, 1)) + float(stats.norm.logsf(abs(z)))
    return min(0.0, log_p / math.log(10.0))


def threshold_two_sided(alpha: float, tests: int) -> float:
    return float(stats.norm.isf(alpha / (2.0 * max(tests, 1))))


#: Share of a trend detector's rate charged to the confidence bound of its statistic's variance.
NUISANCE_SHARE = 0.1


def bounded_two_sided(
    projection: float, variance: float, standard_error: float, tests: int, alpha: float
) -> tuple[float, float]:
    """(z, log10 p) of a Gaussian linear statistic L = Σ w_t e_t whose variance V(θ) depends on fitted
    noise variances θ, family-wise over ``tests`` (Bonferroni), at the rate ``alpha``.

    Given θ, L ~ N(0, V(θ)) exactly under the model, and the p-value 2Φ̄(|L|/√V(θ)) grows with V. The
    nuisance θ is handled as Berger & Boos (1994, JASA 89, 1012) do: with γ = NUISANCE_SHARE · α and
    V_γ = V̂ + Φ̄⁻¹(γ) se(V̂) an upper (1 − γ) confidence bound of V, p = tests · 2Φ̄(|L|/√V_γ) + γ is a
    valid p-value (the supremum of the exact p over the confidence set, plus its non-coverage). The
    bound's coverage is asymptotic (V̂ is a linear function of GLS estimates) and not exact: se(V̂) is
    evaluated at the fitted variances, so it shrinks with V̂, and to first order the bound is exceeded
    with probability Φ(−z_γ / (1 + z_γ r)), r = se/V, z_γ = Φ̄⁻¹(γ) — above γ when r is small (long
    records), far below it when r is near 1 (300 s); docs/loop_detection_rates.md measures it on clean
    records, and the detectors' own rejection rates at a nominal level. The weights w, chosen
    from the fitted variances, are treated as fixed (they depend on the data only through the Allan
    variance). The Student-t reference with Satterthwaite degrees of freedom it replaces also assumed L
    independent of V̂, which it is not (both are large when the record's low-frequency power is)."""
    z = projection / bounded_standard_deviation(variance, standard_error, alpha)
    log_p = math.log(2.0 * max(tests, 1)) + float(stats.norm.logsf(abs(z)))
    return z, min(0.0, float(np.logaddexp(log_p, math.log(NUISANCE_SHARE * alpha))) / math.log(10.0))


def bounded_standard_deviation(variance: float, standard_error: float, alpha: float) -> float:
    """√V_γ, the square root of the upper (1 − γ) confidence bound of :func:`bounded_two_sided`."""
    upper = variance + float(stats.norm.isf(NUISANCE_SHARE * alpha)) * standard_error
    return math.sqrt(max(upper, 1e-300))


def bounded_threshold(alpha: float, tests: int) -> float:
    """The |z| of :func:`bounded_two_sided` at which p = ``alpha``."""
    return float(stats.norm.isf((1.0 - NUISANCE_SHARE) * alpha / (2.0 * max(tests, 1))))
