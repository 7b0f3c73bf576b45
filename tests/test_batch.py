"""``carousel-theory batch`` on a real Dask LocalCluster of 2 worker processes: the table, a corrupt
file, a worker killed in the middle, a task time-out, a resumed run, and the command without Dask."""

from __future__ import annotations

import json
import math
import os
import signal
import sys
import threading

import numpy as np
import pyarrow.csv as pa_csv
import pyarrow.parquet as pq
import pytest

from carousel_theory.batch.cluster import connect
from carousel_theory.batch.discovery import content_hash, discover_recordings
from carousel_theory.batch.fleet import FleetJob, run_fleet
from carousel_theory.batch.report import effect_frequencies, find_outliers, robust_z_scores, write_report
from carousel_theory.batch.rows import BatchRow, error_row
from carousel_theory.batch.store import read_table, write_atomically, write_table
from carousel_theory.batch.tasks import TASKS, TaskOptions, check_options
from carousel_theory.cli import main
from carousel_theory.data import load_recording
from carousel_theory.fitting import fit_noise_model
from carousel_theory.simulate import simulate_recording, write_recording

SMALL_SAMPLES = 4000
#: A record whose fit lasts about a second: long enough to kill its worker in the middle of the task.
MEDIUM_SAMPLES = 60_000
#: A record whose closed loop lasts well over the time-out of the test (it is cancelled, never finished):
#: 10,000 s at 100 Hz, where the loop takes seconds even on a quiet machine.
SLOW_SAMPLES = 1_000_000


def _write(path, samples, seed, axes=("wx", "wy")):
    recording = simulate_recording(
        samples,
        100.0,
        rng=np.random.default_rng(seed),
        white_variance=3.6e-5,
        rrw_variance=1e-11,
        axes=axes,
    )
    return write_recording(recording, path)


