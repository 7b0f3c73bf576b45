"""Noise-model fit speed against allantools' overlapping Allan deviation, same axis, same run; and the
τ-covariance against the dense reference.

Usage: ``python benchmarks/bench_fit_vs_allantools.py [--sizes 1000000 10000000] [--models white,rrw ...]``

For each size a seeded axis of white + rate random walk + 1/f (d = 0.5) + first-order Gauss–Markov noise
at 100 Hz is drawn (:func:`carousel_theory.simulate.sample_noise`). Timed, once each, in this process:
``allantools.oadev`` at octave τ (``data_type="freq"``) and ``carousel_theory.fitting.fit_noise_model``
with each requested component set (the fit includes its own overlapping Allan variance). Prints the
times and the ratio fit / allantools (the target is ≤ 3).

Then, at ``--dense-size`` samples, the covariance of the Allan variance estimates across octave τ from
:func:`carousel_theory.tau_covariance.allan_estimate_covariance` is compared with the dense O(n)-per-pair
reference :func:`carousel_theory.allan.allan_covariance` for the fitted white + RRW model (largest
relative difference; the tests hold both to 1e-11 at small sizes and to exact integers), and the
white + RRW + 1/f + AR covariance (summed column by column, doubling the triangle along octave τ) is
compared with each pair's lag sum computed on its own (the tests hold both to dense Toeplitz algebra).
"""

from __future__ import annotations

import argparse
import time

import allantools
import numpy as np

from carousel_theory.allan import allan_covariance
from carousel_theory.fitting import fit_noise_model
from carousel_theory.noise_model import NoiseModel
from carousel_theory.simulate import sample_noise
from carousel_theory.tau_covariance import _lag_sum, _LongMemory, allan_estimate_covariance

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


def _pair_by_pair_check(size: int) -> None:
    """The full model's covariance (doubling along octave τ) against each pair's lag sum on its own."""
    sizes = 2 ** np.arange(int(np.log2(size / 3)) + 1)
    terms = size - 2 * sizes + 1

    def pairs() -> np.ndarray:
        memory = _LongMemory(TRUTH, sizes, size)
        result = np.empty((len(sizes), len(sizes)))
        pairs_of_sizes = list(zip(sizes.tolist(), terms.tolist(), strict=True))
        for j, (m_j, K_j) in enumerate(pairs_of_sizes):
            for i, (m_i, K_i) in enumerate(pairs_of_sizes[: j + 1]):
                total = _lag_sum(memory, m_i, m_j, K_i, K_j, "overlapping")[0]
                result[i, j] = result[j, i] = total / (2.0 * m_i**2 * m_j**2 * K_i * K_j)
        return result

    fast_time, fast = _timed(lambda: allan_estimate_covariance(TRUTH, sizes, size).covariance)
    pair_time, reference = _timed(pairs)
    difference = float(np.max(np.abs(fast - reference) / np.abs(reference)))
    print(
        f"white + RRW + 1/f + AR covariance across {len(sizes)} octave τ at n = {size}: doubling "
        f"{fast_time:.3f} s, pair by pair {pair_time:.3f} s, largest relative difference {difference:.2e}"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[1_000_000, 10_000_000])
    parser.add_argument(
        "--models", nargs="+", default=["white,rrw", "white,rrw,flicker,ar"], help="component sets to fit"
    )
    parser.add_argument("--dense-size", type=int, default=100_000)
    args = parser.parse_args()
    rng = np.random.default_rng(2026)
    print(f"{'samples':>10} {'model':>22} {'fit (s)':>9} {'allantools (s)':>15} {'fit/allantools':>15}")
    for size in args.sizes:
        y = sample_noise(TRUTH, size, rng=rng)
        peer_time, _ = _timed(lambda y=y: allantools.oadev(y, rate=100.0, data_type="freq", taus="octave"))
        for text in args.models:
            components = tuple(text.split(","))
            fit_time, _ = _timed(lambda c=components, y=y: fit_noise_model(y, 100.0, c))
            print(f"{size:>10} {text:>22} {fit_time:>9.2f} {peer_time:>15.2f} {fit_time / peer_time:>15.2f}")
    _dense_check(args.dense_size, rng)
    _pair_by_pair_check(args.dense_size)


if __name__ == "__main__":
    main()
