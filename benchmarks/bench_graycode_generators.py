"""Allan variance of 1/f-type generators against their target constant, from τ₀ to the longest τ.

Generators (all of length 2^n, unit sample time, non-overlapping Allan variance (20) at τ = 2^m):

* Gray-code R = C K x (``carousel_theory.graycode.sequence``): target C²/2 (TIM 2014 §IV); shown
  exactly (``allan_variance_exact``) and as a Monte Carlo mean over the same replicates as the others,
  with its exact standard error (``allan_estimator_variance``): R has only n random variables, so a
  single realisation's Allan variance is far noisier than that of the other generators.
* Deterministic S_{2^n} (Algorithm 1): its statistic, target ½.
* Fractional integration, d = ½ (TIM 2014 eq. (3), ``processes.fractional_coefficients``), σ_w = 1:
  one-sided PSD |2 sin πf|^{−1}·2 ≈ 1/(π f) at low f, so the flicker target 2 ln 2 · h₋₁ = 2 ln 2/π.
* FFT shaping of white noise to a one-sided PSD h₋₁/f (h₋₁ = 1): target 2 ln 2.

(allantools.noise.pink is not used: it draws from an unseeded global generator and has no stated
PSD level, so it has no target to compare with.)

Prints, per τ, each generator's Allan variance divided by its target (1 = exactly on target), with
the Monte Carlo standard error of that ratio. ``--plot FILE.png`` also draws the ratios.

Run: python benchmarks/bench_graycode_generators.py [--order 14] [--replicates 1000] [--seed 1]
     [--plot FILE.png]
"""

from __future__ import annotations

import argparse
import math
import sys
import time

import numpy as np

from carousel_theory.graycode import (
    allan_estimator_variance,
    allan_variance_exact,
    deterministic_sequence,
    sequence,
)
from carousel_theory.processes import fractional_coefficients


def allan_variances(samples: np.ndarray, order: int) -> np.ndarray:
    """Non-overlapping Allan variance (20) of each row of ``samples`` at τ = 2^m, m = 0 … order − 1."""
    result = np.empty((samples.shape[0], order))
    for m in range(order):
        means = samples.reshape(samples.shape[0], -1, 2**m).mean(axis=2)
        result[:, m] = np.sum(np.diff(means, axis=1) ** 2, axis=1) / (2 * (means.shape[1] - 1))
    return result


def fractional_integration(length: int, replicates: int, rng: np.random.Generator) -> np.ndarray:
    """f_t = Σ_{i ≤ t} ψ_{t−i} w_i, d = ½, by FFT convolution (exact up to rounding)."""
    psi = fractional_coefficients(0.5, length)
    size = 2 * length
    white = rng.standard_normal((replicates, length))
    return np.fft.irfft(np.fft.rfft(white, size, axis=1) * np.fft.rfft(psi, size), size, axis=1)[:, :length]


