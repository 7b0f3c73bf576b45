"""Delimited text recordings: comma, semicolon, tab or whitespace separated, with a header row.

The delimiter is read from the header row (the first of ``,``, ``;`` and a tab that it holds; otherwise
runs of spaces and tabs), or given (``delimiter=``, ``--delimiter``). Comma, semicolon and tab files are
parsed by ``pyarrow.csv`` when pyarrow is installed (the ``data`` extra): its streaming reader parses
blocks of 4 MB on all cores straight into float64 columns, without holding the text in memory, each
block copied into columns sized once from the file (whose untouched pages cost nothing), so the peak is
the columns themselves; pandas' C engine is as fast on
one core but names neither the row nor the column of a bad value. Whitespace-separated files, and every
file without pyarrow, are parsed by ``numpy.loadtxt`` (whose C parser splits on runs of whitespace).
When the parser refuses a file, the file is scanned once more, line by line, to name the row (counted
from 0, header excluded) and the column of the first bad field; that scan reads lines of at most
``MAX_LINE_BYTES``. The first ``BINARY_CHECK_BYTES`` (64 KiB) are read to check the header and that the
file is text (no NUL byte, valid UTF-8) before the rest is parsed.
"""

from __future__ import annotations

import codecs
import csv
from itertools import count
from pathlib import Path
from typing import Any

import numpy as np

from carousel_theory.readers._common import check_values, looks_numeric

__all__ = ["BINARY_CHECK_BYTES", "DELIMITERS", "MAX_LINE_BYTES", "check_delimiter", "read_text"]

#: Bytes of a text file checked for binary content (NUL bytes, invalid UTF-8) before it is parsed; the
#: header row must end within them.
BINARY_CHECK_BYTES = 1 << 16
#: Longest line the scan that names a bad field reads; a longer one is refused, not held in memory.
MAX_LINE_BYTES = 1 << 20
#: ``delimiter=`` names and the separator each stands for (None: runs of spaces and tabs).
DELIMITERS: dict[str, str | None] = {"comma": ",", "semicolon": ";", "tab": "\t", "whitespace": None}
_AUTO = "auto"


def check_delimiter(delimiter: Any) -> str:
    """``delimiter`` as one of ``"auto"`` and the names of :data:`DELIMITERS` (``","`` → ``"comma"``)."""
    by_character = {character: name for name, character in DELIMITERS.items() if character is not None}
    if isinstance(delimiter, str) and delimiter in by_character:
        return by_character[delimiter]
    if delimiter == _AUTO or delimiter in DELIMITERS:
        return str(delimiter)
    raise ValueError(
        f"delimiter={delimiter!r}: must be 'auto' or one of {', '.join(DELIMITERS)} (or ',', ';', '\\t')"
    )


def _kind(path: Path) -> str:
    """What messages call the file: "CSV" for a .csv file, "text" for any other."""
    return "CSV" if path.suffix.lower() == ".csv" else "text"


def _split(line: str, separator: str | None) -> list[str]:
    if separator is None:
        return line.split()
    return next(csv.reader([line], delimiter=separator), [])


def _header_text(path: Path) -> tuple[str, bool]:
    """(the decoded first block, whether it is the whole file); refuses binary or non-UTF-8 content."""
    with path.open("rb") as handle:
        head = handle.read(BINARY_CHECK_BYTES)
    whole = len(head) < BINARY_CHECK_BYTES
    if b"\x00" in head or head[:4] == b"PK\x03\x04":
        raise ValueError(
            f"{path}: not a {_kind(path)} text file (binary content in the first {len(head)} bytes)"
        )
    try:
        # An incremental decoder accepts a character cut by the block's end, and nothing else invalid.
        text = codecs.getincrementaldecoder("utf-8-sig")().decode(head, final=whole)
    except UnicodeDecodeError as error:
        raise ValueError(
            f"{path}: not a {_kind(path)} text file (not UTF-8 at byte {error.start} of the first block)"
        ) from None
    if not whole and "\n" not in text and "\r" not in text:
        raise ValueError(
            f"{path}: not a {_kind(path)} file (no line break in the first {BINARY_CHECK_BYTES} bytes: "
            "the header row is missing or the file is not line-oriented text)"
        )
    return text, whole


