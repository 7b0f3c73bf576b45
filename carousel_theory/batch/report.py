"""The fleet report: how the fleet's noise parameters are distributed, which units stand out, which
effects the loop found how often, and what failed.

Outliers are flagged by the modified z-score of Iglewicz and Hoaglin (1993) on the logarithm of each
parameter (the parameters are positive and spread over decades): z = (x − median) / (1.4826 · MAD), with
MAD the median absolute deviation from the median (1.4826 · MAD estimates σ for Gaussian data); a unit is
flagged when |z| > 3.5. Median and MAD ignore up to half the fleet being wrong, unlike the mean and the
standard deviation, which one broken unit can move arbitrarily.
"""

from __future__ import annotations

import collections
import math
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from carousel_theory.batch.rows import BatchRow
from carousel_theory.batch.store import write_atomically
from carousel_theory.units import from_rad_per_s, rate_to_rad_per_s

__all__ = ["OUTLIER_THRESHOLD", "PARAMETERS", "Outlier", "robust_z_scores", "write_report"]

#: The fleet parameters: (row field, label, unit).
PARAMETERS = (
    ("angle_random_walk_deg_per_sqrt_h", "angle random walk", "°/√h"),
    ("bias_instability_deg_per_h", "bias instability", "°/h"),
    ("rate_random_walk_deg_per_h_per_sqrt_h", "rate random walk", "°/h/√h"),
)
#: |modified z| above which a unit is flagged (Iglewicz & Hoaglin 1993).
OUTLIER_THRESHOLD = 3.5
#: 1/Φ⁻¹(3/4): scales the MAD to σ for Gaussian data.
MAD_TO_SIGMA = 1.4826


@dataclass(frozen=True)
class Outlier:
    """A unit whose parameter lies far from the fleet's median on the robust scale."""

    path: str
    axis: str
    parameter: str
    value: float
    z: float


def robust_z_scores(values: Sequence[float] | np.ndarray) -> np.ndarray:
    """Modified z-scores of log10(values): (x − median) / (1.4826 MAD); NaN where the MAD is 0 or a value
    is not positive."""
    array = np.asarray(values, dtype=np.float64)
    scores = np.full(array.shape, math.nan)
    usable = np.isfinite(array) & (array > 0)
    if usable.sum() < 3:
        return scores
    logs = np.log10(array[usable])
    median = float(np.median(logs))
    mad = float(np.median(np.abs(logs - median)))
    if mad > 0:
        scores[usable] = (logs - median) / (MAD_TO_SIGMA * mad)
    return scores


def _ok(rows: Sequence[BatchRow]) -> list[BatchRow]:
    return [row for row in rows if row.status == "ok"]


def find_outliers(rows: Sequence[BatchRow]) -> list[Outlier]:
    """Every (unit, parameter) with |modified z| > :data:`OUTLIER_THRESHOLD`, sorted by path and axis."""
    good = _ok(rows)
    flagged = []
    for name, _, _ in PARAMETERS:
        scores = robust_z_scores([getattr(row, name) for row in good])
        for row, score in zip(good, scores, strict=True):
            if math.isfinite(score) and abs(score) > OUTLIER_THRESHOLD:
                flagged.append(Outlier(row.path, row.axis, name, getattr(row, name), float(score)))
    return sorted(flagged, key=lambda o: (o.path, o.axis, o.parameter))


def _distribution_lines(rows: Sequence[BatchRow]) -> list[str]:
    lines = [
        "| parameter | unit | units | median | robust σ (1.4826 MAD) | 5 % | 95 % |",
        "|---|---|---|---|---|---|---|",
    ]
    for name, label, unit in PARAMETERS:
        values = np.array([getattr(row, name) for row in _ok(rows)], dtype=np.float64)
        values = values[np.isfinite(values)]
        if values.size == 0:
            lines.append(f"| {label} | {unit} | 0 | — | — | — | — |")
            continue
        median = float(np.median(values))
        spread = MAD_TO_SIGMA * float(np.median(np.abs(values - median)))
        low, high = np.percentile(values, [5, 95])
        lines.append(
            f"| {label} | {unit} | {values.size} | {median:.4g} | {spread:.3g} | {low:.4g} | {high:.4g} |"
        )
    return lines


