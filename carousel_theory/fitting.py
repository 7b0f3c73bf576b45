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
of the diagonal of (JᵀC⁻¹J)⁻¹ with J the Jacobian of the model curve; the order d, when fitted, is
profiled (the GLS objective is minimised over d) and enters J through ∂(Aθ)/∂d, so the variances'
errors include the uncertainty of d. A bound (a variance at zero) is reported rather than hidden.
On simulated records (tests/test_fitting.py) the estimates are unbiased and the mean squared standard
error matches the Monte Carlo variance; a variance identified by few long-τ points (rate random walk) is
skewed, so :meth:`FitResult.interval` gives χ² intervals with ν = 2θ̂²/SE² rather than θ̂ ± 1.96 SE.

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

__all__ = ["COMPONENTS", "FitResult", "NoiseModel", "fit_noise_model"]


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
    extra: dict[Any, Any] = field(default_factory=dict, compare=False, repr=False)

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

        key = (
            "minimum",
            length,
            self.white_variance,
            self.rrw_variance,
            self.flicker_variance,
            self.flicker_d,
            self.quantization,
            self.sample_rate,
        )
        if key not in self.extra:  # the 1/f curve costs O(n) per τ, and reports ask for it often
            sizes = octave_cluster_sizes(length)
            # Between octaves: the minimum of a smooth curve is found on a log grid of 8 points per octave.
            grid = np.unique(np.rint(np.geomspace(1, sizes[-1], 8 * len(sizes))).astype(np.int64))
            values = model_allan_variance(self, grid, length=length)
            best = int(np.argmin(values))
            self.extra[key] = (math.sqrt(float(values[best])), float(grid[best] / self.sample_rate))
        return self.extra[key]

    def bias_instability(self, length: int) -> float:
        """Bias instability B = min σ_A / 0.664 (rad/s) of the model's Allan curve (IEEE Std 952)."""
        return units.bias_instability_from_allan_minimum(self.minimum_allan_deviation(length)[0])


