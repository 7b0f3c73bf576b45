"""Size of the studentized trend statistic under its bootstrap reference, on whole simulated records.

Each record is one axis of the case's model simulated sample by sample (100 Hz), with its GLS warm-up
statistic L = Σ w_t e_t (weights for e^{−t/τ_c} chosen under the true model on blocks of the first long τ
and held fixed), the noise refitted jointly on r = e − (L/I) g by the loop's fitter (its covariance
across τ fixed from a pilot record, as the loop's refits fix it from the view's fit), z = L/√V(θ̂) and p
from :func:`carousel_theory.closed_loop.studentized.trend_reference` (drawn from that fit, or from it
with the walk raised). A valid reference rejects at most a fraction α of the records at level α.

Commands: ``PYTHONPATH=. python benchmarks/bench_trend_reference.py --case clean --records N --first-seed S``
(one part file per run in benchmarks/trend_reference_parts/), then ``... --write`` to make
docs/trend_reference_size.md from all parts.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
from scipy import stats

from carousel_theory.closed_loop.calibration import long_tau_start
from carousel_theory.closed_loop.linear_statistics import difference_weights
from carousel_theory.closed_loop.residual_model import (
    FittedNoise,
    ModelTerms,
    ResidualFit,
    fit_residual_model,
    noise_variances,
    statistic_units,
)
from carousel_theory.closed_loop.studentized import trend_reference
from carousel_theory.noise_model import NoiseModel
from carousel_theory.simulate import sample_noise

RATE = 100.0
WHITE = 3.6e-5
TIME_CONSTANT = 120.0
LEVELS = (0.05, 0.01, 0.001)
PARTS = Path(__file__).with_name("trend_reference_parts")
DOCUMENT = Path(__file__).resolve().parents[1] / "docs" / "trend_reference_size.md"


@dataclass(frozen=True)
class Case:
    name: str
    description: str
    rrw: float
    flicker: float
    seconds: float = 3600.0
    time_constant: float = TIME_CONSTANT
    raised_walk: float = 0.0  # the replicates' walk raised to at least this many of its GLS se


CASES = {
    case.name: case
    for case in (
        Case("clean", "white + rate random walk (σ_q² = 1e-11), 1 h", 1e-11, 0.0),
        Case(
            "small_walk",
            "white + a walk near the boundary (σ_q² = 1e-12, about 0.6 of its GLS se), 1 h",
            1e-12,
            0.0,
        ),
        Case(
            "flicker", "white + walk (1e-11) + 1/f (σ_f² = 5e-8), fitted with its 1/f term, 1 h", 1e-11, 5e-8
        ),
        Case("short_small_walk", "white + walk 1e-12, 327.68 s, τ_c = 20 s", 1e-12, 0.0, 327.68, 20.0),
        Case(
            "short_small_walk_raised",
            "as above, replicates drawn with the walk raised to ≥ 2 GLS se",
            1e-12,
            0.0,
            327.68,
            20.0,
            2.0,
        ),
    )
}


@dataclass(frozen=True)
class Setup:
    case: Case
    model: NoiseModel
    terms: ModelTerms
    length: int
    pilot: ResidualFit
    block_weights: np.ndarray
    weights: np.ndarray
    regressor: np.ndarray
    regressor_sums: np.ndarray


def setup(case: Case) -> Setup:
    """The true model, a pilot fit (its covariance across τ), and the warm-up's GLS weights on blocks of
    the first long τ under the true model."""
    model = NoiseModel(RATE, white_variance=WHITE, rrw_variance=case.rrw, flicker_variance=case.flicker)
    terms, length = ModelTerms(flicker=bool(case.flicker)), int(case.seconds * RATE)
    pilot = fit_residual_model(sample_noise(model, length, rng=np.random.default_rng(7)), RATE, terms)
    block = int(pilot.sizes[long_tau_start(pilot, length)])
    count = length // block
    regressor = np.exp(-np.arange(length) / RATE / case.time_constant)
    block_weights = difference_weights(FittedNoise(model), regressor, block) / block
    weights = np.zeros(length)
    weights[: count * block] = np.repeat(block_weights, block)
    sums = regressor[: count * block].reshape(count, block).sum(axis=1)
    return Setup(
        case, model, terms, length, pilot, block_weights, weights, regressor - regressor.mean(), sums
    )


def one_record(setup: Setup, seed: int, replicates: int) -> tuple[float, float]:
    """(z, p) of one whole simulated record (seed: the case's number and ``seed``)."""
    number = list(CASES).index(setup.case.name)
    record = sample_noise(setup.model, setup.length, rng=np.random.default_rng([20261123, number, seed]))
    projection = float(np.dot(setup.weights, record))
    information = float(np.dot(setup.block_weights, setup.regressor_sums))
    record -= (projection / information) * setup.regressor
    fit = fit_residual_model(record, RATE, setup.terms, reference=setup.pilot)
    variance = statistic_units(setup.weights).variance(noise_variances(fit.noise))
    z = projection / math.sqrt(max(variance, 1e-300))
    generating = None
    if setup.case.raised_walk:
        floor = setup.case.raised_walk * fit.noise.standard_errors["rrw_variance"]
        model = fit.noise.model
        generating = replace(fit.noise, model=replace(model, rrw_variance=max(model.rrw_variance, floor)))
    reference = trend_reference(
        fit, setup.length, setup.block_weights, projection, setup.regressor_sums, replicates, generating
    )
    return z, reference.sf(z)


def run(case: Case, records: int, first_seed: int, replicates: int) -> Path:
    prepared = setup(case)
    started, values = time.time(), []
    for seed in range(first_seed, first_seed + records):
        values.append(one_record(prepared, seed, replicates))
        if len(values) % 200 == 0:
            print(
                f"{case.name}: {len(values)} records, {time.time() - started:.0f} s",
                file=sys.stderr,
                flush=True,
            )
    PARTS.mkdir(exist_ok=True)
    path = PARTS / f"{case.name}_{first_seed}.json"
    part = {
        "case": case.name,
        "first_seed": first_seed,
        "replicates": replicates,
        "z": [v[0] for v in values],
    }
    part["p"] = [v[1] for v in values]
    path.write_text(json.dumps(part) + "\n")
    return path


def clopper_pearson(k: int, n: int) -> tuple[float, float]:
    low = float(stats.beta.ppf(0.025, k, n - k + 1)) if k else 0.0
    high = float(stats.beta.ppf(0.975, k + 1, n - k)) if k < n else 1.0
    return low, high


def write() -> str:
    parts: dict[str, list[float]] = {}
    replicates: dict[str, set[int]] = {}
    for path in sorted(PARTS.glob("*.json")):
        part = json.loads(path.read_text())
        parts.setdefault(part["case"], []).extend(part["p"])
        replicates.setdefault(part["case"], set()).add(part["replicates"])
    lines = [
        "<!-- generated by benchmarks/bench_trend_reference.py --write — do not edit -->",
        "# Trend statistic: size of the studentized bootstrap reference on whole simulated records",
        "",
        (__doc__ or "").split("\n\n")[1].replace("\n", " "),
        "",
        "Rejections at each level with the 95 % Clopper–Pearson interval; KS: the Kolmogorov–Smirnov test of"
        " the records' p-values against U(0, 1).",
        "",
        "| case | records | replicates | α = 0.05 | α = 0.01 | α = 0.001 | KS p-value |",
        "|---|---|---|---|---|---|---|",
    ]
    for name, case in CASES.items():
        if name not in parts:
            continue
        p = np.asarray(parts[name])
        cells = []
        for level in LEVELS:
            k = int(np.sum(p <= level))
            low, high = clopper_pearson(k, len(p))
            cells.append(f"{k} = {k / len(p):.4f} [{low:.4f}, {high:.4f}]")
        ks = float(stats.kstest(p, "uniform").pvalue)
        counts = "/".join(str(r) for r in sorted(replicates[name]))
        lines.append(f"| {case.description} | {len(p)} | {counts} | {' | '.join(cells)} | {ks:.3g} |")
    return "\n".join(lines) + "\n"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--case", choices=sorted(CASES))
    parser.add_argument("--records", type=int, default=100)
    parser.add_argument("--first-seed", type=int, default=0)
    parser.add_argument("--replicates", type=int, default=200)
    parser.add_argument("--write", action="store_true")
    args = parser.parse_args()
    if args.write:
        DOCUMENT.write_text(write())
        print(DOCUMENT.read_text())
        return
    if args.case is None:
        parser.error("--case is required unless --write")
    print(run(CASES[args.case], args.records, args.first_seed, args.replicates))


if __name__ == "__main__":
    main()
