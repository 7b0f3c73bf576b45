"""``carousel-theory loop``: fit, predict, find the missing effect, add it, report the error before/after."""

from __future__ import annotations

import argparse
from dataclasses import replace
from pathlib import Path
from typing import Any

from carousel_theory.cli._output_units import OutputUnits, add_output_units_option, output_units
from carousel_theory.cli._recording_options import add_recording_options, reader_keywords
from carousel_theory.closed_loop import DEFAULT_ALPHA, run_loop, write_report
from carousel_theory.closed_loop.preparation import default_axes
from carousel_theory.closed_loop.report import REPORT_FILES
from carousel_theory.data import Recording, load_recording
from carousel_theory.json_output import json_document, strict_json
from carousel_theory.output_files import plan_outputs, write_text_atomic
from carousel_theory.units import from_deg_per_hour_per_sqrt_hour, from_deg_per_sqrt_hour


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser(
        "loop",
        help="closed loop on a static recording: residual -> missing effect -> extended model -> error "
        "before/after",
        description=(
            "Fit bias + white noise + rate random walk to each gyro axis, predict the variance of averaged "
            "and (virtually) carouselled bins and the Allan variance, test the catalogue of unmodelled "
            "effects, add the one the evidence supports, refit, and repeat until nothing significant "
            "remains. DATA is a CSV with a header holding at least t,wx,wy (s, rad/s), optionally temp (°C) "
            "and phi (rad), or an NPZ with the same keys."
        ),
    )
    parser.add_argument(
        "data",
        type=Path,
        metavar="DATA",
        help="recording: text (.csv .txt .tsv), .npz, HDF5 (.h5) or MATLAB (.mat)",
    )
    parser.add_argument(
        "--samples-per-revolution",
        "-N",
        type=int,
        default=200,
        metavar="N",
        help="samples per virtual revolution (default 200, as in TIM 2014 §V-C)",
    )
    parser.add_argument("--json", type=Path, metavar="OUT", help="write the result as JSON to this file")
    parser.add_argument(
        "--report", type=Path, metavar="DIR", help="write plots and summary.md into this directory"
    )
    add_recording_options(
        parser, "map a column: time=..., wx=..., wy=..., temperature=..., angle=... (repeatable)"
    )
    parser.add_argument("--axes", metavar="A[,B]", help="the gyro axes to analyse (default wx,wy)")
    parser.add_argument(
        "--alpha",
        type=float,
        default=DEFAULT_ALPHA,
        help="family-wise false-alarm rate of the whole run: every test of every iteration and the final "
        "Allan-variance misfit test (default 0.01)",
    )
    add_output_units_option(parser)
    parser.set_defaults(handler=run)


#: Units of the loop's JSON members by name (most names spell their unit; ``amplitude`` and ``height`` are
#: rate amplitudes of the fitted effects). A member not listed is dimensionless (z, χ², p, counts).
LOOP_UNITS = {
    "bias_rad_s": "rad/s",
    "white_variance_rad2_s2": "(rad/s)^2",
    "long_run_white_variance_rad2_s2": "(rad/s)^2",
    "rrw_variance_rad2_s2": "(rad/s)^2",
    "flicker_variance_rad2_s2": "(rad/s)^2",
    "long_run_white_variance": "(rad/s)^2",
    "white_variance": "(rad/s)^2",
    "rrw_variance": "(rad/s)^2",
    "flicker_variance": "(rad/s)^2",
    "angle_random_walk_deg_per_sqrt_h": "deg/sqrt(h)",
    "rate_random_walk_deg_per_h_per_sqrt_h": "deg/h/sqrt(h)",
    "amplitude": "rad/s",
    "height": "rad/s",
    "frequency_hz": "Hz",
    "phase_rad": "rad",
    "time_s": "s",
    "time_constant_s": "s",
    "coefficient_rad_s_per_degC": "rad/s/degC",
    "temperature_range_degC": "degC",
}


