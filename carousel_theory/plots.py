"""Allan deviation plots of recordings and of fitted noise models (matplotlib, Agg backend).

matplotlib is an optional dependency (the ``plots`` extra): it is imported inside the functions, so this
module imports without it. Every plot function takes ``output_units`` (one of
:data:`carousel_theory.units.RATE_UNITS`: "rad/s", "deg/s", "deg/h"); rates are stored in rad/s and
converted with :func:`carousel_theory.units.from_rad_per_s` only for drawing.

What a reader needs from an Allan deviation plot, and how it is drawn here:

- several axes on one plot are told apart by marker as well as colour, and each axis's points are
  shifted by a small constant factor in τ (:func:`tau_offsets`, 8 % between neighbours) so that error
  bars at the same τ do not hide each other (the x label says so);
- the title names the recording by its file stem (:func:`short_title`), not by its full path;
- the legend sits outside the axes, where it cannot cover data;
- a fitted model is drawn with the τ range that entered the fit (shaded), each fitted component's own
  curve labelled with its log-log slope (IEEE Std 952 Table: white −1/2, rate random walk +1/2,
  quantization −1, 1/f of order d: d − 1/2, flat at d = 1/2), and their sum, the total model.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from carousel_theory.allan import AllanResult
from carousel_theory.fitting import FitResult
from carousel_theory.output_files import atomic_output
from carousel_theory.units import RATE_UNITS, from_rad_per_s

__all__ = [
    "MARKERS",
    "UNIT_LABELS",
    "ComponentCurve",
    "allan_figure",
    "component_curves",
    "fit_figure",
    "plot_allan",
    "plot_fit",
    "pyplot",
    "save_figure",
    "short_title",
    "tau_offsets",
    "unit_label",
]

#: How each accepted output unit is written on an axis.
UNIT_LABELS = {"rad/s": "rad/s", "deg/s": "°/s", "deg/h": "°/h"}
#: Marker of the k-th axis of a recording (with colour C<k>).
MARKERS = ("o", "s", "^", "D", "v", "P", "X", "*")
#: Ratio between neighbouring axes' τ positions (8 % apart; octave τ are 100 % apart).
TAU_OFFSET_STEP = 1.08
#: Where a legend outside the axes is anchored: right of the plotting area, at its top.
OUTSIDE_RIGHT = {"loc": "upper left", "bbox_to_anchor": (1.02, 1.0), "borderaxespad": 0.0}


def unit_label(output_units: str) -> str:
    """The axis label of ``output_units`` ("rad/s", "°/s" or "°/h"); refuses any other unit."""
    if output_units not in RATE_UNITS:
        raise ValueError(f"output_units={output_units!r}: must be one of {sorted(RATE_UNITS)}")
    return UNIT_LABELS[output_units]


def short_title(source: Any, what: str) -> str:
    """``"<file stem>: <what>"``, e.g. ``"adis16405_run1: Allan deviation"`` (a title, not a path)."""
    return f"{Path(str(source)).stem}: {what}"


def tau_offsets(count: int) -> np.ndarray:
    """Multiplicative τ shifts for ``count`` series, centred on 1 and :data:`TAU_OFFSET_STEP` apart."""
    return np.asarray(TAU_OFFSET_STEP ** (np.arange(count) - (count - 1) / 2.0), dtype=np.float64)


def pyplot() -> Any:
    """``matplotlib.pyplot`` on the non-interactive Agg backend (files only, no display needed)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def save_figure(figure: Any, path: Any, dpi: int = 120) -> None:
    """Write ``figure`` to ``path`` atomically (format from the suffix, PNG by default) and close it."""
    try:
        with atomic_output(path) as temporary:
            figure.savefig(temporary, dpi=dpi, format=Path(path).suffix.lstrip(".") or "png")
    finally:
        pyplot().close(figure)


def _deviation_bars(result: AllanResult, output_units: str) -> tuple[np.ndarray, np.ndarray]:
    """Allan deviation in ``output_units`` and its (below, above) error bar lengths (from the deviations,
    which stay finite where the variance leaves float64's range)."""
    low, high = result.adev_interval
    deviation = from_rad_per_s(result.adev, output_units)
    below = deviation - from_rad_per_s(low, output_units)
    above = from_rad_per_s(high, output_units) - deviation
    return deviation, np.vstack([below, above])


