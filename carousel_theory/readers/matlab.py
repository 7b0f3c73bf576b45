"""MATLAB ``.mat`` recordings: v4/v5/v7 through ``scipy.io.loadmat``, v7.3 (HDF5) through h5py.

Each numeric variable is a column: a vector (n × 1 or 1 × n) under its own name, a matrix of at most
``MAX_MATRIX_COLUMNS`` columns as ``NAME[:,j]`` (j from 0: MATLAB's ``gyroBuffer(:,2)`` is
``gyroBuffer[:,1]``). Text, cell arrays and structs are left out. The variables' shapes are listed first
(``scipy.io.whosmat``; the HDF5 headers for v7.3): a file that declares more than ``max_values`` values
is refused before its data are expanded. The file is opened read-only.
"""

from __future__ import annotations

import math
import zlib
from pathlib import Path

import numpy as np

from carousel_theory.readers._common import check_values, is_matrix_shape, matrix_columns
from carousel_theory.readers.hdf5 import read_hdf5

__all__ = ["read_matlab"]

_NUMERIC_CLASSES = frozenset(
    ("double", "single", "logical", *(f"{sign}int{bits}" for sign in ("", "u") for bits in (8, 16, 32, 64)))
)


def _read_errors() -> tuple[type[BaseException], ...]:
    """What a damaged MAT file makes scipy.io raise (scipy.io is imported only when a .mat file is
    read: it costs about a fifth of a second, every command that reads a recording would pay it)."""
    from scipy.io.matlab import MatReadError

    return (
        MatReadError,
        ValueError,
        OSError,
        TypeError,
        EOFError,
        IndexError,
        KeyError,
        zlib.error,
        NotImplementedError,
    )


def _version(path: Path) -> int:
    """The MAT-file major version as scipy.io names it: 0 (v4), 1 (v5/v7) or 2 (v7.3, HDF5)."""
    from scipy.io.matlab import matfile_version

    try:
        with path.open("rb") as handle:
            major, _ = matfile_version(handle)
    except _read_errors() as error:
        raise ValueError(f"{path}: not a MATLAB .mat file ({str(error).splitlines()[0]})") from None
    return int(major)


def read_matlab(path: Path, max_values: int) -> dict[str, np.ndarray]:
    """The columns of a MATLAB ``.mat`` file."""
    if _version(path) == 2:
        return read_hdf5(path, max_values, matlab=True)
    from scipy.io import loadmat, whosmat

    try:
        listed = whosmat(path)
        usable = [
            (name, shape)
            for name, shape, matlab_class in listed
            if matlab_class in _NUMERIC_CLASSES and is_matrix_shape(tuple(shape)) and math.prod(shape) > 0
        ]
        check_values(sum(math.prod(shape) for _, shape in usable), max_values, path, "its variables declare")
        if not usable:
            raise ValueError(
                f"{path}: no numeric vector or matrix among its variables "
                f"{[(name, matlab_class) for name, _, matlab_class in listed]}"
            )
        loaded = loadmat(path, variable_names=[name for name, _ in usable], squeeze_me=False)
    except _read_errors() as error:
        message = str(error).splitlines()[0] if str(error) else type(error).__name__
        if message.startswith(str(path)):
            raise
        raise ValueError(f"{path}: not a readable MATLAB .mat file ({message})") from None
    columns: dict[str, np.ndarray] = {}
    for name, _ in usable:
        columns.update(matrix_columns(name, loaded[name]))
    return columns