def text_header(path: Path, delimiter: str = _AUTO) -> tuple[list[str], str | None]:
    """(column names, separator) from the first line; None as separator means runs of whitespace."""
    text, whole = _header_text(path)
    lines = text.splitlines()
    if not lines or not lines[0].strip():
        raise ValueError(f"{path}: empty {_kind(path)} file (no header row)")
    header_line = lines[0]
    if delimiter == _AUTO:
        found = [character for character in (",", ";", "\t") if character in header_line]
        separator = found[0] if found else (None if len(header_line.split()) > 1 else ",")
    else:
        separator = DELIMITERS[delimiter]
    header = [name.strip() for name in _split(header_line, separator)]
    if any(looks_numeric(name) for name in header):
        raise ValueError(f"{path}: the first row {header_line!r} is not a header row (it holds numbers)")
    if any(not name for name in header):
        raise ValueError(f"{path}: the header row {header_line!r} has an empty column name")
    if len(set(header)) != len(header):
        raise ValueError(f"{path}: repeated column names in the header {header}")
    if len(lines) < 2 and whole:
        raise ValueError(f"{path}: the {_kind(path)} file has a header but no data rows")
    return header, separator


def read_text(path: Path, max_values: int, delimiter: str = _AUTO) -> dict[str, np.ndarray]:
    """The columns of a delimited text file with a header row, as read-only float64 arrays."""
    header, separator = text_header(path, check_delimiter(delimiter))
    try:
        import pyarrow  # noqa: F401
    except ImportError:
        return _read_text_numpy(path, header, separator, max_values)
    if separator is not None:
        return _read_text_arrow(path, header, separator, max_values)
    single = _single_whitespace(path)
    if single is not None:
        try:
            return _read_text_arrow(path, header, single, max_values)
        except ValueError:
            pass  # a padded field further on: numpy.loadtxt reads it, or names the row that is wrong
    return _read_text_numpy(path, header, separator, max_values)


def _single_whitespace(path: Path) -> str | None:
    """The one character (space or tab) between every two fields of the first block's lines, when no
    field is padded: such a whitespace-separated file parses as a delimited one, five times faster."""
    lines = _header_text(path)[0].splitlines()[:-1]  # the last line may be cut by the block's end
    for character in (" ", "\t"):
        if lines and all(line and character.join(line.split()) == line for line in lines):
            return character
    return None


class _Columns:
    """float64 columns filled batch by batch into arrays sized once from the file: rows ≤ bytes / (2 ×
    fields), since every field takes at least one character and one separator or line break. Pages the
    rows never reach are never touched, so they take no memory; nothing is concatenated, and no
    batch-sized pieces are left behind to fragment the heap (a 12-hour CSV at 1 kHz read into 4 MB
    batches would otherwise leave about as much free heap as it holds columns)."""

    def __init__(self, names: list[str], path: Path) -> None:
        capacity = path.stat().st_size // (2 * len(names)) + 1
        self.arrays = {name: np.empty(capacity) for name in names}
        self.rows = 0

    def append(self, name: str, values: np.ndarray) -> None:
        array, end = self.arrays[name], self.rows + len(values)
        if end > len(array):  # only rows with empty fields (refused right after) are this short
            grown = np.empty(max(end, 2 * len(array)))
            grown[: self.rows] = array[: self.rows]
            self.arrays[name] = array = grown
        array[self.rows : end] = values

    def finish(self) -> dict[str, np.ndarray]:
        columns = {}
        for name, array in self.arrays.items():
            columns[name] = array[: self.rows]
            columns[name].setflags(write=False)  # ours alone: read-only, so rad/s columns need no copy
        return columns