def effect_frequencies(rows: Sequence[BatchRow]) -> dict[str, int]:
    """How many recordings the loop found each effect in (a recording counts once whatever its axes)."""
    per_recording = {(row.path, row.effects) for row in _ok(rows) if row.task == "loop"}
    counts: collections.Counter[str] = collections.Counter()
    for _, effects in per_recording:
        counts.update(set(filter(None, effects.split(";"))))
    return dict(sorted(counts.items(), key=lambda item: (-item[1], item[0])))


def _effect_lines(rows: Sequence[BatchRow]) -> list[str]:
    recordings = len({row.path for row in _ok(rows) if row.task == "loop"})
    counts = effect_frequencies(rows)
    if not recordings:
        return ["The loop did not run on this fleet (task other than `loop`)."]
    lines = ["| effect | recordings | share |", "|---|---|---|"]
    lines += [f"| {name} | {count} | {count / recordings:.0%} |" for name, count in counts.items()]
    return lines


def _error_lines(rows: Sequence[BatchRow]) -> list[str]:
    errors = sorted((row for row in rows if row.status != "ok"), key=lambda row: (row.path, row.axis))
    if not errors:
        return ["No recording failed."]
    lines = ["| recording | axis | kind | reason |", "|---|---|---|---|"]
    for row in errors:
        reason = row.error.replace("|", "\\|").replace("\n", " ")
        lines.append(f"| {Path(row.path).name} | {row.axis or '—'} | {row.error_kind} | {reason} |")
    return lines


def _outlier_lines(rows: Sequence[BatchRow]) -> list[str]:
    outliers = find_outliers(rows)
    if not outliers:
        return [f"No unit has |modified z| > {OUTLIER_THRESHOLD:g} on any parameter."]
    lines = ["| recording | axis | parameter | value | modified z |", "|---|---|---|---|---|"]
    for outlier in outliers:
        lines.append(
            f"| {Path(outlier.path).name} | {outlier.axis} | {outlier.parameter} | {outlier.value:.4g} | "
            f"{outlier.z:+.2f} |"
        )
    return lines


def _distribution_panel(plot: Any, values: np.ndarray, label: str, unit: str) -> None:
    """One histogram with the flagged units as red lines: log-spaced bins on a log axis when the values
    span more than a decade, linear ones otherwise (a log axis over less than a decade has no readable
    ticks); whole counts on the y axis."""
    from matplotlib.ticker import MaxNLocator

    scores = robust_z_scores(values)
    positive = values[np.isfinite(values) & (values > 0)]
    if positive.size:
        low, high = positive.min(), positive.max()
        wide = high > 10 * low
        bins = (
            (np.geomspace(low / 1.05, high * 1.05, 25) if wide else np.linspace(low, high, 25))
            if high > low
            else 10
        )
        plot.hist(positive, bins=bins, color="C0", alpha=0.8, label="units")
        if wide:
            plot.set_xscale("log")
        for index, value in enumerate(values[np.abs(np.nan_to_num(scores)) > OUTLIER_THRESHOLD]):
            plot.axvline(
                value, color="C3", lw=1.0, label=None if index else f"flagged (|z| > {OUTLIER_THRESHOLD:g})"
            )
    plot.yaxis.set_major_locator(MaxNLocator(integer=True))
    plot.set_title(f"{positive.size} of {len(values)} axes above 0", fontsize=8)
    plot.set_xlabel(f"{label} ({unit})")
    plot.set_ylabel("units")