@pytest.fixture(scope="module")
def fleet(tmp_path_factory):
    """Three short recordings (CSV and NPZ) and one truncated CSV (cut in the middle of a row)."""
    directory = tmp_path_factory.mktemp("fleet")
    _write(directory / "unit_a.csv", SMALL_SAMPLES, 1)
    _write(directory / "unit_b.npz", SMALL_SAMPLES, 2)
    (directory / "nested").mkdir()
    _write(directory / "nested" / "unit_c.csv", SMALL_SAMPLES, 3)
    whole = (directory / "unit_a.csv").read_bytes()
    cut = whole.index(b",", len(whole) // 2) + 1  # a write that stopped in the middle of a row
    (directory / "truncated.csv").write_bytes(whole[:cut])
    return directory


@pytest.fixture(scope="module")
def medium_file(tmp_path_factory):
    return _write(tmp_path_factory.mktemp("medium") / "medium.npz", MEDIUM_SAMPLES, 8, axes=("wx",))


@pytest.fixture(scope="module")
def slow_file(tmp_path_factory):
    return _write(tmp_path_factory.mktemp("slow") / "slow.npz", SLOW_SAMPLES, 9)


def _same(first: BatchRow, second: BatchRow) -> bool:
    """Field-by-field equality with NaN equal to NaN (the numbers a task does not produce)."""
    for name, value in vars(first).items():
        other = getattr(second, name)
        both_nan = isinstance(value, float) and math.isnan(value) and math.isnan(other)
        if not (value == other or both_nan):
            return False
    return True


@pytest.fixture(scope="module")
def cluster():
    connection = connect(workers=2, dashboard=False)
    yield connection
    connection.close()


@pytest.fixture
def client(cluster):
    """The module's client (the tests that kill or restart a worker come last: nobody waits for the
    restarted worker)."""
    return cluster.client


def _job(paths, out, task="fit", **keywords):
    return FleetJob(paths=tuple(paths), task=task, options=TaskOptions(), out=out, **keywords)


def test_fleet_table_matches_single_file_fits_and_reports_the_corrupt_file(client, fleet, tmp_path):
    paths = discover_recordings([str(fleet)])
    outcome = run_fleet(client, _job(paths, tmp_path, per_axis=True), show_progress=False)
    rows = {(os.path.basename(row.path), row.axis): row for row in outcome.rows}
    assert sorted(rows) == [
        ("truncated.csv", ""),
        ("unit_a.csv", "wx"),
        ("unit_a.csv", "wy"),
        ("unit_b.npz", "wx"),
        ("unit_b.npz", "wy"),
        ("unit_c.csv", "wx"),
        ("unit_c.csv", "wy"),
    ]
    broken = rows[("truncated.csv", "")]
    assert (broken.status, broken.error_kind) == ("error", "data")
    assert "truncated.csv" in broken.error and "CSV" in broken.error
    # Each row holds what the single-file fit gives for that axis, in field units, with its error.
    for path in (p for p in paths if p.name != "truncated.csv"):
        recording = load_recording(path)
        for axis, rates in recording.rates.items():
            expected = fit_noise_model(rates, recording.sample_rate, iterations=3).field_units()
            row = rows[(path.name, axis)]
            assert row.status == "ok" and row.content_hash == content_hash(path)
            assert row.angle_random_walk_deg_per_sqrt_h == expected["angle_random_walk_deg_per_sqrt_h"][0]
            assert row.angle_random_walk_deg_per_sqrt_h_se == expected["angle_random_walk_deg_per_sqrt_h"][1]
            assert row.bias_instability_deg_per_h == expected["bias_instability_deg_per_h"][0]
            assert row.seconds > 0 and row.attempts == 1 and row.worker.startswith("tcp://")
    parquet = pq.read_table(tmp_path / "results.parquet").to_pylist()
    csv = pa_csv.read_csv(tmp_path / "results.csv").to_pylist()
    assert len(parquet) == len(csv) == 7
    assert [r["path"] for r in parquet] == [r["path"] for r in csv] == sorted(r["path"] for r in parquet)
    write_report(outcome.rows, tmp_path, "fit")
    report = (tmp_path / "report.md").read_text(encoding="utf-8")
    assert "truncated.csv" in report and (tmp_path / "distributions.png").stat().st_size > 0


def test_a_resumed_run_recomputes_only_the_changed_file(client, fleet, tmp_path, capsys):
    directory = tmp_path / "in"
    directory.mkdir()
    for name in ("unit_a.csv", "unit_b.npz", "truncated.csv"):
        (directory / name).write_bytes((fleet / name).read_bytes())
    out = tmp_path / "out"
    job = _job(discover_recordings([str(directory)]), out, task="allan")
    first = run_fleet(client, job)  # stderr is not a terminal here: no progress counter
    assert "batch allan" not in capsys.readouterr().err
    assert (first.computed, first.reused) == (3, 0)
    _write(directory / "unit_b.npz", SMALL_SAMPLES, 77)  # new content under the same name
    second = run_fleet(client, job, show_progress=True)
    assert "\rbatch allan 3/3" in capsys.readouterr().err
    assert (second.computed, second.reused) == (1, 2)
    before = {(row.path, row.axis): row for row in first.rows}
    after = {(row.path, row.axis): row for row in second.rows}
    assert before.keys() == after.keys()
    for key, row in after.items():
        if key[0].endswith("unit_b.npz"):
            assert row.content_hash != before[key].content_hash
            assert row.bias_deg_per_h != before[key].bias_deg_per_h
        else:
            assert _same(row, before[key])  # reused as it was, time taken included


def test_the_command_runs_on_an_existing_scheduler(client, fleet, tmp_path, capsys):
    status = main(
        [
            "batch",
            str(fleet / "unit_a.csv"),
            str(fleet / "unit_b.npz"),
            "--task",
            "allan",
            "--out",
            str(tmp_path),
            "--scheduler",
            client.scheduler_info()["address"],
        ]
    )
    assert status == 0
    assert "2 recordings: 2 computed, 0 reused, 0 with an error" in capsys.readouterr().out
    assert len(read_table(tmp_path)) == 4


def test_a_worker_killed_mid_task_is_retried_and_the_fleet_completes(client, fleet, medium_file, tmp_path):
    killed: list[int] = []
    lock = threading.Lock()

    def kill_first_start_of_medium(message):
        with lock:
            if "medium.npz" in message["token"] and not killed:
                killed.append(message["pid"])
                os.kill(message["pid"], signal.SIGKILL)

    paths = [*discover_recordings([str(fleet)]), medium_file]
    outcome = run_fleet(
        client, _job(paths, tmp_path), on_start=kill_first_start_of_medium, show_progress=False
    )
    assert len(killed) == 1
    medium = [row for row in outcome.rows if row.path == str(medium_file)]
    assert len(medium) == 1 and medium[0].status == "ok" and medium[0].attempts == 2
    assert {os.path.basename(row.path) for row in outcome.rows if row.status != "ok"} == {"truncated.csv"}
    assert len(read_table(tmp_path)) == len(outcome.rows) == 8


def test_a_task_over_the_time_out_becomes_an_error_row(client, slow_file, tmp_path):
    job = _job([slow_file], tmp_path, task="loop", task_timeout=2.0)
    outcome = run_fleet(client, job, show_progress=False)
    (row,) = outcome.rows
    assert (row.status, row.error_kind, row.axis) == ("error", "timeout", "")
    assert "--task-timeout=2 s" in row.error and row.content_hash == content_hash(slow_file)
    assert _same(read_table(tmp_path)[0], row)


def test_batch_without_dask_says_which_extra_to_install(monkeypatch, fleet, tmp_path, capsys):
    for name in ("dask", "distributed"):
        monkeypatch.setitem(sys.modules, name, None)
    for name in ("carousel_theory.batch.cluster", "carousel_theory.batch.fleet"):
        monkeypatch.delitem(sys.modules, name, raising=False)
    status = main(["batch", str(fleet), "--out", str(tmp_path)])
    error = capsys.readouterr().err
    assert status == 2
    assert error.count("\n") == 1 and "pip install 'carousel-theory[batch]'" in error
    # The core goes on working with Dask blocked.
    assert main(["fit", str(fleet / "unit_a.csv")]) == 0
    assert not (tmp_path / "results.parquet").exists()


# --- the parts without a cluster ---------------------------------------------------------------------------


def test_robust_z_scores_by_hand():
    # log10 values 0, 1, 2, 3, 6: median 2, absolute deviations 2, 1, 0, 1, 4, MAD 1.
    scores = robust_z_scores([1.0, 10.0, 100.0, 1000.0, 1e6])
    expected = np.array([-2, -1, 0, 1, 4]) / 1.4826
    assert np.allclose(scores, expected, rtol=1e-12, atol=0)


def test_outliers_flag_the_unit_far_from_the_median():
    values = [2.0, 2.1, 1.9, 2.05, 1.95, 2.0, 20.0]
    rows = [
        BatchRow(path=f"u{i}", task="fit", axis="wx", angle_random_walk_deg_per_sqrt_h=v)
        for i, v in enumerate(values)
    ]
    flagged = find_outliers(rows)
    assert [(o.path, o.parameter) for o in flagged] == [("u6", "angle_random_walk_deg_per_sqrt_h")]


def test_effect_frequencies_count_each_recording_once():
    rows = [
        BatchRow(path="a", task="loop", axis="wx", effects="spikes;temperature"),
        BatchRow(path="a", task="loop", axis="wy", effects="spikes;temperature"),
        BatchRow(path="b", task="loop", axis="wx", effects="none"),
        BatchRow(path="c", task="loop", axis="wx", effects="spikes"),
        error_row("d", "loop", "data", "unreadable"),
    ]
    assert effect_frequencies(rows) == {"spikes": 2, "none": 1, "temperature": 1}


def test_an_interrupted_write_leaves_the_previous_table(tmp_path):
    rows = [BatchRow(path="a", task="fit", axis="wx", angle_random_walk_deg_per_sqrt_h=1.5)]
    write_table(rows, tmp_path)

    def interrupted(temporary):
        temporary.write_bytes(b"half a table")
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        write_atomically(tmp_path / "results.parquet", interrupted)
    (back,) = read_table(tmp_path)
    assert _same(back, rows[0])
    assert sorted(p.name for p in tmp_path.iterdir()) == ["results.csv", "results.parquet"]


def test_a_table_round_trips_through_parquet(tmp_path):
    rows = [
        BatchRow(path="b", task="loop", axis="wy", effects="spikes", misfit_before=2.5, attempts=2),
        error_row("a", "loop", "timeout", "too long"),
    ]
    write_table(rows, tmp_path)
    back = read_table(tmp_path)
    assert [row.path for row in back] == ["a", "b"]  # sorted by path
    assert _same(back[0], rows[1]) and _same(back[1], rows[0])


INVALID_CALLS = [
    ("unknown task", lambda: _job([], "out", task="spectrum"), "task='spectrum'"),
    ("design without latitude", lambda: check_options("design", TaskOptions()), "latitude=None"),
    ("design at the pole", lambda: check_options("design", TaskOptions(latitude=90.0)), "latitude=90.0"),
    ("design scheme", lambda: check_options("design", TaskOptions(latitude=60.0, schemes=("spin",))), "spin"),
    ("loop split per axis", lambda: _job([], "out", task="loop", per_axis=True), "per_axis=True"),
    ("non-positive time-out", lambda: _job([], "out", task_timeout=0.0), "task_timeout=0.0"),
    ("no inputs", lambda: discover_recordings([]), "inputs=[]"),
    ("unknown estimator", lambda: check_options("fit", TaskOptions(estimator="mean")), "estimator='mean'"),
    ("unknown component", lambda: check_options("fit", TaskOptions(model=("pink",))), "model=('pink',)"),
    ("scheduler and workers", lambda: connect("tcp://nowhere:1", 2), "workers=2"),
    ("bad error kind", lambda: error_row("a", "fit", "mystery", "?"), "kind='mystery'"),
]


@pytest.mark.parametrize(
    ("call", "message"), [c[1:] for c in INVALID_CALLS], ids=[c[0] for c in INVALID_CALLS]
)
def test_invalid_calls(call, message):
    with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(")", r"\)").replace("[", r"\[")):
        call()


