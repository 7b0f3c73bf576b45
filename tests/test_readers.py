"""The file readers: delimited text, HDF5 and MATLAB .mat beside CSV and NPZ.

Each format is read from small hand-made files and compared with the values written, and each hostile
file (truncated, a wrong column, NaN, non-uniform time, too many values) is refused with the row,
column, member or time where it goes wrong, without changing the file.
"""

from __future__ import annotations

import hashlib
import math
import sys
from pathlib import Path

import numpy as np
import pytest
import scipy.io

from carousel_theory.cli import main
from carousel_theory.data import load_recording

h5py = pytest.importorskip("h5py", reason="h5py (the 'hdf5' extra) is not installed")

ROWS = 40
RATE = 50.0


def _digest(path: Path) -> tuple[str, int]:
    return hashlib.sha256(path.read_bytes()).hexdigest(), path.stat().st_mtime_ns


@pytest.fixture
def columns() -> dict[str, np.ndarray]:
    rng = np.random.default_rng(12)
    return {"t": np.arange(ROWS) / RATE, "wx": rng.standard_normal(ROWS), "wy": rng.standard_normal(ROWS)}


def _text(
    path: Path, columns: dict[str, np.ndarray], separator: str, header_separator: str | None = None
) -> Path:
    names = list(columns)
    lines = [(header_separator or separator).join(names)]
    lines += [separator.join(repr(float(columns[name][i])) for name in names) for i in range(ROWS)]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def _write_matlab_73(path: Path, variables: dict[str, np.ndarray]) -> Path:
    """A MATLAB v7.3 file as MATLAB writes one: HDF5 after a 512-byte header, matrices transposed."""
    with h5py.File(path, "w", userblock_size=512) as handle:
        for name, value in variables.items():
            matrix = np.atleast_2d(value.reshape(-1, 1) if value.ndim == 1 else value)
            dataset = handle.create_dataset(name, data=matrix.T)  # MATLAB is column-major
            dataset.attrs["MATLAB_class"] = np.bytes_("double")
    header = (
        b"MATLAB 7.3 MAT-file, Platform: GLNXA64, Created on: Mon Jan  1 00:00:00 2024 HDF5 schema 1.00 ."
    )
    with path.open("r+b") as handle:
        handle.write(header.ljust(116, b" ") + b"\x00" * 8 + b"\x00\x02IM")
    return path


def _check_same(recording, columns: dict[str, np.ndarray]) -> None:
    assert recording.sample_rate == RATE and recording.uniform
    for name in ("wx", "wy"):
        np.testing.assert_array_equal(recording.rates[name], columns[name])


# --- delimited text ------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("separator", "header_separator", "suffix"),
    [
        ("  ", " ", ".txt"),  # runs of spaces
        ("\t", "\t", ".tsv"),
        (
            " \t ",
            "\t",
            ".txt",
        ),  # mixed spaces and tabs: whitespace-separated (header has a tab: forced below)
        (";", ";", ".csv"),
    ],
    ids=["spaces", "tabs", "mixed-whitespace", "semicolons"],
)
def test_delimited_text_is_read(tmp_path, columns, separator, header_separator, suffix):
    path = _text(tmp_path / f"r{suffix}", columns, separator, header_separator)
    before = _digest(path)
    delimiter = "whitespace" if separator.strip() == "" and len(separator) > 1 else "auto"
    _check_same(load_recording(path, delimiter=delimiter), columns)
    assert _digest(path) == before


def test_whitespace_is_detected_without_a_delimiter(tmp_path, columns):
    path = _text(tmp_path / "r.txt", columns, "   ", " ")
    _check_same(load_recording(path), columns)


def test_forced_delimiter_refuses_a_file_it_does_not_fit(tmp_path, columns):
    path = _text(tmp_path / "r.csv", columns, ",")
    with pytest.raises(ValueError, match=r"row 0 .*, column 't,wx,wy': '0.0,.*' is not a number"):
        load_recording(path, delimiter="semicolon")


