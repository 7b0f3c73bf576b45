"""The loop's report: a Markdown summary and the plots (Allan deviation, averaged and carouselled bins)."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from scipy import stats

from carousel_theory.closed_loop.detection import json_value
from carousel_theory.closed_loop.evaluation import BAND_EXPECTED_EXCEEDANCE, BAND_SIGMA, BinSeries, Evaluation
from carousel_theory.closed_loop.result import LoopResult, Step
from carousel_theory.output_files import write_text_atomic
from carousel_theory.plots import pyplot, save_figure, short_title, unit_label
from carousel_theory.units import from_rad_per_s

__all__ = ["allan_report_figure", "bins_report_figure", "render_summary", "write_report"]


def _number(value: Any) -> str:
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        return f"{float(value):.4g}"
    return str(value)


def _header(result: LoopResult) -> list[str]:
    lines = [
        f"# Closed loop on `{result.source}`",
        "",
        f"- axes: {', '.join(result.axes)}; samples per revolution N = {result.samples_per_revolution}",
        f"- effects (in the order added): **{', '.join(result.effects)}**",
        f"- headline error `{result.metric}`: {result.error_before:.4g} before, "
        f"{result.error_after:.4g} after "
        "(root mean square of the z-values of every prediction; about 1 when the model is right)",
        f"- family-wise false-alarm rate of the run α = {result.alpha:g} (split over the iterations, the "
        "detectors and the final misfit test)",
        "",
    ]
    if result.observations:
        lines += ["## Observations", ""] + [f"- {note}" for note in result.observations] + [""]
    return lines


def _axis_rows(result: LoopResult, axis: str) -> list[str]:
    before, after = result.metrics_before, result.metrics_after
    rows = [
        f"| Allan variance {axis}: {key} | {before['allan'][axis][key]:.4g} | "
        f"{after['allan'][axis][key]:.4g} |"
        for key in ("rms_z", "max_abs_z", "fraction_outside_95")
    ]
    rows.append(
        f"| averaged bins {axis}: exceedance of ±2σ (expect {BAND_EXPECTED_EXCEEDANCE:.4f}) | "
        f"{before['averaged_bins'][axis]['exceedance_2sigma']:.4f} | "
        f"{after['averaged_bins'][axis]['exceedance_2sigma']:.4f} |"
    )
    key = "excess_kurtosis_of_differences"
    rows.append(
        f"| tails {axis}: excess kurtosis of differences | {before['tails'][axis][key]:.4g} | "
        f"{after['tails'][axis][key]:.4g} |"
    )
    return rows


def _metrics_table(result: LoopResult) -> list[str]:
    lines = [
        "## Error before and after, in the same metrics",
        "",
        "| metric | before | after |",
        "|---|---|---|",
    ]
    lines.append(f"| {result.metric} | {result.error_before:.4g} | {result.error_after:.4g} |")
    for axis in result.axes:
        lines += _axis_rows(result, axis)
    before, after = result.metrics_before["carouselled_bins"], result.metrics_after["carouselled_bins"]
    if before and after:
        lines.append(
            f"| carouselled bins ({before['mode']}): exceedance of ±2σ | {before['exceedance_2sigma']:.4f} | "
            f"{after['exceedance_2sigma']:.4f} |"
        )
        lines.append(
            f"| carouselled bins: mean squared z (expect 1) | {before['mean_square_z']:.4g} | "
            f"{after['mean_square_z']:.4g} |"
        )
    tests_before, tests_after = (
        result.metrics_before["residual_tests"],
        result.metrics_after["residual_tests"],
    )
    for name in sorted(set(tests_before) | set(tests_after)):
        b, a = tests_before.get(name, {}).get("z"), tests_after.get(name, {}).get("z")
        lines.append(
            f"| residual test {name}: z | {'—' if b is None else f'{b:.3g}'} | "
            f"{'—' if a is None else f'{a:.3g}'} |"
        )
    return [*lines, ""]


def _model_table(result: LoopResult) -> list[str]:
    lines = ["## Fitted noise model (per axis)", ""]
    lines += ["| axis | model | bias (rad/s) | long-run white σ² | RRW σ_q² | 1/f σ_f² | AR coefficients |"]
    lines += ["|---|---|---|---|---|---|---|"]
    for label, model in (("before", result.model_before), ("after", result.model_after)):
        for axis in result.axes:
            m = model[axis]
            ar = ", ".join(f"{a:.3g}" for a in m["ar_coefficients"]) or "—"
            lines.append(
                f"| {axis} | {label} | {m['bias_rad_s']:.5g} | {m['long_run_white_variance_rad2_s2']:.4g} | "
                f"{m['rrw_variance_rad2_s2']:.4g} | {m['flicker_variance_rad2_s2']:.4g} | {ar} |"
            )
    return [*lines, ""]


def _step_lines(step: Step) -> list[str]:
    lines = [
        f"**Iteration {step.iteration}** (error {step.error:.4g}; each test at "
        f"α = {step.detector_alpha:.3g}): "
        f"{step.decision}",
        "",
    ]
    significant = [d for d in step.detections if d.significant]
    if significant:
        lines += ["| significant test | statistic | threshold | log10 p |", "|---|---|---|---|"]
        lines += [
            f"| {d.effect} ({d.statistic_name}) | {_number(d.statistic)} | {_number(d.threshold)} | "
            f"{_number(d.log10_p)} |"
            for d in significant
        ]
        lines.append("")
    for trial in step.trials:
        lines.append(
            f"- tried **{trial.detection.effect}**: error {trial.error_before:.4g} → "
            f"{trial.error_after:.4g}; "
            f"its evidence afterwards log10 p = {_number(trial.verification.log10_p)}; {trial.decision}"
        )
    lines += [f"- note: {d.note}" for d in step.detections if d.note]
    return [*lines, ""]


def render_summary(result: LoopResult, plots: Sequence[str] = ()) -> str:
    """The markdown summary of one run of the loop (deterministic for a given result)."""
    lines = _header(result) + _metrics_table(result) + _model_table(result) + ["## Steps", ""]
    for step in result.steps:
        lines += _step_lines(step)
    if result.fitted_effects:
        lines += ["## Fitted effects", ""]
        lines += [f"- **{f['effect']}**: `{json_value(f['parameters'])}`" for f in result.fitted_effects]
        lines.append("")
    if plots:
        lines += ["## Plots", ""] + [f"![{name}]({name})" for name in plots] + [""]
    return "\n".join(lines)


def _plot_allan(
    plot: Any, axis: str, before: Evaluation, after: Evaluation, output_units: str = "rad/s"
) -> None:
    """One axis's panel: the Allan deviation as recorded and after removal, its 95 % band, the models."""

    def deviation(avar: Any) -> np.ndarray:
        return from_rad_per_s(np.sqrt(avar), output_units)

    fit = after.view.fits[axis]
    low = fit.observed * fit.edf / stats.chi2.ppf(0.975, fit.edf)
    high = fit.observed * fit.edf / stats.chi2.ppf(0.025, fit.edf)
    plot.fill_between(fit.tau, deviation(low), deviation(high), color="0.85", label="95 % interval (after)")
    recorded = before.view.fits[axis]
    plot.loglog(recorded.tau, deviation(recorded.observed), "x", color="0.45", label="measured (as recorded)")
    plot.loglog(fit.tau, deviation(fit.observed), "k.", ms=6, label="measured (effects removed)")
    plot.loglog(fit.tau, deviation(fit.model), "-", color="C0", lw=1.6, label="model after")
    plot.loglog(recorded.tau, deviation(recorded.model), "--", color="C3", lw=1.2, label="model before")
    plot.set_xlabel("averaging time τ (s)")
    plot.set_ylabel(f"Allan deviation ({unit_label(output_units)})")
    plot.set_title(axis, fontsize=10)
    plot.grid(True, which="major", alpha=0.35)


