"""``carousel-theory derive``: regenerate derivations/*.md from SymPy."""

from __future__ import annotations

import argparse
from pathlib import Path

from carousel_theory.cli._files import write_or_compare
from carousel_theory.derivations import all_documents
from carousel_theory.output_files import plan_outputs
from carousel_theory.progress import progress


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser(
        "derive",
        help="regenerate the derivation documents (derivations/*.md) from SymPy",
        description="Derive every closed form with SymPy and write one markdown document per section.",
    )
    parser.add_argument(
        "--out", type=Path, default=Path("derivations"), help="directory (default: derivations)"
    )
    parser.add_argument(
        "--check", action="store_true", help="write nothing; fail if any document would change"
    )
    parser.add_argument("--only", metavar="NAME", help="only the document with this name")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    documents = all_documents()
    if args.only:
        documents = [d for d in documents if d.name == args.only]
        if not documents:
            names = ", ".join(d.name for d in all_documents())
            raise ValueError(f"--only={args.only!r}: no such document (have: {names})")
    if not args.check:
        plan_outputs([(args.out, "directory"), *((args.out / f"{d.name}.md", "file") for d in documents)])
    unchanged = True
    for document in progress(documents, label="deriving"):
        same = write_or_compare(args.out / f"{document.name}.md", document.render(), args.check)
        unchanged = unchanged and same
    if args.check:
        print(
            "derivations up to date" if unchanged else "derivations out of date: run `carousel-theory derive`"
        )
        return 0 if unchanged else 1
    print(f"wrote {len(documents)} documents to {args.out}")
    return 0
