"""HDF5 recordings (and MATLAB v7.3 ``.mat`` files, which are HDF5), read with h5py (the ``hdf5`` extra).

Every numeric dataset is a column, named by its path in the file (``imu/wx``), or by its own name when
all of them sit in one group. A compound dataset (a table with named numeric fields) gives one column
per field. A 2-D dataset of at most ``MAX_MATRIX_COLUMNS`` columns gives one column per column, named
``NAME[:,j]`` (j from 0); a MATLAB matrix is seen as MATLAB shows it (h5py sees it transposed), so
MATLAB's ``gyroBuffer(:,2)`` is ``gyroBuffer[:,1]`` here. Other datasets (text, references, higher
dimensions) are left out. The shapes of the datasets are read first: a file that declares more than
``max_values`` values is refused before any data are read. The file is opened read-only.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from carousel_theory.readers._common import check_values, is_matrix_shape, matrix_columns

__all__ = ["HDF5_INSTALL_HINT", "HDF5_SIGNATURE", "has_hdf5_signature", "import_h5py", "read_hdf5"]

HDF5_SIGNATURE = b"\x89HDF\r\n\x1a\n"
HDF5_INSTALL_HINT = 'pip install "carousel-theory[hdf5]"'
#: MATLAB classes read as numbers; "char", "cell", "struct" and the others are left out.
_MATLAB_NUMERIC = frozenset(
    ("double", "single", "logical", *(f"{sign}int{bits}" for sign in ("", "u") for bits in (8, 16, 32, 64)))
)
_MATLAB_INTERNAL = ("#refs#", "#subsystem#")


def import_h5py() -> Any:
    """The h5py module, or a one-line ``ModuleNotFoundError`` that says how to install it."""
    try:
        import h5py
    except ModuleNotFoundError:
        raise ModuleNotFoundError(
            f"reading HDF5 and MATLAB v7.3 files needs h5py: {HDF5_INSTALL_HINT}", name="h5py"
        ) from None
    return h5py


def has_hdf5_signature(path: Path) -> bool:
    """True when the HDF5 signature sits at byte 0 or after a user block (512, 1024, … bytes)."""
    with path.open("rb") as handle:
        for offset in (0, 512, 1024, 2048, 4096):
            handle.seek(offset)
            if handle.read(8) == HDF5_SIGNATURE:
                return True
    return False


def _numeric_datasets(handle: Any, matlab: bool) -> list[Any]:
    """The datasets that can hold columns, in the file's order."""
    h5py = import_h5py()
    found: list[Any] = []

    def visit(name: str, item: Any) -> None:
        if not isinstance(item, h5py.Dataset) or name.startswith(_MATLAB_INTERNAL):
            return
        if matlab:
            matlab_class = item.attrs.get("MATLAB_class", b"")
            matlab_class = matlab_class.decode() if isinstance(matlab_class, bytes) else str(matlab_class)
            if matlab_class not in _MATLAB_NUMERIC or "MATLAB_empty" in item.attrs:
                return
        kind = item.dtype.kind
        numeric = kind in "biufc" or (kind == "V" and item.dtype.names is not None)
        shape = tuple(reversed(item.shape)) if matlab else tuple(item.shape)
        if numeric and (shape == () or is_matrix_shape(shape)):
            found.append(item)

    handle.visititems(visit)
    return found


def _column_names(datasets: list[Any]) -> list[str]:
    paths = [dataset.name.lstrip("/") for dataset in datasets]
    parents = {path.rpartition("/")[0] for path in paths}
    return [path.rpartition("/")[2] for path in paths] if len(parents) == 1 else paths


def _dataset_columns(name: str, dataset: Any, matlab: bool) -> dict[str, np.ndarray]:
    values = np.asarray(dataset[()])
    if matlab:
        values = values.T
    if values.dtype.names is not None:  # a compound table: one column per numeric field
        return {
            field: np.asarray(values[field]).reshape(-1)
            for field in values.dtype.names
            if values.dtype[field].kind in "biufc"
        }
    return {name: values} if values.ndim == 0 else matrix_columns(name, values)


def read_hdf5(path: Path, max_values: int, *, matlab: bool = False) -> dict[str, np.ndarray]:
    """The columns of an HDF5 file (``matlab=True``: a MATLAB v7.3 file, matrices transposed back)."""
    h5py = import_h5py()
    if not has_hdf5_signature(path):
        with path.open("rb") as handle:
            start = handle.read(8)
        raise ValueError(f"{path}: not an HDF5 file (no HDF5 signature; the file starts with {start!r})")
    try:
        with h5py.File(path, "r") as handle:
            datasets = _numeric_datasets(handle, matlab)
            # A compound table holds one value per field and row.
            declared = sum(math.prod(d.shape) * len(d.dtype.names or (None,)) for d in datasets)
            check_values(declared, max_values, path, "its datasets declare")
            columns: dict[str, np.ndarray] = {}
            for name, dataset in zip(_column_names(datasets), datasets, strict=True):
                columns.update(_dataset_columns(name, dataset, matlab))
    except (OSError, KeyError, RuntimeError, ValueError, TypeError) as error:
        message = str(error).splitlines()[0] if str(error) else type(error).__name__
        if message.startswith(str(path)):
            raise
        raise ValueError(f"{path}: not a readable HDF5 file ({message})") from None
    if not columns:
        raise ValueError(f"{path}: no numeric datasets (columns) in the file")
    return columns
