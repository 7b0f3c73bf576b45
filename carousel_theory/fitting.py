"""Noise-model identification from a gyro recording, with standard errors: one fitter for ``fit`` and the
closed loop.

Method: generalized least squares on the Allan variance at octave τ (a GMWM-like estimator: the Haar
wavelet variance is half the overlapping Allan variance). For fixed 1/f order d and fixed AR
coefficients the model Allan variance is linear in the driving variances,
σ_A²(m) = σ_WN²·a_WN(m) + σ_q²·a_RRW(m) + Q²·a_Q(m) + σ_w²·a_f(m; d) + σ_AR²·a_AR(m; φ), with the exact
stationary curves of :mod:`carousel_theory.noise_model`. The estimate minimises
(â − Aθ)ᵀ C⁻¹ (â − Aθ) under θ ≥ 0, where C is the covariance of the estimates across τ computed from the
current model by :mod:`carousel_theory.tau_covariance` (exact and independent of the record length for
white, RRW and quantization; finite lag sums for 1/f and AR, by the lag quadrature's
:data:`~carousel_theory.lag_plan.WEIGHTS_RULE`), iterated from a diagonal start until a
step moves no parameter by more than ``tolerance`` (0.05) of its standard error, at most ``iterations``
times (the closed loop, whose false-alarm rates were measured that way, always takes three). With a
model-based C the weights do not depend on the noise in each point, which avoids the downward bias of
weighting with the observed Allan variance. Standard errors: the diagonal of (JᵀC⁻¹J)⁻¹; a fitted d is
profiled and enters J through ∂(Aθ)/∂d. A parameter at zero is reported in ``at_bound``.

Intervals (``FitResult.interval``): χ²-based from the standard error by default. That error is a plug-in
one, C evaluated at the estimate, so a weakly determined variance (a rate random walk or 1/f term known
to tens of percent) reports a small error exactly when it is underestimated: white + RRW at 10⁶
samples, θ̂ ± 1.96 s held the walk on 45 of 58 records (docs/fit_calibration.md).
:func:`inverted_interval` (``method="inverted"``) inverts the test with the error at each candidate
value θ₀, {θ₀ ≥ 0 : |θ̂ − θ₀| ≤ z s(θ₀)}, so that the record is judged by the spread the candidate
itself would give; it costs one covariance across τ per step of its root search. The 1/f order d has no
χ²-based interval of its own and its ±z·s under-covers: its standard error comes from the χ²'s curvature
at d̂, and the χ² is far from a parabola in d where the 1/f term trades off against the white and RRW
terms (white + RRW + 1/f + Gauss–Markov at 10⁶ samples: d̂ ± 1.96 s held d = 0.5 on 36 of 44 records,
docs/fit_calibration.md). :func:`order_interval`, its default interval, inverts the χ² difference
instead: 42 of 44.

AR short noise: the coefficients are estimated before the GLS from the record with its slow part
removed (:mod:`carousel_theory.autoregression`), and only the innovation variance is fitted by GLS; give
``ar_coefficients`` to fix them. With "ar" alone the AR process is the whole short noise (as in the
closed loop, where it replaces white noise): Yule–Walker, order the largest p ≤ ``ar_order`` whose
partial autocorrelation exceeds 4/√n. With "white" and "ar" the short noise is white + AR(p): the
high-order Yule–Walker equations, which white noise does not reach (plain Yule–Walker fits the sum, an
ARMA process, whose AR term's Allan variance is not the data's), or plain Yule–Walker when its
coefficients describe the record's autocovariance better (a sensor's internal filter colours all its
white noise); :func:`carousel_theory.autoregression.short_noise_coefficients`. A record whose lags
show no correlation is refused with a pointer to the model without "ar". Those estimates read the record
less a moving average of W samples, which biases a long correlation time low; an estimated AR(1)
coefficient whose correlation time exceeds W/AR_REFINED_FRACTION, in a fit that the χ² rejects at
AR_REFINED_LEVEL, is therefore refined by the GLS χ² on the Allan variance (a grid in log τ_c from W/200
to W, then Brent's method, the fit solved again at the result; its variance 2/(∂²χ²/∂φ²), d profiled).
White + RRW + 1/f + Gauss–Markov at 10⁶ samples, φ = 0.99 (τ_c = 1 s against W = 10 s), 30 records
(``benchmarks/bench_ar_refinement.py``): φ̂ = 0.9898 ± 0.0005 (standard deviation), φ̂ ± 1.96 s held φ
on 29, 3 fits rejected at 0.05, against 0.980 ± 0.010 and 30 rejected with the record's estimate; at
φ = 0.95 the 4 fits of 30 that the record's estimate left rejected were refined, and none is. The estimated
coefficients' sampling error (their large-sample covariance,
:func:`carousel_theory.autoregression.coefficient_covariance`; for a refined one, 2/(∂²χ²/∂φ²)) is
carried into the parameters' covariance as S Cov(φ̂) Sᵀ, S = ∂θ̂/∂φ of the GLS at its final C: held
fixed, it was missing from the standard errors (white + RRW + 1/f + AR(1), φ = 0.8, 40 records of 10⁶
samples: the AR variance's 95 % interval covered the truth 31 times, its standardized error spread 1.93;
with the true φ given, 39 times and 0.97). ``FitResult.ar_coefficient_errors`` gives the coefficients'
own standard errors.

Typed API (for ``fit`` and for the closed loop)
    :func:`observe_allan` → :class:`ObservedAllan` (compute once per record, reuse for every fit);
    :class:`FitOptions` (components, d fixed or fitted, AR order or coefficients, τ range, minimum
    clusters, estimator, iterations); :func:`fit_observed` and :func:`fit_noise_model` → :class:`FitResult`
    (model, standard errors, χ², its p-value, per-τ model curve, degrees of freedom of each τ);
    :func:`nested_test` → :class:`NestedTest` (χ² difference of a fit with and without a term under the
    fuller model's covariance, and its p-value); :func:`consistency_test` → :class:`ConsistencyTest`
    (are estimates from several runs one population?).

Units: the model is stored in per-sample discrete terms (TIM 2014 §II) with its sample rate; see
:mod:`carousel_theory.units` for the conversions (0.664 factor, continuous vs discrete densities).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from scipy import stats
from scipy.optimize import brentq, minimize_scalar, nnls

from carousel_theory import units
from carousel_theory._validation import (
    check_finite_array,
    check_fractional_order,
    check_positive_integer,
    check_positive_real,
    check_probability,
)
from carousel_theory.allan import (
    AllanResult,
    allan_variance,
    check_tau_range,
    equivalent_degrees_of_freedom,
    with_model_intervals,
)
from carousel_theory.autoregression import (
    ShortNoiseEstimate,
    correlation_is_long,
    high_pass_window,
    short_noise_estimate,
    yule_walker,
    yule_walker_estimate,
)
from carousel_theory.formulas import formula
from carousel_theory.increment_sums import squared_rising_factorial_sum
from carousel_theory.lag_plan import WEIGHTS_RULE
from carousel_theory.noise_model import NoiseModel, check_ar_coefficients, term_allan_variance
from carousel_theory.progress import progress
from carousel_theory.signal_checks import UnusableSignalError, check_noise_signal, check_recording_signals
from carousel_theory.tau_covariance import allan_estimate_covariance

__all__ = [
    "COMPONENTS",
    "COMPONENT_OF_PARAMETER",
    "ConsistencyTest",
    "FitOptions",
    "FitResult",
    "NestedTest",
    "NoiseModel",
    "ObservedAllan",
    "consistency_test",
    "fit_noise_model",
    "fit_observed",
    "fit_recording",
    "inverted_interval",
    "nested_test",
    "observe_allan",
    "order_interval",
    "yule_walker",
]

COMPONENTS = ("white", "rrw", "flicker", "quantization", "ar")
#: Standard errors a GLS step may move each parameter by and count as settled (FitOptions.tolerance).
DEFAULT_TOLERANCE = 0.05
#: Below these degrees of freedom 2θ̂²/s² a variance's interval is 0 … θ̂ + z·s (FitResult.interval).
MINIMUM_INTERVAL_DEGREES = 1.0
#: Relative load on C's diagonal where a candidate of :func:`inverted_interval` makes it indefinite to
#: rounding (measured: eigenvalues down to −2·10⁻¹⁰ of the largest variance, RRW 10⁶ times its estimate).
CANDIDATE_JITTER = 1e-9
#: Relative step of the central differences that carry the AR coefficients' error into the parameters.
AR_STEP = 1e-5
#: The 1/f orders d the fit searches (a bounded scalar search) and :func:`order_interval` reports.
ORDER_RANGE = (0.02, 0.98)
#: Grid step of :func:`order_interval`'s scan of ORDER_RANGE (each end then refined by Brent's method).
ORDER_GRID_STEP = 0.01
#: The correlation times :func:`_profiled_ar` searches, as fractions of the estimator's window W: from
#: W/200 to W (an AR(1) of longer τ_c, whose Allan variance the record's RRW and 1/f terms mimic, is not
#: refined; nor is its design, of about 39 τ_c lags, grown without bound).
AR_PROFILE_RANGE = (1.0 / 200.0, 1.0)
#: Points of :func:`_profiled_ar`'s grid over AR_PROFILE_RANGE (log-spaced: τ_c × 1.55 per step).
AR_PROFILE_POINTS = 13
#: An estimated AR(1) coefficient whose correlation time exceeds W/this (W the estimator's high-pass
#: window) and whose fit the χ² rejects at AR_REFINED_LEVEL is refined by the GLS χ²: four times as early
#: as its bias shows (W/20, :data:`carousel_theory.autoregression.LONG_CORRELATION_FRACTION`), so that the
#: estimates that the bias brought below W/20 are refined too (at φ = 0.99, τ_c = W/10, with RRW and 1/f
#: beside it, they come out 0.96–0.99).
AR_REFINED_FRACTION = 80.0
#: The χ² p-value below which a fit with a long estimated correlation time has its coefficient refined.
AR_REFINED_LEVEL = 0.05
#: :attr:`ShortNoiseEstimate.estimator` of an AR(1) coefficient refined by the GLS χ².
ALLAN_PROFILE = "the GLS χ² on the Allan variance"
#: Parameter name of each component in :class:`NoiseModel`.
_PARAMETER = {
    "white": "white_variance",
    "rrw": "rrw_variance",
    "flicker": "flicker_variance",
    "quantization": "quantization_squared",
    "ar": "ar_variance",
}
#: The component each driving parameter belongs to (the inverse of ``_PARAMETER``).
COMPONENT_OF_PARAMETER = {parameter: component for component, parameter in _PARAMETER.items()}


@dataclass(frozen=True)
class FitResult:
    """An identified noise model with its uncertainty.

    Attributes
    ----------
    model : NoiseModel
        The estimate.
    standard_errors : dict[str, float]
        Standard error of each fitted parameter: ``bias``, ``white_variance``, ``rrw_variance``,
        ``flicker_variance``, ``flicker_d``, ``quantization_squared`` (those fitted).
    covariance : ndarray
        Covariance matrix of the linear parameters, in the order of ``parameters``.
    parameters : tuple[str, ...]
        Names of the linear parameters (the rows of ``covariance``).
    method : str
        How the estimate was made.
    allan : AllanResult
        The Allan variance the fit used, with intervals from the fitted model's degrees of freedom.
    model_avar : ndarray
        The fitted model's Allan variance at ``allan.tau``.
    used : ndarray of bool
        Which τ entered the fit.
    chi_square : float
        The GLS objective (â − Aθ)ᵀ C⁻¹ (â − Aθ) at the estimate; about ``degrees_of_freedom`` when the
        model fits.
    degrees_of_freedom : int
        Number of τ used minus number of fitted parameters.
    at_bound : tuple[str, ...]
        Parameters held at zero by the non-negativity constraint (their standard errors are not valid).
    length : int
        Number of samples of the record.
    tau_covariance : ndarray
        The covariance C of the used Allan variance estimates across τ under which the fit was made.
    iterations : int
        Re-evaluations of C the fit took (0 under a given C).
    ar_coefficient_errors : tuple[float, ...]
        Standard errors of the AR coefficients estimated from the record (large-sample, Bartlett's
        formula; empty when they were given or there is no AR term). Their error is also carried into
        ``covariance`` and ``standard_errors``.
    ar_error_covariance : ndarray or None
        The part of ``covariance`` that is the AR coefficients' error carried into the parameters (zero
        when they were given or there is no AR term).
    ar_estimator : str
        How the AR coefficients were found: :data:`carousel_theory.autoregression.PLAIN` or
        :data:`~carousel_theory.autoregression.HIGH_ORDER` Yule–Walker on the record, :data:`ALLAN_PROFILE`
        (an AR(1) coefficient of long correlation time refined by the GLS χ²), "given", or "" without AR.
    """

    model: NoiseModel
    standard_errors: dict[str, float]
    covariance: np.ndarray
    parameters: tuple[str, ...]
    method: str
    allan: Any
    model_avar: np.ndarray
    used: np.ndarray
    chi_square: float
    degrees_of_freedom: int
    at_bound: tuple[str, ...]
    length: int
    tau_covariance: np.ndarray | None = None
    iterations: int = 0
    ar_coefficient_errors: tuple[float, ...] = ()
    ar_error_covariance: np.ndarray | None = None
    ar_estimator: str = ""

    @property
    def components(self) -> tuple[str, ...]:
        """The fitted components (names of :data:`COMPONENTS`), in the order of ``parameters``."""
        return tuple(COMPONENT_OF_PARAMETER[p] for p in self.parameters if p in COMPONENT_OF_PARAMETER)

    @property
    def p_value(self) -> float:
        """P(χ²_ν ≥ ``chi_square``), ν = ``degrees_of_freedom``: the model's misfit test (1 when ν = 0)."""
        if self.degrees_of_freedom <= 0:
            return 1.0
        return float(stats.chi2.sf(self.chi_square, self.degrees_of_freedom))

    @property
    def edf(self) -> np.ndarray:
        """Equivalent degrees of freedom of each τ's estimate under the fitted model."""
        return np.asarray(self.allan.edf)

    def interval(self, name: str, level: float = 0.95, method: str = "chi-square") -> tuple[float, float]:
        """Confidence interval of a fitted parameter at ``level``.

        ``method="inverted"`` (variances only): :func:`inverted_interval`, whose error is evaluated at each
        candidate value rather than at the estimate (for a weakly determined term; see the module text).
        ``method="wald"``: θ̂ ± z·s for any parameter. The default, ``"chi-square"``:

        For a variance parameter θ̂ with standard error s the interval is χ²-based, like the Allan
        variance's own: with ν = 2θ̂²/s², ν θ̂/χ²_ν((1+level)/2) … ν θ̂/χ²_ν((1−level)/2); a variance is
        skewed and positive, which a symmetric ±z·s interval ignores. Below ν = 1 (s > √2 θ̂: the
        variance is barely determined) the χ² quantiles collapse towards 0 faster than ν (at ν = 0.005 the
        lower end would be 111 θ̂, above the estimate), so the interval is then 0 … θ̂ + z·s. For d: the
        d₀ whose GLS χ² exceeds the fit's by at most χ²₁(level) (:func:`order_interval`; d̂ ± z·s
        under-covers, module text). For the bias: θ̂ ± z·s.
        """
        if name not in self.standard_errors:
            raise ValueError(f"name={name!r}: must be one of {sorted(self.standard_errors)}")
        level = check_probability("level", level)
        if method not in ("chi-square", "inverted", "wald"):
            raise ValueError(f"method={method!r}: must be 'chi-square', 'inverted' or 'wald'")
        if method != "wald" and (method == "inverted" or name == "flicker_d"):
            key = (name, level)
            if key not in self._searched_intervals:
                self._searched_intervals[key] = (
                    order_interval(self, level)
                    if name == "flicker_d"
                    else inverted_interval(self, name, level)
                )
            return self._searched_intervals[key]
        value, error = self.value(name), self.standard_errors[name]
        if method == "wald" or name == "bias" or value <= 0 or not error > 0:
            z = float(stats.norm.ppf((1 + level) / 2))
            return value - z * error, value + z * error
        degrees = 2.0 * (value / error) ** 2
        if degrees < MINIMUM_INTERVAL_DEGREES:
            return 0.0, value + float(stats.norm.ppf((1 + level) / 2)) * error
        return (
            degrees * value / float(stats.chi2.ppf((1 + level) / 2, degrees)),
            degrees * value / float(stats.chi2.ppf((1 - level) / 2, degrees)),
        )

    @functools.cached_property
    def _searched_intervals(self) -> dict[tuple[str, float], tuple[float, float]]:
        """The intervals by test inversion computed so far (each costs a search over covariances or
        over d)."""
        return {}

    def value(self, name: str) -> float:
        """The estimate of a parameter by its name in ``standard_errors``."""
        if name == "quantization_squared":
            return float(self.model.quantization) ** 2
        return float(getattr(self.model, name))

    def field_units(self) -> dict[str, tuple[float, float]]:
        """(value, standard error) in the field's units: ARW °/√h, RRW °/h/√h, bias and bias instability °/h.

        Standard errors of the square-root quantities by the delta method: SE(√v) = SE(v) / (2√v).
        """
        model = self.model
        result: dict[str, tuple[float, float]] = {
            "bias_deg_per_h": (
                model.bias_deg_per_hour(),
                units.rad_per_s_to_deg_per_h(self.standard_errors["bias"]),
            )
        }
        if "white_variance" in self.standard_errors:
            value = model.angle_random_walk_deg_per_sqrt_hour()
            result["angle_random_walk_deg_per_sqrt_h"] = (
                value,
                _relative_sqrt_error(self, "white_variance") * value,
            )
        if "rrw_variance" in self.standard_errors:
            value = model.rate_random_walk_deg_per_hour_per_sqrt_hour()
            result["rate_random_walk_deg_per_h_per_sqrt_h"] = (
                value,
                _relative_sqrt_error(self, "rrw_variance") * value,
            )
        minimum, _ = model.minimum_allan_deviation(self.length)
        result["bias_instability_deg_per_h"] = (
            units.rad_per_s_to_deg_per_h(units.bias_instability_from_allan_minimum(minimum)),
            units.rad_per_s_to_deg_per_h(
                units.bias_instability_from_allan_minimum(self.minimum_deviation_error())
            ),
        )
        return result

    def _bounded_error(self, name: str) -> float:
        """The standard error of ``name``, NaN when it is held at zero (``at_bound``: it has none)."""
        return math.nan if name in self.at_bound else float(self.standard_errors[name])

    def paper_units(self) -> dict[str, tuple[float, float]]:
        """(value, standard error) in TIM 2014 Table III's terms: σ_WN² (τ = 1 s) in (rad/s)², σ_q² in
        (rad/s)²/s, bias instability in rad/s; a term held at zero has no standard error (NaN), as in
        :meth:`field_units`."""
        rate = float(self.model.sample_rate)
        result: dict[str, tuple[float, float]] = {}
        if "white_variance" in self.standard_errors:
            result["white_variance_at_1s"] = (
                self.model.white_variance_at_one_second(),
                self._bounded_error("white_variance") / rate,
            )
        if "rrw_variance" in self.standard_errors:
            result["rrw_variance_per_s"] = (
                self.model.rrw_variance_per_second(),
                self._bounded_error("rrw_variance") * rate,
            )
        minimum, _ = self.model.minimum_allan_deviation(self.length)
        result["bias_instability"] = (
            units.bias_instability_from_allan_minimum(minimum),
            units.bias_instability_from_allan_minimum(self.minimum_deviation_error()),
        )
        return result

    def minimum_deviation_error(self) -> float:
        """Standard error of the model's minimum Allan deviation, by the delta method over the linear
        parameters (numerical gradient)."""
        base, _ = self.model.minimum_allan_deviation(self.length)
        gradient = np.zeros(len(self.parameters))
        for k, name in enumerate(self.parameters):
            value = self.value(name)
            step = max(abs(value), self.standard_errors[name], 1e-300) * 1e-4
            gradient[k] = (
                _shifted(self.model, name, step).minimum_allan_deviation(self.length)[0] - base
            ) / step
        return float(np.sqrt(max(gradient @ self.covariance @ gradient, 0.0)))