def _plot_bins(
    plot: Any, before: BinSeries, after: BinSeries, title: str, output_units: str = "rad/s"
) -> None:
    """One panel of TIM 2014 Fig. 7: the bins with the effects removed (solid grey, as in the figure) over
    the bins as recorded (orange, seen where an effect was removed), and the ±2σ band predicted by the
    model after (dashed black, as in the figure) and before (dotted red)."""
    plot.plot(
        before.time, from_rad_per_s(before.values, output_units), color="C1", lw=0.8, label="as recorded"
    )
    plot.plot(
        after.time, from_rad_per_s(after.values, output_units), color="0.35", lw=0.6, label="effects removed"
    )
    for bins, style, colour, name in (
        (before, ":", "C3", "±2σ, model before"),
        (after, "--", "k", "±2σ, model after"),
    ):
        band = from_rad_per_s(BAND_SIGMA * np.sqrt(bins.variance), output_units)
        plot.plot(bins.time, band, style, color=colour, lw=1.0, label=name)
        plot.plot(bins.time, -band, style, color=colour, lw=1.0)
    plot.set_ylabel(f"rate ({unit_label(output_units)})")
    plot.set_title(title, fontsize=9, loc="left")
    plot.grid(True, alpha=0.3)


def allan_report_figure(result: LoopResult, output_units: str = "rad/s") -> Any:
    """The Allan deviation of every axis before and after the loop, one panel per axis, one legend below."""
    before, after = result.evaluation_before, result.evaluation_after
    assert before is not None and after is not None
    figure, grid = pyplot().subplots(
        1, len(result.axes), figsize=(5.2 * len(result.axes), 4.6), squeeze=False, layout="constrained"
    )
    for plot, axis in zip(grid[0], result.axes, strict=True):
        _plot_allan(plot, axis, before, after, output_units)
    figure.suptitle(short_title(result.source, "Allan deviation before and after the loop"), fontsize=10)
    figure.legend(*grid[0][0].get_legend_handles_labels(), loc="outside lower center", ncols=5, fontsize=8)
    return figure


