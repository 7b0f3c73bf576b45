"""``carousel-theory loop``: fit, predict, find the missing effect, add it, report the error before/after."""

from __future__ import annotations

import argparse
from pathlib import Path

from carousel_theory.cli._recording_options import add_recording_options
from carousel_theory.closed_loop import DEFAULT_ALPHA, run_loop, write_report
from carousel_theory.closed_loop.report import REPORT_FILES
from carousel_theory.data import load_recording
from carousel_theory.json_output import json_document, strict_json
from carousel_theory.output_files import plan_outputs, write_text_atomic


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
    parser.add_argument("data", type=Path, metavar="DATA", help="recording (.csv or .npz)")
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
    parser.set_defaults(handler=run)


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
        time_unit=args.time_unit,
        max_values=args.max_values,
    )
    result = run_loop(
        recording, samples_per_revolution=args.samples_per_revolution, axes=axes, alpha=args.alpha
    )
    print(f"{result.source}: effects {', '.join(result.effects)}")
    print(f"{result.metric}: {result.error_before:.4g} before, {result.error_after:.4g} after")
    for note in result.observations:
        print(f"note: {note}")
    if args.json is not None:
        write_text_atomic(args.json, strict_json(json_document("loop", result.as_dict())))
        print(f"wrote {args.json}")
    if args.report is not None:
        written = write_report(result, args.report)
        print(f"wrote {', '.join(written)} to {args.report}")
    return 0