def _relative_sqrt_error(result: FitResult, name: str) -> float:
    value = result.value(name)
    return result.standard_errors[name] / (2.0 * value) if value > 0 else float("inf")


def _shifted(model: NoiseModel, name: str, step: float) -> NoiseModel:
    from dataclasses import replace

    if name == "quantization_squared":
        return replace(model, quantization=math.sqrt(model.quantization**2 + step))
    return replace(model, **{name: getattr(model, name) + step})


# --- the observed Allan variance and the options ---------------------------------------------------


@dataclass(frozen=True)
class ObservedAllan:
    """The octave Allan variance of one record, computed once and shared by every fit of that record.

    Attributes
    ----------
    allan : AllanResult
        Octave τ up to a third of the record, white-noise intervals.
    length : int
        Samples in the record.
    mean : float
        The record mean (the bias estimate).
    sample_rate : float
        Samples per second.
    ar_source : ndarray or None
        The record, kept only when AR coefficients are to be estimated from it.
    """

    allan: AllanResult
    length: int
    mean: float
    sample_rate: float
    ar_source: np.ndarray | None = None


def observe_allan(
    y: Any, sample_rate: float, *, estimator: str = "overlapping", keep_record: bool = False
) -> ObservedAllan:
    """The octave Allan variance of ``y`` (one pass over the data) for :func:`fit_observed`."""
    sample_rate = float(check_positive_real("sample_rate", sample_rate))
    samples = check_finite_array("y", y, min_length=3)
    allan = allan_variance(samples, sample_rate, "octave", estimator=estimator)
    return ObservedAllan(
        allan, len(samples), float(samples.mean()), sample_rate, samples if keep_record else None
    )


