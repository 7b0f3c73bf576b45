"""Reading recordings: CSV/NPZ/arrays/DataFrame, units, and every refusal with its message."""

from __future__ import annotations

import hashlib
import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from carousel_theory.data import Recording, load_recording, recording_from_arrays


def _write_csv(path: Path, header: str, rows: list[list[float]], delimiter: str = ",") -> Path:
    lines = [header] + [delimiter.join(repr(float(v)) for v in row) for row in rows]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def _digest(path: Path) -> tuple[str, int]:
    return hashlib.sha256(path.read_bytes()).hexdigest(), path.stat().st_mtime_ns


@pytest.fixture
def regular_rows() -> list[list[float]]:
    rng = np.random.default_rng(11)
    return [[i / 50.0, *rng.standard_normal(2)] for i in range(40)]


def test_csv_with_time_column(tmp_path, regular_rows):
    path = _write_csv(tmp_path / "r.csv", "t,wx,wy", regular_rows)
    before = _digest(path)
    recording = load_recording(path)
    assert _digest(path) == before  # never modified
    assert isinstance(recording, Recording)
    assert recording.sample_rate == pytest.approx(50.0, rel=1e-12)
    assert set(recording.rates) == {"wx", "wy"}
    np.testing.assert_array_equal(recording.rates["wy"], [row[2] for row in regular_rows])
    assert recording.uniform and recording.temperature is None and recording.angle is None
    assert recording.duration == pytest.approx(40 / 50.0)


def test_csv_units_mapping_and_delimiters(tmp_path, regular_rows):
    path = _write_csv(
        tmp_path / "r.csv", "time;gyro_a;other;T;phi", [[*r, 25.0, 0.1] for r in regular_rows], ";"
    )
    recording = load_recording(
        path, columns={"time": "time", "wx": "gyro_a", "temperature": "T", "angle": "phi"}, units="deg/s"
    )
    assert list(recording.rates) == ["wx"]
    np.testing.assert_allclose(
        recording.rates["wx"], [r[1] * math.pi / 180 for r in regular_rows], rtol=1e-15
    )
    np.testing.assert_array_equal(recording.temperature, np.full(40, 25.0))
    np.testing.assert_array_equal(recording.angle, np.full(40, 0.1))
    hourly = load_recording(path, columns={"wx": "gyro_a"}, units="deg/h", sample_rate=50.0)
    np.testing.assert_allclose(
        hourly.rates["wx"], [r[1] * math.pi / 180 / 3600 for r in regular_rows], rtol=1e-15
    )


def test_csv_without_time_needs_sample_rate(tmp_path, regular_rows):
    path = _write_csv(tmp_path / "r.csv", "wx,wy", [r[1:] for r in regular_rows])
    recording = load_recording(path, sample_rate=20.0)
    np.testing.assert_allclose(recording.time, np.arange(40) / 20.0)
    with pytest.raises(ValueError, match="no time column and no sample_rate"):
        load_recording(path)


def test_npz_uses_fs_entry(tmp_path):
    rng = np.random.default_rng(2)
    path = tmp_path / "r.npz"
    np.savez(
        path, wx=rng.standard_normal(30), wz=rng.standard_normal(30), ax=np.zeros(30), fs=np.float64(10.0)
    )
    before = _digest(path)
    recording = load_recording(path)
    assert _digest(path) == before
    assert set(recording.rates) == {"wx", "wz"} and recording.sample_rate == 10.0


def test_arrays_and_dataframe_agree():
    rng = np.random.default_rng(3)
    frame = pd.DataFrame({"wx": rng.standard_normal(16), "wy": rng.standard_normal(16)})
    from_frame = recording_from_arrays(frame, sample_rate=4.0)
    from_dict = recording_from_arrays(
        {"wx": frame["wx"].to_numpy(), "wy": frame["wy"].to_numpy()}, sample_rate=4.0
    )
    for name in ("wx", "wy"):
        np.testing.assert_array_equal(from_frame.rates[name], from_dict.rates[name])


def test_irregular_timing_kept_on_request():
    time = np.concatenate((np.arange(10) * 0.1, 2.0 + np.arange(10) * 0.1))
    recording = recording_from_arrays({"wx": np.zeros(20)}, time=time, irregular="keep")
    assert not recording.uniform
    assert "gap" in recording.notes[0] and "t[9]" in recording.notes[0]


