"""The IEEE Std 952 parameters of a fitted noise model, in SI and in their conventional units.

Each parameter is a :class:`NoiseParameter`: its SI value (rad, s) and the same value in the units a
datasheet uses — angle random walk °/√h, bias instability °/h, rate random walk °/h/√h, quantization µrad
and arcsec — each with its standard error. The conversions are those of :mod:`carousel_theory.units`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from carousel_theory import units
from carousel_theory.fitting import FitResult

__all__ = ["NoiseParameter", "Quantity", "noise_parameters"]


@dataclass(frozen=True)
class Quantity:
    """A value, its standard error (NaN when there is none) and its unit (a name of
    :data:`carousel_theory.units.UNIT_NAMES`)."""

    value: float
    standard_error: float
    unit: str

    def scaled(self, factor: float, unit: str) -> Quantity:
        """The same quantity in ``unit``, one of which is ``factor`` of this quantity's unit."""
        return Quantity(self.value * factor, self.standard_error * factor, unit)

    def text(self) -> str:
        """``value ± error unit`` (``± —`` when there is no standard error; a zero without one is a term
        held at zero, and says so), in the printed unit."""
        if self.value == 0 and not math.isfinite(self.standard_error):
            return f"0 {units.display_unit(self.unit)} (held at zero: no standard error)"
        error = f"{self.standard_error:.2g}" if math.isfinite(self.standard_error) else "—"
        return f"{self.value:.4g} ± {error} {units.display_unit(self.unit)}"


@dataclass(frozen=True)
class NoiseParameter:
    """One IEEE Std 952 parameter: ``name`` (the JSON key), ``description``, its SI quantity and the same
    in the conventional units (one or more)."""

    name: str
    description: str
    si: Quantity
    conventional: tuple[Quantity, ...]


def _sqrt_error(value: float, variance_error: float) -> float:
    """Standard error of √v by the delta method: SE(v) / (2√v) (NaN at v = 0: no error there)."""
    return variance_error / (2.0 * value) if value > 0 else math.nan


#: (field key of FitResult.field_units, name, description, conventional unit, SI unit, 1 conventional in SI).
_DENSITIES = (
    (
        "angle_random_walk_deg_per_sqrt_h",
        "angle_random_walk",
        "angle random walk N",
        "deg/sqrt(h)",
        "rad/sqrt(s)",
        units.from_deg_per_sqrt_hour(1.0),
    ),
    (
        "rate_random_walk_deg_per_h_per_sqrt_h",
        "rate_random_walk",
        "rate random walk K",
        "deg/h/sqrt(h)",
        "rad/s/sqrt(s)",
        units.from_deg_per_hour_per_sqrt_hour(1.0),
    ),
)


def _white_and_walk(fit: FitResult) -> list[NoiseParameter]:
    field = fit.field_units()
    found = []
    for key, name, description, unit, si_unit, to_si in _DENSITIES:
        if key in field:
            value, error = field[key]
            conventional = Quantity(float(value), float(error), unit)
            found.append(
                NoiseParameter(name, description, conventional.scaled(to_si, si_unit), (conventional,))
            )
    return found


def _instabilities(fit: FitResult) -> list[NoiseParameter]:
    value, error = fit.paper_units()["bias_instability"]
    si = Quantity(float(value), float(error), "rad/s")
    per_hour = units.rad_per_s_to_deg_per_h(1.0)
    found = [
        NoiseParameter(
            "bias_instability",
            "bias instability (model's min σ_A / 0.664)",
            si,
            (si.scaled(per_hour, "deg/h"),),
        )
    ]
    model = fit.model
    if "flicker_variance" in fit.standard_errors and model.flicker_d == 0.5:
        level = units.bias_instability_from_flicker_variance(model.flicker_variance)
        flicker = Quantity(level, _sqrt_error(level, fit.standard_errors["flicker_variance"]), "rad/s")
        found.append(
            NoiseParameter(
                "flicker_bias_instability",
                "bias instability B of the 1/f term (d = 1/2)",
                flicker,
                (flicker.scaled(per_hour, "deg/h"),),
            )
        )
    return found


def noise_parameters(fit: FitResult) -> tuple[NoiseParameter, ...]:
    """The IEEE Std 952 parameters of ``fit``: angle random walk and rate random walk (when fitted), the
    bias instability (the model's minimum Allan deviation / √(2 ln 2/π)), the 1/f term's own B (when a
    1/f term of order d = 1/2 is fitted: the inverse of the datasheet conversion of
    :func:`carousel_theory.units.flicker_variance_from_bias_instability`) and the quantization (when
    fitted), each in SI and in conventional units, with standard errors."""
    found = _white_and_walk(fit) + _instabilities(fit)
    if "quantization_squared" in fit.standard_errors:  # the fit's parameter is Q²
        level = float(fit.model.quantization)
        si = Quantity(level, _sqrt_error(level, float(fit.standard_errors["quantization_squared"])), "rad")
        found.append(
            NoiseParameter(
                "quantization",
                "angle quantization Q",
                si,
                (
                    si.scaled(units.to_microradians(1.0), "urad"),
                    si.scaled(units.to_arcseconds(1.0), "arcsec"),
                ),
            )
        )
    return tuple(found)
