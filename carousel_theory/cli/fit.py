"""``carousel-theory fit``: identify a noise model per gyro column, with standard errors, in the field's and
TIM 2014 Table III's units; optionally a plot and a markdown report over several recordings."""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path
from typing import Any

import numpy as np

from carousel_theory.cli.allan import add_recording_arguments, plot_allan, read_recording, result_as_json
from carousel_theory.fitting import COMPONENTS, FitResult, consistency_test, fit_recording
from carousel_theory.json_output import json_document, strict_json
from carousel_theory.output_files import plan_outputs, write_text_atomic
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
    parser.add_argument("data", type=Path, nargs="+", metavar="DATA", help="recording(s) (.csv or .npz)")
    add_recording_arguments(parser)
    parser.add_argument(
        "--model",
        type=_components,
        default=("white", "rrw"),
        metavar="C[,C...]",
        help=f"components from {', '.join(COMPONENTS)} (default white,rrw)",
    )
    parser.add_argument(
        "--flicker-d", type=float, help="fix the 1/f order d (default: fitted when flicker is used)"
    )
    parser.add_argument(
        "--tau-min", type=float, help="smallest τ (s) in the fit (e.g. above the sensor's filter)"
    )
    parser.add_argument("--tau-max", type=float, help="largest τ (s) in the fit")
    parser.add_argument("--iterations", type=int, default=3, help="covariance re-evaluations (default 3)")
    parser.add_argument(
        "--markdown", type=Path, metavar="FILE.md", help="write a Table III-style markdown report"
    )
    parser.set_defaults(handler=run)


def _fit_file(path: Path, args: argparse.Namespace) -> tuple[Any, dict[str, FitResult]]:
    recording = read_recording(path, args)
    fits = fit_recording(
        recording,
        args.model,
        tau_min=args.tau_min,
        tau_max=args.tau_max,
        label=f"fit {path.name}: axes",
        flicker_d=args.flicker_d,
        estimator=args.estimator,
        iterations=args.iterations,
    )
    return recording, fits


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


#: Why a standard error is null in ``fit --json``: a term held at zero has none (see ``at_bound``).
FIT_NULL_REASONS = {
    **dict.fromkeys(
        ("white_variance", "rrw_variance", "flicker_variance", "flicker_d", "quantization", "ar_variance"),
        "no standard error: the term is held at zero, the bound of its range (listed in at_bound)",
    ),
    "standard_error": "no standard error: the parameter comes from a term held at zero (see at_bound)",
}


def _with_errors(parameters: dict[str, tuple[float, float]]) -> dict[str, dict[str, float]]:
    """``{name: {"value", "standard_error"}}``: an object per parameter, so a null error has its reason."""
    return {key: {"value": value, "standard_error": error} for key, (value, error) in parameters.items()}


def fit_as_json(fit: FitResult) -> dict[str, Any]:
    model = fit.model
    return {
        "model": {
            "sample_rate": model.sample_rate,
            "bias": model.bias,
            "white_variance": model.white_variance,
            "rrw_variance": model.rrw_variance,
            "flicker_variance": model.flicker_variance,
            "flicker_d": model.flicker_d,
            "quantization": model.quantization,
            "ar_variance": model.ar_variance,
            "ar_coefficients": list(model.ar_coefficients),
        },
        "standard_errors": dict(fit.standard_errors),
        "field_units": _with_errors(fit.field_units()),
        "paper_units": _with_errors(fit.paper_units()),
        "chi_square": fit.chi_square,
        "degrees_of_freedom": fit.degrees_of_freedom,
        "p_value": fit.p_value,
        "at_bound": list(fit.at_bound),
        "method": fit.method,
        "allan": result_as_json(fit.allan),
        "model_avar": fit.model_avar.tolist(),
        "used": fit.used.tolist(),
    }


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
        f"Command: `carousel-theory fit {' '.join(str(path) for path in args.data)} "
        f"--model {','.join(args.model)}"
        + (f" --tau-min {args.tau_min:g}" if args.tau_min is not None else "")
        + (f" --tau-max {args.tau_max:g}" if args.tau_max is not None else "")
        + (f" --flicker-d {args.flicker_d:g}" if args.flicker_d is not None else "")
        + f" --estimator {args.estimator} --iterations {args.iterations} --markdown {args.markdown}`",
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


