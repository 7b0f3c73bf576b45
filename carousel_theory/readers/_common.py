"""What every recording reader shares: the memory bound, the refusal that names it, and column splitting."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

__all__ = [
    "MAX_MATRIX_COLUMNS",
    "MAX_VALUES",
    "check_values",
    "is_matrix_shape",
    "looks_numeric",
    "matrix_columns",
]

#: Most values (all columns together) a reader expands into memory unless the caller raises the limit
#: (``max_values=``, ``--max-values``): 10⁹ values are 8 GB as float64, 12 h at 1 kHz of 23 columns.
MAX_VALUES = 10**9
#: A 2-D dataset or MATLAB variable with at most this many columns (and more rows) is read as that many
#: columns, named ``NAME[:,j]`` (j from 0); a wider one is not a table of channels and is skipped.
MAX_MATRIX_COLUMNS = 64


def check_values(values: int, max_values: int, path: Path, what: str) -> None:
    """Refuse, before expanding them, more values than ``max_values``."""
    if values > max_values:
        raise ValueError(
            f"{path}: {what} {values} values ({values * 8 / 1e9:.3g} GB as float64), more than "
            f"max_values={max_values} (the default {MAX_VALUES} is 8 GB); raise max_values "
            "(--max-values) if the machine has the memory"
        )


def looks_numeric(text: str) -> bool:
    """True when ``text`` parses as a float."""
    try:
        float(text)
    except ValueError:
        return False
    return True


def is_matrix_shape(shape: tuple[int, ...]) -> bool:
    """A vector, or a 2-D table of at most ``MAX_MATRIX_COLUMNS`` channels (one per column)."""
    if len(shape) == 1:
        return True
    if len(shape) != 2:
        return False
    rows, columns = shape
    return min(rows, columns) == 1 or (columns <= MAX_MATRIX_COLUMNS and rows > columns)


def matrix_columns(name: str, array: Any) -> dict[str, np.ndarray]:
    """A vector as one column ``name``; an n × k table (k ≤ ``MAX_MATRIX_COLUMNS``) as ``name[:,j]``.

    A 1 × n or n × 1 matrix (MATLAB's vectors) is a vector. Anything else is left out: ``{}``.
    """
    array = np.asarray(array)
    if array.ndim == 1:
        return {name: array}
    if array.ndim == 2 and min(array.shape) == 1:
        return {name: array.reshape(-1)}
    if array.ndim == 2 and is_matrix_shape(array.shape):
        return {f"{name}[:,{j}]": np.ascontiguousarray(array[:, j]) for j in range(array.shape[1])}
    return {}
