"""NPZ recordings (``numpy.savez`` / ``savez_compressed``): one member per column.

An NPZ written without compression is memory-mapped, read-only: its arrays are paged in as the
analysis touches them. A compressed NPZ is decompressed into memory. The headers of all members are
read first: a file whose headers declare more than ``max_values`` values, or whose zip directory states
an uncompressed size other than the header's shape implies, is refused before anything is expanded.
"""

from __future__ import annotations

import math
import zipfile
from pathlib import Path
from typing import Any

import numpy as np

from carousel_theory.readers._common import check_values

__all__ = ["read_npz"]


def read_npz(path: Path, max_values: int) -> dict[str, np.ndarray]:
    with path.open("rb") as handle:
        magic = handle.read(4)
    if magic != b"PK\x03\x04":
        raise ValueError(f"{path}: not an NPZ file (an NPZ is a zip archive; the file starts with {magic!r})")
    try:
        with zipfile.ZipFile(path) as archive:
            members = [info for info in archive.infolist() if info.filename.endswith(".npy")]
            values = sum(_member_values(archive, info, path) for info in members)
            check_values(values, max_values, path, "its arrays' headers declare")
            mapped = {info.filename[:-4]: _mapped_member(path, info) for info in members}
        if all(array is not None for array in mapped.values()):
            return {name: array for name, array in mapped.items() if array is not None}
        with np.load(path, allow_pickle=False) as loaded:
            return {name: np.asarray(loaded[name]) for name in loaded.files}
    except (ValueError, OSError, zipfile.BadZipFile) as error:
        message = str(error)
        if not message.startswith(str(path)):
            message = f"{path}: not a readable NPZ file ({error})"
        raise ValueError(message) from None


def _npy_header(handle: Any) -> tuple[tuple[int, ...], bool, np.dtype]:
    """(shape, Fortran order, dtype) from the header of an .npy stream, leaving it at the data."""
    version = np.lib.format.read_magic(handle)
    read_header = (
        np.lib.format.read_array_header_1_0 if version == (1, 0) else np.lib.format.read_array_header_2_0
    )
    return read_header(handle)


def _member_values(archive: zipfile.ZipFile, info: zipfile.ZipInfo, path: Path) -> int:
    """The number of values an .npy member's header declares, checked against the zip directory.

    Only the header is read (decompressing a few hundred bytes): the shape it declares bounds what the
    member expands to, and the uncompressed size the zip directory states must match it exactly, so a
    deflate bomb or a header claiming 10¹² samples is refused before anything is expanded.
    """
    with archive.open(info) as member:
        shape, _, dtype = _npy_header(member)
        header_bytes = member.tell()
    if dtype.hasobject:
        raise ValueError(
            f"{path}: member {info.filename!r} holds Python objects ({dtype}); only numbers are read"
        )
    values = math.prod(int(n) for n in shape)
    expected = header_bytes + values * dtype.itemsize
    if info.file_size != expected:
        raise ValueError(
            f"{path}: member {info.filename!r} declares shape {shape} of {dtype} ({expected} bytes with its "
            f"header) but the zip directory says it holds {info.file_size} bytes; the file is corrupt"
        )
    return values


def _mapped_member(path: Path, info: zipfile.ZipInfo) -> np.ndarray | None:
    """A read-only memory map of an uncompressed .npy member (None when compressed or an object array)."""
    if info.compress_type != zipfile.ZIP_STORED:
        return None
    with path.open("rb") as handle:
        handle.seek(info.header_offset)
        local = handle.read(30)
        if local[:4] != b"PK\x03\x04":
            raise ValueError(f"member {info.filename!r}: bad local header")
        name_length, extra_length = (
            int.from_bytes(local[26:28], "little"),
            int.from_bytes(local[28:30], "little"),
        )
        handle.seek(info.header_offset + 30 + name_length + extra_length)
        shape, fortran_order, dtype = _npy_header(handle)
        offset = handle.tell()
    if dtype.hasobject:
        return None
    if int(np.prod(shape)) == 0:
        return np.zeros(shape, dtype=dtype)
    return np.memmap(
        path, dtype=dtype, mode="r", offset=offset, shape=shape, order="F" if fortran_order else "C"
    )
