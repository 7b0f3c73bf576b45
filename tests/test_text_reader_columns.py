"""The text reader's columns, sized once from the file: exact values over many batches, and rows shorter
than the size bound (only rows with empty fields can be) still refused by row and column."""

from __future__ import annotations

import numpy as np
import pytest

from carousel_theory.readers.text import read_text

pytest.importorskip("pyarrow", reason="the pyarrow reader (the 'data' extra) is not installed")


def test_values_over_many_batches_are_exact(tmp_path):
    # ~9 MB of text: three 4 MB batches; repr round-trips every float exactly.
    rng = np.random.default_rng(8)
    values = rng.standard_normal((200_000, 2)) * 10.0 ** rng.integers(-8, 8, size=(200_000, 2))
    path = tmp_path / "long.csv"
    path.write_text("a,b\n" + "".join(f"{x!r},{y!r}\n" for x, y in values.tolist()), encoding="utf-8")
    columns = read_text(path, 10**9)
    np.testing.assert_array_equal(columns["a"], values[:, 0])
    np.testing.assert_array_equal(columns["b"], values[:, 1])
    assert not columns["a"].flags.writeable


def test_rows_shorter_than_the_bound_are_refused_by_row(tmp_path):
    # "1,\n" is 3 bytes for 2 fields, below the 4 of the size bound: the first column outgrows its
    # array (and is grown) before the empty second column is refused, naming row 0.
    path = tmp_path / "short_rows.csv"
    path.write_text("t,wx\n" + "1,\n" * 1000, encoding="utf-8")
    with pytest.raises(ValueError, match=r"row 0 .*column 'wx' is empty"):
        read_text(path, 10**9)