def distributions_figure(rows: Sequence[BatchRow], output_units: str = "deg/h") -> Any:
    """Histograms of ARW, bias instability and RRW across the fleet (log-spaced bins), flagged units
    marked in red, one legend below the panels. The bias instability is drawn in ``output_units`` (the
    default °/h matches the report's table); ARW and RRW stay in °/√h and °/h/√h (IEEE Std 952)."""
    from carousel_theory.plots import pyplot, unit_label

    unit_label(output_units)
    good = _ok(rows)
    figure, axes = pyplot().subplots(1, len(PARAMETERS), figsize=(11.0, 3.8), layout="constrained")
    for plot, (name, label, unit) in zip(axes, PARAMETERS, strict=True):
        values = np.array([getattr(row, name) for row in good], dtype=np.float64)
        if name == "bias_instability_deg_per_h":
            values = from_rad_per_s(rate_to_rad_per_s(values, "deg/h"), output_units)
            unit = unit_label(output_units)
        _distribution_panel(plot, values, label, unit)
    recordings = len({row.path for row in good})
    figure.suptitle(f"Fleet distributions: {recordings} recordings, {len(good)} axes", fontsize=10)
    handles = {
        text: handle for plot in axes for handle, text in zip(*plot.get_legend_handles_labels(), strict=True)
    }
    figure.legend(list(handles.values()), list(handles), loc="outside lower center", ncols=2, fontsize=8)
    return figure


def plot_distributions(rows: Sequence[BatchRow], path: Path, output_units: str = "deg/h") -> Path:
    """Write :func:`distributions_figure` to ``path`` atomically."""
    figure = distributions_figure(rows, output_units)
    try:
        write_atomically(path, lambda temporary: figure.savefig(temporary, dpi=110, format="png"))
    finally:
        from carousel_theory.plots import pyplot

        pyplot().close(figure)
    return path


def render_report(rows: Sequence[BatchRow], task: str, plot_name: str | None) -> str:
    """The Markdown text of the fleet report."""
    recordings = sorted({row.path for row in rows})
    failed = sorted({row.path for row in rows if row.status != "ok"})
    total_seconds = sum(row.seconds for row in rows if math.isfinite(row.seconds))
    lines = [
        f"<!-- generated by `carousel-theory batch --task {task}`; do not edit -->",
        "",
        "# Fleet report",
        "",
        f"{len(recordings)} recordings, {len(rows)} rows (one per recording and axis), task `{task}`; "
        f"{len(failed)} recordings with an error; {total_seconds:.1f} s of task time in all.",
        "",
        "## Distributions across the fleet",
        "",
        *_distribution_lines(rows),
        "",
    ]
    if plot_name:
        lines += [f"![distributions]({plot_name})", ""]
    lines += [
        "## Outliers",
        "",
        "Modified z-score of log10(value): (x − median) / (1.4826 · MAD), flagged above "
        f"{OUTLIER_THRESHOLD:g} in magnitude (Iglewicz & Hoaglin 1993).",
        "",
        *_outlier_lines(rows),
        "",
        "## Effects found by the loop",
        "",
        *_effect_lines(rows),
        "",
        "## Errors",
        "",
        *_error_lines(rows),
        "",
    ]
    return "\n".join(lines)


def _write_text(path: Path, text: str) -> None:
    path.write_text(text, encoding="utf-8")


def write_report(rows: Sequence[BatchRow], directory: Path, task: str) -> list[Path]:
    """Write ``report.md`` (and ``distributions.png`` when matplotlib is installed) into ``directory``,
    atomically; return the files written."""
    written = []
    plot_name: str | None = "distributions.png"
    try:
        written.append(plot_distributions(rows, directory / "distributions.png"))
    except ModuleNotFoundError as error:
        if error.name != "matplotlib":
            raise
        plot_name = None
    report = directory / "report.md"
    text = render_report(rows, task, plot_name)
    write_atomically(report, lambda temporary: _write_text(temporary, text))
    return [report, *written]