@dataclass(frozen=True)
class FitOptions:
    """What to fit.

    Attributes
    ----------
    components : tuple of str
        From :data:`COMPONENTS`; the bias (record mean) is always estimated.
    flicker_d : float or None
        Fixed 1/f order, or None to fit it (profile GLS) when "flicker" is a component.
    ar_order : int
        Largest AR order tried by Yule–Walker when "ar" is a component.
    ar_coefficients : tuple of float or None
        Fixed AR coefficients (then ``ar_order`` is ignored).
    tau_range : (float or None, float or None) or None
        Only τ in [low, high] s enter the fit (the short-τ cut-off above a sensor's filter); None at
        either end leaves it open.
    minimum_clusters : int
        Only τ with at least this many disjoint clusters in the record enter the fit.
    iterations : int
        Most re-evaluations of the model-based covariance C.
    tolerance : float or None
        Stop re-evaluating C once a GLS step moved no parameter by more than this many of its standard
        errors (None: always ``iterations``).
    """

    components: tuple[str, ...] = ("white", "rrw")
    flicker_d: float | None = None
    ar_order: int = 4
    ar_coefficients: tuple[float, ...] | None = None
    tau_range: tuple[float | None, float | None] | None = None
    minimum_clusters: int = 3
    iterations: int = 3
    tolerance: float | None = DEFAULT_TOLERANCE

    def __post_init__(self) -> None:
        components = self.components
        if isinstance(components, str) or not all(isinstance(c, str) for c in components):
            raise TypeError(f"components={components!r}: must be a tuple of names from {COMPONENTS}")
        unknown = [c for c in components if c not in COMPONENTS]
        if unknown or not components or len(set(components)) != len(components):
            raise ValueError(f"components={components!r}: must be distinct names from {COMPONENTS}")
        object.__setattr__(self, "components", tuple(c for c in COMPONENTS if c in components))
        if self.flicker_d is not None:
            object.__setattr__(self, "flicker_d", float(check_fractional_order("flicker_d", self.flicker_d)))
        check_positive_integer("ar_order", self.ar_order)
        check_positive_integer("minimum_clusters", self.minimum_clusters, minimum=2)
        check_positive_integer("iterations", self.iterations)
        if self.tolerance is not None:
            object.__setattr__(self, "tolerance", float(check_positive_real("tolerance", self.tolerance)))
        check_tau_range(self.tau_range)  # an open end (None) is 0 or ∞
        if self.ar_coefficients is not None and not len(self.ar_coefficients):
            raise ValueError(
                "ar_coefficients=(): must hold at least one coefficient (AR(0) is white noise: use 'white')"
            )
        if self.ar_coefficients is not None:
            check_ar_coefficients(tuple(self.ar_coefficients))