def test_missing_input_names_the_pattern(tmp_path):
    with pytest.raises(FileNotFoundError, match="nothing_here"):
        discover_recordings([str(tmp_path / "nothing_here" / "*.csv")])


def test_design_task_agrees_with_the_fit_and_design_commands(fleet, tmp_path, capsys):
    """The fleet's design row against the two single-file commands chained by hand: ``fit --json`` into
    ``design --noise``."""
    path = str(fleet / "unit_a.csv")
    options = TaskOptions(latitude=61.5, design_durations=(20.0,), schemes=("static", "carousel:N=200"))
    check_options("design", options)
    rows = TASKS["design"](path, options, None)
    assert [row.axis for row in rows] == ["wx", "wy"]
    assert main(["fit", path, "--json"]) == 0
    noise = tmp_path / "fit.json"
    noise.write_text(capsys.readouterr().out, encoding="utf-8")
    command = ["design", "--noise", str(noise), "--latitude", "61.5", "--duration", "20"]
    command += ["--scheme", "static", "--scheme", "carousel:N=200", "--json"]
    assert main(command) == 0
    design = json.loads(capsys.readouterr().out)
    best = next(s for s in design["schemes"] if s["scheme"] == design["recommended"])
    for row in rows:
        assert row.design_scheme == design["recommended"]
        assert row.design_heading_sigma_deg == pytest.approx(best["heading_sigma_deg"], rel=1e-9)
