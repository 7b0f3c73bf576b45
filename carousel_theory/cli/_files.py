"""Writing generated files: only where the user said, and a ``--check`` mode that compares instead."""

from __future__ import annotations

import difflib
from pathlib import Path

__all__ = ["write_or_compare"]


def write_or_compare(path: Path, text: str, check: bool) -> bool:
    """Write ``text`` to ``path``; with ``check``, write nothing and return whether the file already
    holds exactly ``text`` (printing a short diff when it does not)."""
    if not check:
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
        return True
    if not path.exists():
        print(f"{path}: missing (regenerate it)")
        return False
    current = path.read_text(encoding="utf-8")
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
