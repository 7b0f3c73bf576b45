"""A 12-hour recording at 1 kHz (4.32·10⁷ samples × 3 axes) through ``allan``, ``fit`` and ``loop``: wall
time and peak memory of each command.

Usage: ``python benchmarks/bench_long_recording.py [--samples 43200000] [--format npz csv]
[--commands allan fit loop] [--keep DIR]``

A seeded white + rate-random-walk recording (3 axes, 1 kHz, :func:`carousel_theory.simulate.sample_noise`)
is written once to a temporary directory as an uncompressed NPZ (``numpy.savez``, with an ``fs`` entry)
and/or as a CSV with a time column (written by pyarrow). Each command (``python -m carousel_theory allan
FILE``, ``python -m carousel_theory fit FILE`` and ``python -m carousel_theory loop FILE``) then runs in
its own subprocess; its wall time and its peak resident set size
(``resource.getrusage(RUSAGE_CHILDREN).ru_maxrss`` of that process alone, read in a fresh wrapper process)
are printed. The target is a peak below 4 GB.

With ``--keep DIR`` the recordings stay in DIR, and a recording already there (written by an earlier run
with the same ``--samples``; its length is checked) is used again instead of being written anew.

Measured with this script (2 shared cores, loaded by other work; wall times vary by ±50 %), 4.32·10⁷
samples × 3 axes: ``loop`` NPZ 3.13 GB (334 s), CSV 3.38 GB (504 s); ``allan`` and ``fit`` NPZ 2.07 and
2.07 GB (10.6 and 14.8 s), CSV 2.32 and 2.34 GB (33 and 35 s). The target is met with about 0.6 GB to
spare. (With the confidence-set trend reference, before its 1/f unit was limited to refits with a 1/f
term and computed once per reference, the NPZ loop had risen to 5.06 GB.)

Where the loop's memory goes was found once with a resident-set probe around each stage (not part of this
script; its figures cannot be rerun from here): the loop holds about 1.3 GB from its start (the interpreter
and libraries, the time column and the two analysed axes, 0.32 GB each) and about 1.8 GB at its end (the
fitted models and the shared 1/f unit autocovariance, 0.32 GB); its highest stage is the warm-up
detector's joint test (its refit and confidence-set reference).
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from carousel_theory.noise_model import NoiseModel
from carousel_theory.simulate import sample_noise

RATE = 1000.0
MODEL = NoiseModel(sample_rate=RATE, white_variance=3.6e-5 * 10, rrw_variance=1e-15)

#: The commands measured, in this order.
COMMANDS = ("allan", "fit", "loop")

#: Runs one command in a child and prints (wall time, the child's peak RSS in kB) as its last line.
_WRAPPER = """
import resource, subprocess, sys, time
start = time.perf_counter()
code = subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL).returncode
wall = time.perf_counter() - start
print(code, wall, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)
"""


def _existing(directory: Path, samples: int, formats: list[str]) -> dict[str, Path] | None:
    """The recordings an earlier run left in ``directory``, if all are there with ``samples`` rows."""
    paths = {kind: directory / f"long.{kind}" for kind in formats}
    if not all(path.exists() for path in paths.values()):
        return None
    if "npz" in paths and np.load(paths["npz"], mmap_mode="r")["wx"].shape[0] != samples:
        return None
    if "csv" in paths:
        with paths["csv"].open("rb") as handle:
            rows = sum(chunk.count(b"\n") for chunk in iter(lambda: handle.read(1 << 24), b""))
        if rows != samples + 1:
            return None
    return paths


def _write(directory: Path, samples: int, formats: list[str]) -> dict[str, Path]:
    rng = np.random.default_rng(43_200_000)
    axes = {name: sample_noise(MODEL, samples, rng=rng) for name in ("wx", "wy", "wz")}
    paths = {}
    if "npz" in formats:
        paths["npz"] = directory / "long.npz"
        np.savez(paths["npz"], fs=np.array(RATE), **axes)
    if "csv" in formats:
        import pyarrow as arrow
        import pyarrow.csv as arrow_csv

        paths["csv"] = directory / "long.csv"
        table = arrow.table({"t": np.arange(samples) / RATE, **axes})
        arrow_csv.write_csv(table, paths["csv"], arrow_csv.WriteOptions(quoting_style="none"))
    return paths


def _measure(command: list[str]) -> tuple[int, float, float]:
    output = subprocess.run(
        [sys.executable, "-c", _WRAPPER, *command], capture_output=True, text=True, check=True
    ).stdout.split()
    return int(output[-3]), float(output[-2]), float(output[-1]) / 1024**2


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=43_200_000)
    parser.add_argument("--format", nargs="+", default=["npz"], choices=("npz", "csv"))
    parser.add_argument("--commands", nargs="+", default=list(COMMANDS), choices=COMMANDS)
    parser.add_argument(
        "--keep", type=Path, help="write the recordings here instead of a temporary directory"
    )
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as temporary:
        directory = args.keep or Path(temporary)
        directory.mkdir(parents=True, exist_ok=True)
        start = time.perf_counter()
        paths = _existing(directory, args.samples, args.format) if args.keep else None
        if paths is None:
            paths = _write(directory, args.samples, args.format)
            elapsed = time.perf_counter() - start
            print(f"wrote {args.samples} samples × 3 axes at {RATE:g} Hz in {elapsed:.1f} s")
        else:
            print(f"using the {args.samples}-sample recordings in {directory}")
        print(f"{'format':>6} {'command':>8} {'exit':>5} {'wall (s)':>9} {'peak (GB)':>10} {'file (GB)':>10}")
        for kind, path in paths.items():
            for command in args.commands:
                code, wall, peak = _measure([sys.executable, "-m", "carousel_theory", command, str(path)])
                size = path.stat().st_size / 1024**3
                print(f"{kind:>6} {command:>8} {code:>5} {wall:>9.1f} {peak:>10.2f} {size:>10.2f}")


if __name__ == "__main__":
    main()
