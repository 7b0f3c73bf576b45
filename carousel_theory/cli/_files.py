"""Writing generated files: only where the user said, and a ``--check`` mode that compares instead."""

from __future__ import annotations

import difflib
from pathlib import Path

from carousel_theory.output_files import write_text_atomic

__all__ = ["write_or_compare"]


def write_or_compare(path: Path, text: str, check: bool) -> bool:
    """Write ``text`` to ``path``; with ``check``, write nothing and return whether the file already
    holds exactly ``text`` (printing a short diff when it does not).

    The file is written whole or not at all (a temporary file renamed over it, see
    :mod:`carousel_theory.output_files`); callers check their outputs with ``plan_outputs`` first.
    """
    if not check:
        write_text_atomic(path, text)
        return True
    if not path.is_file():
        print(f"{path}: missing (regenerate it)")
        return False
    current = path.read_text(encoding="utf-8", errors="replace")
    if current == text:
        return True
    diff = difflib.unified_diff(
        current.splitlines(),
        text.splitlines(),
        f"{path} (committed)",
        f"{path} (regenerated)",
        lineterm="",
        n=1,
    )
    print("\n".join(list(diff)[:40]))
    return False
