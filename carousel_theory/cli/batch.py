"""``carousel-theory batch``: a fleet of recordings on Dask, one table and one report out."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from carousel_theory.cli._recording_options import add_recording_options

if TYPE_CHECKING:  # the adapter imports the analyses: only when the command runs
    from carousel_theory.batch.tasks import TaskOptions

#: What to install when Dask or pyarrow is missing.
INSTALL_HINT = "python -m pip install 'carousel-theory[batch]'"
_BATCH_MODULES = ("dask", "distributed", "pyarrow")
_COLUMN_ALIASES = {"t": "time", "temp": "temperature", "phi": "angle"}


def _names(text: str) -> tuple[str, ...]:
    names = tuple(name.strip() for name in text.split(",") if name.strip())
    if not names:
        raise argparse.ArgumentTypeError(f"{text!r}: must be comma-separated names")
    return names


def _add_task_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--estimator", default="overlapping", help="allan, fit: Allan variance estimator")
    parser.add_argument(
        "--model", type=_names, default=("white", "rrw"), metavar="C[,C...]", help="fit: components"
    )
    parser.add_argument("--flicker-d", type=float, help="fit: fix the 1/f order d")
    parser.add_argument("--tau-min", type=float, help="fit: smallest τ (s) in the fit")
    parser.add_argument("--tau-max", type=float, help="fit: largest τ (s) in the fit")
    parser.add_argument(
        "--iterations", type=int, default=3, help="fit: covariance re-evaluations (default 3)"
    )
    parser.add_argument(
        "--samples-per-revolution",
        "-N",
        type=int,
        default=200,
        metavar="N",
        help="loop: samples per revolution",
    )
    parser.add_argument("--alpha", type=float, default=0.01, help="loop: false-alarm rate of each test")
    parser.add_argument("--axes", type=_names, metavar="A[,B]", help="loop: the gyro axes to analyse")
    parser.add_argument("--latitude", type=float, metavar="DEG", help="design: site latitude, degrees")
    parser.add_argument(
        "--duration", type=float, action="append", metavar="S", help="design: record length, s (repeatable)"
    )
    parser.add_argument(
        "--scheme", action="append", default=[], metavar="TEXT", help="design: a scheme (default: a sweep)"
    )


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser(
        "batch",
        help="run allan, fit or loop over a fleet of recordings on Dask; one table and a fleet report out",
        description=(
            "Run one analysis over many recordings on a Dask cluster: an embedded local cluster by default "
            "(--workers N), or an existing one with --scheduler ADDRESS. Writes OUT/results.parquet and "
            "OUT/results.csv (one row per recording and axis, with errors as rows) and OUT/report.md with "
            "distributions.png. Re-running with the same --out reuses the rows of unchanged files (keyed "
            f"by their content hash). Needs the batch extra: {INSTALL_HINT}."
        ),
    )
    parser.add_argument(
        "inputs", nargs="+", metavar="INPUT", help="files, directories or quoted globs ('lab/**/*.csv')"
    )
    parser.add_argument("--task", default="fit", help="allan, fit, loop or design (default fit)")
    parser.add_argument(
        "--out", type=Path, required=True, metavar="DIR", help="directory of the table and report"
    )
    parser.add_argument("--workers", type=int, help="local worker processes (default: one per core)")
    parser.add_argument(
        "--scheduler", metavar="ADDRESS", help="an existing Dask scheduler, e.g. tcp://head:8786"
    )
    parser.add_argument(
        "--task-timeout", type=float, metavar="SECONDS", help="error row for a task running longer"
    )
    parser.add_argument(
        "--per-axis", action="store_true", help="allan, fit: one task per axis (long records)"
    )
    parser.add_argument(
        "--no-dashboard", action="store_true", help="do not start the local cluster's dashboard"
    )
    add_recording_options(parser, "map a column: time=..., wx=..., temperature=..., angle=... (repeatable)")
    _add_task_options(parser)
    parser.set_defaults(handler=run)


def _options(args: argparse.Namespace) -> TaskOptions:
    from carousel_theory.batch.tasks import TaskOptions, check_options

    options = TaskOptions(
        columns=tuple((_COLUMN_ALIASES.get(ours, ours), theirs) for ours, theirs in args.column),
        units=args.units,
        sample_rate=args.sample_rate,
        time_unit=args.time_unit,
        max_values=args.max_values,
        estimator=args.estimator,
        model=args.model,
        flicker_d=args.flicker_d,
        tau_min=args.tau_min,
        tau_max=args.tau_max,
        iterations=args.iterations,
        samples_per_revolution=args.samples_per_revolution,
        alpha=args.alpha,
        loop_axes=args.axes,
        latitude=args.latitude,
        design_durations=tuple(args.duration or (3600.0,)),
        schemes=tuple(args.scheme),
    )
    check_options(args.task, options)
    return options


def run(args: argparse.Namespace) -> int:
    try:
        import pyarrow  # noqa: F401

        from carousel_theory.batch.cluster import connect
        from carousel_theory.batch.fleet import FleetJob, run_fleet
    except ModuleNotFoundError as error:
        if (error.name or "").partition(".")[0] not in _BATCH_MODULES:
            raise
        print(f"carousel-theory batch: error: needs Dask and pyarrow: {INSTALL_HINT}", file=sys.stderr)
        return 2
    from carousel_theory.batch.discovery import discover_recordings
    from carousel_theory.batch.report import write_report

    if args.out.exists() and not args.out.is_dir():
        raise ValueError(f"--out {args.out}: is a file; give a directory")
    job = FleetJob(
        paths=tuple(discover_recordings(args.inputs)),
        task=args.task,
        options=_options(args),
        out=args.out,
        per_axis=args.per_axis,
        task_timeout=args.task_timeout,
    )
    connection = connect(args.scheduler, args.workers, dashboard=not args.no_dashboard)
    try:
        outcome = run_fleet(connection.client, job)
    finally:
        connection.close()
    written = write_report(outcome.rows, args.out, args.task)
    failed = len({row.path for row in outcome.rows if row.status != "ok"})
    print(
        f"{len(job.paths)} recordings: {outcome.computed} computed, {outcome.reused} reused, "
        f"{failed} with an error; {outcome.wall_seconds:.1f} s"
    )
    names = [path.name for path in (*outcome.tables.values(), *written)]
    print(f"wrote {', '.join(names)} to {args.out}")
    return 0
