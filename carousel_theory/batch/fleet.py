"""Running a fleet on a Dask client: submission, results as they finish, time-outs, dead workers,
checkpoints and resume.

Each recording goes through two tasks: a hash stage (content hash, and the axes when split per axis),
then — unless an earlier table holds its result — one compute task per recording (or per axis). Results
are gathered as they finish. A task that raises becomes an error row inside the worker; a worker that
dies has its task re-run by Dask on another worker (up to ``distributed.scheduler.allowed-failures``
times, then an error row of kind "worker"); a task running longer than ``task_timeout`` seconds is
cancelled, its worker restarted, and an error row of kind "timeout" written. The table is rewritten
atomically every ``checkpoint_seconds`` and at the end, so an interrupted run can be resumed.
"""

from __future__ import annotations

import collections
import contextlib
import itertools
import threading
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from distributed import Client, Future, as_completed

from carousel_theory.batch.cluster import START_TOPIC, HashOutcome, compute_stage, hash_stage
from carousel_theory.batch.rows import BatchRow, error_row
from carousel_theory.batch.store import ResumeIndex, read_table, write_table
from carousel_theory.batch.tasks import PER_AXIS_TASKS, TASKS, TaskOptions
from carousel_theory.progress import progress

__all__ = ["FleetJob", "FleetOutcome", "run_fleet"]

_POLL_SECONDS = 0.1


@dataclass(frozen=True)
class FleetJob:
    """What to run: the recordings, the task and its options, and where the table goes."""

    paths: tuple[Path, ...]
    task: str
    options: TaskOptions
    out: Path
    per_axis: bool = False
    task_timeout: float | None = None

    def __post_init__(self) -> None:
        if self.task not in TASKS:
            raise ValueError(f"task={self.task!r}: must be one of {sorted(TASKS)}")
        if self.per_axis and self.task not in PER_AXIS_TASKS:
            raise ValueError(f"per_axis=True: task {self.task!r} runs on whole recordings only")
        if self.task_timeout is not None and not self.task_timeout > 0:
            raise ValueError(f"task_timeout={self.task_timeout!r}: must be > 0 seconds")


@dataclass
class FleetOutcome:
    """The rows of the whole fleet, how many recordings were reused from an earlier table, and the wall
    time of the run."""

    rows: list[BatchRow]
    reused: int
    computed: int
    wall_seconds: float
    tables: dict[str, Path] = field(default_factory=dict)


@dataclass
class _Pending:
    path: str
    stage: str
    axis: str | None = None
    digest: str = ""
    token: str = ""


class _StartLog:
    """Start events of compute tasks, received on the client's event thread."""

    def __init__(self, on_start: Callable[[dict[str, Any]], None] | None) -> None:
        self._lock = threading.Lock()
        self.starts: dict[str, list[float]] = collections.defaultdict(list)
        self.workers: dict[str, str] = {}
        self._on_start = on_start

    def __call__(self, event: tuple[float, dict[str, Any]]) -> None:
        _, message = event
        with self._lock:
            self.starts[message["token"]].append(time.monotonic())
            self.workers[message["token"]] = message["worker"]
        if self._on_start is not None:
            self._on_start(message)

    def running_since(self, token: str) -> tuple[float | None, str]:
        with self._lock:
            starts = self.starts.get(token)
            return (starts[-1] if starts else None), self.workers.get(token, "")

    def attempts(self, token: str) -> int:
        with self._lock:
            return len(self.starts.get(token, ()))