def _draw_deviation(
    plot: Any, result: AllanResult, output_units: str, index: int, offset: float, label: str
) -> Any:
    """Error bars of one Allan deviation series: colour and marker of series ``index``, τ × ``offset``."""
    deviation, bars = _deviation_bars(result, output_units)
    return plot.errorbar(
        result.tau * offset,
        deviation,
        yerr=bars,
        fmt=MARKERS[index % len(MARKERS)],
        ms=4.0,
        capsize=2.0,
        elinewidth=0.9,
        color=f"C{index}",
        label=label,
    )


def _log_axes(plot: Any, output_units: str) -> None:
    plot.set_xscale("log")
    plot.set_yscale("log")
    plot.set_xlabel("averaging time τ (s)")
    plot.set_ylabel(f"Allan deviation σ_A(τ) ({unit_label(output_units)})")
    plot.grid(True, which="major", alpha=0.35)
    plot.grid(True, which="minor", alpha=0.12)


def allan_figure(results: Mapping[str, AllanResult], title: str, *, output_units: str = "rad/s") -> Any:
    """The figure of :func:`plot_allan` (a matplotlib Figure, not yet written).

    Parameters
    ----------
    results : mapping of column name to AllanResult
        The estimates (TIM 2014 eq. (20) and its overlapping form), in (rad/s)².
    title : str
        The plot title, e.g. from :func:`short_title`.
    output_units : {"rad/s", "deg/s", "deg/h"}
        The unit of the deviation axis.
    """
    unit_label(output_units)
    plt = pyplot()
    figure, plot = plt.subplots(figsize=(8.0, 4.8), layout="constrained")
    for index, ((name, result), offset) in enumerate(
        zip(results.items(), tau_offsets(len(results)), strict=True)
    ):
        label = f"{name} ({result.estimator}, {100 * result.confidence:g} % interval)"
        _draw_deviation(plot, result, output_units, index, float(offset), label)
    _log_axes(plot, output_units)
    if len(results) > 1:
        plot.set_xlabel(
            f"averaging time τ (s); columns shifted by ×{TAU_OFFSET_STEP:g} in τ to separate their bars"
        )
    plot.set_title(title, fontsize=10)
    plot.legend(fontsize=8, **OUTSIDE_RIGHT)
    return figure


def plot_allan(
    path: Any, results: Mapping[str, AllanResult], title: str, *, output_units: str = "rad/s"
) -> None:
    """Write the log-log Allan deviation of each column with its confidence interval, one marker and a
    small τ offset per column, the legend outside (:func:`allan_figure`); ``path`` is written atomically
    (PNG unless its suffix names another matplotlib format). A constant column (every deviation 0) has
    nothing to show on log axes and is refused."""
    if not any(np.any(result.adev > 0) for result in results.values()):
        raise ValueError(
            f"--plot {path}: every Allan deviation is 0 (constant columns); a log axis shows none"
        )
    save_figure(allan_figure(results, title, output_units=output_units), path)


@dataclass(frozen=True)
class ComponentCurve:
    """One fitted term's Allan variance at the fit's τ (its driving variance times the unit-term curve).

    ``slope`` is the term's log-log slope of the Allan deviation (None where it has none, as for an
    autoregressive term, which turns from flat to −1/2 at its correlation time).
    """

    term: str
    label: str
    slope: float | None
    tau: np.ndarray
    avar: np.ndarray


#: Colour of each term's curve, the same in every panel.
TERM_COLOURS = {"white": "C1", "rrw": "C2", "flicker": "C3", "quantization": "C4", "ar": "C5"}
#: Name and Allan deviation slope of each term (IEEE Std 952-1997 Annex C; 1/f: d − 1/2).
_TERM_NAMES = {
    "white": ("white noise (angle random walk)", -0.5),
    "rrw": ("rate random walk", 0.5),
    "quantization": ("quantization", -1.0),
    "flicker": ("1/f noise", None),
    "ar": ("autoregressive (Gauss–Markov)", None),
}


def _slope_text(slope: float | None) -> str:
    if slope is None:
        return "slope varies"
    fractions = {-1.0: "−1", -0.5: "−1/2", 0.5: "+1/2", 0.0: "0"}
    return "slope " + fractions.get(round(slope, 6), f"{slope:+.2f}".replace("-", "−"))