# --- the GLS ---------------------------------------------------------------------------------------


def _model_with(
    sample_rate: float, bias: float, values: dict[str, float], flicker_d: float, ar: tuple[float, ...]
) -> NoiseModel:
    return NoiseModel(
        sample_rate=sample_rate,
        bias=bias,
        white_variance=values.get("white", 0.0),
        rrw_variance=values.get("rrw", 0.0),
        flicker_variance=values.get("flicker", 0.0),
        flicker_d=flicker_d,
        quantization=math.sqrt(values.get("quantization", 0.0)),
        ar_variance=values.get("ar", 0.0),
        ar_coefficients=ar,
    )


def _design(problem: _Problem, d: float) -> np.ndarray:
    """Columns: the exact Allan variance of each component at unit parameter (quantization: Q = 1 rad)."""
    sizes = tuple(int(m) for m in problem.sizes)
    columns = []
    for name in problem.components:
        if name == "flicker":
            columns.append(term_allan_variance(name, problem.sizes, d))
        else:
            columns.append(_fixed_column(name, sizes, problem.ar, problem.sample_rate))
    return np.column_stack(columns)


@functools.lru_cache(maxsize=64)
def _fixed_column(name: str, sizes: tuple[int, ...], ar: tuple[float, ...], sample_rate: float) -> np.ndarray:
    """A design column that does not depend on d, computed once per (τ set, AR coefficients)."""
    column = term_allan_variance(name, np.asarray(sizes, dtype=np.int64), ar_coefficients=ar)
    column = column * sample_rate**2 if name == "quantization" else column
    column.setflags(write=False)
    return column


def _generalized_least_squares(
    design: np.ndarray, observed: np.ndarray, cholesky: np.ndarray
) -> tuple[np.ndarray, float, np.ndarray]:
    """Non-negative GLS with C = LLᵀ: (θ, objective, whitened design)."""
    whitened_design = np.linalg.solve(cholesky, design)
    whitened_observed = np.linalg.solve(cholesky, observed)
    # Columns differ by many orders of magnitude; scale them so that NNLS is well conditioned.
    scale = np.linalg.norm(whitened_design, axis=0)
    scale[scale == 0] = 1.0
    theta_scaled, residual_norm = nnls(whitened_design / scale, whitened_observed)
    return theta_scaled / scale, float(residual_norm**2), whitened_design


@dataclass(frozen=True)
class _Problem:
    """The used τ of one fit: sizes, observed values, components, fixed AR coefficients, record length."""

    sizes: np.ndarray
    observed: np.ndarray
    components: tuple[str, ...]
    ar: tuple[float, ...]
    length: int
    sample_rate: float
    estimator: str
    fit_d: bool


def _used_mask(observed: ObservedAllan, options: FitOptions) -> np.ndarray:
    allan = observed.allan
    sizes = np.asarray(allan.samples_per_cluster)
    used = observed.length // sizes >= options.minimum_clusters
    if options.tau_range is not None:
        low, high = check_tau_range(options.tau_range)
        used &= (allan.tau >= low * (1 - 1e-12)) & (allan.tau <= high * (1 + 1e-12))
    parameter_count = len(options.components) + int(_fits_d(options))
    if used.sum() <= parameter_count:
        raise ValueError(
            f"y: {int(used.sum())} octave τ in range, too few to fit {parameter_count} parameters "
            f"{options.components + (('flicker_d',) if _fits_d(options) else ())}; the recording "
            f"({observed.length} samples) is too short or tau_range too narrow"
        )
    if np.any(allan.avar[used] <= 0):
        index = int(np.flatnonzero(used & (allan.avar <= 0))[0])
        raise UnusableSignalError(
            f"y: the Allan variance is 0 at τ = {allan.tau[index]:.4g} s (m = "
            f"{int(sizes[index])} samples); a noise model needs a positive Allan "
            "variance at every τ it fits (a record that repeats itself every m samples has none): check the "
            "recording or narrow tau_range"
        )
    return used


def _fits_d(options: FitOptions) -> bool:
    return "flicker" in options.components and options.flicker_d is None


def _short_noise(observed: ObservedAllan, options: FitOptions) -> ShortNoiseEstimate:
    """The AR coefficients: given (zero covariance), or estimated from the record with their covariance."""
    if "ar" not in options.components:
        return ShortNoiseEstimate((), "", np.zeros((0, 0)))
    if options.ar_coefficients is not None:
        given = tuple(float(c) for c in options.ar_coefficients)
        return ShortNoiseEstimate(given, "given", np.zeros((len(given), len(given))))
    if observed.ar_source is None:
        raise ValueError(
            "observed: the AR coefficients are estimated from the record; observe it with "
            "keep_record=True or give FitOptions(ar_coefficients=...)"
        )
    beside_white = "white" in options.components
    estimator = short_noise_estimate if beside_white else yule_walker_estimate
    estimate = estimator(observed.ar_source, observed.sample_rate, options.ar_order)
    if not estimate.coefficients:
        rule = f"no partial autocorrelation up to order {options.ar_order} exceeds 4/√n"
        rule += " and no autocovariance at lags ≥ 1 exceeds 4 γ(0)/√n" if beside_white else ""
        raise ValueError(
            f"y: no short correlated noise in the record ({rule}); fit without 'ar' "
            "(its short noise is white) or give the coefficients (ar_coefficients, `fit --ar-coefficients`)"
        )
    return estimate


def _coefficient_errors(short: ShortNoiseEstimate) -> tuple[float, ...]:
    """The estimated AR coefficients' standard errors; () when they were given or there are none."""
    if short.estimator in ("", "given"):
        return ()
    return tuple(float(e) for e in np.sqrt(np.maximum(np.diag(short.covariance), 0.0)))


