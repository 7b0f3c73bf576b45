"""``carousel-theory fit``: identify a noise model per gyro column, with standard errors, in the field's and
TIM 2014 Table III's units; optionally a plot and a markdown report over several recordings."""

from __future__ import annotations

import argparse
import math
import sys
import textwrap
from pathlib import Path
from typing import Any

import numpy as np

from carousel_theory.cli._fit_output import (
    FIT_NULL_REASONS,
    ar_coefficients_text,
    fit_as_json,
    fit_lines,
    order_interval_text,
)
from carousel_theory.cli._output_units import OutputUnits, add_output_units_option, output_units
from carousel_theory.cli.allan import add_recording_arguments, read_recording
from carousel_theory.fit_defaults import DEFAULT_TAU_MIN, DEFAULT_TAU_MIN_OCTAVES, LADDER, select_default_fit
from carousel_theory.fit_diagnostics import FitNotice, fit_notices
from carousel_theory.fitting import COMPONENTS, DEFAULT_TOLERANCE, FitResult, consistency_test, fit_recording
from carousel_theory.json_output import json_document, strict_json
from carousel_theory.output_files import plan_outputs, write_text_atomic
from carousel_theory.plots import plot_fit, short_title
from carousel_theory.units import BIAS_INSTABILITY_FACTOR, bias_instability_from_allan_minimum

#: Rows of the Table III-style summary: (key, label, unit, source of the value).
PAPER_ROWS = (
    ("white_variance_at_1s", "σ_WN² (τ = 1 s)", "(rad/s)²"),
    ("rrw_variance_per_s", "σ_q²", "(rad/s)²/s"),
    ("bias_instability", "bias instability (model min σ_A / 0.664)", "rad/s"),
)
FIELD_ROWS = (
    ("angle_random_walk_deg_per_sqrt_h", "angle random walk", "°/√h"),
    ("rate_random_walk_deg_per_h_per_sqrt_h", "rate random walk", "°/h/√h"),
    ("bias_instability_deg_per_h", "bias instability", "°/h"),
    ("bias_deg_per_h", "bias (record mean)", "°/h"),
)


def _components(text: str) -> tuple[str, ...]:
    names = tuple(name.strip() for name in text.split(",") if name.strip())
    unknown = [name for name in names if name not in COMPONENTS]
    if unknown or not names:
        raise argparse.ArgumentTypeError(
            f"{text!r}: must be comma-separated names from {', '.join(COMPONENTS)}"
        )
    return names


def _coefficients(text: str) -> tuple[float, ...]:
    try:
        values = tuple(float(part) for part in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r}: must be comma-separated numbers φ1,φ2,...") from None
    return values


def _add_ar_options(parser: argparse.ArgumentParser) -> None:
    """--ar-coefficients and --ar-order (the AR term's coefficients given, or the order they are
    estimated with)."""
    parser.add_argument(
        "--ar-coefficients",
        type=_coefficients,
        metavar="PHI[,PHI...]",
        help="give the AR (Gauss–Markov) coefficients instead of estimating them from the record, e.g. "
        "exp(−1/(f_s τ_c)) for a known correlation time τ_c (only with 'ar' in --model)",
    )
    parser.add_argument(
        "--ar-order",
        type=int,
        help="largest AR order the coefficients are estimated with (default 4; only with 'ar' in --model)",
    )


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser(
        "fit",
        help="identify white noise, rate random walk, 1/f noise and bias per gyro column, with errors",
        description=(
            "Fit a noise model to every gyro column of each DATA file by generalized least squares on the "
            "octave Allan variance (model-based covariance across τ). Prints the model in the field's "
            "units (°/√h, °/h/√h, °/h) and in TIM 2014 Table III's (σ_WN² at τ = 1 s, σ_q², bias "
            "instability), with standard errors; --markdown writes a Table III-style report with the "
            "run-to-run consistency."
        ),
    )
    parser.add_argument(
        "data",
        type=Path,
        nargs="+",
        metavar="DATA",
        help="recording(s): text (.csv .txt .tsv), .npz, HDF5 (.h5) or MATLAB (.mat)",
    )
    add_recording_arguments(parser)
    parser.add_argument(
        "--model",
        type=_components,
        metavar="C[,C...]",
        help=f"components from {', '.join(COMPONENTS)} (default: per axis the first of "
        + "; ".join(step.describe() for step in LADDER)
        + " that the recording does not reject by its χ² test)",
    )
    parser.add_argument(
        "--flicker-d", type=float, help="fix the 1/f order d (default: fitted when flicker is used)"
    )
    _add_ar_options(parser)
    parser.add_argument(
        "--tau-min",
        type=float,
        help="smallest τ (s) in the fit, above the sensor's internal filter (default: every τ, or "
        f"{DEFAULT_TAU_MIN:g} s for the default model when it is rejected over every τ and the recording "
        f"leaves {DEFAULT_TAU_MIN_OCTAVES} octave τ above it)",
    )
    parser.add_argument("--tau-max", type=float, help="largest τ (s) in the fit")
    parser.add_argument(
        "--iterations",
        type=int,
        default=3,
        help="most covariance re-evaluations (default 3; fewer once a step moves no parameter by more "
        "than 0.05 of its standard error)",
    )
    parser.add_argument(
        "--all-iterations",
        action="store_true",
        help="take every one of --iterations, even after a step that moved no parameter",
    )
    parser.add_argument(
        "--markdown", type=Path, metavar="FILE.md", help="write a Table III-style markdown report"
    )
    add_output_units_option(parser)
    parser.set_defaults(handler=run)


