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


def _command_names() -> list[str]:
    return sorted(m.name for m in pkgutil.iter_modules(__path__) if not m.name.startswith("_"))


def build_parser(command: str | None = None) -> argparse.ArgumentParser:
    """The parser of every sub-command, or only of ``command`` when it names one (a run imports only the
    modules its command needs, so it starts without the others' dependencies)."""
    parser = argparse.ArgumentParser(
        prog="carousel-theory",
        description="Exact variance propagation of gyro error processes under averaging and carouseling.",
    )
    parser.add_argument("--version", action="version", version=f"carousel-theory {__version__}")
    parser.add_argument(
        "--debug", action="store_true", help="show the full traceback of an unforeseen error (any position)"
    )
    subparsers = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    names = _command_names()
    for name in [command] if command in names else names:
        importlib.import_module(f"{__name__}.{name}").register(subparsers)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    arguments = list(sys.argv[1:] if argv is None else argv)
    debug = "--debug" in arguments
    arguments = [argument for argument in arguments if argument != "--debug"]
    command = next((argument for argument in arguments if not argument.startswith("-")), None)
    args = build_parser(command).parse_args(arguments)
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