def _ar_error_covariance(problem: _Problem, solution: _Solution, ar_covariance: np.ndarray) -> np.ndarray:
    """S Cov(φ̂) Sᵀ: the estimated AR coefficients' error carried into the fitted parameters (θ, and d
    when fitted, which is held), S = ∂θ̂/∂φ by central differences of the GLS at the fit's C and d; 0
    when the coefficients were given or there are none."""
    size = len(problem.components) + int(problem.fit_d)
    if not np.any(ar_covariance):
        return np.zeros((size, size))
    cholesky = np.linalg.cholesky(solution.covariance)
    columns = []
    for index, value in enumerate(problem.ar):
        step = AR_STEP * max(1.0, abs(value))
        solved = []
        for sign in (1.0, -1.0):
            shifted = (*problem.ar[:index], value + sign * step, *problem.ar[index + 1 :])
            design = _design(replace(problem, ar=shifted), solution.d)
            solved.append(_generalized_least_squares(design, problem.observed, cholesky)[0])
        columns.append((solved[0] - solved[1]) / (2.0 * step))
    sensitivity = np.column_stack(columns)
    if problem.fit_d:
        sensitivity = np.vstack((sensitivity, np.zeros((1, len(problem.ar)))))
    return sensitivity @ ar_covariance @ sensitivity.T


def _iterations_method(solution: _Solution, options: FitOptions, fixed: bool) -> str:
    if fixed:
        return "held at the given one"
    if solution.settled:
        return (
            f"{solution.evaluations} iterations (the last moved no parameter by more than "
            f"{options.tolerance:g} of its standard error)"
        )
    return f"{solution.evaluations} iterations"


def _ar_method(short: ShortNoiseEstimate) -> str:
    if not short.coefficients:
        return ""
    p = len(short.coefficients)
    if short.estimator == "given":
        return f", AR({p}) coefficients given"
    if short.estimator == ALLAN_PROFILE:
        return (
            f", AR(1) coefficient by {ALLAN_PROFILE} (the record's estimate is biased low at its correlation "
            "time; its error, from the χ²'s curvature, carried into the standard errors)"
        )
    return (
        f", AR({p}) coefficients by {short.estimator} (their sampling error, Bartlett's formula, carried "
        "into the standard errors)"
    )


def _objective(problem: _Problem, d: float, cholesky: np.ndarray) -> float:
    """The GLS χ² of ``problem`` at 1/f order d under C = LLᵀ, the variances refitted."""
    return _generalized_least_squares(_design(problem, d), problem.observed, cholesky)[1]


def _profile_d(problem: _Problem, cholesky: np.ndarray, d: float) -> float:
    """The d minimising the GLS objective at fixed covariance (bounded scalar search)."""
    if not problem.fit_d:
        return d

    def objective(order: float) -> float:
        return _objective(problem, order, cholesky)

    return float(minimize_scalar(objective, bounds=ORDER_RANGE, method="bounded", options={"xatol": 1e-4}).x)


@dataclass(frozen=True)
class _Solution:
    """The iterated GLS's end: θ, d, the C it used, χ², and the covariance evaluations it took."""

    theta: np.ndarray
    d: float
    covariance: np.ndarray
    chi_square: float
    evaluations: int
    settled: bool


def _solve(
    problem: _Problem,
    d: float,
    options: FitOptions,
    fixed_covariance: np.ndarray | None,
    start: np.ndarray | None = None,
) -> _Solution:
    """Iterated GLS. C starts at ``start``, or diagonal (white-noise degrees of freedom of the data), and
    is re-evaluated at most ``options.iterations`` times; with ``options.tolerance`` it stops once the last
    step moved no parameter by more than that many of its standard errors."""
    iterations = 1 if fixed_covariance is not None else options.iterations
    if fixed_covariance is not None:
        covariance = fixed_covariance
    elif start is not None:
        covariance = start
    else:
        degrees = np.maximum(_white_edf(problem), 1.0)
        covariance = np.diag(2.0 * problem.observed**2 / degrees)
    previous: tuple[np.ndarray, float] | None = None
    for iteration in range(iterations + 1):
        cholesky = np.linalg.cholesky(covariance)
        d = _profile_d(problem, cholesky, d)
        theta, chi_square, _ = _generalized_least_squares(_design(problem, d), problem.observed, cholesky)
        settled = previous is not None and _settled(problem, previous, (theta, d), covariance, options)
        if iteration == iterations or fixed_covariance is not None or not np.any(theta > 0) or settled:
            break
        previous = (theta, d)
        model = _model_with(
            problem.sample_rate, 0.0, dict(zip(problem.components, theta, strict=True)), d, problem.ar
        )
        covariance = allan_estimate_covariance(
            model, problem.sizes, problem.length, estimator=problem.estimator, bound=False, rule=WEIGHTS_RULE
        ).covariance
    return _Solution(theta, d, covariance, chi_square, iteration, settled)


def _solved(
    problem: _Problem,
    short: ShortNoiseEstimate,
    options: FitOptions,
    start_d: float,
    fixed_covariance: np.ndarray | None,
) -> tuple[_Problem, ShortNoiseEstimate, _Solution]:
    """:func:`_solve`; when an estimated AR(1) coefficient's correlation time exceeds W/AR_REFINED_FRACTION
    (:func:`carousel_theory.autoregression.correlation_is_long`) and the χ² rejects the fit at
    AR_REFINED_LEVEL, the coefficient is refined by the GLS χ² and the fit solved again with it
    (:func:`_profiled_ar`, module text)."""
    _check_fixed_covariance(fixed_covariance, len(problem.observed))
    solution = _solve(problem, start_d, options, fixed_covariance)
    long = short.estimator not in ("", "given") and correlation_is_long(
        short.coefficients, problem.sample_rate, AR_REFINED_FRACTION
    )
    degrees = len(problem.observed) - len(problem.components) - int(problem.fit_d)
    rejected = degrees > 0 and float(stats.chi2.sf(solution.chi_square, degrees)) < AR_REFINED_LEVEL
    if fixed_covariance is not None or not long or not rejected:
        return problem, short, solution
    refined = _profiled_ar(problem, solution)
    if refined is None:
        return problem, short, solution
    problem = replace(problem, ar=refined.coefficients)
    # The first solution's C, evaluated with the record's coefficient, starts the second iteration.
    return problem, refined, _solve(problem, solution.d, options, None, start=solution.covariance)


def _profiled_ar(problem: _Problem, solution: _Solution) -> ShortNoiseEstimate | None:
    """The AR(1) coefficient φ = exp(−1/τ_c) minimising the GLS χ² at the solution's covariance across τ,
    searched over log τ_c on AR_PROFILE_RANGE (an AR_PROFILE_POINTS grid, then Brent's method in the
    best point's cells, both at the solution's d; the fit is solved again at the result, d profiled); its
    variance 2/(∂²χ²/∂φ²) with d profiled (the χ² is −2 log L up to a constant). None when it does not
    lower the χ² (d profiled at both) or where its curvature is not positive."""
    cholesky = np.linalg.cholesky(solution.covariance)

    def objective(phi: float, profiled: bool = True) -> float:
        shifted = replace(problem, ar=(phi,))
        order = _profile_d(shifted, cholesky, solution.d) if profiled else solution.d
        return _objective(shifted, order, cholesky)

    def at_log_time(log_time: float) -> float:
        return objective(math.exp(-math.exp(-log_time)), profiled=False)

    window = high_pass_window(problem.sample_rate)
    low, high = (math.log(window * fraction) for fraction in AR_PROFILE_RANGE)
    grid = np.linspace(low, high, AR_PROFILE_POINTS)
    best = int(np.argmin([at_log_time(float(u)) for u in grid]))
    bracket = (grid[max(best - 1, 0)], grid[min(best + 1, len(grid) - 1)])
    found = minimize_scalar(at_log_time, bounds=bracket, method="bounded", options={"xatol": 1e-4})
    phi = math.exp(-math.exp(-float(found.x)))
    at_phi = objective(phi)
    if not at_phi < objective(problem.ar[0]):
        return None
    step = 1e-2 * (1.0 - phi)
    curvature = (objective(phi + step) - 2.0 * at_phi + objective(phi - step)) / step**2
    if not curvature > 0:  # not a minimum the χ² resolves: keep the record's estimate
        return None
    return ShortNoiseEstimate((phi,), ALLAN_PROFILE, np.array([[2.0 / curvature]]))


