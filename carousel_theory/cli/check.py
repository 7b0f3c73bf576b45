"""``carousel-theory check``: decide every claim of both papers and write paper_check.md/.json."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from carousel_theory.claims import all_claims
from carousel_theory.cli._files import write_or_compare
from carousel_theory.report import JSON_NAME, MARKDOWN_NAME, render_json, render_markdown, run_checks, summary


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser(
        "check",
        help="decide every claim of both papers; write paper_check.md and paper_check.json",
        description="Run the check of every claim of both papers and write paper_check.md (for people) "
        "and paper_check.json (for machines) into --out (default: the current directory).",
    )
    parser.add_argument(
        "--out", type=Path, default=Path("."), help="directory for the two files (default: .)"
    )
    parser.add_argument(
        "--check",
        action="store_true",
        help="write nothing; fail if either file would change or any claim's status regressed",
    )
    parser.add_argument("--only", metavar="PREFIX", help="check only the claims whose id starts with PREFIX")
    parser.set_defaults(handler=run)


def _regressions(previous_json: Path, checked: list) -> list[str]:
    if not previous_json.exists():
        return []
    before = {c["id"]: c["status"] for c in json.loads(previous_json.read_text(encoding="utf-8"))["claims"]}
    return [
        f"{item.claim.id}: {before[item.claim.id]} -> {item.verdict.status.value}"
        for item in checked
        if item.claim.id in before and before[item.claim.id] != item.verdict.status.value
    ]


def run(args: argparse.Namespace) -> int:
    claims = all_claims()
    if args.only is not None and not args.only.strip():
        raise ValueError(f"--only={args.only!r}: must be a non-empty claim-id prefix, e.g. TIM2014-eq18")
    if args.only:
        claims = [claim for claim in claims if claim.id.startswith(args.only)]
        if not claims:
            raise ValueError(f"--only={args.only!r}: no claim id starts with it")
    checked = run_checks(claims)
    print(summary(checked))
    failed = any(item.verdict.status.value == "failed" for item in checked)
    if args.only:  # a partial run never writes the full registry
        print(f"--only {args.only}: a partial run writes no file (paper_check.md and .json need every claim)")
        return 1 if failed else 0
    regressions = _regressions(args.out / JSON_NAME, checked) if args.check else []
    same_md = write_or_compare(args.out / MARKDOWN_NAME, render_markdown(checked), args.check)
    same_json = write_or_compare(args.out / JSON_NAME, render_json(checked), args.check)
    if regressions:
        print("status changed:\n  " + "\n  ".join(regressions))
    if args.check and not (same_md and same_json):
        print(f"{MARKDOWN_NAME}/{JSON_NAME} are out of date: run `carousel-theory check` and commit them")
    else:
        print(
            f"wrote {args.out / MARKDOWN_NAME} and {args.out / JSON_NAME}" if not args.check else "up to date"
        )
    return 1 if (failed or regressions or (args.check and not (same_md and same_json))) else 0
