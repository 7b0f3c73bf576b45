"""``carousel-theory figures``: regenerate the papers' simulation figures as PNG."""

from __future__ import annotations

import argparse
from pathlib import Path

from carousel_theory.cli._arguments import seed
from carousel_theory.figures import DEFAULT_REALISATIONS, DEFAULT_SEED, FIGURES, write_figures
from carousel_theory.output_files import plan_outputs


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser(
        "figures",
        help="regenerate the papers' simulation figures (TIM 2014 Figs. 2-5, SJ 2012 Fig. 2) as PNG",
        description="Draw TIM 2014 Figs. 2-5 and SJ 2012 Fig. 2 with the exact theory over a seeded Monte "
        "Carlo and write them as PNG files. Needs matplotlib (the 'plots' extra).",
    )
    parser.add_argument(
        "--out", type=Path, default=Path("docs/figures"), help="output directory (default: docs/figures)"
    )
    parser.add_argument(
        "--realisations",
        type=int,
        default=DEFAULT_REALISATIONS,
        help=f"Monte Carlo realisations for Figs. 4 and 5 (default: {DEFAULT_REALISATIONS}, as in TIM 2014; "
        "a run estimated over 60 s needs --force)",
    )
    parser.add_argument(
        "--seed", type=seed, default=DEFAULT_SEED, help=f"random seed (default: {DEFAULT_SEED})"
    )
    parser.add_argument(
        "--only", nargs="+", metavar="NAME", choices=sorted(FIGURES), help="only these figures"
    )
    parser.add_argument(
        "--force",
        action="store_true",
        help="run a Monte Carlo whose estimated time exceeds the budget (60 s) instead of refusing it",
    )
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    try:
        import matplotlib  # noqa: F401
    except ImportError:  # pragma: no cover - matplotlib is in the test extras
        raise ValueError("matplotlib is needed: pip install 'carousel-theory[plots]'") from None
    names = args.only or list(FIGURES)
    plan_outputs([(args.out, "directory"), *((args.out / FIGURES[name].file_name, "file") for name in names)])
    written = write_figures(
        args.out, realisations=args.realisations, seed=args.seed, only=args.only, force=args.force
    )
    for path in written:
        print(f"wrote {path}")
    return 0