def _settled(
    problem: _Problem,
    previous: tuple[np.ndarray, float],
    current: tuple[np.ndarray, float],
    covariance: np.ndarray,
    options: FitOptions,
) -> bool:
    """Did the last GLS step move every parameter (θ, and d when fitted) by at most ``options.tolerance``
    of its standard error under ``covariance``?"""
    if options.tolerance is None:
        return False
    theta, d = current
    _, parameter_covariance = _parameter_covariance(problem, theta, d, covariance)
    errors = np.sqrt(np.maximum(np.diag(parameter_covariance), 0.0))
    change = np.abs(theta - previous[0])
    if problem.fit_d:
        change = np.append(change, abs(d - previous[1]))
    moved = change > 0
    return bool(np.all(change[moved] <= options.tolerance * errors[moved]))


def _white_edf(problem: _Problem) -> np.ndarray:
    """The degrees of freedom of the Allan variance estimates of white noise at the used τ (the iterated
    GLS's diagonal start), in exact integers
    (:func:`~carousel_theory.allan.equivalent_degrees_of_freedom`)."""
    overlapping = problem.estimator == "overlapping"
    edf = []
    for m in problem.sizes.tolist():
        terms = problem.length - 2 * m + 1 if overlapping else problem.length // m - 1
        stride = 1 if overlapping else m
        edf.append(
            equivalent_degrees_of_freedom("white", m, terms, stride, problem.length, problem.sample_rate)
        )
    return np.array(edf)


def _parameter_covariance(
    problem: _Problem, theta: np.ndarray, d: float, covariance: np.ndarray
) -> tuple[tuple[str, ...], np.ndarray]:
    """(names, covariance of the parameters) from (JᵀC⁻¹J)⁻¹; d's column is ∂(Aθ)/∂d when d is fitted."""
    cholesky = np.linalg.cholesky(covariance)
    design = _design(problem, d)
    jacobian = np.linalg.solve(cholesky, design)
    names = tuple(_PARAMETER[c] for c in problem.components)
    if problem.fit_d:
        upper, lower = min(d + 1e-4, 0.999), max(d - 1e-4, 0.001)
        derivative = (_design(problem, upper) - _design(problem, lower)) @ theta / (upper - lower)
        jacobian = np.column_stack((jacobian, np.linalg.solve(cholesky, derivative)))
        names = (*names, "flicker_d")
    # Columns differ by many orders of magnitude: invert the information matrix of the column-scaled
    # problem, then scale back.
    column_scale = np.linalg.norm(jacobian, axis=0)
    column_scale[column_scale == 0] = 1.0
    scaled = jacobian / column_scale
    return names, np.linalg.pinv(scaled.T @ scaled) / np.outer(column_scale, column_scale)


def _bias_variance(model: NoiseModel, length: int) -> float:
    """Var(ȳ) of the record mean under ``model`` (bias excluded): the record is one averaged bin of
    N = length samples, so white and RRW come from the registry (``white_average_var``,
    ``rrw_average_var`` at k = 1), 1/f from :func:`carousel_theory.propagation.flicker_averaged_bin_variance`,
    quantization (a white angle error differenced into the rate) adds 2 f_s² Q²/n², and the AR term
    its long-run variance /n (the leading term; the end correction is O(1/n²))."""
    n = float(length)
    variance = model.white_variance * float(formula("white_average_var").numeric(N=length))
    variance += model.rrw_variance * float(formula("rrw_average_var").numeric(N=length, k=1))
    variance += 2.0 * (model.sample_rate * model.quantization) ** 2 / n**2
    variance += model.long_run_ar_variance / n if model.ar_variance else 0.0
    if model.flicker_variance:
        variance += model.flicker_variance * _flicker_mean_variance(float(model.flicker_d), length)
    return variance


def _flicker_mean_variance(d: float, length: int) -> float:
    """Var ȳ of N = ``length`` samples of the 1/f process of TIM 2014 eq. (3) at σ_w² = 1:
    N⁻² Σ_{j<N} Ψ_j² (:func:`carousel_theory.propagation.flicker_averaged_bin_variance` at k = 1) with
    the partial sums Ψ_j = ψ_0 + … + ψ_j = Γ(j + 1 + d)/(Γ(1 + d) Γ(j + 1)) in closed form (the
    coefficients of (1 − B)^{−d−1}), summed by
    :func:`carousel_theory.increment_sums.squared_rising_factorial_sum` at a cost independent of N."""
    total = squared_rising_factorial_sum(d, length)
    return total / (math.gamma(1.0 + d) ** 2 * float(length) ** 2)


def fit_observed(
    observed: ObservedAllan, options: FitOptions, *, fixed_covariance: np.ndarray | None = None
) -> FitResult:
    """Fit ``options`` to an :class:`ObservedAllan` (see the module text).

    ``fixed_covariance`` (across the used τ) replaces the iterated model-based C: :func:`nested_test`
    fits the reduced model under the fuller model's C so that the χ² difference is a likelihood-ratio-
    type statistic.
    """
    used = _used_mask(observed, options)
    allan = observed.allan
    short = _short_noise(observed, options)
    problem = _Problem(
        np.asarray(allan.samples_per_cluster)[used],
        allan.avar[used],
        options.components,
        short.coefficients,
        observed.length,
        observed.sample_rate,
        allan.estimator,
        _fits_d(options),
    )
    start_d = 0.5 if options.flicker_d is None else options.flicker_d
    problem, short, solution = _solved(problem, short, options, start_d, fixed_covariance)
    theta, d, covariance, chi_square = solution.theta, solution.d, solution.covariance, solution.chi_square
    names, parameter_covariance = _parameter_covariance(problem, theta, d, covariance)
    ar_error = _ar_error_covariance(problem, solution, short.covariance)
    parameter_covariance = parameter_covariance + ar_error
    values = dict(zip(options.components, theta, strict=True))
    model = _model_with(observed.sample_rate, observed.mean, values, d, short.coefficients)
    errors = dict(zip(names, np.sqrt(np.maximum(np.diag(parameter_covariance), 0.0)), strict=True))
    errors["bias"] = math.sqrt(_bias_variance(model, observed.length))
    refreshed = with_model_intervals(allan, model, observed.length) if model.terms() else allan
    tau_used = allan.tau[used]
    method = (
        f"generalized least squares on the {allan.estimator} Allan variance at {int(used.sum())} octave τ "
        f"({tau_used[0]:.4g} s … {tau_used[-1]:.4g} s), model-based covariance across τ, "
        + _iterations_method(solution, options, fixed_covariance is not None)
        + (", 1/f order d profiled" if problem.fit_d else "")
        + _ar_method(short)
    )
    return FitResult(
        model=model,
        standard_errors=errors,
        covariance=parameter_covariance,
        parameters=names,
        method=method,
        allan=refreshed,
        model_avar=model.allan_variance(np.asarray(allan.samples_per_cluster)),
        used=used,
        chi_square=chi_square,
        degrees_of_freedom=int(used.sum()) - len(names),
        at_bound=tuple(name for name, value in zip(names, theta, strict=False) if value <= 0),
        length=observed.length,
        tau_covariance=covariance,
        iterations=solution.evaluations,
        ar_coefficient_errors=_coefficient_errors(short),
        ar_error_covariance=ar_error,
        ar_estimator=short.estimator,
    )


