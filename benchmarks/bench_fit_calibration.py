"""Are the fit's standard errors and its χ² test calibrated? Coverage of each parameter's interval and the
misfit test's size on seeded records of known models.

Usage: ``python benchmarks/bench_fit_calibration.py [--sizes 100000 1000000] [--records 60] [--seed 2026]
[--write docs/fit_calibration.md]``

For each model below and each size, ``--records`` records are drawn
(:func:`carousel_theory.simulate.sample_noise`, a ``numpy.random.Generator`` seeded from
(seed, model, size)) and fitted with :func:`carousel_theory.fitting.fit_noise_model` with the model's own
components, so every fitted model is the true one. Counted per (model, size):

- the χ² misfit test's rejections at 0.05 (its size; the interval is Clopper–Pearson's exact 95 % one,
  :meth:`scipy.stats.binomtest.proportion_ci`);
- for each parameter, how often θ̂ ± 1.96 s (s its standard error) holds the truth (nominal 0.95), and
  the spread (standard deviation) of z = (θ̂ − θ)/s (nominal 1), over the records where the parameter
  was not held at zero; those are counted apart ("at 0");
- for each variance, how often :meth:`carousel_theory.fitting.FitResult.interval` holds the truth: the
  default χ²-based interval (from the same standard error, over the same records), and the interval by
  test inversion (``method="inverted"``, :func:`carousel_theory.fitting.inverted_interval`; over every
  record, those at 0 included, since its lower end may be 0);
- for the 1/f order d, how often its interval (both columns: the d whose GLS χ² exceeds the fit's by at
  most χ²₁(0.95), :func:`carousel_theory.fitting.order_interval`) holds the truth, over the records
  where the 1/f term is not at 0 and over every record (at 0 the χ² does not depend on d and the
  interval is the whole range searched);
- the AR coefficient the same way, with ``FitResult.ar_coefficient_errors``.

Reading the table. A plug-in standard error comes from the covariance across τ evaluated at the
estimate, so for a weakly determined variance (a rate random walk or 1/f term known to tens of percent)
it shrinks with the estimate: records that underestimate the term report a small error, the ±1.96 s
interval under-covers and z spreads wider than 1 although the estimate itself is unbiased. The
inverted interval evaluates the error at each candidate value instead, and so does not share that flaw.
For d the error comes from the χ²'s curvature at d̂, and the χ² is far from a parabola in d where the 1/f
term trades off against the white and RRW terms; its χ²-difference interval follows the χ² itself.

Prints one Markdown table; ``--write PATH`` also writes it with this text's method as a document.
"""

from __future__ import annotations

import argparse
import sys
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from scipy import stats

from carousel_theory.fitting import FitResult, fit_noise_model
from carousel_theory.noise_model import NoiseModel
from carousel_theory.progress import progress
from carousel_theory.simulate import sample_noise

RATE = 100.0
WHITE, RRW, FLICKER, AR = 3.6e-5, 1e-14, 1e-9, 4e-6
#: Name: (true model, fitted components). The last is the fit benchmark's model
#: (benchmarks/bench_fit_vs_allantools.py).
MODELS: dict[str, tuple[NoiseModel, tuple[str, ...]]] = {
    "white + RRW": (NoiseModel(sample_rate=RATE, white_variance=WHITE, rrw_variance=RRW), ("white", "rrw")),
    "white + Gauss–Markov (φ = 0.8)": (
        NoiseModel(sample_rate=RATE, white_variance=WHITE, ar_variance=AR, ar_coefficients=(0.8,)),
        ("white", "ar"),
    ),
    "white + RRW + 1/f (d = 0.5) + Gauss–Markov (φ = 0.8)": (
        NoiseModel(
            sample_rate=RATE,
            white_variance=WHITE,
            rrw_variance=RRW,
            flicker_variance=FLICKER,
            flicker_d=0.5,
            ar_variance=AR,
            ar_coefficients=(0.8,),
        ),
        ("white", "rrw", "flicker", "ar"),
    ),
}
Z95 = 1.959963984540054


@dataclass
class Tally:
    """Per (model, size): the test's p-values and each parameter's standardized errors."""

    p_values: list[float] = field(default_factory=list)
    z: dict[str, list[float]] = field(default_factory=dict)
    interval_covers: dict[str, list[bool]] = field(default_factory=dict)
    inverted_covers: dict[str, list[bool]] = field(default_factory=dict)
    at_zero: dict[str, int] = field(default_factory=dict)


