"""1/f bin variances (TIM 2014 §III-D) for N = 200, k = 1 … 1000: the one-cumulative-sum method of
carousel_theory.propagation against two baselines measured in the same run:

- each bin as its own weighted sum (`weighted_sum_variance` on the zero-padded weight vector, one FFT
  per bin), for k = 1 … 200;
- the dense covariance F Fᵀ of the (kN)×(kN) Toeplitz matrix F, then e_kᵀ (F Fᵀ) e_k, for small k.

Run: python benchmarks/bench_flicker_bins.py
"""

from __future__ import annotations

import time

import numpy as np
import scipy.linalg

from carousel_theory.processes import fractional_coefficients
from carousel_theory.propagation import (
    flicker_bin_variances,
    flicker_carouselled_bin_variance,
    weighted_sum_variance,
)
from carousel_theory.weights import averaging_weights, carousel_weights

N, K_MAX, ORDER = 200, 1000, 0.5
#: The per-bin baseline is quadratic in k; it runs to this many bins only.
SMALL = 200


def best_of(function, repeats: int = 3) -> tuple[float, object]:
    best, result = float("inf"), None
    for _ in range(repeats):
        start = time.perf_counter()
        result = function()
        best = min(best, time.perf_counter() - start)
    return best, result


def per_bin_sums(method: str, k_max: int) -> np.ndarray:
    weight_sets = [averaging_weights(N)] if method == "averaged" else list(carousel_weights(N))
    out = np.zeros(k_max)
    for k in range(1, k_max + 1):
        for weights in weight_sets:
            vector = np.zeros(k * N)
            vector[(k - 1) * N :] = weights
            out[k - 1] += weighted_sum_variance(vector, "flicker", ORDER)
    return out


def dense(method: str, k: int) -> float:
    size = k * N
    psi = fractional_coefficients(ORDER, size)
    F = scipy.linalg.toeplitz(psi, np.zeros(size))
    weight_sets = [averaging_weights(N)] if method == "averaged" else list(carousel_weights(N))
    total = 0.0
    for weights in weight_sets:
        e = np.zeros(size)
        e[(k - 1) * N :] = weights
        covariance = F @ F.T  # the dense (kN)×(kN) covariance of the 1/f samples
        total += float(e @ covariance @ e)
    return total


def main() -> None:
    print(f"1/f bin variances, d = {ORDER}, N = {N}")
    for method in ("averaged", "carouselled"):
        fast_time, _ = best_of(lambda method=method: flicker_bin_variances(ORDER, N, K_MAX, method))
        print(f"  {method}: all bins k = 1 … {K_MAX} at once: {fast_time * 1e3:.1f} ms")
        part_time, part = best_of(lambda method=method: flicker_bin_variances(ORDER, N, SMALL, method))
        naive_time, naive = best_of(lambda method=method: per_bin_sums(method, SMALL), repeats=1)
        print(
            f"    k = 1 … {SMALL}: {part_time * 1e3:.1f} ms vs one FFT per bin {naive_time:.2f} s "
            f"(ratio {naive_time / part_time:.0f}×, max relative difference "
            f"{np.max(np.abs(part - naive) / naive):.1e})"
        )
        for k in (1, 2, 5, 10):
            own_time, own = best_of(lambda method=method, k=k: flicker_bin_variances(ORDER, N, k, method))
            dense_time, value = best_of(lambda method=method, k=k: dense(method, k), repeats=1)
            print(
                f"    k = {k:2d}: bins 1 … k {own_time * 1e3:6.2f} ms vs dense F Fᵀ ({k * N}×{k * N}) "
                f"{dense_time * 1e3:8.1f} ms (ratio {dense_time / own_time:6.0f}×, relative difference "
                f"{abs(value - own[-1]) / value:.1e})"
            )
    mp_time, _ = best_of(lambda: flicker_carouselled_bin_variance(0.5, N, 10, digits=50), repeats=1)
    print(f"  carouselled, 50 digits, k = 10 (recursion in h): {mp_time:.2f} s")


if __name__ == "__main__":
    main()
