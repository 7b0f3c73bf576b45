"""``carousel-theory formula``: list the named closed forms, or evaluate one exactly or at any precision.

    carousel-theory formula --list [--json]
    carousel-theory formula NAME --set KEY=VALUE ... [--exact | --digits D] [--json]

Values given to ``--set`` are read exactly: integers (``200``, ``1e6``), fractions (``1/2``) and
decimals (``0.3`` is 3/10, not the nearest float). Without ``--exact`` the command prints the
exact value (when the formula has a closed form) and the value to ``--digits`` significant digits
(default 50, the package's working precision for checks). With ``--json`` it prints the document
``carousel-theory/formula`` (docs/schemas/formula.schema.json): the version header, ``name``,
``parameters`` (strings), ``exact`` (SymPy string, or null), ``value`` (decimal string with ``digits``
significant digits), ``digits``, ``source``; ``--list --json`` prints ``carousel-theory/formula-list``.

The 1/f entries have no closed form: their ``exact`` is null unless ``--exact`` is given (for
``flicker_average_var`` with rational d it is then computed in O(kN) exact rational arithmetic,
which grows quickly with kN; ``flicker_carousel_var`` has no exact form and ``--exact`` fails).

Evaluations whose estimated cost exceeds the budget of :mod:`carousel_theory.evaluation_cost`
(60 s, 4 GiB) are refused before any work with a one-line message naming the value, the rule and
the estimate; ``--force`` runs them anyway. Exact values and decimals longer than Python's
4300-digit int-string limit are printed in full.
"""

from __future__ import annotations

import argparse
import contextlib
import sys
from collections.abc import Iterator
from typing import Any

import mpmath
import sympy as sp

from carousel_theory.formulas import FORMULAS, PARAMETER_HELP, formula
from carousel_theory.json_output import json_document, strict_json

DEFAULT_DIGITS = 50


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser(
        "formula",
        help="list the named closed forms, or evaluate one exactly or at any precision",
        description="Evaluate a named closed form of the theory (σ² = 1, bins numbered from 1). "
        "Values for --set are read exactly: 200, 1e6, 1/2, 0.3 (= 3/10).",
    )
    parser.add_argument("name", nargs="?", metavar="NAME", help="formula name (see --list)")
    parser.add_argument("--list", action="store_true", help="list every formula with its parameters")
    parser.add_argument(
        "--set",
        action="append",
        default=[],
        metavar="KEY=VALUE",
        dest="assignments",
        help="a parameter value, e.g. --set N=200 --set rho=1/2 (repeat for each parameter)",
    )
    precision = parser.add_mutually_exclusive_group()
    precision.add_argument("--exact", action="store_true", help="print only the exact value (fail if none)")
    precision.add_argument(
        "--digits",
        type=int,
        default=DEFAULT_DIGITS,
        metavar="D",
        help=f"significant digits of the decimal value (default {DEFAULT_DIGITS})",
    )
    parser.add_argument("--json", action="store_true", help="print one JSON object instead of text")
    parser.add_argument(
        "--force",
        action="store_true",
        help="run an evaluation whose estimated cost exceeds the budget (60 s, 4 GiB) instead of refusing it",
    )
    parser.set_defaults(handler=run)


@contextlib.contextmanager
def unlimited_int_string_digits() -> Iterator[None]:
    """Lift Python's int-string conversion limit (4300 digits) while printing a computed value.

    The limit guards against quadratic-time parsing of untrusted text; the values printed here are
    the package's own results, whose size the evaluation budget already bounds.
    """
    previous = sys.get_int_max_str_digits()
    sys.set_int_max_str_digits(0)
    try:
        yield
    finally:
        sys.set_int_max_str_digits(previous)


def parse_exact_number(key: str, text: str) -> sp.Rational:
    """``200`` → 200, ``1/2`` → 1/2, ``0.3`` → 3/10, ``1e6`` → 10⁶; anything else is a ValueError."""
    try:
        value = sp.Rational(text.strip())
    except ZeroDivisionError:
        raise ValueError(f"--set {key}={text!r}: division by zero") from None
    except (TypeError, ValueError, SyntaxError):
        raise ValueError(
            f"--set {key}={text!r}: must be an integer, a fraction like 1/2 or a decimal like 0.3"
        ) from None
    return value


