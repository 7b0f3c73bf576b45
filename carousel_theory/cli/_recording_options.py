"""Command-line options for reading a recording, shared by the commands that take DATA."""

from __future__ import annotations

import argparse

from carousel_theory.data import MAX_VALUES, TIME_UNITS
from carousel_theory.units import RATE_UNITS

__all__ = ["add_reader_options", "add_recording_options", "column_mapping"]


def column_mapping(text: str) -> tuple[str, str]:
    """Parse one ``--column OURS=THEIRS`` value."""
    ours, equals, theirs = text.partition("=")
    if not equals or not ours.strip() or not theirs.strip():
        raise argparse.ArgumentTypeError(f"{text!r}: must be OURS=THEIRS, e.g. wx=gyro_x or time=t_s")
    return ours.strip(), theirs.strip()


def add_recording_options(parser: argparse.ArgumentParser, column_help: str) -> None:
    """``--column``, ``--units``, ``--sample-rate``, ``--time-unit`` and ``--max-values``."""
    parser.add_argument(
        "--column", action="append", type=column_mapping, default=[], metavar="OURS=THEIRS", help=column_help
    )
    parser.add_argument("--units", default="rad/s", choices=tuple(RATE_UNITS), help="units of the rates")
    parser.add_argument(
        "--sample-rate", type=float, help="samples per second when the file has no time column"
    )
    add_reader_options(parser)


def add_reader_options(parser: argparse.ArgumentParser) -> None:
    """``--time-unit`` and ``--max-values``, the options every command that reads a recording takes."""
    parser.add_argument(
        "--time-unit",
        choices=tuple(TIME_UNITS),
        help="unit of a numeric time column (default s; e.g. ms for epoch milliseconds); "
        "datetime64 columns carry their own",
    )
    parser.add_argument(
        "--max-values",
        type=int,
        default=MAX_VALUES,
        help=f"refuse a file of more values, all columns together (default {MAX_VALUES:.0e}, "
        "8 GB as float64)",
    )