def test_require_duration():
    recording = recording_from_arrays({"wx": np.zeros(10)}, sample_rate=10.0)
    recording.require_duration(1.0, "a test")
    with pytest.raises(ValueError, match=r"lasts 1 s, too short for an Allan variance at tau=1 s"):
        recording.require_duration(3.0, "an Allan variance at tau=1 s")


def _bad_csv(tmp_path: Path, text: str | bytes, name: str = "bad.csv") -> Path:
    path = tmp_path / name
    if isinstance(text, bytes):
        path.write_bytes(text)
    else:
        path.write_text(text, encoding="utf-8")
    return path


GOOD_TIME = "\n".join(f"{i / 10},{i}" for i in range(6))

BAD_FILES = [
    ("empty", "", "r.csv", {}, "empty file"),
    ("header-only", "t,wx\n", "r.csv", {}, "no data rows"),
    ("no-header", "0.0,1.0\n0.1,2.0\n", "r.csv", {}, "not a header row"),
    ("nan", "t,wx\n0,1\n0.1,nan\n0.2,3\n", "r.csv", {}, r"column 'wx' holds nan at row 1"),
    ("inf", "t,wx\n0,1\n0.1,2\n0.2,inf\n", "r.csv", {}, r"column 'wx' holds inf at row 2"),
    ("non-monotonic", "t,wx\n0,1\n0.2,2\n0.1,3\n0.3,4\n", "r.csv", {}, r"not strictly increasing: t\[1\]"),
    ("repeated-time", "t,wx\n0,1\n0.1,2\n0.1,3\n", "r.csv", {}, "not strictly increasing"),
    ("gap", "t,wx\n0,1\n0.1,2\n0.2,3\n0.5,4\n0.6,5\n", "r.csv", {}, r"gap: 1 steps .* t\[2\]=0.2 s"),
    ("jitter", "t,wx\n0,1\n0.1,2\n0.2,3\n0.31,4\n0.4,5\n0.5,6\n", "r.csv", {}, "non-uniform timestamps"),
    ("binary-as-csv", b"PK\x03\x04\x00\x00binary", "r.csv", {}, "not a CSV text file"),
    ("text-as-npz", "t,wx\n0,1\n", "r.npz", {}, "not an NPZ file"),
    ("unknown-extension", "t,wx\n0,1\n", "r.dat", {}, "unknown extension"),
    ("no-gyro", "t,temp\n0,1\n0.1,2\n", "r.csv", {}, "no gyro columns"),
    (
        "missing-mapped",
        "t,wx\n0,1\n0.1,2\n",
        "r.csv",
        {"columns": {"wy": "gyro_y"}},
        r"\['gyro_y'\] not found",
    ),
    (
        "rate-disagrees",
        "t,wx\n0,1\n0.1,2\n0.2,3\n",
        "r.csv",
        {"sample_rate": 20.0},
        "disagrees with the time",
    ),
    ("one-sample", "t,wx\n0,1\n", "r.csv", {}, "at least 2 samples"),
    ("bad-units", "t,wx\n0,1\n0.1,2\n", "r.csv", {"units": "rpm"}, "units='rpm'"),
    ("bad-irregular", "t,wx\n0,1\n0.1,2\n", "r.csv", {"irregular": "drop"}, "irregular='drop'"),
    ("ragged", "t,wx\n0,1\n0.1\n", "r.csv", {}, "unreadable CSV data"),
    ("words-in-data", "t,wx\n0,1\n0.1,abc\n", "r.csv", {}, "unreadable CSV data"),
]


@pytest.mark.parametrize(
    ("text", "name", "options", "message"), [b[1:] for b in BAD_FILES], ids=[b[0] for b in BAD_FILES]
)
def test_bad_files_are_refused_with_where(tmp_path, text, name, options, message):
    path = _bad_csv(tmp_path, text, name)
    before = _digest(path)
    with pytest.raises(ValueError, match=message):
        load_recording(path, **options)
    assert _digest(path) == before