def parse_assignments(assignments: list[str]) -> dict[str, sp.Rational]:
    values: dict[str, sp.Rational] = {}
    for assignment in assignments:
        key, separator, text = assignment.partition("=")
        key = key.strip()
        if not separator or not key:
            raise ValueError(f"--set {assignment!r}: must have the form KEY=VALUE")
        if key in values:
            raise ValueError(f"--set {key}: given twice")
        values[key] = parse_exact_number(key, text)
    return values


def format_value(value: mpmath.mpf, digits: int) -> str:
    """A decimal string with ``digits`` significant digits (trailing zeros kept)."""
    return mpmath.nstr(value, digits, strip_zeros=False)


def _listing(as_json: bool) -> str:
    if as_json:
        entries = [
            {
                "name": entry.name,
                "parameters": list(entry.parameters),
                "closed_form": entry.expression is not None,
                "source": entry.source,
                "assumptions": entry.assumptions,
                "description": entry.description,
                "latex": entry.latex(),
            }
            for entry in FORMULAS.values()
        ]
        return strict_json(json_document("formula-list", {"formulas": entries}), indent=2).rstrip("\n")
    width = max(len(name) for name in FORMULAS)
    lines = []
    for entry in FORMULAS.values():
        lines.append(f"{entry.name:<{width}}  ({', '.join(entry.parameters)})  {entry.source}")
        lines.append(f"{'':<{width}}  {entry.description}")
    lines.append("")
    lines.append("parameters: " + "; ".join(f"{key}: {text}" for key, text in PARAMETER_HELP.items()))
    return "\n".join(lines)


def _evaluate(args: argparse.Namespace) -> tuple[Any, dict[str, sp.Rational], sp.Expr | None, str, int]:
    """The entry, the parsed values, the exact value (or None), the decimal string and its digits."""
    entry = formula(args.name)
    values = parse_assignments(args.assignments)
    digits = args.digits
    if digits < 1:
        raise ValueError(f"--digits={digits}: must be an integer >= 1")
    exact: sp.Expr | None = None
    if entry.expression is not None or args.exact:
        exact = entry.exact(force=args.force, **values)  # raises ValueError when no exact form exists
    if args.exact:
        assert exact is not None
        decimal = sp.Float(sp.N(exact, DEFAULT_DIGITS + 10), DEFAULT_DIGITS + 10)
        with mpmath.workdps(DEFAULT_DIGITS + 10):  # the mpf must carry the digits it is printed with
            return (
                entry,
                values,
                exact,
                format_value(mpmath.mpf(decimal._mpf_), DEFAULT_DIGITS),
                DEFAULT_DIGITS,
            )
    with mpmath.workdps(digits):
        value = format_value(entry.evaluate(digits=digits, force=args.force, **values), digits)
    return entry, values, exact, value, digits


def run(args: argparse.Namespace) -> int:
    if args.list:
        if args.name or args.assignments:
            raise ValueError("--list takes no NAME and no --set")
        print(_listing(args.json))
        return 0
    if not args.name:
        raise ValueError("NAME is required (or --list); see `carousel-theory formula --list`")
    entry, values, exact, value, digits = _evaluate(args)
    with unlimited_int_string_digits():
        _print_result(args, entry, values, exact, value, digits)
    return 0


def _print_result(
    args: argparse.Namespace, entry: Any, values: dict[str, sp.Rational], exact: Any, value: str, digits: int
) -> None:
    if args.json:
        result: dict[str, Any] = {
            "name": entry.name,
            "parameters": {key: str(values[key]) for key in entry.parameters},
            "exact": None if exact is None else str(exact),
            "value": value,
            "digits": digits,
            "source": entry.source,
        }
        sys.stdout.write(strict_json(json_document("formula", result), indent=None))
        return
    call = f"{entry.name}({', '.join(f'{key}={values[key]}' for key in entry.parameters)})"
    if exact is not None:
        print(f"{call} = {exact}")
    if not args.exact:
        print(f"{call} ≈ {value}")
