"""``carousel-theory export``: the formula registry as JSON, LaTeX, Python or C source."""

from __future__ import annotations

import argparse
from pathlib import Path

from carousel_theory.cli._files import write_or_compare
from carousel_theory.export import FORMATS, export_formulas


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser(
        "export",
        help="export the formula registry as JSON, LaTeX, Python or C source",
        description="Print every closed form of the formula registry with SymPy's printers (JSON, LaTeX, "
        "Python, C). Entries without a closed form (1/f noise) are listed as documented omissions.",
    )
    parser.add_argument("--format", required=True, choices=sorted(FORMATS), help="output format")
    parser.add_argument("-o", "--output", type=Path, help="write to this file instead of standard output")
    parser.add_argument(
        "--check", action="store_true", help="with -o: write nothing; fail if the file would change"
    )
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    if args.check and args.output is None:
        raise ValueError("--check needs -o FILE (the file to compare with)")
    text = export_formulas(args.format)
    if args.output is None:
        print(text, end="")
        return 0
    if args.output.is_dir():
        raise IsADirectoryError(f"-o {args.output}: is a directory; give a file name")
    same = write_or_compare(args.output, text, args.check)
    if args.check:
        print(f"{args.output} up to date" if same else f"{args.output} out of date: rerun without --check")
        return 0 if same else 1
    print(f"wrote {args.output}")
    return 0
