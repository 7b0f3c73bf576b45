"""Regression tests for the reader and simulate items of issue 13 (hostile files and arguments).

Each test is named after the item it pins: ``test_issue13_item4_...`` is item 4 of the issue.
"""

from __future__ import annotations

import io
import json
import tracemalloc
import zipfile
from pathlib import Path

import numpy as np
import pytest

from carousel_theory.cli import main
from carousel_theory.cli._errors import BAD_INPUT
from carousel_theory.data import MAX_LINE_BYTES, load_recording, recording_from_arrays
from carousel_theory.simulate import samples_for_duration, simulate_recording


def _npy_bytes(array: np.ndarray) -> bytes:
    buffer = io.BytesIO()
    np.lib.format.write_array(buffer, array)
    return buffer.getvalue()


def _claiming_header(shape: tuple[int, ...]) -> bytes:
    """An .npy member whose header declares ``shape`` of float64 but holds 8 bytes of data."""
    buffer = io.BytesIO()
    header = {"descr": "<f8", "fortran_order": False, "shape": shape}
    np.lib.format.write_array_header_1_0(buffer, header)
    return buffer.getvalue() + bytes(8)


# --- item 4: --duration inf / nan / 1e12 -------------------------------------------------------


@pytest.mark.parametrize(
    ("duration", "fragment"),
    [("inf", "duration=inf: must be finite"), ("nan", "duration=nan"), ("1e12", "max_samples=")],
)
def test_issue13_item4_simulate_refuses_unbounded_durations(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], duration: str, fragment: str
) -> None:
    out = tmp_path / "x.csv"
    status = main(["simulate", str(out), "--seed", "1", "--duration", duration])
    assert status == BAD_INPUT
    assert fragment in capsys.readouterr().err
    assert not out.exists()


