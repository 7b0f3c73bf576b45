"""Allan variance speed against allantools, same input, same τ, same run.

Usage: ``python benchmarks/bench_allan_vs_allantools.py [--sizes 1000000 10000000] [--repeats 3]``

For each size, a seeded white + rate-random-walk record at 100 Hz is analysed at octave τ (up to a third
of the record) by ``carousel_theory.allan.allan_variance`` (which also computes the χ² intervals) and by
``allantools.oadev`` / ``allantools.adev`` (``data_type="freq"``, the same τ; squared). Prints the best
of ``--repeats`` wall times, the ratio allantools / ours (> 1 means we are faster) and the largest
relative difference of the values.
"""

from __future__ import annotations

import argparse
import time

import allantools
import numpy as np

from carousel_theory.allan import allan_variance


def _best_time(function, repeats: int) -> tuple[float, object]:
    best, result = float("inf"), None
    for _ in range(repeats):
        start = time.perf_counter()
        result = function()
        best = min(best, time.perf_counter() - start)
    return best, result


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[1_000_000, 10_000_000])
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    rng = np.random.default_rng(2014)
    print(
        f"{'samples':>10} {'estimator':>16} {'ours (s)':>10} {'allantools (s)':>15} {'ratio':>7} "
        f"{'max rel diff':>13}"
    )
    for size in args.sizes:
        y = 7e-3 + 6e-3 * rng.standard_normal(size) + 1e-6 * np.cumsum(rng.standard_normal(size))
        for estimator, peer in (("overlapping", allantools.oadev), ("non-overlapping", allantools.adev)):
            ours_time, ours = _best_time(
                lambda e=estimator, y=y: allan_variance(y, 100.0, estimator=e), args.repeats
            )
            taus = ours.tau  # type: ignore[attr-defined]
            peer_time, peer_result = _best_time(
                lambda p=peer, t=taus, y=y: p(y, rate=100.0, data_type="freq", taus=t), args.repeats
            )
            difference = np.max(np.abs(peer_result[1] ** 2 / ours.avar - 1))  # type: ignore[attr-defined,index]
            print(
                f"{size:>10} {estimator:>16} {ours_time:>10.3f} {peer_time:>15.3f} "
                f"{peer_time / ours_time:>7.2f} {difference:>13.2e}"
            )


if __name__ == "__main__":
    main()
