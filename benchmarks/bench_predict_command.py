"""Wall time and peak memory of ``carousel-theory predict`` on a recording, each size in a fresh process.

Run from the repository root::

    PYTHONPATH=. python benchmarks/bench_predict_command.py [--recording FILE]
        [--sizes 6000:60000 100000:1000000]

For each ``calibration:horizon`` pair the command ``python -m carousel_theory predict FILE
--calibration N --horizon H`` (σ_w², σ_v² estimated by REML from the calibration segment, then the
Kalman forecast with white noise) runs in its own child process; the child's wall time and peak
resident set size (``getrusage(RUSAGE_CHILDREN).ru_maxrss`` read in an intermediate process that
runs only that child) are printed, with its CPU time (user + system, which a loaded machine
distorts less than the wall time) and the time the same process needs only to start the command
(``predict --help``: interpreter and imports), the baseline every size pays.

With ``--baseline DIR`` (a checkout or ``git archive`` export of an earlier commit) every command
also runs with ``PYTHONPATH=DIR``, in the same run, and the CPU-time ratio baseline/current is
printed: on a shared machine only a same-run comparison means anything.

Without ``--recording`` a seeded synthetic recording (1/f of order ½ plus white noise, 100 Hz, as
long as the largest calibration + horizon) is written to a temporary directory. The measured
ADIS16405 runs (10⁶ samples each) also serve: the horizon may run past the end of the recording.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

_MEASURE = """
import json, resource, subprocess, sys, time
start = time.perf_counter()
completed = subprocess.run(sys.argv[1:], capture_output=True, text=True)
elapsed = time.perf_counter() - start
usage = resource.getrusage(resource.RUSAGE_CHILDREN)
print(json.dumps({"seconds": elapsed, "cpu_seconds": usage.ru_utime + usage.ru_stime,
                  "peak_bytes": usage.ru_maxrss * 1024, "code": completed.returncode,
                  "stdout": completed.stdout, "stderr": completed.stderr[-2000:]}))
"""


def _measure(command: list[str], code: Path | None = None) -> dict:
    """Run ``command`` in the measuring process; with ``code``, from that directory and with it on
    PYTHONPATH (``python -m`` puts the working directory first on the path)."""
    environment = dict(os.environ)
    if code is not None:
        environment["PYTHONPATH"] = str(code)
    completed = subprocess.run(
        [sys.executable, "-c", _MEASURE, *command],
        capture_output=True,
        text=True,
        check=True,
        env=environment,
        cwd=code,
    )
    return json.loads(completed.stdout)


def _line(label: str, result: dict) -> str:
    return (
        f"  {label:24s} {result['seconds']:8.2f} s wall   {result['cpu_seconds']:8.2f} s CPU   "
        f"peak RSS {result['peak_bytes'] / 2**20:7.0f} MiB"
    )


def _synthetic_recording(directory: Path, length: int) -> Path:
    from carousel_theory.long_memory import fractional_integral

    rng = np.random.default_rng(2012)
    rates = 1e-3 + 2e-4 * fractional_integral(rng.standard_normal(length), 0.5)
    rates += 6e-4 * rng.standard_normal(length)
    path = directory / "synthetic_gyro.npz"
    np.savez(path, t=np.arange(length) / 100.0, wx=rates, fs=100.0)
    return path


def _parse_sizes(texts: list[str]) -> list[tuple[int, int]]:
    sizes = []
    for text in texts:
        calibration, _, horizon = text.partition(":")
        sizes.append((int(calibration), int(horizon)))
    return sizes


def _run_size(base: list[str], recording: Path, n: int, h: int, output: Path, baseline: Path | None) -> None:
    command = [*base, str(recording.resolve()), "--calibration", str(n), "--horizon", str(h)]
    command += ["--output", str(output.resolve())]
    result = _measure(command)
    if result["code"] != 0:
        print(f"  {n} + {h}: failed (exit {result['code']}): {result['stderr']}")
        return
    print(_line(f"{n} + {h}", result))
    print("    " + result["stdout"].splitlines()[0])
    if baseline is not None:
        before = _measure(command, baseline.resolve())
        print(_line(f"{n} + {h} (baseline)", before))
        print(f"    CPU time baseline/current: {before['cpu_seconds'] / result['cpu_seconds']:.2f}×")
        print("    " + before["stdout"].splitlines()[0])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--recording", type=Path, help="a recording (default: a synthetic one)")
    parser.add_argument("--sizes", nargs="+", default=["6000:60000", "100000:1000000"])
    parser.add_argument("--baseline", type=Path, help="also run the code in this directory (PYTHONPATH)")
    args = parser.parse_args()
    sizes = _parse_sizes(args.sizes)
    with tempfile.TemporaryDirectory() as temporary:
        recording = args.recording or _synthetic_recording(Path(temporary), max(n + h for n, h in sizes))
        base = [sys.executable, "-m", "carousel_theory", "predict"]
        print(f"recording {recording}")
        print(_line("start-up (predict --help)", _measure([*base, "--help"])))
        for n, h in sizes:
            _run_size(base, recording, n, h, Path(temporary) / f"forecast_{n}_{h}.csv", args.baseline)


if __name__ == "__main__":
    main()