def _parameter_rows(fits: dict[str, FitResult], axes: list[str], args: argparse.Namespace) -> list[str]:
    """Table III's and the field's rows, then the 1/f rows when fitted."""
    paper = {axis: fit.paper_units() for axis, fit in fits.items()}
    field = {axis: fit.field_units() for axis, fit in fits.items()}
    lines = []
    for table, rows in ((paper, PAPER_ROWS), (field, FIELD_ROWS)):
        for key, label, unit in rows:
            if all(key in table[a] for a in axes):
                lines.append(_row(label, unit, [_format(*table[a][key]) for a in axes]))
    if "flicker" in args.model:
        lines.append(
            _row(
                "1/f σ_w² (eq. (3))",
                "(rad/s)²",
                [
                    _format(fits[a].model.flicker_variance, fits[a].standard_errors["flicker_variance"])
                    for a in axes
                ],
            )
        )
        if args.flicker_d is None:
            lines.append(
                _row(
                    "1/f order d",
                    "—",
                    [_format(fits[a].model.flicker_d, fits[a].standard_errors["flicker_d"]) for a in axes],
                )
            )
    return lines


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
    """Parameters at a bound, and the axes whose χ² says the model misfits (p < 0.01)."""
    bounds = [f"{a}: {', '.join(fits[a].at_bound)}" for a in axes if fits[a].at_bound]
    lines = ["", f"Parameters held at zero: {'; '.join(bounds)}." if bounds else "No parameter at a bound."]
    misfits = [
        f"{a} (p = {fits[a].p_value:.2g}; scale its standard errors by about "
        f"{math.sqrt(fits[a].chi_square / fits[a].degrees_of_freedom):.2g})"
        for a in axes
        if fits[a].p_value < 0.01
    ]
    if misfits:
        lines.append(
            "The model does not explain every τ within the Allan variance's own uncertainty for "
            + ", ".join(misfits)
            + ": the standard errors above assume the model and are too small there."
        )
    return [*lines, ""]


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
    return [*lines, "", *_missing_axes_note(files, axes)]


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


def markdown_report(files: list[tuple[Any, dict[str, FitResult]]], args: argparse.Namespace) -> str:
    """The Table III-style report: one table per recording and a run-to-run consistency table."""
    lines = _report_header(files, args)
    axes = list(
        dict.fromkeys(name for _, fits in files for name in fits)
    )  # every axis of every run, in order
    for recording, fits in files:
        lines += [
            f"## {Path(recording.source).name}",
            "",
            f"{len(recording)} samples at {recording.sample_rate:g} Hz ({recording.duration / 3600:.3g} h).",
            "",
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
    if args.flicker_d is not None and "flicker" not in args.model:
        raise ValueError(
            f"--flicker-d={args.flicker_d!r}: only with 'flicker' in --model (got {args.model!r})"
        )


def run(args: argparse.Namespace) -> int:
    if args.iterations < 1:
        raise ValueError(f"--iterations={args.iterations!r}: must be >= 1")
    _check_fit_options(args)
    plan_outputs([(args.plot, "file"), (args.markdown, "file")], inputs=args.data)
    files = [_fit_file(path, args) for path in args.data]
    if args.plot:
        recording, fits = files[0]
        models = {name: (fit.allan.tau, fit.model_avar) for name, fit in fits.items()}
        plot_allan(
            args.plot,
            {name: fit.allan for name, fit in fits.items()},
            f"{Path(recording.source).name}: Allan deviation and fitted {'+'.join(args.model)} model",
            models,
        )
    if args.markdown:
        write_text_atomic(args.markdown, markdown_report(files, args))
    if args.json:
        document = {
            "files": [
                {
                    "source": recording.source,
                    "columns": {name: fit_as_json(fit) for name, fit in fits.items()},
                }
                for recording, fits in files
            ]
        }
        sys.stdout.write(strict_json(json_document("fit", document, FIT_NULL_REASONS)))
        return 0
    for recording, fits in files:
        print(f"{recording.source}: {len(recording)} samples at {recording.sample_rate:g} Hz")
        for name, fit in fits.items():
            print(
                f"  {name}: {fit.method}; χ² = {fit.chi_square:.3g} on {fit.degrees_of_freedom} "
                "degrees of freedom"
            )
            for key, value in {**fit.paper_units(), **fit.field_units()}.items():
                print(f"    {key:40s} {_format(*value)}")
            if fit.at_bound:
                print(f"    held at zero: {', '.join(fit.at_bound)}")
    for path in (args.plot, args.markdown):
        if path:
            print(f"wrote {path}")
    return 0
