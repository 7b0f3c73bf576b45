"""``carousel-theory export``: the formula registry as JSON, LaTeX, Python (NumPy) or C99 source.

``--format c -o DIR/NAME.c`` writes the source and its header ``DIR/NAME.h`` (which the source
includes); ``--format latex --fragment`` writes only the equations, for ``\\input``.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from carousel_theory.cli._files import write_or_compare
from carousel_theory.export import FORMATS, export_formulas
from carousel_theory.output_files import plan_outputs


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser(
        "export",
        help="export the formula registry as JSON, LaTeX, Python (NumPy) or C99 source",
        description="Print every closed form of the formula registry with SymPy's printers (JSON, LaTeX, "
        "Python with NumPy, C99 with its header). Entries without a closed form (1/f noise) are listed as "
        "documented omissions. With --format c and -o NAME.c, the header NAME.h is written beside it.",
    )
    parser.add_argument("--format", required=True, choices=sorted(FORMATS), help="output format")
    parser.add_argument(
        "--fragment",
        action="store_true",
        help="with --format latex: only the numbered equations (ASCII, amsmath), to \\input into a document",
    )
    parser.add_argument("-o", "--output", type=Path, help="write to this file instead of standard output")
    parser.add_argument(
        "--check", action="store_true", help="with -o: write nothing; fail if the file would change"
    )
    parser.set_defaults(handler=run)


def _header_path(args: argparse.Namespace) -> Path | None:
    """The C header written beside ``-o NAME.c`` (None for every other output)."""
    if args.format != "c" or args.output is None:
        return None
    header = args.output.with_suffix(FORMATS["c-header"])
    if header == args.output:
        raise ValueError(f"-o {args.output}: the C source needs a name not ending in .h (e.g. formulas.c)")
    return header


def _documents(args: argparse.Namespace, header: Path | None) -> list[tuple[Path | None, str]]:
    """(path, text) of every file the command writes (path None: standard output)."""
    if header is None:
        return [(args.output, export_formulas(args.format, fragment=args.fragment))]
    return [
        (args.output, export_formulas("c", header_name=header.name)),
        (header, export_formulas("c-header")),
    ]


def run(args: argparse.Namespace) -> int:
    if args.check and args.output is None:
        raise ValueError("--check needs -o FILE (the file to compare with)")
    if args.fragment and args.format != "latex":
        raise ValueError(f"--fragment: only with --format latex, not --format {args.format}")
    header = _header_path(args)
    if not args.check:
        plan_outputs([(args.output, "file"), (header, "file")])
    documents = _documents(args, header)
    if args.output is None:
        print(documents[0][1], end="")
        return 0
    stale = []
    for path, text in documents:
        assert path is not None
        same = write_or_compare(path, text, args.check)
        if args.check:
            print(f"{path} up to date" if same else f"{path} out of date: rerun without --check")
            stale += [] if same else [path]
        else:
            print(f"wrote {path}")
    return 1 if stale else 0
