"""Noise-model fit speed against allantools' overlapping Allan deviation, same axis, same run; and the
τ-covariance against the dense reference.

Usage: ``python benchmarks/bench_fit_vs_allantools.py [--sizes 1000000 10000000] [--models white,rrw ...]
[--records K] [--phi 0.8 0.95 ...] [--breakdown] [--seed S] [--fresh K [--repeat R]] [--dense-size N]``

For each size a seeded axis of white + rate random walk + 1/f (d = 0.5) + first-order Gauss–Markov noise
at 100 Hz is drawn (:func:`carousel_theory.simulate.sample_noise`). Timed, once each, in this process:
``allantools.oadev`` at octave τ (``data_type="freq"``) and ``carousel_theory.fitting.fit_noise_model``
with each requested component set (the fit includes its own overlapping Allan variance). Prints the
wall times, the ratio fit / allantools (the target is ≤ 3), the same ratio of CPU times of this
process (steadier on a shared machine), and the fit's χ² test (the model is the one drawn, so it should
not be rejected). With ``--records K`` K records of each size are drawn and timed in turn: the first fit
of the process also pays its one-time work (caches of Gauss rules, windows and lambdified closed forms,
and the pairs' structure), the later ones are what a session fitting many axes pays per axis (the
structure is kept for the next record of the same length, whatever its Gauss–Markov coefficient,
:mod:`carousel_theory.lag_quadrature`); the first ratio and the median of the later ones are printed.
``--phi`` draws the axes with other Gauss–Markov coefficients (the AR term's long-run variance kept): the
fit's cost should not grow with the correlation time. A fit stops re-evaluating its covariance across τ
once a step moved no parameter by more than 0.05 of its standard error, so records differ in the
evaluations they take (each row shows them). With ``--breakdown`` each fit is run once more and its CPU
time is split into the τ-covariances (the pairs' structure, the values at exact lags and Gauss nodes, the
sums and the rest) and everything else. With ``--fresh K`` each model's first fit is timed instead in K new
processes (records drawn with the seeds 2026, 2027, …), which is what a command-line fit of one axis pays
after its imports; the median and the range of the K CPU ratios are printed, and the ratios grouped by the
covariance evaluations each fit took. ``--repeat R`` times each record's first fit in R processes and
takes their median (a shared machine's interference only ever adds time). ``--dense-size 0`` skips the
comparisons below.

The fit weights its GLS with the lag quadrature's :data:`~carousel_theory.lag_plan.WEIGHTS_RULE`
(:mod:`carousel_theory.lag_quadrature`, module text: Rules).

Then, at ``--dense-size`` samples, the covariance of the Allan variance estimates across octave τ from
:func:`carousel_theory.tau_covariance.allan_estimate_covariance` is compared with the dense O(n)-per-pair
reference :func:`carousel_theory.allan.allan_covariance` for the fitted white + RRW model (largest
relative difference; the tests hold both to 1e-11 at small sizes and to exact integers), and the
white + RRW + 1/f + AR covariance (exact lags near the breakpoints, discrete Gauss blocks with a proved
error bound elsewhere, :mod:`carousel_theory.lag_quadrature`) is compared with the same cross-covariance
summed over every lag of the record (the tests hold it to dense Toeplitz algebra and to 30-digit sums),
by the proved rule and by the fit's.
"""

from __future__ import annotations

import argparse
import contextlib
import itertools
import math
import subprocess
import sys
import time
from collections.abc import Iterator
from dataclasses import replace

import allantools
import numpy as np

from carousel_theory import fitting, lag_quadrature, tau_covariance
from carousel_theory.allan import allan_covariance
from carousel_theory.fitting import fit_noise_model
from carousel_theory.lag_plan import PROVED_RULE, WEIGHTS_RULE
from carousel_theory.lag_quadrature import LagModel, _make_pair, _values
from carousel_theory.noise_model import NoiseModel
from carousel_theory.simulate import sample_noise
from carousel_theory.tau_covariance import allan_estimate_covariance

TRUTH = NoiseModel(
    sample_rate=100.0,
    white_variance=3.6e-5,
    rrw_variance=1e-14,
    flicker_variance=1e-9,
    flicker_d=0.5,
    ar_variance=4e-6,
    ar_coefficients=(0.8,),
)


def _timed(function):
    start = time.perf_counter()
    result = function()
    return time.perf_counter() - start, result


def _timed_both(function):
    """(wall time, CPU time of this process, its result) of one call: on a shared machine the CPU time is
    the steadier of the two (the wall time also counts the other processes' turns)."""
    wall, cpu = time.perf_counter(), time.process_time()
    result = function()
    return time.perf_counter() - wall, time.process_time() - cpu, result