def test_cli_delimiter_option(tmp_path, columns, capsys):
    path = _text(tmp_path / "r.txt", columns, " ")
    assert main(["allan", str(path), "--delimiter", "whitespace", "--json"]) == 0
    assert '"wx"' in capsys.readouterr().out


BAD_TEXT = [
    ("whitespace-nan", "t wx\n0 1\n0.02 nan\n0.04 3\n", r"column 'wx' holds nan at row 1"),
    (
        "whitespace-ragged",
        "t wx\n0 1\n0.02\n0.04 3\n",
        r"row 1 \(counted from 0, header excluded\) has 1 fields",
    ),
    ("whitespace-word", "t wx\n0 1\n0.02 x1\n", r"row 1 .*column 'wx': 'x1' is not a number"),
    ("whitespace-non-uniform", "t wx\n0 1\n0.02 2\n0.05 3\n0.06 4\n0.08 5\n", "gap|non-uniform"),
    ("semicolon-truncated", "t;wx\n0;1\n0.02;2\n0.04;", r"row 2 .*column 'wx' is empty"),
]


@pytest.mark.parametrize(("text", "message"), [b[1:] for b in BAD_TEXT], ids=[b[0] for b in BAD_TEXT])
def test_bad_text_is_refused_with_where(tmp_path, text, message):
    path = tmp_path / "bad.txt"
    path.write_text(text, encoding="utf-8")
    before = _digest(path)
    with pytest.raises(ValueError, match=message):
        load_recording(path)
    assert _digest(path) == before


# --- HDF5 ----------------------------------------------------------------------------------------


def test_hdf5_columns_at_the_root(tmp_path, columns):
    path = tmp_path / "r.h5"
    with h5py.File(path, "w") as handle:
        for name, values in columns.items():
            handle.create_dataset(name, data=values)
        handle.create_dataset("description", data="static run")  # text: left out
    before = _digest(path)
    _check_same(load_recording(path), columns)
    assert _digest(path) == before


def test_hdf5_matrix_and_group_with_column_mapping(tmp_path, columns):
    path = tmp_path / "r.hdf5"
    table = np.column_stack([columns["t"], columns["wx"], columns["wy"]])
    with h5py.File(path, "w") as handle:
        handle.create_dataset("imu/gyro", data=table, compression="gzip")
    recording = load_recording(path, columns={"time": "gyro[:,0]", "wx": "gyro[:,1]", "wy": "gyro[:,2]"})
    _check_same(recording, columns)
    with pytest.raises(ValueError, match=r"no gyro columns found among \['gyro\[:,0\]'"):
        load_recording(path)  # matrix columns are gyro axes only when mapped


def test_hdf5_compound_table(tmp_path, columns):
    path = tmp_path / "r.h5"
    table = np.zeros(ROWS, dtype=[("t", "f8"), ("wx", "f8"), ("wy", "f8")])
    for name in table.dtype.names:
        table[name] = columns[name]
    with h5py.File(path, "w") as handle:
        handle.create_dataset("table", data=table)
    _check_same(load_recording(path), columns)


def _hdf5(path: Path, **datasets: np.ndarray) -> Path:
    with h5py.File(path, "w") as handle:
        for name, values in datasets.items():
            handle.create_dataset(name, data=values)
    return path


def test_hdf5_values_are_counted_before_they_are_read(tmp_path):
    path = tmp_path / "big.h5"
    with h5py.File(path, "w") as handle:
        # 10⁹ declared values, chunked and never written: a few kB on disk.
        handle.create_dataset("wx", shape=(10**9,), dtype="f8", chunks=(1024,), compression="gzip")
        handle.create_dataset("t", shape=(10,), dtype="f8")
    assert path.stat().st_size < 100_000
    with pytest.raises(ValueError, match=r"its datasets declare 1000000010 values .* max_values=1000000000"):
        load_recording(path)
    with pytest.raises(ValueError, match="max_values=5"):
        load_recording(path, max_values=5)


