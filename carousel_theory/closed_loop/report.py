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
from carousel_theory.output_files import atomic_output, write_text_atomic

__all__ = ["render_summary", "write_report"]


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


def _plot_allan(plot: Any, axis: str, before: Evaluation, after: Evaluation) -> None:
    for label, evaluation, style in (("before", before, "--"), ("after", after, "-")):
        fit = evaluation.view.fits[axis]
        if label == "after":
            low = fit.observed * fit.edf / stats.chi2.ppf(0.975, fit.edf)
            high = fit.observed * fit.edf / stats.chi2.ppf(0.025, fit.edf)
            plot.fill_between(fit.tau, np.sqrt(low), np.sqrt(high), color="0.85", label="95 % interval")
            plot.loglog(fit.tau, np.sqrt(fit.observed), "k.", label="measured (after removal)")
        plot.loglog(fit.tau, np.sqrt(fit.model), style, label=f"model {label}")
    recorded = before.view.fits[axis]
    plot.loglog(recorded.tau, np.sqrt(recorded.observed), "x", color="0.5", label="measured (as recorded)")
    plot.set_xlabel("τ (s)")
    plot.set_ylabel("Allan deviation (rad/s)")
    plot.set_title(axis)
    plot.legend(fontsize=7)


def _plot_bins(plot: Any, before: BinSeries, after: BinSeries, colour: str, label: str) -> None:
    plot.plot(before.time, before.values, color="0.6", lw=0.6, label="as recorded")
    plot.plot(after.time, after.values, color="k", lw=0.6, label="effects removed")
    for bins, style, name in ((before, "--", "±2σ before"), (after, "-", "±2σ after")):
        band = BAND_SIGMA * np.sqrt(bins.variance)
        plot.plot(bins.time, band, colour + style, lw=0.8, label=name)
        plot.plot(bins.time, -band, colour + style, lw=0.8)
    plot.set_ylabel(label)
    plot.legend(fontsize=7, loc="upper right")


#: The files :func:`write_report` writes into its folder.
REPORT_FILES = ("allan_deviation.png", "bins.png", "summary.md")


def write_report(result: LoopResult, directory: Any) -> list[str]:
    """Write ``summary.md`` and the plots (matplotlib, Agg backend, imported here) into ``directory``.

    Plots: the Allan deviation with its 95 % intervals and the model before/after for each axis; the
    averaged bins of each axis and the carouselled bins with the ±2σ bands of the model before and after
    (as TIM 2014 Fig. 7). Returns the file names written.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    directory = Path(directory)
    if directory.exists() and not directory.is_dir():
        raise ValueError(f"report directory {directory}: exists and is not a directory")
    directory.mkdir(parents=True, exist_ok=True)
    before, after = result.evaluation_before, result.evaluation_after
    assert before is not None and after is not None
    figure, grid = plt.subplots(1, len(result.axes), figsize=(6 * len(result.axes), 4.5), squeeze=False)
    for plot, axis in zip(grid[0], result.axes, strict=True):
        _plot_allan(plot, axis, before, after)
    figure.tight_layout()
    with atomic_output(directory / "allan_deviation.png") as temporary:
        figure.savefig(temporary, dpi=110, format="png")
    plt.close(figure)
    carousel = (
        before.carouselled is not None and after.carouselled is not None and len(after.carouselled.values)
    )
    rows = len(result.axes) + (1 if carousel else 0)
    figure, grid = plt.subplots(rows, 1, figsize=(9, 2.6 * rows), squeeze=False)
    for row, axis in enumerate(result.axes):
        _plot_bins(grid[row][0], before.averaged[axis], after.averaged[axis], "b", f"averaged {axis} (rad/s)")
    if carousel:
        assert before.carouselled is not None and after.carouselled is not None
        _plot_bins(grid[-1][0], before.carouselled, after.carouselled, "r", "carouselled (rad/s)")
    grid[-1][0].set_xlabel("time (s)")
    figure.tight_layout()
    with atomic_output(directory / "bins.png") as temporary:
        figure.savefig(temporary, dpi=110, format="png")
    plt.close(figure)
    written = ["allan_deviation.png", "bins.png"]
    write_text_atomic(directory / "summary.md", render_summary(result, written))
    return [*written, "summary.md"]