def _dense_check(size: int, rng: np.random.Generator) -> None:
    y = sample_noise(NoiseModel(sample_rate=100.0, white_variance=3.6e-5, rrw_variance=1e-14), size, rng=rng)
    model = fit_noise_model(y, 100.0).model
    sizes = 2 ** np.arange(int(np.log2(size / 3)) + 1)
    fast_time, fast = _timed(lambda: allan_estimate_covariance(model, sizes, size).covariance)
    dense_time, dense = _timed(lambda: allan_covariance(model, sizes, size))
    difference = float(np.max(np.abs(fast - dense) / np.abs(dense)))
    print(
        f"\ncovariance across {len(sizes)} octave τ at n = {size}: closed form {fast_time:.3f} s, dense "
        f"reference {dense_time:.3f} s, largest relative difference {difference:.2e}"
    )


def _every_lag_check(size: int) -> None:
    """The full model's covariance (Gauss blocks with a proved bound) against every lag summed."""
    sizes = 2 ** np.arange(int(np.log2(size / 3)) + 1)
    terms = size - 2 * sizes + 1
    lag_model = LagModel.of(TRUTH)

    def every_lag() -> np.ndarray:
        result = np.empty((len(sizes), len(sizes)))
        pairs_of_sizes = list(zip(sizes.tolist(), terms.tolist(), strict=True))
        for j, (m_j, K_j) in enumerate(pairs_of_sizes):
            for i, (m_i, K_i) in enumerate(pairs_of_sizes[: j + 1]):
                pair = _make_pair(m_i, m_j, K_i, K_j)
                lags = np.arange(-(K_i - 1), K_j, dtype=float)
                values, _ = _values(pair, lag_model, lags)
                total = float(np.dot(pair.count(lags), values * values))
                result[i, j] = result[j, i] = total / (2.0 * m_i**2 * m_j**2 * K_i * K_j)
        return result

    threshold = tau_covariance.EVERY_LAG_LENGTH
    tau_covariance.EVERY_LAG_LENGTH = 0  # the quadrature even where a short record would sum every lag
    try:
        fast = {
            rule: _timed(lambda rule=rule: allan_estimate_covariance(TRUTH, sizes, size, rule=rule))
            for rule in (PROVED_RULE, WEIGHTS_RULE)
        }
    finally:
        tau_covariance.EVERY_LAG_LENGTH = threshold
    pair_time, reference = _timed(every_lag)
    for rule, name in ((PROVED_RULE, "proved rule"), (WEIGHTS_RULE, "fit's weights rule")):
        fast_time, result = fast[rule]
        difference = float(np.max(np.abs(result.covariance - reference) / np.abs(reference)))
        bound = float(np.max(result.truncation_bound / np.abs(reference)))
        print(
            f"white + RRW + 1/f + AR covariance across {len(sizes)} octave τ at n = {size}, {name}: Gauss "
            f"blocks {fast_time:.3f} s, every lag {pair_time:.3f} s, largest relative difference "
            f"{difference:.2e} (proved bound {bound:.2e} + rounding)"
        )


@contextlib.contextmanager
def _clocked(module: object, name: str, spent: dict[str, float]) -> Iterator[None]:
    """Replace ``module.name`` by a wrapper adding its CPU time to ``spent[name]`` (restored on exit)."""
    original = getattr(module, name)

    def wrapper(*args, **kwargs):
        start = time.process_time()
        try:
            return original(*args, **kwargs)
        finally:
            spent[name] = spent.get(name, 0.0) + time.process_time() - start

    setattr(module, name, wrapper)
    try:
        yield
    finally:
        setattr(module, name, original)


def _breakdown(y: np.ndarray, components: tuple[str, ...]) -> None:
    """Where the fit's CPU time goes (a second fit of the same axis, the pair batches'
    cache emptied first so that planning is counted as on a first call; modules already imported): the
    τ-covariances, and within them the pairs' structure (plans, partitions, gathers; once per record),
    the terms' values at the exact lags and Gauss nodes (each covariance), and the sums with the rest."""
    lag_quadrature.pair_batch.cache_clear()
    spent: dict[str, float] = {}
    with contextlib.ExitStack() as stack:
        stack.enter_context(_clocked(fitting, "allan_estimate_covariance", spent))
        stack.enter_context(_clocked(lag_quadrature, "pair_batch", spent))
        stack.enter_context(_clocked(lag_quadrature, "term_values", spent))
        total = _timed_both(lambda: fit_noise_model(y, 100.0, components))[1]
    covariance = spent.get("allan_estimate_covariance", 0.0)
    batch, values = spent.get("pair_batch", 0.0), spent.get("term_values", 0.0)
    print(
        f"{'':>10} {'CPU breakdown':>22}: fit {total:.3f} s = τ-covariances {covariance:.3f} s (pairs' "
        f"structure {batch:.3f}, values {values:.3f}, sums and the rest {covariance - batch - values:.3f}) "
        f"+ everything else {total - covariance:.3f} s"
    )


def _truth(phi: float) -> NoiseModel:
    """The drawn model with the Gauss–Markov coefficient φ, its long-run variance kept (that of φ = 0.8)."""
    long_run = TRUTH.ar_variance / (1.0 - TRUTH.ar_coefficients[0]) ** 2
    return replace(TRUTH, ar_coefficients=(phi,), ar_variance=long_run * (1.0 - phi) ** 2)