def _record(tally: Tally, fit: FitResult, truth: NoiseModel) -> None:
    tally.p_values.append(fit.p_value)
    # The models here have no quantization, the one parameter whose name is not a NoiseModel attribute.
    true_values = {name: float(getattr(truth, name)) for name in fit.parameters}
    for name in fit.parameters:
        # d's χ²-difference interval is its test inversion too, and is defined with the 1/f term at 0
        low, high = fit.interval(name, method="inverted")
        inverted = bool(low <= true_values[name] <= high)
        tally.inverted_covers.setdefault(name, []).append(inverted)
        zero = "flicker_variance" if name == "flicker_d" else name
        if zero in fit.at_bound or fit.standard_errors.get(name, 0.0) <= 0.0:
            tally.at_zero[name] = tally.at_zero.get(name, 0) + 1
            continue
        z = (fit.value(name) - true_values[name]) / fit.standard_errors[name]
        tally.z.setdefault(name, []).append(z)
        low, high = fit.interval(name)
        tally.interval_covers.setdefault(name, []).append(bool(low <= true_values[name] <= high))
    for index, error in enumerate(fit.ar_coefficient_errors):
        name = f"φ_{index + 1}"
        if index < len(truth.ar_coefficients) and error > 0:
            z = (fit.model.ar_coefficients[index] - truth.ar_coefficients[index]) / error
            tally.z.setdefault(name, []).append(z)


def _interval(successes: int, trials: int) -> str:
    ci = stats.binomtest(successes, trials).proportion_ci(confidence_level=0.95, method="exact")
    return f"{successes}/{trials} = {successes / trials:.3f} [{ci.low:.3f}, {ci.high:.3f}]"


def _rows(model_name: str, size: int, tally: Tally) -> list[str]:
    runs = len(tally.p_values)
    rejected = sum(p < 0.05 for p in tally.p_values)
    test = _interval(rejected, runs)
    rows = [f"| {model_name} | {size:.0e} | χ² test, rejections at 0.05 | {test} | | | | |"]
    for name in sorted(set(tally.z) | set(tally.at_zero)):
        z = np.asarray(tally.z.get(name, []))
        coverage = _interval(int(np.sum(np.abs(z) <= Z95)), len(z)) if len(z) else "—"
        chi_square, inverted = (
            _interval(sum(c), len(c)) if (c := covers.get(name, [])) else "—"
            for covers in (tally.interval_covers, tally.inverted_covers)
        )
        spread = f"{np.std(z, ddof=1):.2f}" if len(z) > 1 else "—"
        at_zero = tally.at_zero.get(name, 0)
        rows.append(f"| | | {name} | {coverage} | {chi_square} | {inverted} | {spread} | {at_zero} |")
    return rows


def calibrate(sizes: list[int], records: int, seed: int) -> list[str]:
    """The table's rows for every model and size."""
    rows = [
        "| model | n | parameter | θ̂ ± 1.96 s covers the truth (or: the test rejects) "
        "| χ²-based interval covers | inverted interval covers (every record) | spread of z | at 0 |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for model_index, (name, (truth, components)) in enumerate(MODELS.items()):
        for size in sizes:
            rng = np.random.default_rng([seed, model_index, size])
            tally = Tally()
            for _ in progress(range(records), label=f"{name}, n = {size}"):
                record = sample_noise(truth, size, rng=rng)
                _record(tally, fit_noise_model(record, RATE, components), truth)
            rows.extend(_rows(name, size, tally))
    return rows


def _document(rows: list[str], command: str) -> str:
    method = (__doc__ or "").split("Prints one")[0].split("[--write docs/fit_calibration.md]``")[-1].strip()
    return "\n".join(
        [
            "# Calibration of the fit's standard errors and χ² test",
            "",
            f"Measured with `{command}`.",
            "",
            method,
            "",
            *rows,
            "",
        ]
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[100_000, 1_000_000])
    parser.add_argument("--records", type=int, default=60)
    parser.add_argument("--seed", type=int, default=2026)
    parser.add_argument("--write", type=Path, default=None, help="also write the table as a document here")
    args = parser.parse_args()
    if args.records < 2 or min(args.sizes) < 1000:
        parser.error(f"--records {args.records}, --sizes {args.sizes}: need ≥ 2 records of ≥ 1000 samples")
    rows = calibrate(args.sizes, args.records, args.seed)
    print("\n".join(rows))
    if args.write is not None:
        command = "python benchmarks/bench_fit_calibration.py " + " ".join(sys.argv[1:])
        args.write.write_text(_document(rows, command.strip()), encoding="utf-8")
        print(f"wrote {args.write}", file=sys.stderr)


if __name__ == "__main__":
    main()