def test_issue13_item4_the_refusal_states_the_memory_and_the_option_raises_the_limit(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "x.csv"
    arguments = ["simulate", str(out), "--seed", "1", "--duration", "10", "--sample-rate", "100"]
    assert main([*arguments, "--max-samples", "999"]) == BAD_INPUT
    message = capsys.readouterr().err
    # 1000 samples of wx, wy, t and temp: 4 float64 columns, 32,000 bytes.
    assert "samples=1000: more than max_samples=999" in message
    assert "3.2e-05 GB" in message and "--max-samples" in message
    assert not out.exists()
    assert main([*arguments, "--max-samples", "1000"]) == 0
    assert len(load_recording(out)) == 1000


def test_issue13_item4_api_bounds_before_any_work() -> None:
    with pytest.raises(ValueError, match=r"duration=inf: must be finite"):
        samples_for_duration(float("inf"), 100.0)
    with pytest.raises(ValueError, match=r"duration=nan"):
        samples_for_duration(float("nan"), 100.0)
    with pytest.raises(ValueError, match=r"sample count overflows"):
        samples_for_duration(1e300, 1e300)
    assert samples_for_duration(600, 100) == 60_000
    with pytest.raises(ValueError, match=r"samples=1000000000000: more than max_samples=100000000"):
        simulate_recording(10**12, 100.0, rng=np.random.default_rng(1))


# --- item 5: NPZ headers claiming 10¹² samples, deflate bombs ----------------------------------


@pytest.mark.parametrize("compression", [zipfile.ZIP_STORED, zipfile.ZIP_DEFLATED])
def test_issue13_item5_npz_header_claiming_1e12_samples_is_refused(tmp_path: Path, compression: int) -> None:
    path = tmp_path / "claims.npz"
    with zipfile.ZipFile(path, "w", compression=compression) as archive:
        archive.writestr("wx.npy", _claiming_header((10**12,)))
        archive.writestr("t.npy", _npy_bytes(np.arange(3.0)))
    with pytest.raises(ValueError, match=r"declares shape \(1000000000000,\).*zip directory says") as caught:
        load_recording(path)
    assert str(path) in str(caught.value)


def test_issue13_item5_deflate_bomb_is_refused_from_its_header_before_expanding(tmp_path: Path) -> None:
    path = tmp_path / "bomb.npz"
    np.savez_compressed(path, wx=np.zeros(10**7), fs=np.float64(100.0))
    assert path.stat().st_size < 200_000  # 80 MB of zeros in a small file
    tracemalloc.start()
    try:
        with pytest.raises(
            ValueError, match=r"10000001 values \(0\.08 GB as float64\), more than max_values=1000000"
        ):
            load_recording(path, max_values=10**6)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert peak < 8_000_000  # a tenth of the expanded size: nothing was decompressed
    assert len(load_recording(path, max_values=10**7 + 1)) == 10**7


def test_issue13_item5_uncompressed_npz_obeys_the_same_limit(tmp_path: Path) -> None:
    path = tmp_path / "plain.npz"
    np.savez(path, t=np.arange(1000) / 100.0, wx=np.zeros(1000))
    with pytest.raises(ValueError, match=r"2000 values .* more than max_values=1999"):
        load_recording(path, max_values=1999)
    assert len(load_recording(path, max_values=2000)) == 1000


def test_issue13_item5_csv_obeys_the_limit_and_cli_option(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = tmp_path / "r.csv"
    rows = "\n".join(f"{i / 100!r},{0.001 * (i % 7)!r}" for i in range(500))
    path.write_text("t,wx\n" + rows + "\n")
    with pytest.raises(ValueError, match=r"rows already hold 1000 values .* more than max_values=999"):
        load_recording(path, max_values=999)
    assert main(["allan", str(path), "--max-values", "999"]) == BAD_INPUT
    assert "max_values=999" in capsys.readouterr().err
    assert main(["allan", str(path), "--max-values", "1000", "--json"]) == 0


# --- item 6: reserved, duplicate and non-identifier axis names ----------------------------------


@pytest.mark.parametrize(
    ("axes", "fragment"),
    [
        ("t,wx", "'t' is reserved"),
        ("temp,phi", "'temp' is reserved"),
        ("allow_pickle,wx", "'allow_pickle' is reserved"),
        ("wx,FS", "'FS' is reserved"),
        ("wx,wx", "must be distinct"),
        ("wx,WX", "must be distinct"),
        ("w x,wy", "'w x' must be an identifier"),
        ("wx,w-y", "'w-y' must be an identifier"),
    ],
)
@pytest.mark.parametrize("suffix", [".csv", ".npz"])
def test_issue13_item6_simulate_refuses_colliding_axis_names(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], axes: str, fragment: str, suffix: str
) -> None:
    out = tmp_path / f"r{suffix}"
    assert main(["simulate", str(out), "--seed", "1", "--duration", "1", "--axes", axes]) == BAD_INPUT
    assert fragment in capsys.readouterr().err
    assert not out.exists()


def test_issue13_item6_api_refuses_reserved_axes() -> None:
    with pytest.raises(ValueError, match=r"axes=\('time',\): 'time' is reserved"):
        simulate_recording(10, 10.0, rng=np.random.default_rng(1), axes=("time",))


# --- item 7: time units, datetime64, complex columns ---------------------------------------------


def test_issue13_item7_integer_epoch_milliseconds_with_time_unit(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = tmp_path / "ms.csv"
    start = 1_700_000_000_000
    rows = "\n".join(f"{start + 10 * i},{0.001 * (i % 5)!r}" for i in range(400))
    path.write_text("t,wx\n" + rows + "\n")
    recording = load_recording(path, time_unit="ms")
    assert recording.sample_rate == 100.0
    assert recording.time_origin == 1_700_000_000.0
    np.testing.assert_array_equal(recording.time[:3], [0.0, 0.01, 0.02])
    assert main(["allan", str(path), "--time-unit", "ms", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["sample_rate"] == 100.0
    # Without a unit the column is seconds, as documented: 0.1 Hz.
    assert load_recording(path).sample_rate == 0.1


def test_issue13_item7_datetime64_times_are_converted_exactly(tmp_path: Path) -> None:
    path = tmp_path / "dates.npz"
    start = np.datetime64("2023-11-14T22:13:20", "ns")  # 1.7·10⁹ s after the epoch
    times = start + np.arange(300) * np.timedelta64(10, "ms")
    np.savez(path, t=times, wx=np.zeros(300))
    recording = load_recording(path)
    assert recording.sample_rate == 100.0
    assert recording.time_origin == 1_700_000_000.0
    assert recording.time[1] == 0.01
    with pytest.raises(ValueError, match=r"time_unit='ms': the time column .* carries its own unit"):
        load_recording(path, time_unit="ms")
    durations = recording_from_arrays({"wx": np.zeros(4)}, time=np.arange(4) * np.timedelta64(2, "ms"))
    assert durations.sample_rate == 500.0


def test_issue13_item7_complex_columns_are_refused(tmp_path: Path) -> None:
    path = tmp_path / "complex.npz"
    np.savez(path, t=np.arange(10) / 10.0, wx=np.arange(10) + 1j)
    with pytest.raises(TypeError, match=r"column 'wx' holds complex numbers"):
        load_recording(path)
    with pytest.raises(TypeError, match=r"column 'wy' holds complex numbers"):
        recording_from_arrays({"wy": np.ones(5, dtype=complex)}, sample_rate=1.0)


def test_issue13_item7_unknown_time_unit_is_refused() -> None:
    with pytest.raises(ValueError, match=r"time_unit='min': must be one of s, ms, us, ns"):
        recording_from_arrays({"wx": np.zeros(4)}, time=np.arange(4), time_unit="min")


# --- item 8: epoch seconds at 100 Hz ---------------------------------------------------------------


def test_issue13_item8_epoch_seconds_at_100_hz_are_uniform(tmp_path: Path) -> None:
    path = tmp_path / "epoch.csv"
    rows = "\n".join(f"{1_700_000_000 + i // 100}.{i % 100:02d}0000,0.0" for i in range(1000))
    path.write_text("t,wx\n" + rows + "\n")
    assert "1700000000.010000" in path.read_text()
    recording = load_recording(path)
    assert recording.uniform and recording.sample_rate == 100.0
    assert recording.time_origin == 1_700_000_000.0


def test_issue13_item8_real_jitter_at_epoch_times_is_still_refused() -> None:
    time = 1_700_000_000.0 + np.arange(1000) / 100.0
    time[500] += 1e-4  # 1 % of a step, 200 times the float spacing at 1.7·10⁹ s
    with pytest.raises(ValueError, match=r"non-uniform timestamps: 2 steps"):
        recording_from_arrays({"wx": np.zeros(1000)}, time=time)


# --- item 13: binary content noticed from the first block -------------------------------------------


def test_issue13_item13_invalid_utf8_in_the_first_block_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "binary.csv"
    path.write_bytes(b"t,wx\n" + b"0.0,1.0\n" * 600 + bytes(range(128, 256)) * 400)
    with pytest.raises(ValueError, match=r"not a CSV text file \(not UTF-8 at byte 4805"):
        load_recording(path)


def test_issue13_item13_file_without_line_breaks_is_refused_from_the_first_block(tmp_path: Path) -> None:
    path = tmp_path / "one_line.csv"
    path.write_bytes(b"wx" + b"A" * (8 << 20))
    with pytest.raises(ValueError, match=r"no line break in the first 65536 bytes"):
        load_recording(path)


def test_issue13_item13_overlong_row_is_not_read_whole(tmp_path: Path) -> None:
    path = tmp_path / "long_row.csv"
    path.write_bytes(b"t,wx\n0,1\n" + b"7" * (3 * MAX_LINE_BYTES))
    with pytest.raises(ValueError, match=r"row 1 .* is longer than 1048576 characters"):
        load_recording(path)


def test_issue13_item13_binary_after_the_first_block_names_the_row(tmp_path: Path) -> None:
    path = tmp_path / "late_binary.csv"
    text = b"t,wx\n" + b"".join(b"%d,0.5\n" % i for i in range(20_000))
    path.write_bytes(text + b"1\x00\x00\x00,\x00\n")
    with pytest.raises(ValueError, match=r"row 20000 .* NUL bytes"):
        load_recording(path)
