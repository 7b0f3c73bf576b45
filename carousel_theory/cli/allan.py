"""``carousel-theory allan``: Allan variance of each gyro column of a recording, with confidence intervals."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

import numpy as np

from carousel_theory.allan import ESTIMATORS, NOISE_TYPES, AllanResult, allan_variance
from carousel_theory.cli._fit_output import allan_record
from carousel_theory.cli._output_units import OutputUnits, add_output_units_option, output_units
from carousel_theory.cli._recording_options import add_recording_options, reader_keywords
from carousel_theory.data import Recording, load_recording
from carousel_theory.json_output import json_document, strict_json
from carousel_theory.output_files import plan_outputs
from carousel_theory.plots import plot_allan, short_title
from carousel_theory.progress import progress
from carousel_theory.signal_checks import check_recording_length


def add_recording_arguments(parser: argparse.ArgumentParser) -> None:
    """Options shared by ``allan`` and ``fit`` for reading a recording."""
    add_recording_options(
        parser,
        "map a column of the file: time=..., wx=..., wy=... (repeatable; default: t/time and w*/gyro*)",
    )
    parser.add_argument(
        "--estimator",
        default="overlapping",
        choices=ESTIMATORS,
        help="Allan variance estimator (default overlapping)",
    )
    parser.add_argument("--json", action="store_true", help="print the result as JSON on stdout")
    parser.add_argument("--plot", type=Path, metavar="FILE.png", help="write a log-log Allan deviation plot")


def read_recording(path: Path, args: argparse.Namespace) -> Recording:
    """Load DATA with the shared options; irregular timing is refused (the Allan variance needs a uniform
    sample rate)."""
    columns = dict(args.column) if args.column else None
    recording = load_recording(
        path,
        columns=columns,
        sample_rate=args.sample_rate,
        units=args.units,
        **reader_keywords(args),
    )
    for note in recording.notes:  # what --resample did, on stderr: stdout may be JSON
        print(f"note: {note}", file=sys.stderr)
    check_recording_length(recording)
    return recording


def _taus(text: str) -> Any:
    if text == "octave":
        return "octave"
    try:
        return np.array([float(value) for value in text.split(",")])
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r}: must be 'octave' or comma-separated seconds") from None


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser(
        "allan",
        help="Allan variance of each gyro column with chi-square confidence intervals",
        description=(
            "Compute the overlapping or non-overlapping (TIM 2014 eq. (20)) Allan variance of every gyro "
            "column of DATA (.csv with a header row, or .npz), at octave τ or given τ, with confidence "
            "intervals from the equivalent degrees of freedom of the assumed noise type. Rates are in rad/s, "
            "τ in s."
        ),
    )
    parser.add_argument(
        "data",
        type=Path,
        metavar="DATA",
        help="recording: text (.csv .txt .tsv), .npz, HDF5 (.h5) or MATLAB (.mat)",
    )
    add_recording_arguments(parser)
    parser.add_argument(
        "--taus", type=_taus, default="octave", help="'octave' (default) or comma-separated τ in s"
    )
    parser.add_argument(
        "--noise",
        default="white",
        choices=NOISE_TYPES,
        help="noise type behind the degrees of freedom (default white)",
    )
    parser.add_argument("--confidence", type=float, default=0.95, help="interval level (default 0.95)")
    add_output_units_option(parser)
    parser.set_defaults(handler=run)


def result_as_json(result: AllanResult) -> dict[str, Any]:
    """The per-column JSON record in rad/s: tau (s), avar, ci_low, ci_high, edf, clusters, units."""
    return allan_record(result, OutputUnits())


def _document(
    recording: Recording, results: dict[str, AllanResult], args: argparse.Namespace
) -> dict[str, Any]:
    return {
        "source": recording.source,
        "sample_rate": recording.sample_rate,
        "samples": len(recording),
        "estimator": args.estimator,
        "noise": args.noise,
        "confidence": args.confidence,
        "output_units": args.output_units,
        "columns": {name: allan_record(result, output_units(args)) for name, result in results.items()},
        "units": {"sample_rate": "Hz"},
    }


def _table_lines(name: str, result: AllanResult, args: argparse.Namespace) -> list[str]:
    """τ, the Allan deviation and its interval in ``--output-units``, and the EDF, one row per τ."""
    output = output_units(args)
    deviation, low, high = (output.rates(values) for values in (result.adev, *result.adev_interval))
    degrees = np.asarray(result.edf)
    lines = [
        f"\n{name}: τ (s), Allan deviation ({output.rate_label}), {100 * args.confidence:g} % interval "
        f"({output.rate_label}), EDF"
    ]
    for i in range(len(result.tau)):
        interval = f"[{low[i]:11.4e}, {high[i]:11.4e}]"
        lines.append(f"  {result.tau[i]:12.6g}  {deviation[i]:12.5e}  {interval}  {degrees[i]:10.4g}")
    return lines


def run(args: argparse.Namespace) -> int:
    if not (0 < args.confidence < 1):
        raise ValueError(f"--confidence={args.confidence!r}: must be in (0, 1)")
    plan_outputs([(args.plot, "file")], inputs=[args.data])
    recording = read_recording(args.data, args)
    results = {}
    for name, rates in progress(recording.rates.items(), len(recording.rates), "allan: axes"):
        results[name] = allan_variance(
            rates,
            recording.sample_rate,
            args.taus,
            estimator=args.estimator,
            noise=args.noise,
            confidence=args.confidence,
        )
    if args.plot:
        plot_allan(
            args.plot,
            results,
            short_title(recording.source, "Allan deviation"),
            output_units=args.output_units,
        )
    if args.json:
        sys.stdout.write(strict_json(json_document("allan", _document(recording, results, args))))
        return 0
    print(
        f"{recording.source}: {len(recording)} samples at {recording.sample_rate:g} Hz, "
        f"{args.estimator} estimator"
    )
    for name, result in results.items():
        print("\n".join(_table_lines(name, result, args)))
    if args.plot:
        print(f"\nwrote {args.plot}")
    return 0