def fft_flicker(
    length: int, replicates: int, rng: np.random.Generator, h_minus_one: float = 1.0
) -> np.ndarray:
    """White noise shaped in frequency to the one-sided PSD h₋₁/f (two-sided h₋₁/(2|f|)), zero mean."""
    frequencies = np.fft.rfftfreq(length)
    two_sided = np.zeros_like(frequencies)
    two_sided[1:] = h_minus_one / (2 * frequencies[1:])
    # E|Z_k|² = N S(f_k) gives Var x_t = ∫ S(f) df with numpy's 1/N inverse normalisation
    scale = np.sqrt(length * two_sided / 2)
    scale[-1] *= math.sqrt(2)  # the Nyquist bin is real
    spectrum = scale * (rng.standard_normal((replicates, frequencies.size)) + 1j * rng.standard_normal(
        (replicates, frequencies.size)))  # fmt: skip
    spectrum[:, -1] = spectrum[:, -1].real
    return np.fft.irfft(spectrum, length, axis=1)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--order", type=int, default=14, help="n: sequences of length 2^n (default 14)")
    parser.add_argument("--replicates", type=int, default=1000, help="Monte Carlo replicates (default 1000)")
    parser.add_argument("--seed", type=int, default=1, help="seed of numpy.random.default_rng (default 1)")
    parser.add_argument("--plot", metavar="FILE.png", help="also write a plot of the ratios")
    args = parser.parse_args(argv)
    if not 2 <= args.order <= 22:
        parser.error(f"--order={args.order}: must be in 2..22")
    if args.replicates < 2:
        parser.error(f"--replicates={args.replicates}: must be >= 2")
    order, replicates, length = args.order, args.replicates, 2**args.order
    rng = np.random.default_rng(args.seed)
    start = time.perf_counter()

    gray = np.stack([sequence(order, 1.0, rng=rng) for _ in range(replicates)])
    fractional = fractional_integration(length, replicates, rng)
    shaped = fft_flicker(length, replicates, rng)
    curves = {  # name: (Allan variances, replicates × τ; target constant)
        "Gray R (Monte Carlo)": (allan_variances(gray, order), 0.5),
        "fractional d=1/2": (allan_variances(fractional, order), 2 * math.log(2) / math.pi),
        "FFT 1/f": (allan_variances(shaped, order), 2 * math.log(2)),
    }
    exact_gray = np.array([float(allan_variance_exact(order, m, 1.0)) for m in range(order)]) / 0.5
    deterministic = allan_variances(deterministic_sequence(order)[None, :], order)[0] / 0.5
    ratios = {name: values.mean(axis=0) / target for name, (values, target) in curves.items()}
    errors = {
        name: values.std(axis=0, ddof=1) / math.sqrt(replicates) / target
        for name, (values, target) in curves.items()
    }
    # Gray R: the ratio is 2σ_A²/C², whose variance is known exactly (Gaussian x); at the longest τ it is
    # one χ²₁ per replicate, too skewed for the sample standard error
    gray_spread = np.array([math.sqrt(float(allan_estimator_variance(order, m, 1.0))) for m in range(order)])
    errors["Gray R (Monte Carlo)"] = gray_spread / math.sqrt(replicates)

    print(" ".join(["python", *sys.argv]))
    print(f"n = {order} (length {length}), {replicates} replicates, seed {args.seed}; "
          f"ratio = Allan variance / target constant (± Monte Carlo standard error)")  # fmt: skip
    header = f"{'tau':>6} {'Gray exact':>11} {'S (determ.)':>11}"
    for name in curves:
        header += f" {name:>24}"
    print(header)
    for m in range(order):
        row = f"{2**m:>6} {exact_gray[m]:>11.4f} {deterministic[m]:>11.4f}"
        for name in curves:
            row += f" {ratios[name][m]:>15.4f} ± {errors[name][m]:.4f}"
        print(row)
    worst = {name: float(np.max(np.abs(r - 1))) for name, r in ratios.items()}
    print("largest |ratio − 1|: " + ", ".join(f"{name} {value:.3f}" for name, value in worst.items()))
    print(
        "one realisation of Gray R: relative standard deviation of its Allan variance "
        f"{gray_spread[0]:.3f} at τ = 1 and {gray_spread[-1]:.3f} at the longest τ (only n = {order} random "
        "variables; exact, and it does not shrink as the length grows)"
    )
    print(f"elapsed {time.perf_counter() - start:.1f} s")

    if args.plot:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        taus = 2.0 ** np.arange(order)
        figure, axes = plt.subplots(figsize=(7, 4))
        axes.plot(taus, exact_gray, "k-", label="Gray R, exact")
        axes.plot(taus, deterministic, "k:", marker="s", label="S (deterministic)")
        for name in curves:
            axes.errorbar(taus, ratios[name], yerr=errors[name], marker="o", capsize=2, label=name)
        axes.set_xscale("log", base=2)
        axes.axhline(1.0, color="grey", lw=0.5)
        axes.set_xlabel("τ (samples)")
        axes.set_ylabel("Allan variance / target")
        axes.set_title(f"1/f generators, length 2^{order}, {replicates} replicates")
        axes.legend(fontsize=8)
        figure.tight_layout()
        figure.savefig(args.plot, dpi=120)
        print(f"wrote {args.plot}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