def _fit_file(path: Path, args: argparse.Namespace) -> tuple[Any, dict[str, FitResult], list[str]]:
    """Read and fit one recording (the default model: :func:`select_default_fit`); the notes say which
    model each axis needed."""
    recording = read_recording(path, args)
    common = {
        "tau_min": args.tau_min,
        "tau_max": args.tau_max,
        "label": f"fit {path.name}: axes",
        "estimator": args.estimator,
        "iterations": args.iterations,
        "tolerance": None if args.all_iterations else DEFAULT_TOLERANCE,
    }
    if args.model is None:
        fits, notes = select_default_fit(recording, **common)
        return recording, fits, notes
    ar = {"ar_coefficients": args.ar_coefficients} if args.ar_coefficients is not None else {}
    ar |= {"ar_order": args.ar_order} if args.ar_order is not None else {}
    return recording, fit_recording(recording, args.model, flicker_d=args.flicker_d, **common, **ar), []


def _measured_bias_instability(fit: FitResult) -> tuple[float, float, float, float]:
    """(min ADEV, its τ, B low, B high): the data's minimum Allan deviation and its interval, / 0.664."""
    allan = fit.allan
    best = int(np.argmin(allan.avar))
    return (
        math.sqrt(allan.avar[best]),
        float(allan.tau[best]),
        bias_instability_from_allan_minimum(math.sqrt(allan.ci_low[best])),
        bias_instability_from_allan_minimum(math.sqrt(allan.ci_high[best])),
    )


def _format(value: float, error: float) -> str:
    if not math.isfinite(error):
        return f"{value:.3g} ± ∞"
    return f"{value:.3g} ± {error:.2g}"


def _consistency(values: list[tuple[float, float]]) -> str:
    """The run-to-run consistency test (:func:`carousel_theory.fitting.consistency_test`), formatted."""
    test = consistency_test(values)
    if test is None:
        return "—"
    return (
        f"{test.mean:.3g} (spread {test.spread:.2g}; χ²={test.chi_square:.3g}/{test.degrees_of_freedom}, "
        f"p={test.p_value:.2g})"
    )


def _row(label: str, unit: str, cells: list[str]) -> str:
    return f"| {label} | {unit} | " + " | ".join(cells) + " |"


