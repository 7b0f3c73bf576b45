"""``--output-units``: the rate unit of every printed figure and JSON array of allan, fit, loop and predict.

Rates (Allan deviations, biases, forecasts) are shown in the chosen unit and their variances in its
square; the IEEE Std 952 parameters are always shown in their conventional units (°/√h, °/h, °/h/√h,
µrad and arcsec) beside SI, whatever the option (see :mod:`carousel_theory.cli._noise_parameters`).
"""

from __future__ import annotations

import argparse
from dataclasses import dataclass
from typing import Any

import numpy as np

from carousel_theory.units import RATE_UNITS, display_unit, from_rad_per_s, square_unit

__all__ = ["OutputUnits", "add_output_units_option", "output_units"]


def add_output_units_option(parser: argparse.ArgumentParser) -> None:
    """``--output-units rad/s|deg/s|deg/h`` (default rad/s: the output of earlier versions)."""
    parser.add_argument(
        "--output-units",
        default="rad/s",
        choices=tuple(RATE_UNITS),
        help="unit of the printed and JSON rates (default rad/s); the IEEE Std 952 parameters are "
        "always printed in °/√h, °/h, °/h/√h beside SI",
    )


@dataclass(frozen=True)
class OutputUnits:
    """One rate unit of :data:`carousel_theory.units.RATE_UNITS`, with conversions from rad/s."""

    rate: str = "rad/s"

    @property
    def variance(self) -> str:
        """The ASCII name of the variance unit, e.g. ``(deg/h)^2``."""
        return square_unit(self.rate)

    @property
    def rate_label(self) -> str:
        """The printed rate unit, e.g. ``°/h``."""
        return display_unit(self.rate)

    @property
    def variance_label(self) -> str:
        """The printed variance unit, e.g. ``(°/h)²``."""
        return display_unit(self.variance)

    def rates(self, values: Any) -> Any:
        """Rates in rad/s → this unit (a float for a scalar, an array otherwise)."""
        converted = from_rad_per_s(values, self.rate)
        return float(converted) if np.ndim(converted) == 0 else converted

    def variances(self, values: Any) -> Any:
        """Variances in (rad/s)² → this unit squared."""
        factor = float(from_rad_per_s(1.0, self.rate)) ** 2
        converted = np.asarray(values, dtype=np.float64) * factor
        return float(converted) if np.ndim(converted) == 0 else converted


def output_units(args: argparse.Namespace) -> OutputUnits:
    """The parsed ``--output-units`` of ``args`` (rad/s when the command has no such option)."""
    return OutputUnits(getattr(args, "output_units", "rad/s"))
