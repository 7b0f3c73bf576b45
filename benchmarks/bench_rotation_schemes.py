"""Estimate covariance of rotation schemes: `scheme_variance.estimate_covariances` (all record lengths of a
scheme from one pass of cumulative sums, 1/f by one FFT per length) against the dense quadratic form
W C Wᵀ with the (n×n) covariance matrix of each process, both timed in the same run.

Part 1 — a sweep of 100 schemes × 50 durations (1 min … 1 h at 100 Hz, bias + white + RRW; up to
360 000 samples per record): the total time of the fast method, and, for the smallest durations the dense
method could not hold (an n×n matrix of 360 000² doubles is 1 TB), so the dense method runs in part 2 only.
Part 2 — side by side at n = 500 … 3000 for the same schemes: time per scheme for 10 lengths, ratio,
and the largest relative difference.

Run: PYTHONPATH=. python benchmarks/bench_rotation_schemes.py
"""

from __future__ import annotations

import time

import numpy as np

from carousel_theory.design import record_length
from carousel_theory.fitting import NoiseModel
from carousel_theory.processes import covariance_matrix
from carousel_theory.rotation_schemes import Carousel, Indexing, Static, demodulation_weights
from carousel_theory.scheme_variance import estimate_covariances

RATE = 100.0
NOISE = [NoiseModel(RATE, white_variance=1e-4, rrw_variance=1e-10)]
BIAS_VARIANCE = 1e-8


def schemes() -> list:
    """100 schemes: static, 49 carousel rates (integer and non-integer), 50 indexing set-ups."""
    result: list = [Static()]
    result += [Carousel(samples) for samples in np.round(np.geomspace(20, 6000, 49), 1)]
    for positions in (2, 4):
        result += [
            Indexing(positions, dwell, 100) for dwell in np.unique(np.geomspace(10, 6000, 25).astype(int))
        ]
    return result[:100]


def fast(scheme, lengths):
    pattern = scheme.pattern(max(lengths))
    return estimate_covariances(pattern, lengths, NOISE, BIAS_VARIANCE)


def dense(scheme, lengths):
    totals = []
    for n in lengths:
        W = demodulation_weights(scheme.pattern(n))
        total = np.zeros((2, 2))
        for process, variance in (("bias", BIAS_VARIANCE), ("white", 1e-4), ("rrw", 1e-10)):
            C = covariance_matrix(process, n)
            for gyro in (0, 1):
                total += variance * (W[:, gyro, :] @ C @ W[:, gyro, :].T)
        totals.append(total)
    return totals


def part_1(all_schemes) -> None:
    durations = np.geomspace(60, 3600, 50)
    start = time.perf_counter()
    evaluated = 0
    for scheme in all_schemes:
        lengths = sorted(
            {record_length(scheme, d, RATE) for d in durations if d * RATE >= (scheme.cycle_length() or 1)}
        )
        fast(scheme, lengths)
        evaluated += len(lengths)
    elapsed = time.perf_counter() - start
    print(
        f"part 1: {len(all_schemes)} schemes, {evaluated} (scheme, duration) pairs up to 360000 samples: "
        f"{elapsed:.2f} s"
    )


def part_2(all_schemes) -> None:
    print("n      schemes  fast (s)  dense (s)   ratio dense/fast  max relative difference")
    picked = all_schemes[::10]
    for n in (500, 1000, 2000, 3000):
        lengths = [int(v) for v in np.linspace(n // 10, n, 10)]
        start = time.perf_counter()
        fast_results = [fast(s, lengths) for s in picked]
        fast_time = time.perf_counter() - start
        start = time.perf_counter()
        dense_results = [dense(s, lengths) for s in picked]
        dense_time = time.perf_counter() - start
        worst = max(
            float(np.max(np.abs(f.total()[:2, :2] - d)) / np.max(np.abs(d)))
            for fs, ds in zip(fast_results, dense_results, strict=True)
            for f, d in zip(fs, ds, strict=True)
        )
        print(
            f"{n:<6} {len(picked):<8} {fast_time:<9.3f} {dense_time:<11.3f} "
            f"{dense_time / fast_time:<17.0f} {worst:.1e}"
        )


def main() -> None:
    all_schemes = schemes()
    part_1(all_schemes)
    part_2(all_schemes)


if __name__ == "__main__":
    main()