def component_curves(fit: FitResult) -> list[ComponentCurve]:
    """The Allan variance of each term of ``fit.model`` with a positive driving variance, at the fit's τ.

    Each is ``value × model.unit(term).allan_variance(m)``; their sum is ``fit.model_avar``.
    """
    model = fit.model
    sizes = np.asarray(fit.allan.samples_per_cluster)
    curves = []
    for term, value in model.terms().items():
        name, slope = _TERM_NAMES[term]
        if term == "flicker":
            slope = float(model.flicker_d) - 0.5  # reached at long τ
            name = f"{name}, d = {model.flicker_d:.2f}, long-τ"
        label = f"{name}, {_slope_text(slope)}"
        avar = value * model.unit(term).allan_variance(sizes)
        curves.append(ComponentCurve(term, label, slope, np.asarray(fit.allan.tau), np.asarray(avar)))
    return curves


def _draw_fit_axis(plot: Any, name: str, fit: FitResult, output_units: str) -> None:
    """One axis of :func:`plot_fit`: fit range, data (used filled, unused hollow), components, total."""
    tau_used = fit.allan.tau[fit.used]
    plot.axvspan(tau_used[0], tau_used[-1], color="0.9", zorder=0, label="τ range of the fit")
    deviation, bars = _deviation_bars(fit.allan, output_units)
    for mask, face, text in ((fit.used, "C0", "fitted"), (~fit.used, "white", "not fitted")):
        if np.any(mask):
            plot.errorbar(
                fit.allan.tau[mask],
                deviation[mask],
                yerr=bars[:, mask],
                fmt="o",
                ms=4.0,
                capsize=2.0,
                color="C0",
                markerfacecolor=face,
                label=f"{name} data, {text} ({100 * fit.allan.confidence:g} % interval)",
            )
    for curve in component_curves(fit):
        plot.plot(
            curve.tau,
            from_rad_per_s(np.sqrt(curve.avar), output_units),
            "--",
            color=TERM_COLOURS[curve.term],
            lw=1.2,
            label=curve.label,
        )
    plot.plot(
        fit.allan.tau,
        from_rad_per_s(np.sqrt(fit.model_avar), output_units),
        "k-",
        lw=1.5,
        label="total model",
    )
    _log_axes(plot, output_units)
    low, high = float(np.min(deviation[deviation > 0])), float(np.max(deviation))
    plot.set_ylim(low / 3.0, high * 3.0)  # component lines far below the data do not squash it
    rejected = " — rejected (p < 0.01)" if fit.p_value < 0.01 else ""
    plot.set_title(f"{name}: χ² = {fit.chi_square:.3g} on {fit.degrees_of_freedom} dof{rejected}", fontsize=9)
    plot.legend(fontsize=7, **OUTSIDE_RIGHT)


def fit_figure(fits: Mapping[str, FitResult], title: str, *, output_units: str = "rad/s") -> Any:
    """One panel per column: the Allan deviation, the τ range of the fit (shaded), each fitted term's
    curve with its slope, and the total model (a matplotlib Figure, not yet written).

    Parameters
    ----------
    fits : mapping of column name to FitResult
        From :func:`carousel_theory.fitting.fit_recording`.
    title : str
        The figure title, e.g. from :func:`short_title`.
    output_units : {"rad/s", "deg/s", "deg/h"}
        The unit of the deviation axes.
    """
    unit_label(output_units)
    if not fits:
        raise ValueError("fits={}: must hold at least one fitted column")
    plt = pyplot()
    rows = len(fits)
    figure, grid = plt.subplots(rows, 1, figsize=(9.5, 3.3 * rows), squeeze=False, layout="constrained")
    for plot, (name, fit) in zip(grid[:, 0], fits.items(), strict=True):
        _draw_fit_axis(plot, name, fit, output_units)
    figure.suptitle(title, fontsize=10)
    return figure


def plot_fit(path: Any, fits: Mapping[str, FitResult], title: str, *, output_units: str = "rad/s") -> None:
    """Write :func:`fit_figure` to ``path`` atomically."""
    save_figure(fit_figure(fits, title, output_units=output_units), path)
