"""Command-line options for reading a recording, shared by the commands that take DATA."""

from __future__ import annotations

import argparse
from typing import Any

from carousel_theory.data import DELIMITERS, MAX_VALUES, TIME_UNITS
from carousel_theory.units import RATE_UNITS

__all__ = [
    "add_reader_options",
    "add_recording_options",
    "column_mapping",
    "reader_keywords",
    "reader_options_given",
    "resample_rate",
]


def resample_rate(text: str) -> float | str:
    """Parse one ``--resample`` value: a positive rate in Hz, or ``auto``."""
    if text == "auto":
        return text
    try:
        rate = float(text)
    except ValueError:
        rate = float("nan")
    if not (rate > 0 and rate != float("inf")):
        raise argparse.ArgumentTypeError(f"{text!r}: must be a positive rate in Hz or 'auto'")
    return rate


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
    """``--time-unit``, ``--max-values``, ``--resample`` and ``--delimiter``, the options every command
    that reads a recording takes."""
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
    parser.add_argument(
        "--resample",
        type=resample_rate,
        metavar="HZ",
        help="average irregularly timed samples onto a uniform grid of HZ (bin means; 'auto': the highest "
        "mean rate / 2^k whose empty bins can be bridged); gaps are refused with their time",
    )
    parser.add_argument(
        "--delimiter",
        choices=("auto", *DELIMITERS),
        default="auto",
        help="separator of a text file (default auto: read from the header row)",
    )


def reader_keywords(args: argparse.Namespace) -> dict[str, Any]:
    """The keywords of :func:`carousel_theory.data.load_recording` that :func:`add_reader_options` sets."""
    return {
        "time_unit": args.time_unit,
        "max_values": args.max_values,
        "resample": args.resample,
        "delimiter": args.delimiter,
    }


def reader_options_given(args: argparse.Namespace) -> list[str]:
    """The options of :func:`add_reader_options` given with other than their default values."""
    defaults = {"time_unit": None, "max_values": MAX_VALUES, "resample": None, "delimiter": "auto"}
    return [
        f"--{name.replace('_', '-')}"
        for name, value in reader_keywords(args).items()
        if value != defaults[name]
    ]
