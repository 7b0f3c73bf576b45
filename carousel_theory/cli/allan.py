"""``carousel-theory allan``: Allan variance of each gyro column of a recording, with confidence intervals."""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path
from typing import Any

import numpy as np

from carousel_theory.allan import ESTIMATORS, NOISE_TYPES, AllanResult, allan_variance
from carousel_theory.cli._recording_options import add_recording_options
from carousel_theory.data import Recording, load_recording
from carousel_theory.json_output import json_document, strict_json
from carousel_theory.output_files import atomic_output, plan_outputs
from carousel_theory.progress import progress


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
    return load_recording(
        path,
        columns=columns,
        sample_rate=args.sample_rate,
        units=args.units,
        time_unit=args.time_unit,
        max_values=args.max_values,
    )


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
    parser.add_argument("data", type=Path, metavar="DATA", help="recording (.csv or .npz)")
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
    parser.set_defaults(handler=run)


def result_as_json(result: AllanResult) -> dict[str, Any]:
    """The per-column JSON record: tau (s), avar, ci_low, ci_high, edf, clusters."""
    return {
        "tau": result.tau.tolist(),
        "avar": result.avar.tolist(),
        "ci_low": result.ci_low.tolist(),
        "ci_high": result.ci_high.tolist(),
        "edf": None if result.edf is None else result.edf.tolist(),
        "clusters": result.clusters.tolist(),
    }


def plot_allan(
    path: Path,
    results: dict[str, AllanResult],
    title: str,
    models: dict[str, tuple[np.ndarray, np.ndarray]] | None = None,
) -> None:
    """Log-log Allan deviation with its intervals per column, and model curves (τ, AVAR) when given."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(figsize=(7.5, 5.0), layout="constrained")
    for index, (name, result) in enumerate(results.items()):
        colour = f"C{index}"
        deviation = np.sqrt(result.avar)
        below = deviation - np.sqrt(result.ci_low)
        above = np.sqrt(result.ci_high) - deviation
        axes.errorbar(
            result.tau,
            deviation,
            yerr=[below, above],
            fmt="o",
            ms=3.5,
            capsize=2.5,
            color=colour,
            label=f"{name} ({result.estimator}, {100 * result.confidence:g} % interval)",
        )
        if models and name in models:
            tau, avar = models[name]
            axes.plot(tau, np.sqrt(avar), "-", color=colour, lw=1.3, label=f"{name} fitted model")
    axes.set_xscale("log")
    axes.set_yscale("log")
    axes.set_xlabel("averaging time τ (s)")
    axes.set_ylabel("Allan deviation σ_A(τ) (rad/s)")
    axes.set_title(title, fontsize=10)
    axes.grid(True, which="both", alpha=0.3)
    axes.legend(fontsize=8)
    with atomic_output(path) as temporary:
        figure.savefig(temporary, dpi=120, format=Path(path).suffix.lstrip(".") or "png")
    plt.close(figure)


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
        plot_allan(args.plot, results, f"{recording.source}: Allan deviation")
    if args.json:
        document = {
            "source": recording.source,
            "sample_rate": recording.sample_rate,
            "samples": len(recording),
            "estimator": args.estimator,
            "noise": args.noise,
            "confidence": args.confidence,
            "columns": {name: result_as_json(result) for name, result in results.items()},
        }
        sys.stdout.write(strict_json(json_document("allan", document)))
        return 0
    print(
        f"{recording.source}: {len(recording)} samples at {recording.sample_rate:g} Hz, "
        f"{args.estimator} estimator"
    )
    for name, result in results.items():
        degrees = np.asarray(result.edf)
        print(f"\n{name}: τ (s), Allan deviation (rad/s), {100 * args.confidence:g} % interval, EDF")
        for i in range(len(result.tau)):
            print(
                f"  {result.tau[i]:12.6g}  {math.sqrt(result.avar[i]):12.5e}  "
                f"[{math.sqrt(result.ci_low[i]):11.4e}, {math.sqrt(result.ci_high[i]):11.4e}]  "
                f"{degrees[i]:10.4g}"
            )
    if args.plot:
        print(f"\nwrote {args.plot}")
    return 0
