"""The Dask side of a fleet: which cluster runs it, and the functions its workers execute.

By default an embedded ``distributed.LocalCluster`` of worker processes (one thread each: the analyses
are NumPy code that holds the GIL much of the time); with a scheduler address, the Dask cluster already
running there. The worker functions only read the recordings; every failure inside them becomes an
error row, so a task never raises into the fleet.
"""

from __future__ import annotations

import importlib.util
import os
import sys
import time
import warnings
import zipfile
from dataclasses import dataclass
from typing import TextIO

from distributed import Client, LocalCluster, get_worker

from carousel_theory.batch.discovery import content_hash
from carousel_theory.batch.rows import BatchRow, error_row
from carousel_theory.batch.tasks import TASKS, TaskOptions, recording_axes

__all__ = ["START_TOPIC", "ClusterConnection", "compute_stage", "connect", "hash_stage"]

#: Topic of the event each task logs when it starts (for time-outs, attempts and tests).
START_TOPIC = "carousel-theory-batch-start"
#: Exceptions that mean "this file, with these options, cannot be analysed" (kind "data").
DATA_ERRORS = (
    ValueError,
    TypeError,
    FileNotFoundError,
    IsADirectoryError,
    PermissionError,
    zipfile.BadZipFile,
)


@dataclass
class ClusterConnection:
    """A client and, for the embedded cluster, the cluster it owns (closed with :meth:`close`)."""

    client: Client
    cluster: LocalCluster | None

    @property
    def dashboard(self) -> str | None:
        """The dashboard's address, when the scheduler serves one (its pages need bokeh)."""
        services = self.client.scheduler_info().get("services", {})
        if "dashboard" not in services or importlib.util.find_spec("bokeh") is None:
            return None
        return str(self.client.dashboard_link)

    def close(self) -> None:
        self.client.close()
        if self.cluster is not None:
            self.cluster.close()


def connect(
    scheduler: str | None = None,
    workers: int | None = None,
    *,
    dashboard: bool = True,
    stream: TextIO | None = None,
) -> ClusterConnection:
    """A client on the scheduler at ``scheduler``, or on a new local cluster of ``workers`` processes
    (default: one per core). Prints the dashboard's address on ``stream`` (stderr) when one runs."""
    if scheduler is not None and workers is not None:
        raise ValueError(f"workers={workers!r}: give either a scheduler address or a worker count, not both")
    if workers is not None and workers < 1:
        raise ValueError(f"workers={workers!r}: must be >= 1")
    cluster = None
    if scheduler is None:
        with warnings.catch_warnings():
            # Port 8787 taken: Dask serves the dashboard on a free port instead, printed below.
            warnings.filterwarnings("ignore", message="Port .* is already in use", category=UserWarning)
            cluster = LocalCluster(
                n_workers=workers or os.cpu_count() or 1,
                threads_per_worker=1,
                processes=True,
                # Without a dashboard Dask still opens an HTTP port; ":0" takes a free one.
                dashboard_address=":8787" if dashboard else ":0",
            )
        client = Client(cluster)
    else:
        client = Client(scheduler)
    connection = ClusterConnection(client, cluster)
    if dashboard and connection.dashboard:
        print(f"Dask dashboard: {connection.dashboard}", file=stream or sys.stderr)
    return connection


@dataclass(frozen=True)
class HashOutcome:
    """What the first stage learnt about a file: its content hash and, when split per axis, its axes."""

    content_hash: str
    axes: tuple[str, ...] | None
    error: str


def hash_stage(path: str, options: TaskOptions, split_axes: bool) -> HashOutcome:
    """Run on a worker: hash the file (and list its axes when the task is split per axis)."""
    try:
        digest = content_hash(path)
        axes = recording_axes(path, options) if split_axes else None
    except DATA_ERRORS as error:
        return HashOutcome("", None, f"{type(error).__name__}: {error}")
    return HashOutcome(digest, axes, "")


def _announce_start(token: str) -> str:
    """Log the start of a task on the scheduler's event stream; return the worker's address."""
    try:
        worker = get_worker()
    except ValueError:  # not on a worker (called directly): nothing to announce
        return ""
    worker.log_event(START_TOPIC, {"token": token, "pid": os.getpid(), "worker": worker.address})
    return str(worker.address)


def compute_stage(
    path: str, task: str, options: TaskOptions, axis: str | None, digest: str, token: str
) -> list[BatchRow]:
    """Run on a worker: one task of the adapter, its failure turned into an error row, and the
    bookkeeping (hash, options, seconds, worker) stamped on every row."""
    address = _announce_start(token)
    start = time.perf_counter()
    try:
        rows = TASKS[task](path, options, axis)
    except DATA_ERRORS as error:
        rows = [error_row(path, task, "data", f"{type(error).__name__}: {error}", axis or "")]
    except Exception as error:  # the fleet goes on; the row says what broke
        rows = [error_row(path, task, "internal", f"{type(error).__name__}: {error}", axis or "")]
    seconds = time.perf_counter() - start
    fingerprint = options.fingerprint()
    return [
        row.stamped(content_hash=digest, options=fingerprint, seconds=seconds, worker=address, attempts=1)
        for row in rows
    ]