def test_hdf5_compound_table_counts_every_field(tmp_path, columns):
    path = tmp_path / "r.h5"
    table = np.zeros(ROWS, dtype=[("t", "f8"), ("wx", "f8"), ("wy", "f8")])
    with h5py.File(path, "w") as handle:
        handle.create_dataset("table", data=table)
    with pytest.raises(ValueError, match=rf"declare {3 * ROWS} values"):
        load_recording(path, max_values=3 * ROWS - 1)


def test_missing_h5py_is_one_line_naming_the_extra(tmp_path, columns, monkeypatch, capsys):
    path = _hdf5(tmp_path / "r.h5", **columns)
    monkeypatch.setitem(sys.modules, "h5py", None)  # as if not installed
    with pytest.raises(ModuleNotFoundError, match=r'pip install "carousel-theory\[hdf5\]"'):
        load_recording(path)
    assert main(["allan", str(path)]) == 2
    error = capsys.readouterr().err.strip()
    assert len(error.splitlines()) == 1 and "carousel-theory[hdf5]" in error


# --- MATLAB ---------------------------------------------------------------------------------------


def test_matlab_v5_vectors(tmp_path, columns):
    path = tmp_path / "r.mat"
    scipy.io.savemat(path, {name: values.reshape(-1, 1) for name, values in columns.items()})
    before = _digest(path)
    _check_same(load_recording(path), columns)
    assert _digest(path) == before


def test_matlab_v5_matrix_with_mapping_and_units(tmp_path, columns):
    path = tmp_path / "r.mat"
    scipy.io.savemat(
        path,
        {"gyroBuffer": np.column_stack([columns["t"], columns["wx"], columns["wy"]]), "label": "run 1"},
        do_compression=True,
    )
    recording = load_recording(
        path, columns={"time": "gyroBuffer[:,0]", "wx": "gyroBuffer[:,1]"}, units="deg/s"
    )
    np.testing.assert_allclose(recording.rates["wx"], columns["wx"] * math.pi / 180, rtol=1e-15)


def test_matlab_v73_is_read_as_matlab_shows_it(tmp_path, columns):
    table = np.column_stack([columns["t"], columns["wx"], columns["wy"]])
    path = _write_matlab_73(tmp_path / "r.mat", {"gyroBuffer": table, "wz": columns["wy"]})
    before = _digest(path)
    recording = load_recording(
        path, columns={"time": "gyroBuffer[:,0]", "wx": "gyroBuffer[:,1]", "wy": "gyroBuffer[:,2]"}
    )
    _check_same(recording, columns)
    np.testing.assert_array_equal(load_recording(path, sample_rate=RATE).rates["wz"], columns["wy"])
    assert _digest(path) == before


# --- hostile HDF5 and MATLAB files: one table ----------------------------------------------------


def _mat(path: Path, **variables: np.ndarray) -> Path:
    scipy.io.savemat(path, {name: np.asarray(values).reshape(-1, 1) for name, values in variables.items()})
    return path


def _truncated(writer, suffix: str, keep: float):
    def build(path: Path, columns: dict[str, np.ndarray]) -> Path:
        good = writer(path.with_name(f"good{suffix}"), **columns)
        path.write_bytes(good.read_bytes()[: int(good.stat().st_size * keep)])
        return path

    return build


def _with_nan(writer, name: str, row: int):
    def build(path: Path, columns: dict[str, np.ndarray]) -> Path:
        values = dict(columns)
        values[name] = values[name].copy()
        values[name][row] = math.nan
        return writer(path, **values)

    return build


def _uneven(writer, row: int):
    def build(path: Path, columns: dict[str, np.ndarray]) -> Path:
        time = columns["t"].copy()
        time[row:] += 0.3 / RATE  # one step 30 % too long
        return writer(path, **{**columns, "t": time})

    return build


