"""Growing-state Kalman filter of SJ 2012 §IV-A versus the exact fast predictor, and dense versus
generalized-Schur REML, same data, same run.

Run from the repository root: ``PYTHONPATH=. python benchmarks/bench_predictors.py [--full]``.
Prints the time of each and the ratio, and the
largest difference of forecasts and variances (they must agree to 1e-9), then the REML estimates of
σ_w², σ_v² by a dense Cholesky factorisation per likelihood evaluation (the former implementation,
O(n³) time, O(n²) memory) and by the generalized Schur recursion (O(n²) time, O(n) memory), with
their times, ratio and relative difference.

The Kalman filter costs O((n + h)³) time and O((n + h)²) memory; at 10⁴ + 10⁴ its covariance alone
is 3.2 GB and a run takes hours, so by default its time there is extrapolated from the measured
times at 500 + 500, 1000 + 1000 and 1500 + 1500 by a fitted power law (the exponent is printed).
``--full`` runs it for real (needs about 4 GB of memory and a long time).
"""

from __future__ import annotations

import argparse
import os
import time

# One BLAS thread: on a shared 2-core machine several threads per process only contend; both
# methods get the same setting.
for _variable in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_variable, "1")

import numpy as np  # noqa: E402  (after the thread setting)

from carousel_theory.fast_prediction import fast_kalman_forecast  # noqa: E402
from carousel_theory.long_memory import fractional_integral  # noqa: E402
from carousel_theory.prediction import BiasModel, kalman_forecast, simulate_sections  # noqa: E402
from carousel_theory.restricted_likelihood import estimate_noise_variances  # noqa: E402


def _best_time(function, repeats: int) -> tuple[float, object]:
    best = float("inf")
    result = None
    for _ in range(repeats):
        start = time.perf_counter()
        result = function()
        best = min(best, time.perf_counter() - start)
    return best, result


def _compare(n: int, white: float, rng: np.random.Generator, run_kalman: bool) -> tuple[float | None, float]:
    y = fractional_integral(rng.standard_normal(n), 0.5) + np.sqrt(white) * rng.standard_normal(n)
    options = {"d": 0.5, "driving_variance": 1.0, "white_variance": white}
    fast_time, fast = _best_time(lambda: fast_kalman_forecast(y, n, **options), repeats=5)
    if not run_kalman:
        return None, fast_time
    kalman_time, kalman = _best_time(lambda: kalman_forecast(y, n, **options), repeats=1)
    mean_gap = float(np.abs(fast.mean - kalman.mean).max())
    variance_gap = float(np.abs(fast.bias_variance - kalman.bias_variance).max())
    print(
        f"  {n:>6d} + {n:<6d} σ_v² = {white:<4g} KF {kalman_time:9.3f} s   fast {fast_time * 1e3:9.2f} ms   "
        f"ratio {kalman_time / fast_time:10.0f}×   max |Δmean| {mean_gap:.1e}, max |Δvar| {variance_gap:.1e}"
    )
    return kalman_time, fast_time


def _dense_reml(sections: np.ndarray, d: float) -> tuple[float, float]:
    """The former dense REML: a Cholesky factorisation of Γ + ρI per evaluation of the profile."""
    from scipy.linalg import cho_factor, cho_solve
    from scipy.optimize import minimize_scalar

    from carousel_theory.fast_prediction import fractional_covariance_rows

    count, n = sections.shape
    gamma = fractional_covariance_rows(d, n, n)
    ones = np.ones(n)

    def profile(log_ratio: float) -> tuple[float, float]:
        factor = cho_factor(gamma + np.exp(log_ratio) * np.eye(n), lower=True, check_finite=False)
        log_det = 2.0 * float(np.log(np.diag(factor[0])).sum())
        solved_ones = cho_solve(factor, ones, check_finite=False)
        total_ones = float(ones @ solved_ones)
        solved = cho_solve(factor, sections.T, check_finite=False)
        quadratic = (
            float(np.einsum("ij,ji->", sections, solved))
            - float(((sections @ solved_ones) ** 2).sum()) / total_ones
        )
        scale = quadratic / (count * (n - 1))
        value = -0.5 * (count * (n - 1) * (np.log(scale) + 1.0) + count * (log_det + np.log(total_ones)))
        return float(value), scale

    result = minimize_scalar(
        lambda value: -profile(value)[0],
        bounds=(np.log(1e-4), np.log(1e4)),
        method="bounded",
        options={"xatol": 1e-5},
    )
    scale = profile(float(result.x))[1]
    return scale, scale * float(np.exp(result.x))


def _compare_reml(n: int, rng: np.random.Generator) -> None:
    model = BiasModel(d=0.5, driving_variance=1.0, white_variance=10.0)
    sections = simulate_sections(1, n, model, rng=rng, bias=2.0)
    dense_time, dense = _best_time(lambda: _dense_reml(sections, 0.5), repeats=1)
    schur_time, schur = _best_time(lambda: estimate_noise_variances(sections, 0.5), repeats=1)
    gap = max(
        abs(schur.driving_variance / dense[0] - 1.0),
        abs(schur.white_variance / dense[1] - 1.0),
    )
    print(
        f"  n = {n:>5d}   dense REML {dense_time:8.2f} s   Schur REML {schur_time:8.2f} s   "
        f"ratio {dense_time / schur_time:6.1f}×   max relative difference of σ_w², σ_v² {gap:.1e}"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--full", action="store_true", help="also run the Kalman filter at 10⁴ + 10⁴")
    args = parser.parse_args()
    rng = np.random.default_rng(2012)
    for white in (0.0, 0.5):
        kind = (
            "Table I setting: fractional-difference whitening"
            if white == 0
            else "generalized Schur recursion"
        )
        print(f"σ_v² = {white} ({kind})")
        sizes = (500, 1000, 1500)
        measured = [_compare(n, white, rng, run_kalman=True) for n in sizes]
        exponent, intercept = np.polyfit(np.log(sizes), np.log([m[0] for m in measured]), 1)
        large = 10_000
        if args.full:
            _compare(large, white, rng, run_kalman=True)
        else:
            _, fast_time = _compare(large, white, rng, run_kalman=False)
            extrapolated = float(np.exp(intercept) * large**exponent)
            print(
                f"  {large:>6d} + {large:<6d} σ_v² = {white:<4g} KF ≈ {extrapolated:9.0f} s (extrapolated, "
                f"time ∝ n^{exponent:.2f})   fast {fast_time * 1e3:9.2f} ms   ratio ≈ "
                f"{extrapolated / fast_time:10.0f}×"
            )
    print("REML of σ_w², σ_v² at d = 0.5 on one calibration segment (σ_v²/σ_w² = 10)")
    for n in (1000, 2000, 4000):
        _compare_reml(n, rng)


if __name__ == "__main__":
    main()
