"""Read speed of each recording format against pandas (or h5py / scipy.io directly), in the same run.

One recording of 10⁶ rows (t, wx, wy, wz) is written in every format to a temporary directory; each is
read by ``load_recording`` (with every check: finite values, uniform time) and by the peer that reads the
same file without checks. Prints the best of three runs and the ratio ours / peer.

    python benchmarks/bench_readers.py [--rows 1000000]
"""

from __future__ import annotations

import argparse
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

import h5py
import numpy as np
import pandas as pd
import scipy.io

from carousel_theory.data import load_recording


def _best(function: Callable[[], object], repeats: int = 3) -> float:
    times = []
    for _ in range(repeats):
        started = time.perf_counter()
        function()
        times.append(time.perf_counter() - started)
    return min(times)


def _write_all(directory: Path, rows: int) -> dict[str, Path]:
    rng = np.random.default_rng(2024)
    frame = pd.DataFrame(
        {"t": np.arange(rows) / 100.0, **{n: rng.standard_normal(rows) for n in ("wx", "wy", "wz")}}
    )
    paths = {
        "csv (comma)": directory / "r.csv",
        "text (semicolon)": directory / "r_semicolon.csv",
        "text (whitespace)": directory / "r.txt",
        "hdf5": directory / "r.h5",
        "mat v5": directory / "r.mat",
    }
    frame.to_csv(paths["csv (comma)"], index=False)
    frame.to_csv(paths["text (semicolon)"], index=False, sep=";")
    frame.to_csv(paths["text (whitespace)"], index=False, sep=" ")
    with h5py.File(paths["hdf5"], "w") as handle:
        for name in frame.columns:
            handle.create_dataset(name, data=frame[name].to_numpy())
    scipy.io.savemat(paths["mat v5"], {name: frame[name].to_numpy().reshape(-1, 1) for name in frame.columns})
    return paths


def _peers(paths: dict[str, Path]) -> dict[str, tuple[str, Callable[[], object]]]:
    def hdf5() -> object:
        with h5py.File(paths["hdf5"], "r") as handle:
            return {name: handle[name][()] for name in handle}

    return {
        "csv (comma)": ("pandas.read_csv", lambda: pd.read_csv(paths["csv (comma)"])),
        "text (semicolon)": (
            "pandas.read_csv(sep=';')",
            lambda: pd.read_csv(paths["text (semicolon)"], sep=";"),
        ),
        "text (whitespace)": (
            "pandas.read_csv(sep=r'\\s+')",
            lambda: pd.read_csv(paths["text (whitespace)"], sep=r"\s+"),
        ),
        "hdf5": ("h5py, every dataset", hdf5),
        "mat v5": ("scipy.io.loadmat", lambda: scipy.io.loadmat(paths["mat v5"])),
    }


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rows", type=int, default=1_000_000)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        paths = _write_all(Path(folder), args.rows)
        print(f"{args.rows} rows x 4 columns; best of 3 runs")
        print(f"{'format':20} {'ours (s)':>9} {'peer (s)':>9} {'ours/peer':>9}  peer")
        for name, (peer_name, peer) in _peers(paths).items():
            ours = _best(lambda path=paths[name]: load_recording(path))
            theirs = _best(peer)
            print(f"{name:20} {ours:9.3f} {theirs:9.3f} {ours / theirs:9.2f}  {peer_name}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