def _text_named(suffix: str):
    def build(path: Path, columns: dict[str, np.ndarray]) -> Path:
        path.write_text("t,wx\n0,1\n0.1,2\n", encoding="utf-8")
        return path

    return build


def _only_text(path: Path, columns: dict[str, np.ndarray]) -> Path:
    scipy.io.savemat(path, {"note": "nothing numeric"})
    return path


_UNEVEN = r"non-uniform timestamps: .* t\[20\]-t\[19\]=0\.026 s"
HOSTILE = [
    ("hdf5-truncated", ".h5", _truncated(_hdf5, ".h5", 0.5), {}, r"r\.h5: not a readable HDF5 file"),
    ("hdf5-text", ".h5", _text_named(".h5"), {}, r"not an HDF5 file \(no HDF5 signature"),
    (
        "hdf5-wrong-column",
        ".h5",
        lambda p, c: _hdf5(p, **c),
        {"columns": {"wy": "gyro_y"}},
        r"\['gyro_y'\] not found",
    ),
    ("hdf5-nan", ".h5", _with_nan(_hdf5, "wx", 7), {}, r"column 'wx' holds nan at row 7"),
    ("hdf5-non-uniform", ".h5", _uneven(_hdf5, 20), {}, _UNEVEN),
    ("mat-truncated", ".mat", _truncated(_mat, ".mat", 0.8), {}, r"r\.mat: not a readable MATLAB \.mat file"),
    ("mat-text", ".mat", _text_named(".mat"), {}, r"r\.mat: not a"),
    ("mat-wrong-column", ".mat", lambda p, c: _mat(p, **c), {"columns": {"wx": "gx"}}, r"\['gx'\] not found"),
    ("mat-nan", ".mat", _with_nan(_mat, "wy", 3), {}, r"column 'wy' holds nan at row 3"),
    ("mat-non-uniform", ".mat", _uneven(_mat, 20), {}, _UNEVEN),
    ("mat-no-numbers", ".mat", _only_text, {}, "no numeric vector or matrix"),
    (
        "mat-too-many",
        ".mat",
        lambda p, c: _mat(p, **c),
        {"max_values": 100},
        r"declare 120 values .* max_values=100",
    ),
]


@pytest.mark.parametrize(
    ("suffix", "build", "options", "message"),
    [case[1:] for case in HOSTILE],
    ids=[case[0] for case in HOSTILE],
)
def test_hostile_files_are_refused_with_where(tmp_path, columns, suffix, build, options, message):
    path = build(tmp_path / f"r{suffix}", columns)
    before = _digest(path)
    with pytest.raises(ValueError, match=message):
        load_recording(path, **options)
    assert _digest(path) == before


def test_delimiter_applies_to_text_only(tmp_path, columns):
    path = tmp_path / "r.mat"
    scipy.io.savemat(path, columns)
    with pytest.raises(ValueError, match=r"delimiter='tab': applies to text files, not to .mat files"):
        load_recording(path, delimiter="tab")
    with pytest.raises(ValueError, match=r"delimiter='\|': must be 'auto' or one of"):
        load_recording(path, delimiter="|")


def test_whitespace_file_padded_after_the_first_block_is_still_read(tmp_path):
    # The first 64 KiB hold single spaces (the fast parser is tried); a padded row comes later.
    rows = 6000
    rng = np.random.default_rng(13)
    values = rng.standard_normal(rows)
    lines = ["t wx"] + [f"{i / RATE!r} {float(values[i])!r}" for i in range(rows)]
    lines[rows - 10] = lines[rows - 10].replace(" ", "    ")
    path = tmp_path / "padded.txt"
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    assert path.stat().st_size > 1 << 16
    np.testing.assert_array_equal(load_recording(path).rates["wx"], values)
    lines[rows - 5] = f"{(rows - 6) / RATE!r} oops"
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    with pytest.raises(ValueError, match=rf"row {rows - 6} .*column 'wx': 'oops' is not a number"):
        load_recording(path)
