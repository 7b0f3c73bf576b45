"""Which files a fleet holds, and the content hash that keys their results."""

from __future__ import annotations

import glob
import hashlib
from collections.abc import Sequence
from pathlib import Path

from carousel_theory.readers import SUFFIXES

__all__ = ["RECORDING_SUFFIXES", "content_hash", "discover_recordings"]

#: Extensions read as recordings (those of :func:`carousel_theory.data.load_recording`).
RECORDING_SUFFIXES = tuple(SUFFIXES)
_HASH_BLOCK = 1 << 20


def _directory_files(directory: Path) -> list[Path]:
    return [
        path
        for path in directory.rglob("*")
        if path.is_file() and path.suffix.lower() in RECORDING_SUFFIXES and not path.name.startswith(".")
    ]


def _expand(pattern: str) -> list[Path]:
    path = Path(pattern)
    if path.is_dir():
        return _directory_files(path)
    if path.is_file():
        return [path]
    if glob.has_magic(pattern):
        found = [Path(name) for name in glob.glob(pattern, recursive=True)]
        files = [p for p in found if p.is_file() and p.suffix.lower() in RECORDING_SUFFIXES]
        for directory in (p for p in found if p.is_dir()):
            files += _directory_files(directory)
        return files
    raise FileNotFoundError(f"{pattern}: no such file, directory or matching glob")


def discover_recordings(inputs: Sequence[str]) -> list[Path]:
    """Files, directories (searched recursively for .csv, .npz and .txt) and globs (``**`` allowed) to a
    sorted list of distinct recording files, as absolute paths.

    A file named explicitly is taken whatever its extension (the task then says what is wrong with it); a
    name that is neither a file, a directory nor a glob that matches raises FileNotFoundError, and so
    does a fleet with no recording at all.
    """
    if isinstance(inputs, str) or not inputs:
        raise ValueError(f"inputs={inputs!r}: must be a non-empty list of files, directories or globs")
    found: set[Path] = set()
    for pattern in inputs:
        found.update(path.resolve() for path in _expand(str(pattern)))
    if not found:
        raise FileNotFoundError(
            f"inputs={list(inputs)!r}: no recording ({', '.join(RECORDING_SUFFIXES)}) found"
        )
    return sorted(found)


def content_hash(path: str | Path) -> str:
    """SHA-256 of the file's bytes, hex: results are keyed by content, so a changed file is recomputed
    and a renamed or copied one is not. The file is only read."""
    digest = hashlib.sha256()
    with Path(path).open("rb") as handle:
        while block := handle.read(_HASH_BLOCK):
            digest.update(block)
    return digest.hexdigest()