class _FleetRun:
    """The state of one run: futures in flight, rows of recordings whose axes are not all back yet."""

    def __init__(self, client: Client, job: FleetJob, log: _StartLog) -> None:
        self.client, self.job, self.log = client, job, log
        self.previous = read_table(job.out)
        self.index = ResumeIndex(self.previous)
        self.fingerprint = job.options.fingerprint()
        self.pending: dict[Future, _Pending] = {}
        self.remaining: dict[str, int] = {}
        self.collected: dict[str, list[BatchRow]] = collections.defaultdict(list)
        self.reused = self.computed = 0
        self.tokens = itertools.count()
        self.queue = as_completed()

    def table(self, rows: list[BatchRow]) -> list[BatchRow]:
        """``rows`` plus the earlier table's rows of recordings of this job not finished yet, so that a
        checkpoint, or an interrupted resumed run, loses nothing that was already known."""
        done = {row.path for row in rows}
        wanted = {str(path) for path in self.job.paths}
        return rows + [row for row in self.previous if row.path in wanted and row.path not in done]

    def _submit(self, function: Callable[..., Any], item: _Pending, *args: Any) -> None:
        # A recording's analysis goes before the hashing of files not yet started, so that results flow
        # from the start and not only after the whole fleet is hashed.
        priority = 1 if item.stage == "compute" else 0
        future = self.client.submit(function, *args, pure=False, priority=priority)
        self.pending[future] = item
        self.queue.add(future)

    def _on_hash(self, item: _Pending, outcome: HashOutcome) -> list[BatchRow] | None:
        job = self.job
        if outcome.error:
            return [error_row(item.path, job.task, "data", outcome.error)]
        reused = self.index.reusable(outcome.content_hash, job.task, self.fingerprint, item.path)
        if reused is not None:
            self.reused += 1
            return reused
        axes: tuple[str | None, ...] = outcome.axes or (None,)
        self.remaining[item.path] = len(axes)
        for axis in axes:
            token = f"{item.path}#{axis or ''}#{next(self.tokens)}"
            compute = _Pending(item.path, "compute", axis, outcome.content_hash, token)
            self._submit(
                compute_stage, compute, item.path, job.task, job.options, axis, compute.digest, token
            )
        return None

    def _on_compute(self, item: _Pending, rows: list[BatchRow]) -> list[BatchRow] | None:
        attempts = max(1, self.log.attempts(item.token))
        self.collected[item.path] += [row.stamped(attempts=attempts) for row in rows]
        self.remaining[item.path] -= 1
        if self.remaining[item.path] > 0:
            return None
        self.computed += 1
        return self.collected.pop(item.path)

    def _failed(self, item: _Pending, kind: str, reason: str) -> list[BatchRow] | None:
        row = error_row(item.path, self.job.task, kind, reason, item.axis or "")
        if item.stage == "hash":
            return [row]
        _, worker = self.log.running_since(item.token)
        return self._on_compute(
            item, [row.stamped(content_hash=item.digest, options=self.fingerprint, worker=worker)]
        )

    def _handle(self, item: _Pending, future: Future) -> list[BatchRow] | None:
        if future.status == "cancelled":  # by the cluster (a restart, a lost scheduler), not by this run
            return self._failed(item, "worker", "the cluster cancelled the task")
        if future.status == "error":
            error = future.exception()
            name = type(error).__name__
            kind = "worker" if name == "KilledWorker" else "internal"
            return self._failed(item, kind, f"{name}: {error}")
        result = future.result()
        future.release()
        if item.stage == "hash":
            return self._on_hash(item, result)
        return self._on_compute(item, result)

    def _restart(self, worker: str) -> None:
        """Restart the worker of a cancelled task (a Python thread cannot be stopped otherwise), in the
        background: the fleet goes on on the other workers meanwhile."""

        def restart() -> None:
            # Without a nanny to restart it, the worker stays busy until the task ends.
            with contextlib.suppress(Exception):
                self.client.restart_workers([worker], raise_for_error=False)

        threading.Thread(target=restart, name=f"restart {worker}", daemon=True).start()

    def _expire(self) -> list[list[BatchRow]]:
        timeout = self.job.task_timeout
        if timeout is None:
            return []
        finished = []
        now = time.monotonic()
        for future, item in list(self.pending.items()):
            since, worker = self.log.running_since(item.token) if item.stage == "compute" else (None, "")
            if since is None or now - since <= timeout:
                continue
            del self.pending[future]
            future.cancel()
            if worker:
                self._restart(worker)
            rows = self._failed(item, "timeout", f"the task ran longer than --task-timeout={timeout:g} s")
            if rows is not None:
                finished.append(rows)
        return finished

    def finished(self) -> Iterator[list[BatchRow]]:
        """Submit the fleet and yield the rows of each recording as soon as all of them are back."""
        for path in self.job.paths:
            self._submit(
                hash_stage, _Pending(str(path), "hash"), str(path), self.job.options, self.job.per_axis
            )
        while self.pending:
            batch = self.queue.next_batch(block=False)
            for future in batch:
                waiting = self.pending.pop(future, None)
                rows = None if waiting is None else self._handle(waiting, future)
                if rows is not None:
                    yield rows
            yield from self._expire()
            if not batch:
                time.sleep(_POLL_SECONDS)


def run_fleet(
    client: Client,
    job: FleetJob,
    *,
    on_start: Callable[[dict[str, Any]], None] | None = None,
    checkpoint_seconds: float = 30.0,
    show_progress: bool | None = None,
) -> FleetOutcome:
    """Run ``job`` on ``client`` and write its table (see the module text).

    ``on_start`` is called on the client's event thread with ``{"token", "pid", "worker"}`` whenever a
    compute task starts; ``show_progress`` forces the progress counter on or off (default: on a
    terminal).
    """
    log = _StartLog(on_start)
    client.subscribe_topic(START_TOPIC, log)
    run = _FleetRun(client, job, log)
    start = last_write = time.monotonic()
    rows: list[BatchRow] = []
    try:
        stream = run.finished()
        for finished in progress(
            stream, total=len(job.paths), label=f"batch {job.task}", enabled=show_progress
        ):
            rows += finished
            if time.monotonic() - last_write >= checkpoint_seconds:
                write_table(run.table(rows), job.out)
                last_write = time.monotonic()
    finally:
        client.unsubscribe_topic(START_TOPIC)
        tables = write_table(run.table(rows), job.out)
    return FleetOutcome(rows, run.reused, run.computed, time.monotonic() - start, tables)