def _read_text_arrow(path: Path, header: list[str], separator: str, max_values: int) -> dict[str, np.ndarray]:
    import pyarrow as arrow
    import pyarrow.csv as arrow_csv

    columns = _Columns(header, path)
    try:
        reader = arrow_csv.open_csv(
            path,
            read_options=arrow_csv.ReadOptions(skip_rows=1, column_names=header, block_size=1 << 22),
            parse_options=arrow_csv.ParseOptions(delimiter=separator),
            convert_options=arrow_csv.ConvertOptions(
                column_types=dict.fromkeys(header, arrow.float64()),
                null_values=[""],  # "nan" stays NaN
            ),
            memory_pool=arrow.system_memory_pool(),  # freed blocks go back to the system at once
        )
        for batch in reader:  # batch by batch: the text is never held whole, and Arrow's buffers are freed
            check_values(
                (columns.rows + batch.num_rows) * len(header), max_values, path, "its first rows already hold"
            )
            for index, name in enumerate(header):
                _refuse_empty_fields(path, name, batch.column(index), columns.rows)
                columns.append(name, batch.column(index).to_numpy(zero_copy_only=False))
            columns.rows += batch.num_rows
    except (arrow.ArrowInvalid, UnicodeDecodeError) as error:
        where = _locate_bad_field(path, header, separator, error)
        raise ValueError(f"{path}: unreadable {_kind(path)} data ({where})") from None
    if columns.rows == 0:
        raise ValueError(f"{path}: the {_kind(path)} file has a header but no data rows")
    return columns.finish()


def _refuse_empty_fields(path: Path, name: str, column: Any, offset: int) -> None:
    """An empty field parses as null: name its row (a file cut in the middle of a row ends this way)."""
    if column.null_count:
        first = offset + int(np.flatnonzero(column.is_null().to_numpy(zero_copy_only=False))[0])
        raise ValueError(
            f"{path}: unreadable {_kind(path)} data (row {first} (counted from 0, header excluded), "
            f"column {name!r} is empty: a row with a missing value, or a file cut off in the middle of its "
            "last row)"
        )


def _locate_bad_field(path: Path, header: list[str], separator: str | None, error: Exception) -> str:
    """Scan the file line by line for the first row with a wrong field count or a non-number.

    Lines are read at most ``MAX_LINE_BYTES`` at a time: a file without line breaks is refused, not
    read whole into memory.
    """
    with path.open("r", encoding="utf-8-sig", errors="replace", newline="") as handle:
        handle.readline(MAX_LINE_BYTES)  # the header, checked already
        for row in count():
            line = handle.readline(MAX_LINE_BYTES)
            if not line:
                break
            where = f"row {row} (counted from 0, header excluded)"
            if len(line) >= MAX_LINE_BYTES and not line.endswith(("\n", "\r")):
                return f"{where} is longer than {MAX_LINE_BYTES} characters; not a text recording"
            if "\x00" in line:
                return f"{where} holds NUL bytes: binary content"
            fields = _split(line, separator)
            if separator is None and not fields:
                continue  # numpy.loadtxt skips blank lines
            if len(fields) != len(header):
                return f"{where} has {len(fields)} fields, the header {len(header)}"
            for column, field_text in zip(header, fields, strict=True):
                if field_text.strip() and not looks_numeric(field_text):
                    return f"{where}, column {column!r}: {field_text!r} is not a number"
    return str(error).splitlines()[0]


def _read_text_numpy(
    path: Path, header: list[str], separator: str | None, max_values: int
) -> dict[str, np.ndarray]:
    # Every value takes at least two bytes ("0,"): a file too short to exceed the limit needs no count.
    if path.stat().st_size // 2 > max_values:
        with path.open("rb") as handle:
            lines = sum(block.count(b"\n") for block in iter(lambda: handle.read(1 << 20), b""))
        check_values(lines * len(header), max_values, path, "its rows hold")
    try:
        table = np.loadtxt(
            path,
            delimiter=separator,
            skiprows=1,
            dtype=np.float64,
            ndmin=2,
            comments=None,
            encoding="utf-8-sig",
        )
    except ValueError as error:
        where = _locate_bad_field(path, header, separator, error)
        raise ValueError(f"{path}: unreadable {_kind(path)} data ({where})") from None
    if table.shape[0] == 0:
        raise ValueError(f"{path}: the {_kind(path)} file has a header but no data rows")
    if table.shape[1] != len(header):
        raise ValueError(f"{path}: {table.shape[1]} data columns but {len(header)} header names")
    return {name: table[:, i] for i, name in enumerate(header)}