COMPONENTS = ("white", "rrw", "flicker", "quantization")
#: Parameter name of each component in :class:`NoiseModel`.
_PARAMETER = {
    "white": "white_variance",
    "rrw": "rrw_variance",
    "flicker": "flicker_variance",
    "quantization": "quantization_squared",
}


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

    def interval(self, name: str, level: float = 0.95) -> tuple[float, float]:
        """Confidence interval of a fitted parameter at ``level``.

        For a variance parameter θ̂ with standard error s the interval is χ²-based, like the Allan
        variance's own: with ν = 2θ̂²/s², ν θ̂/χ²_ν((1+level)/2) … ν θ̂/χ²_ν((1−level)/2); a variance is
        skewed and positive, which a symmetric ±z·s interval ignores. For the bias and d: θ̂ ± z·s.
        """
        from scipy import stats

        if name not in self.standard_errors:
            raise ValueError(f"name={name!r}: must be one of {sorted(self.standard_errors)}")
        level = float(check_positive_real("level", level))
        if not level < 1:
            raise ValueError(f"level={level!r}: must be in (0, 1)")
        value, error = self.value(name), self.standard_errors[name]
        if name in ("bias", "flicker_d") or value <= 0 or not error > 0:
            z = float(stats.norm.ppf((1 + level) / 2))
            return value - z * error, value + z * error
        degrees = 2.0 * (value / error) ** 2
        return (
            degrees * value / float(stats.chi2.ppf((1 + level) / 2, degrees)),
            degrees * value / float(stats.chi2.ppf((1 - level) / 2, degrees)),
        )

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

    def paper_units(self) -> dict[str, tuple[float, float]]:
        """(value, standard error) in TIM 2014 Table III's terms: σ_WN² (τ = 1 s) in (rad/s)², σ_q² in
        (rad/s)²/s, bias instability in rad/s."""
        rate = float(self.model.sample_rate)
        result: dict[str, tuple[float, float]] = {}
        if "white_variance" in self.standard_errors:
            result["white_variance_at_1s"] = (
                self.model.white_variance_at_one_second(),
                self.standard_errors["white_variance"] / rate,
            )
        if "rrw_variance" in self.standard_errors:
            result["rrw_variance_per_s"] = (
                self.model.rrw_variance_per_second(),
                self.standard_errors["rrw_variance"] * rate,
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


def _model_with(sample_rate: float, bias: float, values: dict[str, float], flicker_d: float) -> NoiseModel:
    return NoiseModel(
        sample_rate=sample_rate,
        bias=bias,
        white_variance=values.get("white", 0.0),
        rrw_variance=values.get("rrw", 0.0),
        flicker_variance=values.get("flicker", 0.0),
        flicker_d=flicker_d,
        quantization=math.sqrt(values.get("quantization", 0.0)),
    )


def _design(
    components: tuple[str, ...], sizes: np.ndarray, length: int, sample_rate: float, d: float, estimator: str
) -> np.ndarray:
    """Columns: the exact model Allan variance of each component at unit parameter."""
    from carousel_theory.allan import model_allan_variance

    columns = []
    for name in components:
        unit = _model_with(sample_rate, 0.0, {name: 1.0}, d)
        columns.append(model_allan_variance(unit, sizes, length=length, estimator=estimator))
    return np.column_stack(columns)


def _generalized_least_squares(
    design: np.ndarray, observed: np.ndarray, covariance: np.ndarray
) -> tuple[np.ndarray, float, np.ndarray]:
    """Non-negative GLS: (θ, objective, whitened design)."""
    from scipy.optimize import nnls

    cholesky = np.linalg.cholesky(covariance)
    whitened_design = np.linalg.solve(cholesky, design)
    whitened_observed = np.linalg.solve(cholesky, observed)
    # Columns differ by many orders of magnitude; scale them so that NNLS is well conditioned.
    scale = np.linalg.norm(whitened_design, axis=0)
    scale[scale == 0] = 1.0
    theta_scaled, residual_norm = nnls(whitened_design / scale, whitened_observed)
    return theta_scaled / scale, float(residual_norm**2), whitened_design


def _bias_variance(model: NoiseModel, length: int) -> float:
    """Var(ȳ) of the record mean under ``model`` (bias excluded): the record is one averaged bin of
    N = length samples, so white and RRW come from the registry (``white_average_var``,
    ``rrw_average_var`` at k = 1), 1/f from :func:`carousel_theory.propagation.flicker_averaged_bin_variance`,
    and quantization (a white angle error differenced into the rate) adds 2 f_s² Q²/n²."""
    from carousel_theory.formulas import formula
    from carousel_theory.propagation import flicker_averaged_bin_variance

    n = float(length)
    variance = model.white_variance * float(formula("white_average_var").numeric(N=length))
    variance += model.rrw_variance * float(formula("rrw_average_var").numeric(N=length, k=1))
    variance += 2.0 * (model.sample_rate * model.quantization) ** 2 / n**2
    if model.flicker_variance:
        variance += model.flicker_variance * flicker_averaged_bin_variance(model.flicker_d, length, 1)
    return variance


def fit_noise_model(
    y: Any,
    sample_rate: float,
    components: tuple[str, ...] = ("white", "rrw"),
    *,
    flicker_d: float | None = None,
    tau_range: tuple[float, float] | None = None,
    estimator: str = "overlapping",
    iterations: int = 4,
    confidence: float = 0.95,
) -> FitResult:
    """Identify a noise model from rate samples by GLS on the octave Allan variance (see the module text).

    Parameters
    ----------
    y : 1-D array
        Rate samples (rad/s).
    sample_rate : float
        Samples per second.
    components : tuple of {"white", "rrw", "flicker", "quantization"}
        The processes in the model. The bias (record mean) is always estimated.
    flicker_d : float, optional
        Fix the 1/f order d; without it d is fitted (profile GLS) when "flicker" is a component.
    tau_range : (float, float), optional
        Only τ in [low, high] seconds enter the fit (e.g. to skip τ where internal filtering shows).
    estimator : {"overlapping", "non-overlapping"}
        The Allan variance estimator fitted.
    iterations : int
        Re-evaluations of the model-based covariance C.
    confidence : float
        Level of the intervals of the returned Allan variance.
    """
    from scipy.optimize import minimize_scalar

    from carousel_theory._validation import check_finite_array, check_positive_integer
    from carousel_theory.allan import allan_covariance, allan_variance

    sample_rate = float(check_positive_real("sample_rate", sample_rate))
    if isinstance(components, str) or not all(isinstance(c, str) for c in components):
        raise TypeError(f"components={components!r}: must be a tuple of names from {COMPONENTS}")
    unknown = [c for c in components if c not in COMPONENTS]
    if unknown or not components or len(set(components)) != len(components):
        raise ValueError(f"components={components!r}: must be distinct names from {COMPONENTS}")
    components = tuple(c for c in COMPONENTS if c in components)
    if flicker_d is not None:
        flicker_d = float(check_fractional_order("flicker_d", flicker_d))
    iterations = check_positive_integer("iterations", iterations)
    samples = check_finite_array("y", y, min_length=3)
    length = len(samples)
    allan = allan_variance(samples, sample_rate, "octave", estimator=estimator, confidence=confidence)
    sizes = np.asarray(allan.samples_per_cluster)
    degrees = np.asarray(allan.edf)
    used: np.ndarray = np.ones(len(sizes), dtype=np.bool_)
    if tau_range is not None:
        if len(tau_range) != 2:
            raise ValueError(f"tau_range={tau_range!r}: must be (low, high) in seconds")
        low, high = (float(check_positive_real("tau_range", value)) for value in tau_range)
        if not low <= high:
            raise ValueError(f"tau_range={tau_range!r}: low must not exceed high")
        used = (allan.tau >= low * (1 - 1e-12)) & (allan.tau <= high * (1 + 1e-12))
    fit_d = "flicker" in components and flicker_d is None
    parameter_count = len(components) + int(fit_d)
    if used.sum() <= parameter_count:
        raise ValueError(
            f"y: {int(used.sum())} octave τ in range, too few to fit {parameter_count} parameters "
            f"{components + (('flicker_d',) if fit_d else ())}; the recording ({length} samples) is too "
            "short or tau_range too narrow"
        )
    used_sizes, observed = sizes[used], allan.avar[used]
    d = 0.5 if flicker_d is None else flicker_d

    # Start: weights from the white-noise degrees of freedom of the observed values (diagonal).
    covariance = np.diag(2.0 * observed**2 / degrees[used])
    theta = np.zeros(len(components))
    for _ in range(iterations):
        if fit_d:

            def objective(order: float, covariance: np.ndarray = covariance) -> float:
                design = _design(components, used_sizes, length, sample_rate, order, estimator)
                return _generalized_least_squares(design, observed, covariance)[1]

            d = float(
                minimize_scalar(objective, bounds=(0.02, 0.98), method="bounded", options={"xatol": 1e-4}).x
            )
        design = _design(components, used_sizes, length, sample_rate, d, estimator)
        theta, chi_square, whitened = _generalized_least_squares(design, observed, covariance)
        model = _model_with(sample_rate, 0.0, dict(zip(components, theta, strict=True)), d)
        if not any(theta > 0):
            break
        covariance = allan_covariance(model, used_sizes, length, estimator=estimator)
    design = _design(components, used_sizes, length, sample_rate, d, estimator)
    theta, chi_square, whitened = _generalized_least_squares(design, observed, covariance)
    names = tuple(_PARAMETER[c] for c in components)
    jacobian = whitened
    if fit_d:
        # d enters non-linearly: its column of the Jacobian is ∂(Aθ)/∂d, so that the standard errors of
        # the variances include the uncertainty of d (they are strongly correlated with it).
        step = 1e-4
        upper = _design(components, used_sizes, length, sample_rate, min(d + step, 0.999), estimator)
        lower = _design(components, used_sizes, length, sample_rate, max(d - step, 0.001), estimator)
        derivative = (upper - lower) @ theta / (min(d + step, 0.999) - max(d - step, 0.001))
        cholesky = np.linalg.cholesky(covariance)
        jacobian = np.column_stack((whitened, np.linalg.solve(cholesky, derivative)))
        names = (*names, "flicker_d")
    # Columns differ by many orders of magnitude (variances of 1e-12 next to d of order 1): invert the
    # information matrix of the column-scaled problem, then scale back.
    column_scale = np.linalg.norm(jacobian, axis=0)
    column_scale[column_scale == 0] = 1.0
    scaled = jacobian / column_scale
    parameter_covariance = np.linalg.pinv(scaled.T @ scaled) / np.outer(column_scale, column_scale)
    errors = dict(zip(names, np.sqrt(np.diag(parameter_covariance)), strict=True))
    at_bound = tuple(name for name, value in zip(names, theta, strict=False) if value <= 0)
    mean = float(samples.mean())
    model = _model_with(sample_rate, mean, dict(zip(components, theta, strict=True)), d)
    errors["bias"] = math.sqrt(_bias_variance(model, length))
    from carousel_theory.allan import model_allan_variance

    refreshed = allan_variance(
        samples, sample_rate, "octave", estimator=estimator, noise=model, confidence=confidence
    )
    method = (
        f"generalized least squares on the {estimator} Allan variance at {int(used.sum())} octave τ "
        f"({allan.tau[used][0]:.4g} s … {allan.tau[used][-1]:.4g} s), model-based covariance across τ, "
        f"{iterations} iterations" + (", 1/f order d profiled" if fit_d else "")
    )
    return FitResult(
        model=model,
        standard_errors=errors,
        covariance=parameter_covariance,
        parameters=names,
        method=method,
        allan=refreshed,
        model_avar=model_allan_variance(model, sizes, length=length, estimator=estimator),
        used=used,
        chi_square=chi_square,
        degrees_of_freedom=int(used.sum()) - parameter_count,
        at_bound=at_bound,
        length=length,
    )