def _report_header(files: list[tuple[Any, dict[str, FitResult]]], args: argparse.Namespace) -> list[str]:
    first = next(iter(files[0][1].values()))
    return [
        "<!-- generated by `carousel-theory fit ... --markdown`; do not edit -->",
        "",
        "# Noise model of the recordings",
        "",
        f"Command: `carousel-theory fit {' '.join(str(path) for path in args.data)}"
        + (f" --model {','.join(args.model)}" if args.model else "")
        + (f" --tau-min {args.tau_min:g}" if args.tau_min is not None else "")
        + (f" --tau-max {args.tau_max:g}" if args.tau_max is not None else "")
        + (f" --flicker-d {args.flicker_d:g}" if args.flicker_d is not None else "")
        + (
            f" --ar-coefficients {','.join(f'{c:g}' for c in args.ar_coefficients)}"
            if args.ar_coefficients is not None
            else ""
        )
        + (f" --ar-order {args.ar_order}" if args.ar_order is not None else "")
        + f" --estimator {args.estimator} --iterations {args.iterations}"
        + (" --all-iterations" if args.all_iterations else "")
        + f" --markdown {args.markdown}`",
        "",
        f"Method: {first.method}. Values are estimate ± one standard error.",
        "",
        "Conventions (see `carousel_theory.units`): σ_WN² (τ = 1 s) is the variance of a 1-s average of "
        "the white noise, σ²/f_s, numerically the squared angle random walk in rad²/s; σ_q² is the "
        "rate-random-walk increment variance per second, σ_q,sample²·f_s = K²; the bias instability is the "
        f"minimum of the Allan deviation divided by √(2 ln 2/π) = {BIAS_INSTABILITY_FACTOR:.4f} (IEEE Std "
        "952), taken from the fitted model's curve and, separately, from the data's octave points (with "
        "the χ² interval of that point). The bias is the record mean; its standard error comes from the "
        "fitted model (random walk started at zero at the first sample).",
        "",
    ]


#: The printed keys that come from each fitted variance (shown as held at zero when it is).
_DERIVED_KEYS = {
    "white_variance": ("white_variance_at_1s", "angle_random_walk_deg_per_sqrt_h"),
    "rrw_variance": ("rrw_variance_per_s", "rate_random_walk_deg_per_h_per_sqrt_h"),
}


def _held_keys(fit: FitResult) -> set[str]:
    """Printed keys of the parameters held at zero (and the 1/f order d of a 1/f term held at zero)."""
    held = {key for parameter in fit.at_bound for key in (parameter, *_DERIVED_KEYS.get(parameter, ()))}
    return held | ({"flicker_d"} if "flicker_variance" in fit.at_bound else set())


def _cell(fit: FitResult, key: str, value: tuple[float, float], held: str = "0 (held at zero)") -> str:
    """``value ± error``, or ``held`` for a parameter held at zero (it has no standard error)."""
    return held if key in _held_keys(fit) else _format(*value)


def _parameter_rows(fits: dict[str, FitResult], axes: list[str], args: argparse.Namespace) -> list[str]:
    """Table III's and the field's rows, then the 1/f rows when fitted."""
    paper = {axis: fit.paper_units() for axis, fit in fits.items()}
    field = {axis: fit.field_units() for axis, fit in fits.items()}
    lines = []
    for table, rows in ((paper, PAPER_ROWS), (field, FIELD_ROWS)):
        for key, label, unit in rows:
            if all(key in table[a] for a in axes):
                lines.append(_row(label, unit, [_cell(fits[a], key, table[a][key]) for a in axes]))
    for key, label, unit in (
        ("flicker_variance", "1/f σ_w² (eq. (3))", "(rad/s)²"),
        ("flicker_d", "1/f order d", "—"),
        ("ar_variance", "AR innovation variance (per sample)", "(rad/s)²"),
    ):
        if any(key in fits[a].standard_errors for a in axes):
            lines.append(
                _row(
                    label,
                    unit,
                    [
                        _cell(fits[a], key, (getattr(fits[a].model, key), fits[a].standard_errors[key]))
                        if key in fits[a].standard_errors
                        else "—"
                        for a in axes
                    ],
                )
            )
    return lines + _order_interval_rows(fits, axes) + _ar_rows(fits, axes)


def _order_interval_rows(fits: dict[str, FitResult], axes: list[str]) -> list[str]:
    """The fitted 1/f order's 95 % interval (:func:`carousel_theory.fitting.order_interval`), when fitted."""
    if not any("flicker_d" in fits[axis].standard_errors for axis in axes):
        return []
    cells = [order_interval_text(fits[axis]) or "—" for axis in axes]
    return [_row("1/f order d, 95 % interval (χ² difference)", "—", cells)]


def _ar_rows(fits: dict[str, FitResult], axes: list[str]) -> list[str]:
    """The AR coefficients with their standard errors (``given`` when they were), when a term is fitted."""
    cells = [ar_coefficients_text(fits[axis], 3) or "—" for axis in axes]
    return [_row("AR coefficients φ", "—", cells)] if any(c != "—" for c in cells) else []


