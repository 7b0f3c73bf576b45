"""The registry's float64 evaluation of the 1/f entries (TIM 2014 §III-D) against the propagation fast path,
and the evaluation-cost estimates against measured times, all in the same run.

1. ``formula("flicker_carousel_var").numeric(d=0.5, N=200, k=arange(1, 1001))`` against
   ``propagation.flicker_bin_variances(0.5, 200, 1000)`` (the same FFT, so the ratio should be near 1),
   and against one call per bin (what ``numeric`` did before it grouped the bins), for k = 1 … 200.
2. For a few evaluations below the budget, measured time / estimated time
   (``Formula.evaluation_cost``, :mod:`carousel_theory.evaluation_cost`): an estimate is useful when
   the ratio stays within a small factor of 1.

Run: python benchmarks/bench_formula_numeric.py
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
from bench_flicker_bins import best_of  # the same best-of-n timer as the 1/f bin benchmark

from carousel_theory.evaluation_cost import exact_flicker_cost
from carousel_theory.formulas import formula
from carousel_theory.propagation import flicker_bin_variances, flicker_carouselled_bin_variance

N, K_MAX, ORDER = 200, 1000, 0.5
#: The one-call-per-bin baseline is quadratic in k; it runs to this many bins only.
SMALL = 200


def numeric_against_propagation() -> None:
    entry = formula("flicker_carousel_var")
    bins = np.arange(1, K_MAX + 1)
    registry_time, registry = best_of(lambda: entry.numeric(d=ORDER, N=N, k=bins))
    fast_time, fast = best_of(lambda: flicker_bin_variances(ORDER, N, K_MAX, "carouselled"))
    same = np.array_equal(registry, fast)
    print(f"flicker_carousel_var, d = {ORDER}, N = {N}, k = 1 … {K_MAX}:")
    print(
        f"  numeric {registry_time * 1e3:.1f} ms, flicker_bin_variances {fast_time * 1e3:.1f} ms "
        f"(ratio {registry_time / fast_time:.2f}; identical values: {same})"
    )
    small = np.arange(1, SMALL + 1)
    grouped_time, grouped = best_of(lambda: entry.numeric(d=ORDER, N=N, k=small))
    per_bin_time, per_bin = best_of(
        lambda: np.array([flicker_carouselled_bin_variance(ORDER, N, int(k)) for k in small]), repeats=1
    )
    difference = float(np.max(np.abs(grouped - per_bin) / per_bin))
    print(
        f"  k = 1 … {SMALL}: numeric {grouped_time * 1e3:.1f} ms vs one FFT per bin {per_bin_time:.2f} s "
        f"(ratio {per_bin_time / grouped_time:.0f}x, max relative difference {difference:.1e})"
    )


def estimates_against_measurements() -> None:
    print("measured / estimated time:")
    cases = [
        ("rrw_carousel_var at 9000 digits", lambda: formula("rrw_carousel_var").evaluate(digits=9000, N=7),
         formula("rrw_carousel_var").evaluation_cost(digits=9000, N=7)),
        ("flicker_carousel_var, kN = 20000, 50 digits",
         lambda: formula("flicker_carousel_var").evaluate(d=0.5, N=200, k=100),
         formula("flicker_carousel_var").evaluation_cost(d=0.5, N=200, k=100)),
        ("flicker_carousel_var, kN = 2000, 2000 digits",
         lambda: formula("flicker_carousel_var").evaluate(digits=2000, d=0.5, N=200, k=10),
         formula("flicker_carousel_var").evaluation_cost(digits=2000, d=0.5, N=200, k=10)),
        ("flicker_average_var exactly, kN = 4000",
         lambda: formula("flicker_average_var").exact(d=Fraction(1, 2), N=200, k=20),
         exact_flicker_cost("", 4000, 2)),
    ]  # fmt: skip
    for label, run, cost in cases:
        measured, _ = best_of(run, repeats=1)
        print(f"  {label}: {measured:.2f} s measured, {cost.seconds:.2f} s estimated "
              f"(ratio {measured / cost.seconds:.2f})")  # fmt: skip


def main() -> None:
    numeric_against_propagation()
    estimates_against_measurements()


if __name__ == "__main__":
    main()
