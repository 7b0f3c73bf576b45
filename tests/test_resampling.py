"""Resampling by bin means: exact on a uniform grid, block means at f/k, gaps refused with their time,
and ``--resample`` on every command that reads a recording."""

from __future__ import annotations

import json

import numpy as np
import pytest

from carousel_theory.cli import main
from carousel_theory.data import load_recording, recording_from_arrays, resample_recording
from carousel_theory.resampling import MAX_EMPTY_RUN, block_average, default_resample_rate


def _white(samples: int, seed: int) -> np.ndarray:
    return np.random.default_rng(seed).standard_normal(samples)


def test_uniform_input_at_its_own_rate_is_returned_exactly():
    values = _white(1000, 1)
    time = np.arange(1000) / 100.0  # i/100 carries float rounding right at the bin edges
    recording = recording_from_arrays({"wx": values}, time=time, resample=100.0)
    np.testing.assert_array_equal(recording.rates["wx"], values)
    assert recording.sample_rate == 100.0 and recording.uniform
    assert "0 of 1000 bins empty" in recording.notes[-1]


@pytest.mark.parametrize("factor", [2, 5, 10])
def test_integer_fraction_of_the_rate_gives_block_means(factor):
    values = _white(1000, factor)
    time = 1_700_000_000 + np.arange(1000) / 100.0  # epoch seconds: offsets are taken exactly first
    recording = recording_from_arrays({"wx": values}, time=time, resample=100.0 / factor)
    expected = values.reshape(-1, factor).mean(axis=1)
    np.testing.assert_allclose(recording.rates["wx"], expected, rtol=0, atol=1e-15)
    assert recording.time_origin == 1_700_000_000


def test_repeated_timestamps_of_a_burst_are_averaged():
    # Bursts of four samples stamped at once, one burst every 0.04 s: 25 Hz of bin means.
    time = np.repeat(np.arange(50) * 0.04, 4)
    values = np.arange(200, dtype=np.float64)
    with pytest.raises(ValueError, match=r"not strictly increasing.*--resample HZ averages repeated"):
        recording_from_arrays({"wx": values}, time=time)
    recording = recording_from_arrays({"wx": values}, time=time, resample=25.0)
    np.testing.assert_array_equal(recording.rates["wx"], values.reshape(50, 4).mean(axis=1))


def test_short_empty_runs_are_interpolated_between_bin_means():
    time = np.delete(np.arange(1000) / 100.0, [500])  # one missing sample: one empty bin of 999
    values = np.arange(1000, dtype=np.float64)[np.arange(1000) != 500] * 2.0
    averaged = block_average(time, {"wx": values}, 100.0)
    assert (averaged.empty_bins, averaged.bins) == (1, 1000)
    assert averaged.columns["wx"][500] == 1000.0  # halfway between 998 and 1002
    np.testing.assert_array_equal(np.delete(averaged.columns["wx"], 500), values)


def test_a_gap_is_refused_with_its_time():
    time = np.concatenate((np.arange(500) / 100.0, 10.0 + np.arange(500) / 100.0))
    with pytest.raises(ValueError, match=r"no sample between t=4\.99 s and t=10 s after the first .* a gap"):
        recording_from_arrays({"wx": _white(1000, 3)}, time=time, resample=100.0)
    run = MAX_EMPTY_RUN + 1  # one empty bin more than may be bridged
    short = np.delete(np.arange(2000) / 100.0, np.arange(1000, 1000 + run))
    with pytest.raises(ValueError, match=rf"{run} empty bins in a row, more than {MAX_EMPTY_RUN}"):
        block_average(short, {"wx": np.zeros(len(short))}, 100.0)
    bridged = np.delete(np.arange(2000) / 100.0, np.arange(1000, 1000 + MAX_EMPTY_RUN))
    assert block_average(bridged, {"wx": np.zeros(len(bridged))}, 100.0).empty_bins == MAX_EMPTY_RUN


def test_too_high_a_rate_is_refused_for_its_empty_bins():
    time = np.arange(1000) / 100.0
    with pytest.raises(ValueError, match=r"resampling at 150 Hz leaves .* bins empty .* mean rate is 100 Hz"):
        block_average(time, {"wx": np.zeros(1000)}, 150.0)


def test_backwards_timestamps_are_refused():
    with pytest.raises(ValueError, match=r"timestamps go backwards: t\[1\]=0\.2 then t\[2\]=0\.1"):
        block_average(np.array([0.0, 0.2, 0.1, 0.3]), {"wx": np.zeros(4)}, 10.0)