def _data_rows(fits: dict[str, FitResult], axes: list[str]) -> list[str]:
    """The data's minimum Allan deviation, its bias instability interval, the fit's χ²."""
    measured = {axis: _measured_bias_instability(fit) for axis, fit in fits.items()}
    return [
        _row(
            "min ADEV of the data (τ)",
            "rad/s (s)",
            [f"{measured[a][0]:.3g} ({measured[a][1]:.3g})" for a in axes],
        ),
        _row(
            "bias instability from the data, 95 % interval",
            "rad/s",
            [f"{measured[a][2]:.3g} … {measured[a][3]:.3g}" for a in axes],
        ),
        _row(
            "fit χ² / degrees of freedom",
            "—",
            [f"{fits[a].chi_square:.3g} / {fits[a].degrees_of_freedom}" for a in axes],
        ),
    ]


def _verdict_lines(fits: dict[str, FitResult], axes: list[str]) -> list[str]:
    """The notices of each axis (:func:`carousel_theory.fit_diagnostics.fit_notices`): model rejected,
    terms held at zero with their likely cause, the ARW read-off."""
    lines = [f"- {axis}: {notice.message}" for axis in axes for notice in fit_notices(fits[axis])]
    return ["", *(lines or ["No notice: every axis accepts the model and no term is held at zero."]), ""]


def _consistency_section(files: list[tuple[Any, dict[str, FitResult]]], axes: list[str]) -> list[str]:
    lines = [
        "## Run-to-run consistency",
        "",
        "Weighted mean over the runs, the runs' sample standard deviation, and χ² of the runs about the "
        "weighted mean with its p-value: a small p says the runs differ by more than their standard "
        "errors.",
        "",
        "| parameter | unit | " + " | ".join(axes) + " |",
        "|---|---|" + "---|" * len(axes),
    ]
    left_out: list[str] = []
    for key, label, unit, kind in [(*row, "paper") for row in PAPER_ROWS] + [
        (*row, "field") for row in FIELD_ROWS
    ]:
        cells = []
        for axis in axes:
            present = [fits[axis] for _, fits in files if axis in fits]  # runs may hold different axes
            tables = [fit.paper_units() if kind == "paper" else fit.field_units() for fit in present]
            values = [table[key] for table in tables if key in table]
            cells.append(_consistency(values) if len(values) == len(present) >= 2 else "—")
        if any(cell != "—" for cell in cells):
            lines.append(_row(label, unit, cells))
        else:
            left_out.append(label)
    note = (
        [
            f"Left out: {', '.join(left_out)}: on every axis some run has no standard error for it "
            "(its term held at zero there).",
            "",
        ]
        if left_out
        else []
    )
    return [*lines, "", *note, *_missing_axes_note(files, axes)]


def _missing_axes_note(files: list[tuple[Any, dict[str, FitResult]]], axes: list[str]) -> list[str]:
    """Which recordings lack an axis (its consistency uses the runs that have it)."""
    missing = {
        axis: [Path(recording.source).name for recording, fits in files if axis not in fits] for axis in axes
    }
    notes = [f"{axis}: not in {', '.join(names)}" for axis, names in missing.items() if names]
    return (
        [f"Axes missing from some runs (their consistency uses the other runs): {'; '.join(notes)}.", ""]
        if notes
        else []
    )


def markdown_report(
    files: list[tuple[Any, dict[str, FitResult]]],
    args: argparse.Namespace,
    notes: list[list[str]] | None = None,
) -> str:
    """The Table III-style report: one table per recording and a run-to-run consistency table; ``notes``
    (one list per recording) are printed under its heading."""
    lines = _report_header(files, args)
    notes = notes or [[] for _ in files]
    axes = list(
        dict.fromkeys(name for _, fits in files for name in fits)
    )  # every axis of every run, in order
    for (recording, fits), file_notes in zip(files, notes, strict=True):
        lines += [
            f"## {Path(recording.source).name}",
            "",
            f"{len(recording)} samples at {recording.sample_rate:g} Hz ({recording.duration / 3600:.3g} h).",
            "",
            *(f"Note: {note}.\n" for note in file_notes),
            "| parameter | unit | " + " | ".join(fits) + " |",
            "|---|---|" + "---|" * len(fits),
        ]
        own = list(fits)
        lines += _parameter_rows(fits, own, args) + _data_rows(fits, own) + _verdict_lines(fits, own)
    if len(files) > 1:
        lines += _consistency_section(files, axes)
    return "\n".join(lines)