# --- intervals by test inversion ---------------------------------------------------------------------


def inverted_interval(fit: FitResult, name: str, level: float = 0.95) -> tuple[float, float]:
    """Interval of a fitted variance ``name`` at ``level`` by inverting the Wald test with the standard error
    at each candidate value: {θ₀ ≥ 0 : |θ̂ − θ₀| ≤ z s(θ₀)}, s(θ₀)² the parameter's entry of (JᵀC(θ₀)⁻¹J)⁻¹
    (plus the AR coefficients' part, ``fit.ar_error_covariance``), C(θ₀) the covariance across τ of the
    fitted model with that variance at θ₀ (module text). The upper end is inf when no θ₀ is excluded up to
    2⁴⁰ standard errors above the estimate."""
    names = [_PARAMETER[c] for c in fit.components]
    if name not in names:
        raise ValueError(f"name={name!r}: the inverted interval is for the fitted variances {names}")
    level = check_probability("level", level)
    z = float(stats.norm.ppf((1 + level) / 2))
    error_at = _error_at_candidate(fit, names.index(name))
    estimate = fit.value(name)
    spread = error_at(estimate)
    if not spread > 0:
        return estimate, estimate
    lower = _inverted_end(lambda value: estimate - value - z * error_at(value), estimate, -spread)
    upper = _inverted_end(lambda value: value - estimate - z * error_at(value), estimate, spread)
    return lower, upper


def order_interval(fit: FitResult, level: float = 0.95) -> tuple[float, float]:
    """Interval of the fitted 1/f order d at ``level`` by inverting the χ² difference: the d₀ of
    ORDER_RANGE whose GLS χ², the variances refitted at d₀ under the fit's covariance across τ, exceeds
    the fit's by at most χ²₁(level) (a likelihood-ratio-type test, as :func:`nested_test` compares two
    fits). Scanned on a grid of ORDER_GRID_STEP, the ends of the accepted set refined by Brent's method;
    the hull is returned, and an end at the edge of ORDER_RANGE means no d₀ up to it is excluded (with
    the 1/f term at zero, the whole range). Unlike d̂ ± z·s, it follows the χ² where it is not a
    parabola in d (module text)."""
    if "flicker_d" not in fit.parameters:
        raise ValueError(
            f"fit: d was not fitted (parameters {fit.parameters}); its interval needs a fitted d"
        )
    level = check_probability("level", level)
    if fit.tau_covariance is None:
        raise ValueError(
            "fit: carries no covariance across τ (tau_covariance), which the χ² difference needs"
        )
    problem = _problem_of(fit)
    cholesky = np.linalg.cholesky(fit.tau_covariance)
    critical = float(stats.chi2.ppf(level, 1))

    def excess(order: float) -> float:
        return _objective(problem, order, cholesky) - fit.chi_square - critical

    low, high = ORDER_RANGE
    grid = np.linspace(low, high, round((high - low) / ORDER_GRID_STEP) + 1)
    grid = np.unique(np.append(grid, float(fit.model.flicker_d)))  # d̂ itself is accepted
    accepted = np.flatnonzero(np.array([excess(float(order)) for order in grid]) <= 0.0)
    first, last = int(accepted[0]), int(accepted[-1])
    lower = grid[first] if first == 0 else brentq(excess, grid[first - 1], grid[first], xtol=1e-4)
    upper = grid[last] if last == len(grid) - 1 else brentq(excess, grid[last], grid[last + 1], xtol=1e-4)
    return float(lower), float(upper)


def _check_fixed_covariance(covariance: Any, size: int) -> None:
    """Refuse a ``fixed_covariance`` that is not a finite, symmetric, positive definite size × size array
    (None: the fit's own, nothing to check)."""
    if covariance is None:
        return
    matrix = np.asarray(covariance)
    if matrix.shape != (size, size) or matrix.dtype.kind not in "fiu":
        raise ValueError(
            f"fixed_covariance: shape {matrix.shape}; must be a ({size}, {size}) array of numbers, one row "
            "and column per τ the fit uses"
        )
    if not np.all(np.isfinite(matrix)) or not np.array_equal(matrix, matrix.T):
        raise ValueError("fixed_covariance: must be finite and symmetric")
    try:
        np.linalg.cholesky(matrix)
    except np.linalg.LinAlgError:
        raise ValueError("fixed_covariance: must be positive definite (a covariance across τ)") from None


def _problem_of(fit: FitResult) -> _Problem:
    """The GLS problem of a finished fit: its used τ, components, AR coefficients and record."""
    used, allan = fit.used, fit.allan
    return _Problem(
        np.asarray(allan.samples_per_cluster)[used],
        allan.avar[used],
        fit.components,
        tuple(fit.model.ar_coefficients),
        fit.length,
        fit.model.sample_rate,
        allan.estimator,
        "flicker_d" in fit.parameters,
    )


def _error_at_candidate(fit: FitResult, index: int) -> Callable[[float], float]:
    """s(θ₀) of the fitted variance at ``index`` (:func:`inverted_interval`), the others at the estimate."""
    components = fit.components
    d = float(fit.model.flicker_d)
    problem = _problem_of(fit)
    theta = np.array([fit.value(_PARAMETER[c]) for c in components])
    fixed = 0.0 if fit.ar_error_covariance is None else float(fit.ar_error_covariance[index, index])
    covariance_at = _covariance_in_candidate(problem, theta, index, d)

    def error_at(value: float) -> float:
        candidate = theta.copy()
        candidate[index] = value
        covariance = covariance_at(value)
        for jitter in (0.0, CANDIDATE_JITTER):
            try:  # far above the data one term dominates and C can be indefinite to rounding
                loaded = covariance + jitter * np.diag(np.diag(covariance))
                variance = _parameter_covariance(problem, candidate, d, loaded)[1][index, index]
            except np.linalg.LinAlgError:
                continue
            return math.sqrt(max(float(variance) + fixed, 0.0))
        return math.inf  # not excluded: the candidate's spread cannot be told

    return error_at


def _covariance_in_candidate(
    problem: _Problem, theta: np.ndarray, index: int, d: float
) -> Callable[[float], np.ndarray]:
    """C(θ₀) across the used τ with the variance at ``index`` at θ₀ and the others at ``theta``. With
    c = c_rest + θ₀ c_a every Σ N c² is a quadratic in θ₀, C(θ₀) = A + B θ₀ + G θ₀², so three covariances
    give it everywhere: A without the term, G of the term alone at unit variance, and B from one at the
    θ₀ where A and G θ₀² balance (measured against direct evaluation on the ADIS16405 fits, from 10⁻³ to
    10⁸ times the estimate: within 4·10⁻⁸ of each entry)."""

    def covariance(values: np.ndarray) -> np.ndarray:
        if not np.any(values > 0):
            return np.zeros((len(problem.sizes), len(problem.sizes)))
        model = _model_with(
            problem.sample_rate, 0.0, dict(zip(problem.components, values, strict=True)), d, problem.ar
        )
        return allan_estimate_covariance(
            model, problem.sizes, problem.length, estimator=problem.estimator, bound=False, rule=WEIGHTS_RULE
        ).covariance

    rest, alone = theta.copy(), np.zeros_like(theta)
    rest[index], alone[index] = 0.0, 1.0
    constant, square = covariance(rest), covariance(alone)
    linear = np.zeros_like(square)
    if np.any(constant):
        balance = math.sqrt(float(np.linalg.norm(constant) / np.linalg.norm(square)))
        at_balance = rest.copy()
        at_balance[index] = balance
        linear = (covariance(at_balance) - constant - balance**2 * square) / balance
    return lambda value: constant + value * linear + value**2 * square