def test_default_rate_halves_until_bins_can_be_bridged():
    # Bursts: 8 samples 1 ms apart every 80 ms (mean rate 100 Hz); bins of 80 ms or more are all filled.
    time = (np.arange(800) // 8) * 0.08 + (np.arange(800) % 8) * 0.001
    rate = default_resample_rate(time)
    assert rate is not None
    mean_rate = 799 / float(time[-1])
    # f̄ = 799/7.927 s = 100.8 Hz. At f̄/8 = 12.6 Hz the bins (79.4 ms) are shorter than the burst period
    # (80 ms), but 100 bursts drift by only 0.6 ms each, less than a bin: none is empty. At f̄/4 every
    # other bin is empty.
    assert rate == pytest.approx(mean_rate / 8, rel=1e-12)


def test_resample_recording_keeps_temperature_and_unwraps_the_angle():
    time = np.arange(400) / 100.0
    angle = np.mod(np.arange(400) * 0.05, 2 * np.pi)
    recording = recording_from_arrays(
        {"wx": _white(400, 4)}, time=time, temperature=np.full(400, 25.0), angle=angle, irregular="keep"
    )
    halved = resample_recording(recording, 50.0)
    np.testing.assert_array_equal(halved.temperature, np.full(200, 25.0))
    np.testing.assert_allclose(halved.angle, np.unwrap(angle).reshape(200, 2).mean(axis=1), atol=1e-12)


def test_integer_nanosecond_timestamps_with_clock_jitter_are_uniform(tmp_path):
    rng = np.random.default_rng(5)
    stamps = 1_700_000_000_000_000_000 + np.arange(2000, dtype=np.int64) * 10_000_000
    stamps += rng.integers(-2000, 2000, 2000)  # ±2 µs on 10 ms steps: jitter of the stamps
    path = tmp_path / "ns.npz"
    np.savez(path, t=stamps, wx=_white(2000, 6))
    recording = load_recording(path, time_unit="ns")
    assert recording.uniform and recording.sample_rate == 100.0
    text = tmp_path / "ns.csv"  # parsed as float64: 1.7·10¹⁸ ns are known to 256 ns
    text.write_text(
        "t,wx\n"
        + "".join(
            f"{stamp},{value!r}\n" for stamp, value in zip(stamps, _white(2000, 6).tolist(), strict=True)
        )
    )
    assert load_recording(text, time_unit="ns").sample_rate == 100.0
    drifting = stamps.copy()
    drifting[1000:] += 2_000_000  # a 2 ms jump: the samples themselves are no longer uniform
    np.savez(path, t=drifting, wx=_white(2000, 6))
    with pytest.raises(ValueError, match="non-uniform timestamps"):
        load_recording(path, time_unit="ns")


@pytest.fixture
def bursty_npz(tmp_path):
    rng = np.random.default_rng(7)
    time = np.cumsum(rng.choice([0.002, 0.002, 0.03], size=6000))
    path = tmp_path / "bursty.npz"
    np.savez(path, t=time, wx=rng.normal(0, 1e-3, 6000), wy=rng.normal(0, 1e-3, 6000))
    return path


@pytest.mark.parametrize(
    "command",
    [["allan", "--json"], ["fit", "--json"], ["predict", "--calibration", "100"]],
    ids=["allan", "fit", "predict"],
)
def test_every_command_refuses_bursty_timestamps_and_suggests_resample(bursty_npz, command, capsys):
    assert main([command[0], str(bursty_npz), *command[1:]]) == 2
    error = capsys.readouterr().err
    assert "--resample HZ" in error and "Hz is the highest" in error
    assert main([command[0], str(bursty_npz), *command[1:], "--resample", "10"]) == 0
    captured = capsys.readouterr()
    assert "bin-averaged onto a uniform 10 Hz grid" in captured.err + captured.out


def test_allan_json_after_resample_has_the_new_rate(bursty_npz, capsys):
    assert main(["allan", str(bursty_npz), "--resample", "10", "--json"]) == 0
    document = json.loads(capsys.readouterr().out)
    assert document["sample_rate"] == 10.0
    assert document["columns"]["wx"]["tau"][0] == pytest.approx(0.1)


@pytest.mark.slow
def test_loop_uses_the_given_rate(tmp_path, capsys):
    rng = np.random.default_rng(8)
    time = np.cumsum(rng.choice([0.002, 0.002, 0.03], size=20_000))
    path = tmp_path / "bursty.npz"
    np.savez(path, t=time, wx=rng.normal(0, 1e-3, 20_000), wy=rng.normal(0, 1e-3, 20_000))
    assert main(["loop", str(path), "--resample", "20", "--json", str(tmp_path / "loop.json")]) == 0
    assert "uniform 20 Hz grid" in capsys.readouterr().out


@pytest.mark.parametrize("value", ["0", "-5", "nan", "inf", "fast"])
def test_resample_option_refuses_a_rate_that_is_not_one(bursty_npz, value, capsys):
    with pytest.raises(SystemExit):
        main(["allan", str(bursty_npz), "--resample", value])
    assert "must be a positive rate in Hz or 'auto'" in capsys.readouterr().err


def test_resample_needs_a_time_column_and_no_sample_rate():
    with pytest.raises(ValueError, match="has no time column to resample from"):
        recording_from_arrays({"wx": np.zeros(10)}, sample_rate=1.0, resample=1.0)
    with pytest.raises(ValueError, match=r"sample_rate=1\.0 and resample=2\.0: give one"):
        recording_from_arrays({"wx": np.zeros(10)}, time=np.arange(10.0), sample_rate=1.0, resample=2.0)
    with pytest.raises(ValueError, match=r"resample='fast': must be a rate in Hz or 'auto'"):
        recording_from_arrays({"wx": np.zeros(10)}, time=np.arange(10.0), resample="fast")


def test_batch_task_reads_with_the_resample_option(bursty_npz):
    pytest.importorskip("pyarrow", reason="batch rows need pyarrow (the 'batch' extra)")
    from carousel_theory.batch.tasks import TaskOptions, allan_task

    with pytest.raises(ValueError, match="--resample HZ"):
        allan_task(str(bursty_npz), TaskOptions())
    rows = allan_task(str(bursty_npz), TaskOptions(resample=10.0))
    assert [row.axis for row in rows] == ["wx", "wy"] and rows[0].sample_rate_hz == 10.0


def test_a_rate_far_above_the_data_is_refused_before_its_bins_are_counted():
    # 10⁹ Hz on 100 samples at 100 Hz would count 10⁹ bins; refused at once, naming the rate and the share
    time = np.arange(100) / 100.0
    with pytest.raises(ValueError, match=r"resampling at 1e\+09 Hz makes 9\.9e\+08 bins for 100 samples"):
        recording_from_arrays({"wx": _white(100, 5)}, time=time, resample=1e9)