def with_units(value: Any) -> Any:
    """``value`` with a ``units`` map added to every object holding a member of :data:`LOOP_UNITS` (the
    JSON convention of the README)."""
    if isinstance(value, list):
        return [with_units(item) for item in value]
    if not isinstance(value, dict):
        return value
    result = {key: with_units(item) for key, item in value.items()}
    named = {key: LOOP_UNITS[key] for key, item in value.items() if key in LOOP_UNITS and item is not None}
    return {**result, "units": named} if named else result


def loop_document(result: Any, output: OutputUnits) -> dict[str, Any]:
    """``loop --json``: the loop's result with units named wherever a member has one (always SI: the
    names spell their units); the headline errors are standardized, without unit."""
    return {**with_units(result.as_dict()), "output_units": output.rate}


def model_lines(result: Any, output: OutputUnits) -> list[str]:
    """The final model per axis: bias in ``output``, ARW and RRW in °/√h and °/h/√h beside SI."""
    lines = []
    for axis, model in result.model_after.items():
        arw = model["angle_random_walk_deg_per_sqrt_h"]
        rrw = model["rate_random_walk_deg_per_h_per_sqrt_h"]
        lines.append(
            f"{axis}: bias {output.rates(model['bias_rad_s']):.4g} {output.rate_label}; "
            f"ARW {arw:.4g} °/√h ({from_deg_per_sqrt_hour(arw):.4g} rad/√s); "
            f"RRW {rrw:.4g} °/h/√h ({from_deg_per_hour_per_sqrt_hour(rrw):.4g} rad/s/√s)"
        )
    return lines


def analysed_only(recording: Recording, axes: tuple[str, ...] | None) -> Recording:
    """The recording without the gyro columns the loop does not analyse (a 12-hour recording at 1 kHz
    would hold 346 MB per column for the whole run); unchanged when an axis asked for is missing, so
    that the loop's own message names it."""
    wanted = default_axes(recording) if axes is None else axes
    if not set(wanted) <= set(recording.rates) or len(wanted) == len(recording.rates):
        return recording
    return replace(recording, rates={axis: recording.rates[axis] for axis in wanted})


def run(args: argparse.Namespace) -> int:
    columns = None
    if args.column:
        columns = {
            (
                "temperature"
                if ours == "temp"
                else "angle"
                if ours == "phi"
                else "time"
                if ours == "t"
                else ours
            ): theirs
            for ours, theirs in args.column
        }
    axes = None if args.axes is None else tuple(a.strip() for a in args.axes.split(",") if a.strip())
    if axes is not None and len(set(axes)) != len(axes):
        raise ValueError(f"--axes={args.axes!r}: names an axis twice; give each gyro axis once")
    report_files = [] if args.report is None else [args.report / name for name in REPORT_FILES]
    plan_outputs(
        [(args.json, "file"), (args.report, "directory"), *((path, "file") for path in report_files)],
        inputs=[args.data],
    )
    recording = load_recording(
        args.data,
        columns=columns,
        sample_rate=args.sample_rate,
        units=args.units,
        irregular="keep",
        **reader_keywords(args),
    )
    recording = analysed_only(recording, axes)  # the other columns are freed before the loop runs
    result = run_loop(
        recording, samples_per_revolution=args.samples_per_revolution, axes=axes, alpha=args.alpha
    )
    print(f"{result.source}: effects {', '.join(result.effects)}")
    print(f"{result.metric} (no unit): {result.error_before:.4g} before, {result.error_after:.4g} after")
    print("\n".join(model_lines(result, output_units(args))))
    for note in result.observations:
        print(f"note: {note}")
    if args.json is not None:
        document = json_document("loop", loop_document(result, output_units(args)))
        write_text_atomic(args.json, strict_json(document))
        print(f"wrote {args.json}")
    if args.report is not None:
        written = write_report(result, args.report, output_units=args.output_units)
        print(f"wrote {', '.join(written)} to {args.report}")
    return 0