def _timed_records(
    args: argparse.Namespace, size: int, rng: np.random.Generator, phi: float
) -> dict[str, list[float]]:
    """Each record of ``size`` samples: allantools, then each model's fit, one row each; the CPU ratios."""
    ratios: dict[str, list[float]] = {text: [] for text in args.models}
    for record in range(args.records):
        y = sample_noise(_truth(phi), size, rng=rng)
        peer, peer_cpu, _ = _timed_both(
            lambda y=y: allantools.oadev(y, rate=100.0, data_type="freq", taus="octave")
        )
        for text in args.models:
            components = tuple(text.split(","))
            fit, fit_cpu, result = _timed_both(lambda c=components, y=y: fit_noise_model(y, 100.0, c))
            ratios[text].append(fit_cpu / peer_cpu)
            print(
                f"{size:>10} {record + 1:>7} {text:>22} {fit:>9.2f} {peer:>15.2f} {fit / peer:>15.2f} "
                f"{fit_cpu / peer_cpu:>19.2f}   χ² {result.chi_square:.3g} on {result.degrees_of_freedom}, "
                f"p = {result.p_value:.2g}, {result.iterations} iterations"
            )
            if args.breakdown:
                _breakdown(y, components)
    return ratios


def _fresh_processes(args: argparse.Namespace) -> None:
    """Each model's first fit in ``args.fresh`` new processes (a record each, seeds 2026, 2027, …): what a
    command-line fit of one axis pays. Prints the CPU ratios, their median and range."""
    for size, phi, text in itertools.product(args.sizes, args.phi, args.models):
        ratios: dict[int, list[float]] = {}  # by the covariance evaluations the fit took
        for seed in range(2026, 2026 + args.fresh):
            command = [sys.executable, __file__, "--sizes", str(size), "--models", text, "--phi", str(phi)]
            command += ["--seed", str(seed), "--dense-size", "0"]
            repeated = []  # the same record's first fit in ``args.repeat`` processes: their median
            for _ in range(args.repeat):
                output = subprocess.run(command, capture_output=True, text=True, check=True).stdout
                row = next(line for line in output.splitlines() if line.split()[:2] == [str(size), "1"])
                words = row.split()
                repeated.append(float(words[6]))
            ratios.setdefault(int(words[-2]), []).append(float(np.median(repeated)))
        every = [ratio for group in ratios.values() for ratio in group]
        print(
            f"{size:>10} φ = {phi} {text:>22}: first fit of {args.fresh} fresh processes, CPU fit/allantools "
            f"median {float(np.median(every)):.2f}, range {min(every):.2f}–{max(every):.2f}"
        )
        for evaluations, group in sorted(ratios.items()):
            print(
                f"{'':>10} {evaluations} covariance evaluation(s), {len(group)} records: median "
                f"{float(np.median(group)):.2f} ({', '.join(f'{r:.2f}' for r in group)})"
            )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[1_000_000, 10_000_000])
    parser.add_argument(
        "--models", nargs="+", default=["white,rrw", "white,rrw,flicker,ar"], help="component sets to fit"
    )
    parser.add_argument(
        "--records", type=int, default=1, help="records per size, each timed (later ones in a warm process)"
    )
    parser.add_argument("--dense-size", type=int, default=100_000)
    parser.add_argument(
        "--phi", type=float, nargs="+", default=[0.8], help="Gauss–Markov coefficients of the drawn axes"
    )
    parser.add_argument(
        "--breakdown", action="store_true", help="also show where each fit's CPU time goes (one more fit)"
    )
    parser.add_argument("--seed", type=int, default=2026, help="seed of the drawn records")
    parser.add_argument(
        "--fresh", type=int, default=0, help="time each model's first fit in this many new processes instead"
    )
    parser.add_argument(
        "--repeat", type=int, default=1, help="with --fresh: processes per record (their median is taken)"
    )
    args = parser.parse_args()
    if args.fresh:
        _fresh_processes(args)
        return
    rng = np.random.default_rng(args.seed)
    print(
        f"{'samples':>10} {'record':>7} {'model':>22} {'fit (s)':>9} {'allantools (s)':>15} "
        f"{'fit/allantools':>15} {'CPU fit/allantools':>19}"
    )
    for size, phi in itertools.product(args.sizes, args.phi):
        print(f"Gauss–Markov φ = {phi} (τ_c = {-1.0 / (100.0 * math.log(phi)):.3g} s at 100 Hz)")
        for text, ratios in _timed_records(args, size, rng, phi).items():
            if len(ratios) > 1:
                print(
                    f"{size:>10} {text:>22}: CPU ratio of the first record {ratios[0]:.2f}, median of the "
                    f"later ones {float(np.median(ratios[1:])):.2f}"
                )
    if args.dense_size:
        _dense_check(args.dense_size, rng)
        _every_lag_check(args.dense_size)


if __name__ == "__main__":
    main()
