"""``carousel-theory graycode``: verify every property of the Gray-code sequences of TIM 2014 §IV
for all orders n = 2 … N, without forming any 2^n × 2^n matrix."""

from __future__ import annotations

import argparse
import sys

from carousel_theory.graycode_properties import check_up_to
from carousel_theory.json_output import json_document, strict_json


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser(
        "graycode",
        help="verify the constant-Allan-variance Gray-code sequences (TIM 2014 §IV) for n = 2 … N",
        description="Check every property of TIM 2014 §IV (Algorithm 1, eq. (21)-(32), K Kᵀ, Kᵀ K, "
        "stationarity, overlapping Allan variance, bounds) for every order n = 2 … N in O(2^n n) time "
        "and memory per n, and print per property the largest n verified and the time taken.",
    )
    parser.add_argument(
        "--check-up-to",
        metavar="N",
        type=int,
        required=True,
        help="largest order n (sequences of length 2^n); the paper simulated up to 15",
    )
    parser.add_argument("--json", action="store_true", help="print the results as JSON")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    results = check_up_to(args.check_up_to)
    failed = any(result.first_failure is not None for result in results)
    if args.json:
        payload = {
            "up_to": args.check_up_to,
            "all_held": not failed,
            "properties": [
                {
                    "name": result.name,
                    "statement": result.statement,
                    "largest_n_verified": result.largest_verified,
                    "first_failure": result.first_failure,
                    "seconds": round(result.seconds, 3),
                    "units": {"seconds": "s"},
                }
                for result in results
            ],
        }
        sys.stdout.write(strict_json(json_document("graycode", payload), indent=2))
    else:
        width = max(len(result.name) for result in results)
        print(f"{'property':<{width}}  largest n  seconds  statement")
        for result in results:
            failure = "" if result.first_failure is None else f"  FAILED at n = {result.first_failure}"
            print(
                f"{result.name:<{width}}  {result.largest_verified:>9}  {result.seconds:>7.2f}  "
                f"{result.statement}{failure}"
            )
        total = sum(result.seconds for result in results)
        verdict = "a property FAILED" if failed else f"all held for n = 2 … {args.check_up_to}"
        print(f"total {total:.2f} s; {verdict}")
    return 1 if failed else 0
