"""File readers: each turns a recording file into named columns, checked and bounded, never modified.

==================  ===========================================================================
extension           reader
==================  ===========================================================================
.csv .txt .tsv      :func:`~carousel_theory.readers.text.read_text` (comma, semicolon, tab or
                    whitespace separated, with a header row)
.npz                :func:`~carousel_theory.readers.npz.read_npz`
.h5 .hdf5 .hdf      :func:`~carousel_theory.readers.hdf5.read_hdf5` (h5py, the ``hdf5`` extra)
.mat                :func:`~carousel_theory.readers.matlab.read_matlab` (v4–v7 by scipy.io, v7.3 by h5py)
==================  ===========================================================================

Every reader refuses, before it expands anything, a file that declares (or, for text, already holds)
more than ``max_values`` values, and names the row, column or member where a file goes wrong.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from carousel_theory.readers._common import MAX_VALUES
from carousel_theory.readers.hdf5 import read_hdf5
from carousel_theory.readers.matlab import read_matlab
from carousel_theory.readers.npz import read_npz
from carousel_theory.readers.text import DELIMITERS, check_delimiter, read_text

__all__ = ["DELIMITERS", "MAX_VALUES", "SUFFIXES", "read_table"]

#: Extensions (lower case) and the format read for each.
SUFFIXES = {
    ".csv": "text",
    ".txt": "text",
    ".tsv": "text",
    ".npz": "npz",
    ".h5": "hdf5",
    ".hdf5": "hdf5",
    ".hdf": "hdf5",
    ".mat": "matlab",
}


def read_table(path: Path, max_values: int, delimiter: str = "auto") -> dict[str, np.ndarray]:
    """The columns of a recording file, by its extension (see the module text)."""
    delimiter = check_delimiter(delimiter)
    if not path.exists():
        raise FileNotFoundError(f"{path}: no such file")
    if path.is_dir():
        raise ValueError(f"{path}: is a directory, not a recording file")
    if path.stat().st_size == 0:
        raise ValueError(f"{path}: empty file")
    kind = SUFFIXES.get(path.suffix.lower())
    if kind is None:
        raise ValueError(
            f"{path}: unknown extension {path.suffix!r}; must be one of {', '.join(sorted(SUFFIXES))}"
        )
    if kind != "text" and delimiter != "auto":
        raise ValueError(f"delimiter={delimiter!r}: applies to text files, not to {path.suffix} files")
    if kind == "npz":
        return read_npz(path, max_values)
    if kind == "hdf5":
        return read_hdf5(path, max_values)
    if kind == "matlab":
        return read_matlab(path, max_values)
    return read_text(path, max_values, delimiter)
