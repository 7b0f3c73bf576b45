"""Cost of the exact carouselled-RRW closed form against N, beside the dense and the O(N) products.

    python benchmarks/bench_closed_forms.py [--max-dense 4000] [--max-linear 10000000]

For N = 10² … 10⁹ it times

* ``closed float``: ``formula("rrw_carousel_var_sin").numeric(N=N)`` — the registry's float64 value
  of sᵀRRᵀs = (3 csc²(π/N) − 2)/(8N), argument checks included;
* ``closed 50 dig``: ``formula(...).evaluate(N=N, digits=50)`` — SymPy/mpmath at 50 digits;
* ``O(N) cumsum``: the tails Rᵀs by a reversed cumulative sum, then their squared norm (numpy);
* ``dense``: the literal product sᵀ R Rᵀ s with the N×N lower-triangular ones matrix R (numpy),
  feasible only while the N² matrix fits in memory (8N² bytes: 128 MB at N = 4000);

and prints each time with the ratio to the float closed form, measured in the same run (best of
several repeats). The dense and O(N) values are also compared with the closed form.
"""

from __future__ import annotations

import argparse
import math
import time
from collections.abc import Callable

import numpy as np

from carousel_theory.formulas import formula


def best_time(function: Callable[[], object], repeats: int) -> float:
    best = math.inf
    for _ in range(repeats):
        start = time.perf_counter()
        function()
        best = min(best, time.perf_counter() - start)
    return best


def sine_weights(n: int) -> np.ndarray:
    return np.sin(2 * np.pi * np.arange(1, n + 1) / n) / n


def linear_product(n: int) -> float:
    tails = np.cumsum(sine_weights(n)[::-1])[::-1]  # (Rᵀs)_i = Σ_{j ≥ i} s_j
    return float(tails @ tails)


def dense_product(n: int) -> float:
    R = np.tril(np.ones((n, n)))  # TIM 2014 eq. (10)
    s = sine_weights(n)
    return float(s @ R @ (R.T @ s))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--max-dense", type=int, default=4000, help="largest N for the dense product")
    parser.add_argument("--max-linear", type=int, default=10_000_000, help="largest N for the O(N) product")
    args = parser.parse_args()
    entry = formula("rrw_carousel_var_sin")
    sizes = [100, 300, 1000, 3000, 4000, 10_000, 100_000, 1_000_000, 10_000_000, 100_000_000, 1_000_000_000]
    header = (
        f"{'N':>13} {'closed float':>13} {'closed 50 dig':>14} {'O(N) cumsum':>12} {'dense':>11} "
        f"{'cumsum/closed':>14} {'dense/closed':>13} {'rel. diff dense':>16}"
    )
    print(header)
    for n in sizes:
        closed_time = best_time(lambda n=n: entry.numeric(N=n), 200)
        mp_time = best_time(lambda n=n: entry.evaluate(N=n, digits=50), 20)
        value = entry.numeric(N=n)
        linear_time = dense_time = math.nan
        difference = ""
        if n <= args.max_linear:
            linear_time = best_time(lambda n=n: linear_product(n), 3 if n < 10**7 else 1)
            linear_value = linear_product(n)
            difference = f"{abs(linear_value - value) / value:.1e} (O(N))"
        if n <= args.max_dense:
            dense_time = best_time(lambda n=n: dense_product(n), 3)
            difference = f"{abs(dense_product(n) - value) / value:.1e}"

        def show(seconds: float) -> str:
            return "infeasible" if math.isnan(seconds) else f"{seconds * 1e3:.4f} ms"

        linear_ratio = linear_time / closed_time if not math.isnan(linear_time) else math.nan
        dense_ratio = dense_time / closed_time if not math.isnan(dense_time) else math.nan
        times = f"{show(closed_time):>13} {show(mp_time):>14} {show(linear_time):>12} {show(dense_time):>11}"
        print(f"{n:>13,} {times} {linear_ratio:>14.1f} {dense_ratio:>13.1f} {difference:>16}")


if __name__ == "__main__":
    main()
