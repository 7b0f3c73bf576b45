"""A long Gauss–Markov correlation time: the record's AR(1) estimate against the fit's refined one.

Usage: ``python benchmarks/bench_ar_refinement.py [--phi 0.95 0.99] [--records 30] [--size 1000000]``

For each φ, ``--records`` seeded axes of white + RRW + 1/f (d = 0.5) + first-order Gauss–Markov noise at
100 Hz (the model of ``benchmarks/bench_fit_vs_allantools.py``, the AR term's long-run variance kept) are
fitted with all four components by :func:`carousel_theory.fitting.fit_noise_model`. The record's own
estimate (:func:`carousel_theory.autoregression.short_noise_estimate`, which reads the record less its
moving average of W = 10 s and is biased low when τ_c is long) is compared with the fit's coefficient,
which is refined by the GLS χ² on the Allan variance when the estimate's τ_c exceeds W/40
(``FitResult.ar_estimator``). Printed per φ: the mean and standard deviation of both, how often
φ̂ ± 1.96 s holds φ (s the fit's ``ar_coefficient_errors``), the χ² misfit test's rejections at 0.05 of
the fit and of the same fit with the record's estimate given (the fit as it was before the refinement),
and the fit's median CPU time.
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from bench_fit_vs_allantools import _truth  # the fit benchmark's axis, its AR long-run variance kept

from carousel_theory.autoregression import short_noise_estimate
from carousel_theory.fitting import ALLAN_PROFILE, fit_noise_model
from carousel_theory.progress import progress
from carousel_theory.simulate import sample_noise

RATE = 100.0
COMPONENTS = ("white", "rrw", "flicker", "ar")


def _row(phi: float, records: int, size: int) -> str:
    rng = np.random.default_rng([2026, round(phi * 1000), 7])
    record_estimates, fitted, covered, rejected, held_rejected, seconds = [], [], 0, 0, 0, []
    refined = 0
    for _ in progress(range(records), label=f"φ = {phi}"):
        y = sample_noise(_truth(phi), size, rng=rng)
        own = short_noise_estimate(y, RATE, 4).coefficients
        start = time.process_time()
        fit = fit_noise_model(y, RATE, COMPONENTS)
        seconds.append(time.process_time() - start)
        held = fit_noise_model(y, RATE, COMPONENTS, ar_coefficients=own)
        (value,), (error,) = fit.model.ar_coefficients, fit.ar_coefficient_errors
        record_estimates.append(own[0])
        fitted.append(value)
        covered += abs(value - phi) <= 1.959963984540054 * error
        rejected += fit.p_value < 0.05
        held_rejected += held.p_value < 0.05
        refined += fit.ar_estimator == ALLAN_PROFILE
    own_values, fit_values = np.array(record_estimates), np.array(fitted)
    return (
        f"| {phi} | {records} | {own_values.mean():.5f} ± {own_values.std(ddof=1):.5f} | {held_rejected} "
        f"| {fit_values.mean():.5f} ± {fit_values.std(ddof=1):.5f} | {refined} | {covered} | {rejected} "
        f"| {float(np.median(seconds)):.2f} |"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--phi", type=float, nargs="+", default=[0.95, 0.99])
    parser.add_argument("--records", type=int, default=30)
    parser.add_argument("--size", type=int, default=1_000_000)
    args = parser.parse_args()
    print(
        "| φ | records | record's estimate, mean ± sd | its fit rejected at 0.05 | fit's φ̂, mean ± sd "
        "| refined | φ̂ ± 1.96 s holds φ | fit rejected at 0.05 | fit CPU s (median) |"
    )
    print("|---|---|---|---|---|---|---|---|---|")
    for phi in args.phi:
        print(_row(phi, args.records, args.size), flush=True)


if __name__ == "__main__":
    main()