BAD_CALLS = [
    ("path-type", lambda tmp: load_recording(3), TypeError, "path=3"),
    ("missing-file", lambda tmp: load_recording(tmp / "absent.csv"), FileNotFoundError, "no such file"),
    ("directory", lambda tmp: load_recording(tmp), ValueError, "is a directory"),
    (
        "columns-type",
        lambda tmp: load_recording(_bad_csv(tmp, GOOD_TIME.replace("0.0,0", "t,wx\n0.0,0")), columns=3),
        TypeError,
        "columns=3",
    ),
    (
        "rates-not-mapping",
        lambda tmp: recording_from_arrays([1.0, 2.0], sample_rate=1.0),
        TypeError,
        "rates=list",
    ),
    ("rates-empty", lambda tmp: recording_from_arrays({}, sample_rate=1.0), ValueError, "no gyro columns"),
    (
        "rates-2d",
        lambda tmp: recording_from_arrays({"wx": np.zeros((2, 2))}, sample_rate=1.0),
        ValueError,
        "1-dimensional",
    ),
    (
        "rates-strings",
        lambda tmp: recording_from_arrays({"wx": ["a", "b"]}, sample_rate=1.0),
        TypeError,
        "real numbers",
    ),
    (
        "length-mismatch",
        lambda tmp: recording_from_arrays({"wx": np.zeros(3), "wy": np.zeros(4)}, sample_rate=1.0),
        ValueError,
        "has 4 samples but the others have 3",
    ),
    (
        "sample-rate-negative",
        lambda tmp: recording_from_arrays({"wx": np.zeros(3)}, sample_rate=-1.0),
        ValueError,
        "sample_rate=-1.0",
    ),
    (
        "temperature-nan",
        lambda tmp: recording_from_arrays(
            {"wx": np.zeros(3)}, sample_rate=1.0, temperature=[1.0, math.nan, 2.0]
        ),
        ValueError,
        "column 'temperature' holds nan at row 1",
    ),
    (
        "angle-length",
        lambda tmp: recording_from_arrays({"wx": np.zeros(3)}, sample_rate=1.0, angle=[0.0]),
        ValueError,
        "column 'angle' has 1 samples",
    ),
    (
        "source-type",
        lambda tmp: recording_from_arrays({"wx": np.zeros(3)}, sample_rate=1.0, source=1),
        TypeError,
        "source=1",
    ),
]


@pytest.mark.parametrize(
    ("call", "error", "message"), [b[1:] for b in BAD_CALLS], ids=[b[0] for b in BAD_CALLS]
)
def test_bad_calls(tmp_path, call, error, message):
    with pytest.raises(error, match=message):
        call(tmp_path)


@pytest.mark.data
def test_adis16405_run_reads(shared_data):
    path = shared_data / "adis16405_static" / "adis16405_run1.npz"
    before = _digest(path)
    recording = load_recording(path)
    assert _digest(path) == before
    assert len(recording) == 1_000_000 and recording.sample_rate == 100.0 and recording.uniform
    assert set(recording.rates) == {"wx", "wy", "wz"}
    # README: run 1 means 7.011e-03 / -7.258e-03 / -5.123e-03 rad/s.
    assert round(float(recording.rates["wx"].mean()), 6) == 0.007011


@pytest.mark.data
def test_bursty_mpu6050_is_refused_or_kept(shared_data):
    path = shared_data / "mpu6050_static_10min" / "mpu6050_static_10min.npz"
    with pytest.raises(ValueError, match=r"gap.*--resample HZ .*\(12\.4146 Hz is the highest f/2\^k"):
        load_recording(path)
    recording = load_recording(path, irregular="keep")
    assert not recording.uniform and recording.temperature is not None


@pytest.mark.data
def test_bursty_mpu6050_resampled_as_the_loop_reported_it(shared_data):
    """docs/real_data_loop (written before resampling moved into the library) reports 12.41 Hz with 15
    of 8134 bins empty; the library function must bin this recording the same way."""
    path = shared_data / "mpu6050_static_10min" / "mpu6050_static_10min.npz"
    before = _digest(path)
    recording = load_recording(path, resample="auto")
    assert _digest(path) == before
    assert recording.uniform and len(recording) == 8134 and recording.temperature is not None
    assert recording.notes[-1].endswith("uniform 12.41 Hz grid, 15 of 8134 bins empty and interpolated")
    with pytest.raises(ValueError, match=r"no sample between t=649\.779 s and t=650\.276 s"):
        load_recording(path, resample=25.0)


def test_grid_deviation_is_the_plain_expression_bit_for_bit():
    # Formed in one array in place; the same numbers as the expression it replaces.
    from carousel_theory.data import _grid_deviation

    rng = np.random.default_rng(21)
    time = np.arange(100_001) / 100.0 + rng.uniform(-2e-6, 2e-6, 100_001)
    time -= time[0]
    step = float(time[-1] - time[0]) / (len(time) - 1)
    assert _grid_deviation(time) == float(np.max(np.abs(time - np.arange(len(time)) * step)))