def _inverted_end(excess: Callable[[float], float], estimate: float, step: float) -> float:
    """The root of ``excess`` (negative at the estimate, increasing away from it) on the side of ``step``,
    by Brent's method to 10⁻³ of |step|: below, between 0 and the estimate (0 when even θ₀ ≈ 0 is not
    excluded); above, bracketed by doubling steps (inf when none up to 2⁴⁰ steps is excluded)."""
    tolerance = 1e-3 * abs(step)
    if step < 0:
        floor = max(estimate, abs(step)) * 1e-12  # C is singular with the only term at exactly 0
        if estimate <= floor or excess(floor) <= 0:
            return 0.0
        return float(brentq(excess, floor, estimate, xtol=tolerance))
    reach = step
    while excess(estimate + reach) <= 0:
        reach *= 2.0
        if reach > 2.0**40 * step:
            return math.inf
    return float(
        brentq(excess, estimate + reach / 2.0 if reach > step else estimate, estimate + reach, xtol=tolerance)
    )


def fit_noise_model(
    y: Any,
    sample_rate: float,
    components: tuple[str, ...] = ("white", "rrw"),
    *,
    flicker_d: float | None = None,
    tau_range: tuple[float | None, float | None] | None = None,
    estimator: str = "overlapping",
    iterations: int = 3,
    confidence: float = 0.95,
    ar_order: int = 4,
    ar_coefficients: tuple[float, ...] | None = None,
    minimum_clusters: int = 3,
    tolerance: float | None = DEFAULT_TOLERANCE,
) -> FitResult:
    """Identify a noise model from rate samples by GLS on the octave Allan variance (see the module text).

    Parameters
    ----------
    y : 1-D array
        Rate samples (rad/s).
    sample_rate : float
        Samples per second.
    components : tuple of {"white", "rrw", "flicker", "quantization", "ar"}
        The processes in the model. The bias (record mean) is always estimated.
    flicker_d : float, optional
        Fix the 1/f order d; without it d is fitted (profile GLS) when "flicker" is a component.
    tau_range : (float or None, float or None), optional
        Only τ in [low, high] seconds enter the fit (e.g. to skip τ where internal filtering shows);
        either end may be None (open), e.g. ``(0.1, None)``.
    estimator : {"overlapping", "non-overlapping"}
        The Allan variance estimator fitted.
    iterations, tolerance
        Most re-evaluations of the model-based covariance C; stop once a step moved no parameter by more
        than ``tolerance`` standard errors (None: always ``iterations``).
    confidence : float
        Level of the intervals of the returned Allan variance.
    ar_order, ar_coefficients, minimum_clusters
        See :class:`FitOptions`.
    """
    options = FitOptions(
        components, flicker_d, ar_order, ar_coefficients, tau_range, minimum_clusters, iterations, tolerance
    )
    observed = observe_allan(y, sample_rate, estimator=estimator, keep_record="ar" in options.components)
    check_noise_signal(y, "y")
    if confidence != observed.allan.confidence:
        confidence = check_probability("confidence", confidence)
        observed = replace(observed, allan=replace(observed.allan, confidence=confidence))
    return fit_observed(observed, options)


# --- model comparison and run-to-run consistency -----------------------------------------------------


@dataclass(frozen=True)
class NestedTest:
    """A fit with and without one term, compared under the fuller model's covariance across τ.

    ``chi_square_difference`` = χ²(reduced) − χ²(full) is χ² with ``degrees_of_freedom`` (the parameters
    the term adds) when the term is absent; ``p_value`` is its upper tail. A term that cannot lower the
    GLS objective (estimated at zero) gives a difference of 0 and p = 1.
    """

    term: str
    chi_square_difference: float
    degrees_of_freedom: int
    p_value: float
    full: FitResult
    reduced: FitResult


def nested_test(observed: ObservedAllan, options: FitOptions, term: str) -> NestedTest:
    """Is ``term`` needed? Fit ``options`` (which must include it) and the same without it (module text)."""
    if term not in options.components:
        raise ValueError(f"term={term!r}: must be one of the fitted components {options.components}")
    if len(options.components) < 2:
        raise ValueError(f"options.components={options.components!r}: nothing is left without {term!r}")
    full = fit_observed(observed, options)
    reduced_options = replace(options, components=tuple(c for c in options.components if c != term))
    reduced = fit_observed(observed, reduced_options, fixed_covariance=full.tau_covariance)
    if _used_mask(observed, reduced_options).sum() != full.used.sum():
        raise ValueError("the full and the reduced fit use different τ; give an explicit tau_range")
    difference = max(reduced.chi_square - full.chi_square, 0.0)
    degrees = len(full.parameters) - len(reduced.parameters)
    return NestedTest(term, difference, degrees, float(stats.chi2.sf(difference, degrees)), full, reduced)


@dataclass(frozen=True)
class ConsistencyTest:
    """Inverse-variance weighted mean of estimates from several runs and the χ² of the runs about it."""

    mean: float
    spread: float
    chi_square: float
    degrees_of_freedom: int
    p_value: float


def consistency_test(values: Any) -> ConsistencyTest | None:
    """Are the runs one population? ``values`` is a sequence of (estimate, standard error).

    χ² = Σ ((x_k − x̄_w)/s_k)² with x̄_w the inverse-variance weighted mean, on K − 1 degrees of freedom.
    None when there are fewer than 2 runs, an estimate is not finite, or an error is not finite and
    positive.
    """
    estimates = np.array([float(v) for v, _ in values])
    errors = np.array([float(e) for _, e in values])
    finite = np.all(np.isfinite(estimates)) and np.all(np.isfinite(errors))
    if len(estimates) < 2 or not finite or np.any(errors <= 0):
        return None
    weights = 1.0 / errors**2
    mean = float(np.sum(weights * estimates) / np.sum(weights))
    chi_square = float(np.sum(((estimates - mean) / errors) ** 2))
    degrees = len(estimates) - 1
    return ConsistencyTest(
        mean, float(np.std(estimates, ddof=1)), chi_square, degrees, float(stats.chi2.sf(chi_square, degrees))
    )


def fit_recording(
    recording: Any,
    model: Any = ("white", "rrw"),
    *,
    axes: Any = None,
    tau_min: float | None = None,
    tau_max: float | None = None,
    label: str = "fit: axes",
    **options: Any,
) -> dict[str, FitResult]:
    """:func:`fit_noise_model` on each gyro axis of a recording (all of them, or ``axes``), in order.

    ``tau_min`` / ``tau_max`` (s) bound the fitted τ; either alone leaves the other end at one sample or
    the whole record. ``options`` are the remaining keywords of :func:`fit_noise_model`.
    """
    for name, value in (("tau_min", tau_min), ("tau_max", tau_max)):
        if value is not None and not (math.isfinite(value) and value > 0):
            raise ValueError(f"{name}={value!r}: must be a positive number of seconds")
    tau_range = None
    if tau_min is not None or tau_max is not None:
        tau_range = (
            1.0 / recording.sample_rate if tau_min is None else tau_min,
            recording.duration if tau_max is None else tau_max,
        )
    names = list(recording.rates) if axes is None else list(axes)
    unknown = [name for name in names if name not in recording.rates]
    if unknown:
        raise ValueError(f"axes={unknown!r}: not in the recording's axes {sorted(recording.rates)}")
    check_recording_signals(recording, names)
    return {
        name: fit_noise_model(
            recording.rates[name], recording.sample_rate, model, tau_range=tau_range, **options
        )
        for name in progress(names, len(names), label)
    }
