"""A synthetic fleet on Dask: 1 worker against 2 workers in the same run, the scheduler's overhead per
recording, and the cluster a 10,000-unit fleet of 12-hour 1 kHz runs would need to finish overnight.

The fleet: ``--units`` one-hour 100 Hz recordings (NPZ) from
:func:`carousel_theory.simulate.simulate_recording` (bias + white + rate random walk at ADIS16405-like
levels), every tenth with an undeclared effect from the catalogue, run through ``--task`` (default
``loop``) on an embedded LocalCluster of 1 worker process and then of 2, each into a fresh output
directory. For each run: the wall time of :func:`run_fleet` (cluster start excluded), the sum of the task
times measured inside the workers, and the overhead per recording, (workers × wall − Σ task time) /
recordings: the time a worker is not running the analysis (hashing, scheduling, moving the rows, idle at
the end). The speed-up is wall(1) / wall(2).

The extrapolation to 12-hour 1 kHz records (120 × the samples) needs the growth of the task time with the
record's length: the task is also timed in this process on one recording of 1 h and one of 4 h, and the
exponent p of t ∝ samples^p taken from the two. Then

    task time of a 12 h 1 kHz record = t(1 h) · 120^p,
    worker-hours = units · (task time + overhead) / parallel efficiency,

with the efficiency the measured speed-up / 2, and the workers needed = worker-hours / the night's hours.

    python benchmarks/bench_batch_fleet.py --units 50
"""

from __future__ import annotations

import argparse
import importlib
import math
import tempfile
import time
from pathlib import Path

import numpy as np

from carousel_theory.batch.cluster import connect
from carousel_theory.batch.discovery import discover_recordings
from carousel_theory.batch.fleet import FleetJob, run_fleet
from carousel_theory.batch.tasks import TASKS, TaskOptions
from carousel_theory.simulate import simulate_recording, write_recording

RATE, WHITE, WALK = 100.0, 3.6e-5, 1e-11
HOUR_SAMPLES = 3600 * 100
#: Undeclared effects given to every tenth unit, in turn.
EFFECTS = (
    "spikes:amplitude=0.06,rate=2e-4",
    "warmup:amplitude=8e-3,time_constant=30",
    "sinusoid:amplitude=5e-4",
)
TARGET_UNITS, TARGET_SAMPLES = 10_000, 12 * 3600 * 1000


