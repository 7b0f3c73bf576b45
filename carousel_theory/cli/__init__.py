"""The ``carousel-theory`` command.

Each module in this package (not starting with ``_``) defines ``register(subparsers)``, which
adds one sub-command whose parser has a ``handler(args) -> int`` default.

:func:`main` is the one error boundary of the command line: whatever a sub-command raises becomes one
line on stderr naming the command, the file or value and the rule, with exit status 2 for bad input and
1 for a failure (see :mod:`carousel_theory.cli._errors`); ``--debug`` shows the traceback of an
unforeseen error instead. A closed pipe (``carousel-theory … | head``) ends the command quietly.
"""

from __future__ import annotations

import argparse
import importlib
import pkgutil
import sys
from collections.abc import Sequence

from carousel_theory import __version__
from carousel_theory.cli._errors import report_error, silence_closed_pipe

__all__ = ["build_parser", "main"]


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="carousel-theory",
        description="Exact variance propagation of gyro error processes under averaging and carouseling.",
    )
    parser.add_argument("--version", action="version", version=f"carousel-theory {__version__}")
    parser.add_argument(
        "--debug", action="store_true", help="show the full traceback of an unforeseen error (any position)"
    )
    subparsers = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for module_info in sorted(pkgutil.iter_modules(__path__), key=lambda m: m.name):
        if not module_info.name.startswith("_"):
            importlib.import_module(f"{__name__}.{module_info.name}").register(subparsers)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    arguments = list(sys.argv[1:] if argv is None else argv)
    debug = "--debug" in arguments
    arguments = [argument for argument in arguments if argument != "--debug"]
    args = build_parser().parse_args(arguments)
    try:
        return int(args.handler(args))
    except BrokenPipeError:
        return silence_closed_pipe()
    except KeyboardInterrupt:
        print(f"carousel-theory {args.command}: interrupted", file=sys.stderr)
        return 130
    except Exception as error:  # the boundary: every error becomes one line (or a traceback with --debug)
        return report_error(args.command, error, debug=debug)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
