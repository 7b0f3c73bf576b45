"""The fleet table on disk: Parquet and CSV written atomically, read back to resume a run.

Every write goes to a temporary file in the output directory and is renamed over the old one
(``os.replace``, atomic on POSIX and Windows), so a run interrupted at any moment leaves the previous
complete table, never a half-written one. A resumed run reuses a row when the file's content hash, the
task and the options match and the row holds a result or a ``data`` error (a refusal that the same bytes
would meet again); rows that failed for a reason outside the file are computed again.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Callable, Iterable
from dataclasses import asdict
from pathlib import Path

from carousel_theory.batch.rows import COLUMNS, BatchRow, row_from_mapping

__all__ = ["TABLE_NAMES", "ResumeIndex", "read_table", "write_atomically", "write_table"]

#: File names of the table inside the output directory.
TABLE_NAMES = {"parquet": "results.parquet", "csv": "results.csv"}


def _schema() -> object:
    import pyarrow as pa

    kinds = {"str": pa.string(), "int": pa.int64(), "float": pa.float64()}
    return pa.schema([(name, kinds[str(BatchRow.__dataclass_fields__[name].type)]) for name in COLUMNS])


def write_atomically(path: Path, writer: Callable[[Path], object]) -> None:
    """Call ``writer(temporary)`` on a new file beside ``path``, then rename it over ``path``."""
    path.parent.mkdir(parents=True, exist_ok=True)
    handle, temporary_name = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    os.close(handle)
    temporary = Path(temporary_name)
    try:
        writer(temporary)
        os.replace(temporary, path)
    finally:
        temporary.unlink(missing_ok=True)


def _sorted(rows: Iterable[BatchRow]) -> list[BatchRow]:
    return sorted(rows, key=lambda row: (row.path, row.axis, row.task))


def write_table(rows: Iterable[BatchRow], directory: Path) -> dict[str, Path]:
    """Write ``results.parquet`` and ``results.csv`` (columns in :data:`COLUMNS` order, rows sorted by
    path and axis) into ``directory``, each atomically; return their paths."""
    import pyarrow as pa
    import pyarrow.csv as pa_csv
    import pyarrow.parquet as pq

    table = pa.Table.from_pylist([asdict(row) for row in _sorted(rows)], schema=_schema())
    paths = {kind: directory / name for kind, name in TABLE_NAMES.items()}
    write_atomically(paths["csv"], lambda temporary: pa_csv.write_csv(table, temporary))
    write_atomically(paths["parquet"], lambda temporary: pq.write_table(table, temporary))
    return paths


def read_table(directory: Path) -> list[BatchRow]:
    """The rows of ``directory/results.parquet``; none when there is no table yet."""
    import pyarrow.parquet as pq

    path = directory / TABLE_NAMES["parquet"]
    if not path.exists():
        return []
    return [row_from_mapping(record) for record in pq.read_table(path).to_pylist()]


class ResumeIndex:
    """Rows of an earlier run that a new run may reuse, found by (content hash, task, options)."""

    def __init__(self, rows: Iterable[BatchRow]) -> None:
        self._rows: dict[tuple[str, str, str], list[BatchRow]] = {}
        for row in rows:
            self._rows.setdefault((row.content_hash, row.task, row.options), []).append(row)

    def reusable(self, content_hash: str, task: str, options: str, path: str) -> list[BatchRow] | None:
        """The earlier rows of this content, task and options, relabelled with ``path`` (the file may have
        moved), when every one holds a result or a data error; otherwise None (compute again)."""
        rows = self._rows.get((content_hash, task, options))
        if not rows or any(row.status != "ok" and row.error_kind != "data" for row in rows):
            return None
        return [row.stamped(path=path) for row in rows]