def bins_report_figure(result: LoopResult, output_units: str = "rad/s") -> Any:
    """The averaged bins of each axis and the carouselled estimate with their ±2σ bands, stacked as
    (a), (b), (c) like TIM 2014 Fig. 7, one legend below the panels."""
    before, after = result.evaluation_before, result.evaluation_after
    assert before is not None and after is not None
    panels = [(before.averaged[a], after.averaged[a], f"averaged {a}-gyro") for a in result.axes]
    if before.carouselled is not None and after.carouselled is not None and len(after.carouselled.values):
        panels.append((before.carouselled, after.carouselled, "carouselled estimate"))
    figure, grid = pyplot().subplots(
        len(panels),
        1,
        figsize=(10, 2.4 * len(panels) + 0.8),
        squeeze=False,
        sharex=True,
        layout="constrained",
    )
    for index, (plot, (old, new, name)) in enumerate(zip(grid[:, 0], panels, strict=True)):
        _plot_bins(plot, old, new, f"({chr(ord('a') + index)}) {name}", output_units)
    grid[-1][0].set_xlabel("time (s)")
    figure.suptitle(
        short_title(
            result.source,
            f"averaged and carouselled bins with 2σ intervals, N = {result.samples_per_revolution} "
            "(TIM 2014 Fig. 7)",
        ),
        fontsize=10,
    )
    figure.legend(*grid[0][0].get_legend_handles_labels(), loc="outside lower center", ncols=4, fontsize=8)
    return figure


#: The files :func:`write_report` writes into its folder.
REPORT_FILES = ("allan_deviation.png", "bins.png", "summary.md")


def write_report(result: LoopResult, directory: Any, output_units: str = "rad/s") -> list[str]:
    """Write ``summary.md`` and the plots (matplotlib, Agg backend, imported when called) into ``directory``.

    Plots (rates in ``output_units``): the Allan deviation with its 95 % intervals and the model
    before/after for each axis (:func:`allan_report_figure`); the averaged bins of each axis and the
    carouselled bins with the ±2σ bands of the model before and after, as TIM 2014 Fig. 7
    (:func:`bins_report_figure`). Returns the file names written.
    """
    unit_label(output_units)
    directory = Path(directory)
    if directory.exists() and not directory.is_dir():
        raise ValueError(f"report directory {directory}: exists and is not a directory")
    directory.mkdir(parents=True, exist_ok=True)
    save_figure(allan_report_figure(result, output_units), directory / "allan_deviation.png", dpi=110)
    save_figure(bins_report_figure(result, output_units), directory / "bins.png", dpi=110)
    written = ["allan_deviation.png", "bins.png"]
    write_text_atomic(directory / "summary.md", render_summary(result, written))
    return [*written, "summary.md"]