def _check_fit_options(args: argparse.Namespace) -> None:
    """Options that would be ignored or misread are refused instead (issue: silently ignored options)."""
    for name in ("tau_min", "tau_max"):
        value = getattr(args, name)
        if value is not None and not (math.isfinite(value) and value > 0):
            raise ValueError(f"--{name.replace('_', '-')}={value!r}: must be a positive number of seconds")
    if args.tau_min is not None and args.tau_max is not None and args.tau_min >= args.tau_max:
        raise ValueError(f"--tau-min={args.tau_min!r}: must be below --tau-max={args.tau_max!r}")
    given = "the default model" if args.model is None else repr(args.model)
    if args.flicker_d is not None and "flicker" not in (args.model or ()):
        raise ValueError(f"--flicker-d={args.flicker_d!r}: only with 'flicker' in --model (got {given})")
    for option, value in (("--ar-coefficients", args.ar_coefficients), ("--ar-order", args.ar_order)):
        if value is not None and "ar" not in (args.model or ()):
            raise ValueError(f"{option}={value!r}: only with 'ar' in --model (got {given})")
    if args.ar_order is not None and args.ar_order < 1:
        raise ValueError(f"--ar-order={args.ar_order!r}: must be an integer >= 1")
    if args.ar_coefficients is not None and args.ar_order is not None:
        raise ValueError(
            f"--ar-order={args.ar_order!r}: the coefficients are given (--ar-coefficients), not estimated"
        )


def _notice_lines(notices: list[FitNotice], indent: str) -> list[str]:
    """Each notice wrapped at 110 columns under a ``note:`` or ``WARNING:`` tag."""
    lines = []
    for notice in notices:
        tag = "WARNING: " if notice.kind == "model_rejected" else "note: "
        lines += textwrap.wrap(
            tag + notice.message, width=110, initial_indent=indent, subsequent_indent=indent + "  "
        )
    return lines


def _json_document(
    files: list[tuple[Any, dict[str, FitResult]]], notes: list[list[str]], output: OutputUnits
) -> dict[str, Any]:
    """The ``fit --json`` body: per file its source, notes, and per column the fit (Allan variances in
    ``output``) with its notices."""
    return {
        "output_units": output.rate,
        "files": [
            {
                "source": recording.source,
                "notes": file_notes,
                "columns": {
                    name: {
                        **fit_as_json(fit, output),
                        "notices": [{"kind": n.kind, "message": n.message} for n in fit_notices(fit)],
                    }
                    for name, fit in fits.items()
                },
            }
            for (recording, fits), file_notes in zip(files, notes, strict=True)
        ],
    }


def run(args: argparse.Namespace) -> int:
    if args.iterations < 1:
        raise ValueError(f"--iterations={args.iterations!r}: must be >= 1")
    _check_fit_options(args)
    plan_outputs([(args.plot, "file"), (args.markdown, "file")], inputs=args.data)
    fitted = [_fit_file(path, args) for path in args.data]
    files = [(recording, fits) for recording, fits, _ in fitted]
    notes = [file_notes for _, _, file_notes in fitted]
    if args.plot:
        recording, fits = files[0]
        title = short_title(recording.source, "Allan deviation and the fitted noise model")
        plot_fit(args.plot, fits, title, output_units=args.output_units)
    if args.markdown:
        write_text_atomic(args.markdown, markdown_report(files, args, notes))
    if args.json:
        document = _json_document(files, notes, output_units(args))
        sys.stdout.write(strict_json(json_document("fit", document, FIT_NULL_REASONS)))
        return 0
    for (recording, fits), file_notes in zip(files, notes, strict=True):
        print(f"{recording.source}: {len(recording)} samples at {recording.sample_rate:g} Hz")
        for line in _notice_lines([FitNotice("default_range", note) for note in file_notes], "  "):
            print(line)
        for name, fit in fits.items():
            print("\n".join(fit_lines(name, fit, output_units(args))))
            for line in _notice_lines(fit_notices(fit), "    "):
                print(line)
    for path in (args.plot, args.markdown):
        if path:
            print(f"wrote {path}")
    return 0
