"""Var(Σ_t w_t x_t) for rate random walk and 1/f noise: `weighted_sum_variance` (O(n) cumulative
sums, O(n log n) FFT correlation) against the dense quadratic form wᵀ T Tᵀ w (T = R of TIM 2014
eq. (10) or F of §III-D), both timed in the same run, for n from 100 to 4000.

Run: python benchmarks/bench_propagation_vs_dense.py
"""

from __future__ import annotations

import time

import numpy as np
import scipy.linalg

from carousel_theory.processes import fractional_coefficients
from carousel_theory.propagation import weighted_sum_variance


def best_of(function, repeats: int = 3) -> tuple[float, float]:
    best, result = float("inf"), 0.0
    for _ in range(repeats):
        start = time.perf_counter()
        result = function()
        best = min(best, time.perf_counter() - start)
    return best, result


def dense(weights: np.ndarray, process: str) -> float:
    n = weights.shape[0]
    if process == "rrw":
        T = np.tril(np.ones((n, n)))
    else:
        T = scipy.linalg.toeplitz(fractional_coefficients(0.5, n), np.zeros(n))
    coefficients = T.T @ weights
    return float(coefficients @ coefficients)


def main() -> None:
    rng = np.random.default_rng(0)
    print("n      process  weighted_sum_variance   dense wᵀTTᵀw   ratio   relative difference")
    for n in (100, 500, 1000, 2000, 4000):
        weights = rng.standard_normal(n)
        for process in ("rrw", "flicker"):
            d = 0.5 if process == "flicker" else None
            fast_time, fast = best_of(
                lambda weights=weights, process=process, d=d: weighted_sum_variance(weights, process, d)
            )
            dense_time, slow = best_of(
                lambda weights=weights, process=process: dense(weights, process), repeats=1
            )
            print(
                f"{n:5d}  {process:7s}  {fast_time * 1e6:12.1f} µs      {dense_time * 1e3:9.2f} ms  "
                f"{dense_time / fast_time:7.0f}×  {abs(fast - slow) / slow:.1e}"
            )


if __name__ == "__main__":
    main()
