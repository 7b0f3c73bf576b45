"""What ``carousel-theory fit`` prints and its ``--json`` record per gyro column, units named on each.

JSON convention (every document of the package): an object whose members carry a physical unit has a
member ``units`` mapping each such member's name to its unit (an ASCII name of
:data:`carousel_theory.units.UNIT_NAMES`); a member holding ``{value, standard_error}`` or an array has
one unit for all its numbers; a member not named in ``units`` is dimensionless.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from carousel_theory.cli._output_units import OutputUnits
from carousel_theory.fitting import ORDER_RANGE, FitResult
from carousel_theory.noise_parameters import NoiseParameter, Quantity, noise_parameters
from carousel_theory.units import display_unit

__all__ = [
    "FIT_NULL_REASONS",
    "allan_record",
    "ar_coefficients_text",
    "fit_as_json",
    "fit_lines",
    "order_interval_text",
]

#: Why a standard error is null in ``fit --json``: a term held at zero has none (see ``at_bound``).
FIT_NULL_REASONS = {
    **dict.fromkeys(
        (
            "white_variance",
            "rrw_variance",
            "flicker_variance",
            "flicker_d",
            "quantization",
            "quantization_squared",
            "ar_variance",
        ),
        "no standard error: the term is held at zero, the bound of its range (listed in at_bound)",
    ),
    "standard_error": "no standard error: the parameter comes from a term held at zero (see at_bound)",
}

#: Units of the per-sample model of :class:`carousel_theory.noise_model.NoiseModel` (always SI).
MODEL_UNITS = {
    "sample_rate": "Hz",
    "bias": "rad/s",
    "white_variance": "(rad/s)^2",
    "rrw_variance": "(rad/s)^2",
    "flicker_variance": "(rad/s)^2",
    "quantization": "rad",
    "ar_variance": "(rad/s)^2",
}
FIELD_UNITS = {
    "bias_deg_per_h": "deg/h",
    "angle_random_walk_deg_per_sqrt_h": "deg/sqrt(h)",
    "rate_random_walk_deg_per_h_per_sqrt_h": "deg/h/sqrt(h)",
    "bias_instability_deg_per_h": "deg/h",
}
PAPER_UNITS = {
    "white_variance_at_1s": "(rad/s)^2",
    "rrw_variance_per_s": "(rad/s)^2/s",
    "bias_instability": "rad/s",
}


def allan_record(result: Any, output: OutputUnits) -> dict[str, Any]:
    """The JSON record of one Allan variance: tau (s), avar and its interval (in ``output`` squared), adev
    and its interval (in ``output``; finite where avar leaves float64's range), edf, clusters, and the
    ``units`` map."""
    adev_low, adev_high = result.adev_interval
    deviations = {
        "adev": output.rates(result.adev).tolist(),
        "adev_low": output.rates(adev_low).tolist(),
        "adev_high": output.rates(adev_high).tolist(),
    }
    return {
        "tau": result.tau.tolist(),
        "avar": output.variances(result.avar).tolist(),
        "ci_low": output.variances(result.ci_low).tolist(),
        "ci_high": output.variances(result.ci_high).tolist(),
        **deviations,
        "edf": None if result.edf is None else result.edf.tolist(),
        "clusters": result.clusters.tolist(),
        "units": {
            "tau": "s",
            **dict.fromkeys(("avar", "ci_low", "ci_high"), output.variance),
            **dict.fromkeys(deviations, output.rate),
        },
    }


def _with_errors(parameters: dict[str, tuple[float, float]], unit_of: dict[str, str]) -> dict[str, Any]:
    """``{name: {"value", "standard_error"}, "units": {name: unit}}``: a null error has its reason beside."""
    body: dict[str, Any] = {
        key: {"value": value, "standard_error": error} for key, (value, error) in parameters.items()
    }
    return {**body, "units": {key: unit_of[key] for key in parameters}}


def _parameter_objects(parameters: tuple[NoiseParameter, ...]) -> dict[str, Any]:
    """``{"si": {...}, "conventional": {...}}``, each ``{name: {value, standard_error}, units}``; a second
    conventional unit (quantization in arcsec) is the name with ``_<unit>`` appended."""
    si: dict[str, Any] = {}
    conventional: dict[str, Any] = {}
    si_units: dict[str, str] = {}
    conventional_units: dict[str, str] = {}
    for parameter in parameters:
        si[parameter.name] = {"value": parameter.si.value, "standard_error": parameter.si.standard_error}
        si_units[parameter.name] = parameter.si.unit
        for index, quantity in enumerate(parameter.conventional):
            key = parameter.name if index == 0 else f"{parameter.name}_{quantity.unit}"
            conventional[key] = {"value": quantity.value, "standard_error": quantity.standard_error}
            conventional_units[key] = quantity.unit
    return {
        "si": {**si, "units": si_units},
        "conventional": {**conventional, "units": conventional_units},
    }


def fit_as_json(fit: FitResult, output: OutputUnits) -> dict[str, Any]:
    """The ``fit --json`` record of one column (the model and its errors always per-sample SI, read by
    ``design --noise``; the Allan variances in ``output`` squared)."""
    model = fit.model
    values = {key: getattr(model, key) for key in MODEL_UNITS}
    error_units = {**MODEL_UNITS, "quantization_squared": "rad^2"}
    present = {key: error_units[key] for key in fit.standard_errors if key in error_units}
    order = (
        {"flicker_d_interval": list(fit.interval("flicker_d"))} if "flicker_d" in fit.standard_errors else {}
    )
    return {
        "model": {
            **values,
            "flicker_d": model.flicker_d,
            "ar_coefficients": list(model.ar_coefficients),
            "units": MODEL_UNITS,
        },
        "standard_errors": {**dict(fit.standard_errors), "units": present},
        "ieee952": _parameter_objects(noise_parameters(fit)),
        "field_units": _with_errors(fit.field_units(), FIELD_UNITS),
        "paper_units": _with_errors(fit.paper_units(), PAPER_UNITS),
        "chi_square": fit.chi_square,
        "degrees_of_freedom": fit.degrees_of_freedom,
        "p_value": fit.p_value,
        "at_bound": list(fit.at_bound),
        "ar_coefficient_errors": list(fit.ar_coefficient_errors),
        **order,
        "method": fit.method,
        "allan": allan_record(fit.allan, output),
        "model_avar": output.variances(fit.model_avar).tolist(),
        "used": fit.used.tolist(),
        "units": {"model_avar": output.variance},
    }


def _paper_lines(fit: FitResult) -> list[str]:
    labels = {
        "white_variance_at_1s": "σ_WN² (τ = 1 s), TIM 2014 Table III",
        "rrw_variance_per_s": "σ_q², TIM 2014 Table III",
    }
    return [
        f"    {labels[key]:44s} {Quantity(float(value), float(error), PAPER_UNITS[key]).text()}"
        for key, (value, error) in fit.paper_units().items()
        if key in labels
    ]


def fit_lines(name: str, fit: FitResult, output: OutputUnits) -> list[str]:
    """The printed block of one column: the IEEE Std 952 parameters in conventional units beside SI, Table
    III's variances, the bias and the data's minimum Allan deviation in ``output``; every figure with its
    unit."""
    lines = [
        f"  {name}: model {'+'.join(fit.components)}; {fit.method}; χ² = {fit.chi_square:.3g} on "
        f"{fit.degrees_of_freedom} degrees of freedom",
        f"    {'IEEE Std 952 parameter':44s} {'conventional units':28s} SI",
    ]
    for parameter in noise_parameters(fit):
        conventional = "; ".join(quantity.text() for quantity in parameter.conventional)
        lines.append(f"    {parameter.description:44s} {conventional:28s} {parameter.si.text()}")
    lines += _paper_lines(fit)
    bias = Quantity(fit.model.bias, fit.standard_errors["bias"], "rad/s")
    rate = output.rates(1.0)
    lines.append(f"    {'bias (record mean)':44s} {bias.scaled(rate, output.rate).text()}")
    best = int(np.argmin(fit.allan.avar))
    minimum = output.rates(math.sqrt(fit.allan.avar[best]))
    lines.append(
        f"    {'minimum Allan deviation of the data':44s} {minimum:.4g} {display_unit(output.rate)} "
        f"at τ = {fit.allan.tau[best]:.4g} s"
    )
    if "flicker_d" in fit.standard_errors:
        order = f"{fit.model.flicker_d:.3g} ± {fit.standard_errors['flicker_d']:.2g}"
        lines.append(
            f"    {'1/f order d':44s} {order}; 95 % interval {order_interval_text(fit)} (χ² difference)"
        )
    lines += _ar_lines(fit)
    if fit.at_bound:
        lines.append(f"    held at zero: {', '.join(fit.at_bound)}")
    return lines


def order_interval_text(fit: FitResult) -> str:
    """The fitted 1/f order's 95 % interval as ``low … high`` (:func:`carousel_theory.fitting.order_interval`;
    an end at the range searched is marked), "" when d was not fitted."""
    if "flicker_d" not in fit.standard_errors:
        return ""
    low, high = fit.interval("flicker_d")
    ends = [f"{value:.3g}" + (" (edge)" if value in ORDER_RANGE else "") for value in (low, high)]
    return " … ".join(ends)


def ar_coefficients_text(fit: FitResult, digits: int) -> str:
    """The fitted AR coefficients as ``φ ± error`` (``φ (given)`` when they were given), ``digits``
    significant digits; "" without an AR term."""
    if "ar_variance" not in fit.standard_errors:
        return ""
    coefficients = fit.model.ar_coefficients
    errors = fit.ar_coefficient_errors or (math.nan,) * len(coefficients)
    return ", ".join(
        f"{c:.{digits}g} ± {e:.2g}" if math.isfinite(e) else f"{c:.{digits}g} (given)"
        for c, e in zip(coefficients, errors, strict=True)
    )


def _ar_lines(fit: FitResult) -> list[str]:
    """The AR (Gauss–Markov) term: its innovation variance and its coefficients with their standard errors
    (an AR(1)'s correlation time τ_c = −1/(f_s ln φ) with the error d τ_c/dφ · s_φ); none without AR."""
    coefficients = fit.model.ar_coefficients
    if "ar_variance" not in fit.standard_errors or not len(coefficients):
        return []
    variance = Quantity(fit.model.ar_variance, fit.standard_errors["ar_variance"], "(rad/s)^2")
    lines = [f"    {'AR innovation variance (per sample)':44s} {variance.text()}"]
    lines.append(f"    {f'AR({len(coefficients)}) coefficients φ':44s} {ar_coefficients_text(fit, 4)}")
    if len(coefficients) == 1 and 0 < coefficients[0] < 1 and fit.ar_coefficient_errors:
        rate, value = fit.model.sample_rate, float(coefficients[0])
        tau = -1.0 / (rate * math.log(value))
        tau_error = fit.ar_coefficient_errors[0] / (rate * value * math.log(value) ** 2)
        lines.append(f"    {'Gauss–Markov correlation time τ_c':44s} {Quantity(tau, tau_error, 's').text()}")
    return lines
