"""The README's quickstart is exactly two commands, and CI runs the second one verbatim."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def quickstart_commands() -> list[str]:
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    section = readme.split("## Quickstart", 1)[1]
    block = re.search(r"```bash\n(.*?)```", section, flags=re.S)
    assert block is not None, "the quickstart has no bash block"
    return [line for line in block.group(1).splitlines() if line.strip()]


def test_quickstart_is_two_commands_install_and_check_then_install_and_test():
    first, second = quickstart_commands()
    assert "pip install" in first and first.endswith("carousel-theory check")
    assert "pip install" in second and '".[test]"' in second and second.endswith("pytest")


def test_ci_runs_the_second_command_verbatim_and_refuses_an_empty_test_run():
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    assert quickstart_commands()[1] in ci.splitlines()
    assert re.search(r'"\$status" -eq 5', ci), "pytest's exit status 5 (no tests) must fail CI"
