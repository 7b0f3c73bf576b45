"""Likelihood passes of the REML search for σ_v²/σ_w²: Brent's method from a bracket around the Whittle
start (the package's) against Brent's bounded method over the whole of log ρ ∈ [log 10⁻⁴, log 10⁴]
(the former search), same profile likelihood, same stopping rule (xatol = 10⁻⁵), same run.

Run from the repository root::

    PYTHONPATH=. python benchmarks/bench_reml_search.py [--recording FILE] [--long]

For each case it prints the number of passes of the generalized Schur recursion (each one O(n log² n),
about 0.55 s at n = 10⁵ on the 2-core box), the time of both searches, their ratio, and the two
estimates of log ρ with their difference beside the bound 4(√ε |log ρ| + 10⁻⁵/3) that the two stopping
rules together allow. Cases: the three axes of a measured ADIS16405 run at n = 3000, 6000 and 20000
(``--long`` adds the x axis at n = 10⁵), and seeded simulations of y = b + f + v (TIM 2014 eq. (3)),
two of them white-dominated, where the maximum lies at the upper bound of ρ.
"""

from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

import numpy as np
from scipy.optimize import minimize_scalar

import carousel_theory.restricted_likelihood as reml
from carousel_theory.prediction import BiasModel, simulate_sections

_BOUNDS = (1e-4, 1e4)
_DEFAULT_RECORDING = (
    Path(__file__).resolve().parents[1].parent / "shared" / "data" / "adis16405_static" / "adis16405_run1.npz"
)


def _counted_profile():
    """The package's profile likelihood (the private ``_profile``, the function both searches
    maximise), wrapped to count its passes."""
    calls = [0]
    profile = reml._profile

    def counted(data, d, log_ratio):
        calls[0] += 1
        return profile(data, d, log_ratio)

    return counted, calls


def _former_search(sections: np.ndarray, d: float) -> tuple[float, int, float]:
    counted, calls = _counted_profile()
    start = time.perf_counter()
    result = minimize_scalar(
        lambda value: -counted(sections, d, value)[0],
        bounds=(math.log(_BOUNDS[0]), math.log(_BOUNDS[1])),
        method="bounded",
        options={"xatol": 1e-5},
    )
    return float(result.x), calls[0], time.perf_counter() - start


def _package_search(sections: np.ndarray, d: float) -> tuple[float, int, float]:
    counted, calls = _counted_profile()
    original = reml._profile
    reml._profile = counted
    try:
        start = time.perf_counter()
        estimate = reml.estimate_noise_variances(sections, d, _BOUNDS, show_progress=False)
        elapsed = time.perf_counter() - start
    finally:
        reml._profile = original
    return math.log(estimate.white_variance / estimate.driving_variance), calls[0], elapsed


def _compare(name: str, sections: np.ndarray, d: float = 0.5) -> tuple[int, int]:
    new_ratio, new_calls, new_time = _package_search(sections, d)
    old_ratio, old_calls, old_time = _former_search(sections, d)
    allowed = 4.0 * (math.sqrt(np.finfo(np.float64).eps) * abs(old_ratio) + 1e-5 / 3.0)
    difference = abs(new_ratio - old_ratio)
    print(
        f"  {name:28s} passes {new_calls:3d} vs {old_calls:3d}   time {new_time:7.2f} s vs {old_time:7.2f} s "
        f"(ratio {old_time / new_time:4.2f}×)   log ρ {new_ratio:.7f} vs {old_ratio:.7f}, "
        f"|Δ| {difference:.1e} {'≤' if difference <= allowed else '>'} {allowed:.1e}"
    )
    return new_calls, old_calls


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--recording", type=Path, default=_DEFAULT_RECORDING)
    parser.add_argument("--long", action="store_true", help="add the x axis at n = 10⁵ (about 15 s)")
    args = parser.parse_args()
    totals = np.zeros(2, dtype=np.int64)
    print("package search (bracket around the Whittle start) vs former search (bounded over all of log ρ)")
    if args.recording.exists():
        recording = np.load(args.recording)
        lengths = [3000, 6000, 20000]
        for axis in ("wx", "wy", "wz"):
            for n in lengths + ([100_000] if args.long and axis == "wx" else []):
                totals += _compare(f"{args.recording.stem} {axis} n={n}", recording[axis][None, :n])
    else:
        print(f"  (no recording at {args.recording}: measured cases skipped)")
    cases = [
        (1, 4000, 0.5, 1.0, 10.0),
        (1, 4000, 0.5, 1.0, 0.1),
        (20, 200, 0.35, 2.0, 5.0),
        (1, 2000, 0.7, 1.0, 300.0),
        (1, 2000, 0.5, 1.0, 1e6),  # white-dominated: the maximum is at the upper bound of ρ
        (1, 2000, 0.5, 1.0, 1e9),
    ]
    for seed, (count, n, d, driving, white) in enumerate(cases):
        model = BiasModel(d=d, driving_variance=driving, white_variance=white)
        sections = simulate_sections(count, n, model, rng=np.random.default_rng(seed), bias=1.0)
        totals += _compare(f"simulated K={count} n={n} d={d} ρ={white / driving:g}", sections, d)
    print(f"  total passes {totals[0]} vs {totals[1]}")


if __name__ == "__main__":
    main()