def write_fleet(directory: Path, units: int) -> list[str]:
    """The synthetic fleet; returns the effect given to each unit ("" for none)."""
    given = []
    for unit in range(units):
        effect = EFFECTS[(unit // 10) % len(EFFECTS)] if unit % 10 == 9 else ""
        recording = simulate_recording(
            HOUR_SAMPLES,
            RATE,
            rng=np.random.default_rng(1000 + unit),
            white_variance=WHITE,
            rrw_variance=WALK,
            effects=[effect] if effect else [],
        )
        write_recording(recording, directory / f"unit_{unit:04d}.npz")
        given.append(effect.partition(":")[0])
    return given


def time_fleet(paths: list[Path], task: str, workers: int, out: Path) -> dict[str, float]:
    start = time.perf_counter()
    connection = connect(workers=workers, dashboard=False)
    # Workers import the analyses when they unpickle their first task; do it before the clock starts.
    connection.client.run(importlib.import_module, "carousel_theory.batch.tasks")
    started = time.perf_counter() - start
    try:
        job = FleetJob(paths=tuple(paths), task=task, options=TaskOptions(), out=out)
        outcome = run_fleet(connection.client, job, show_progress=False)
    finally:
        connection.close()
    by_recording = {row.path: row.seconds for row in outcome.rows}  # one task per recording
    task_seconds = float(sum(by_recording.values()))
    failed = sum(row.status != "ok" for row in outcome.rows)
    return {
        "workers": workers,
        "wall": outcome.wall_seconds,
        "task": task_seconds,
        "overhead": (workers * outcome.wall_seconds - task_seconds) / len(paths),
        "start": started,
        "failed": failed,
        "effects": outcome.rows,  # type: ignore[dict-item]
    }


def growth_exponent(task: str, directory: Path) -> tuple[float, float, float]:
    """(t of 1 h, t of 4 h, p) for the task run in this process on one recording of each length."""
    times = []
    for hours in (1, 4):
        recording = simulate_recording(
            hours * HOUR_SAMPLES, RATE, rng=np.random.default_rng(7), white_variance=WHITE, rrw_variance=WALK
        )
        path = write_recording(recording, directory / f"growth_{hours}h.npz")
        start = time.perf_counter()
        TASKS[task](str(path), TaskOptions(), None)
        times.append(time.perf_counter() - start)
    return times[0], times[1], math.log(times[1] / times[0]) / math.log(4)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--units", type=int, default=50)
    parser.add_argument("--task", default="loop", choices=sorted(TASKS))
    parser.add_argument("--night-hours", type=float, default=10.0, help="the overnight window (default 10 h)")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as scratch:
        root = Path(scratch)
        (root / "fleet").mkdir()
        given = write_fleet(root / "fleet", args.units)
        paths = discover_recordings([str(root / "fleet")])
        runs = [time_fleet(paths, args.task, workers, root / f"out{workers}") for workers in (1, 2)]
        one_hour, four_hours, exponent = growth_exponent(args.task, root)
    report(args, given, runs, (one_hour, four_hours, exponent))


def report(
    args: argparse.Namespace, given: list[str], runs: list[dict], growth: tuple[float, float, float]
) -> None:
    one_hour, four_hours, exponent = growth
    print(
        f"fleet: {args.units} one-hour 100 Hz recordings, task {args.task}; undeclared effects in "
        f"{sum(bool(e) for e in given)} ({', '.join(sorted({e for e in given if e}))})"
    )
    print("workers  wall (s)  Σ task (s)  overhead/recording (s)  cluster start (s)  error rows")
    for run in runs:
        print(
            f"{run['workers']:7d}  {run['wall']:8.1f}  {run['task']:10.1f}  {run['overhead']:22.3f}  "
            f"{run['start']:17.1f}  {run['failed']:10d}"
        )
    speedup = runs[0]["wall"] / runs[1]["wall"]
    efficiency = min(speedup / 2, 1.0)  # above 1 is noise, not a gain to project
    found = {}
    for row in runs[1]["effects"]:
        if row.axis in ("wx", "") and row.status == "ok":
            for name in filter(None, row.effects.split(";")):
                found[name] = found.get(name, 0) + 1
    print(f"speed-up 1 → 2 workers: {speedup:.2f} (parallel efficiency {efficiency:.0%})")
    print(f"effects the loop named (recordings): {dict(sorted(found.items()))}")
    per_task = runs[0]["task"] / args.units
    print(
        f"task time in process: 1 h {one_hour:.2f} s, 4 h {four_hours:.2f} s, "
        f"growth exponent p = {exponent:.2f}"
    )
    scale = (TARGET_SAMPLES / HOUR_SAMPLES) ** exponent
    target_task = per_task * scale
    overhead = max(runs[1]["overhead"], 0.0)
    worker_hours = TARGET_UNITS * (target_task + overhead) / efficiency / 3600
    workers = math.ceil(worker_hours / args.night_hours)
    linear_hours = TARGET_UNITS * (per_task * TARGET_SAMPLES / HOUR_SAMPLES + overhead) / efficiency / 3600
    print(
        f"10,000 units × 12 h at 1 kHz: {target_task:.0f} s per record (mean task {per_task:.2f} s × "
        f"{TARGET_SAMPLES // HOUR_SAMPLES}^{exponent:.2f}), + {overhead:.2f} s overhead, at {efficiency:.0%} "
        f"efficiency: {worker_hours:.0f} worker-hours, so {workers} single-threaded workers (cores) to "
        f"finish in {args.night_hours:g} h"
    )
    print(
        f"  if the task time grew in proportion to the samples (p = 1, the conservative bound): "
        f"{linear_hours:.0f} worker-hours, {math.ceil(linear_hours / args.night_hours)} workers"
    )


if __name__ == "__main__":
    main()
