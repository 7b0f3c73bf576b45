"""Size of the studentized trend statistic under its bootstrap reference, on whole simulated records.

Each record is one axis of the case's model simulated sample by sample (100 Hz), with its GLS warm-up
statistic L = Σ w_t e_t (weights for e^{−t/τ_c} chosen under the true model on blocks of the first long τ
and held fixed), the noise refitted jointly on r = e − (L/I) g by the loop's fitter (its covariance
across τ fixed from a pilot record, as the loop's refits fix it from the view's fit), z = L/√V(θ̂) and p
from :func:`carousel_theory.closed_loop.studentized.trend_reference` (drawn from that fit, or from it
with the walk raised), or the confidence-set p-value of
:func:`carousel_theory.closed_loop.studentized.boundary_reference` (the largest bootstrap p over the fit
and the ends of the (1 − γ) intervals of the walk and 1/f variances that reach 0, plus γ; the cases
marked "confidence-set", drawn on the same records as the case they name). A valid reference rejects at
most a fraction α of the records at level α.

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

from carousel_theory.closed_loop.calibration import DEFAULT_ALPHA, detector_alpha, long_tau_start
from carousel_theory.closed_loop.detectors import DETECTORS
from carousel_theory.closed_loop.linear_statistics import difference_weights
from carousel_theory.closed_loop.residual_model import (
    FittedNoise,
    ModelTerms,
    ResidualFit,
    fit_residual_model,
    noise_variances,
    statistic_units,
)
from carousel_theory.closed_loop.studentized import CONFIDENCE_SHARE, boundary_reference, trend_reference
from carousel_theory.closed_loop.trend_detectors import WarmupDetector
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
    walk_quantiles: int = 0  # replicates' walk at this many quantiles of N(θ̂_q, se²) truncated at 0
    confidence_level: float = 0.0  # γ > 0: the confidence-set p-value over the boundary nuisances
    records_of: str = ""  # draw the records of this case (the same records, another reference)


#: The warm-up detector's per-test rate in the loop's first iteration: its share of α = 0.01, Bonferroni
#: over its 8 time constants and 2 axes.
LOOP_TEST_LEVEL = detector_alpha(DEFAULT_ALPHA, 1, len(DETECTORS)) / (WarmupDetector.grid_size * 2)
#: γ of the size cases: a tenth of the smallest level reported, so p is valid at each of LEVELS.
SIZE_CONFIDENCE = 1e-4


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
        Case(
            "short_small_walk_mixed",
            "as above, replicates' walk at 8 quantiles of N(σ̂_q², se²) truncated at 0",
            1e-12,
            0.0,
            327.68,
            20.0,
            walk_quantiles=8,
        ),
        Case(
            "short_walk_inside",
            "white + walk 1e-9 (4.5 GLS se), 327.68 s, τ_c = 20 s",
            1e-9,
            0.0,
            327.68,
            20.0,
        ),
        Case(
            "short_walk_inside_mixed",
            "as above, replicates' walk at 8 quantiles of N(σ̂_q², se²) truncated at 0",
            1e-9,
            0.0,
            327.68,
            20.0,
            walk_quantiles=8,
        ),
        Case(
            "short_small_walk_boundary",
            f"white + walk 1e-12, 327.68 s, τ_c = 20 s; confidence-set p-value, γ = {SIZE_CONFIDENCE:g}",
            1e-12,
            0.0,
            327.68,
            20.0,
            confidence_level=SIZE_CONFIDENCE,
            records_of="short_small_walk",
        ),
        Case(
            "small_walk_boundary",
            f"white + walk 1e-12 (0.6 GLS se), 1 h; confidence-set p-value, γ = {SIZE_CONFIDENCE:g}",
            1e-12,
            0.0,
            confidence_level=SIZE_CONFIDENCE,
            records_of="small_walk",
        ),
        Case(
            "flicker_boundary",
            f"white + walk (1e-11) + 1/f (5e-8), 1 h; confidence-set p-value, γ = {SIZE_CONFIDENCE:g}",
            1e-11,
            5e-8,
            confidence_level=SIZE_CONFIDENCE,
            records_of="flicker",
        ),
        Case(
            "flicker_boundary_loop",
            f"white + walk (1e-11) + 1/f (5e-8), 1 h; confidence-set p-value, γ = {CONFIDENCE_SHARE:g} of"
            f" the loop's per-test rate",
            1e-11,
            5e-8,
            confidence_level=CONFIDENCE_SHARE * LOOP_TEST_LEVEL,
            records_of="flicker",
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
    shape_mean: float


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
    centred = regressor - regressor.mean()
    mean = float(regressor.mean())
    return Setup(case, model, terms, length, pilot, block_weights, weights, centred, sums, mean)


def one_record(setup: Setup, seed: int, replicates: int, amplitude: float = 0.0) -> tuple[float, float]:
    """(z, p) of one whole simulated record (seed: the case's number and ``seed``), with a warm-up of
    ``amplitude`` (rad/s) and the case's time constant added."""
    number = list(CASES).index(setup.case.records_of or setup.case.name)
    record = sample_noise(setup.model, setup.length, rng=np.random.default_rng([20261123, number, seed]))
    if amplitude:
        record += amplitude * (setup.regressor + setup.shape_mean)
    projection = float(np.dot(setup.weights, record))
    information = float(np.dot(setup.block_weights, setup.regressor_sums))
    record -= (projection / information) * setup.regressor
    fit = fit_residual_model(record, RATE, setup.terms, reference=setup.pilot)
    variance = statistic_units(setup.weights).variance(noise_variances(fit.noise))
    z = projection / math.sqrt(max(variance, 1e-300))
    if setup.case.confidence_level:
        level = setup.case.confidence_level
        bounded = boundary_reference(
            fit, setup.length, setup.block_weights, projection, level, setup.regressor_sums, replicates
        )
        return z, bounded.sf(z)
    walks = _generating_walks(setup.case, fit)
    fitted = fit.noise.model.rrw_variance
    generating = [
        None if walk == fitted else replace(fit.noise, model=replace(fit.noise.model, rrw_variance=walk))
        for walk in walks
    ]
    share = max(replicates // len(generating), 1)
    references = [
        trend_reference(
            fit, setup.length, setup.block_weights, projection, setup.regressor_sums, share, noise
        )
        for noise in generating
    ]
    return z, float(np.mean([reference.sf(z) for reference in references]))


def _generating_walks(case: Case, fit: ResidualFit) -> list[float]:
    """The walk variances the replicates are drawn from: the fitted one, raised to ``raised_walk`` se, or
    ``walk_quantiles`` stratified quantiles of N(σ̂_q², se²) truncated at 0."""
    walk, error = float(fit.noise.model.rrw_variance), fit.noise.standard_errors["rrw_variance"]
    if case.walk_quantiles:
        below = stats.norm.cdf(-walk / error)
        levels = below + (1.0 - below) * (np.arange(case.walk_quantiles) + 0.5) / case.walk_quantiles
        return [max(walk + error * float(stats.norm.ppf(level)), 0.0) for level in levels]
    return [max(walk, case.raised_walk * error)]


def run(case: Case, records: int, first_seed: int, replicates: int, amplitude: float = 0.0) -> Path:
    prepared = setup(case)
    started, values = time.time(), []
    for seed in range(first_seed, first_seed + records):
        values.append(one_record(prepared, seed, replicates, amplitude))
        if len(values) % 200 == 0:
            print(
                f"{case.name}: {len(values)} records, {time.time() - started:.0f} s",
                file=sys.stderr,
                flush=True,
            )
    PARTS.mkdir(exist_ok=True)
    path = PARTS / f"{case.name}_{first_seed}.json"
    if amplitude:
        path = PARTS / f"{case.name}_warmup{amplitude:g}_{first_seed}.json"
    part = {
        "amplitude": amplitude,
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


def _parts() -> tuple[dict[str, dict], dict[tuple[str, float], dict]]:
    """The parts' p and z by case (null records) and by (case, warm-up amplitude)."""
    null: dict[str, dict] = {}
    power: dict[tuple[str, float], dict] = {}
    for path in sorted(PARTS.glob("*.json")):
        part = json.loads(path.read_text())
        amplitude = float(part.get("amplitude", 0.0))
        entry = (
            power.setdefault((part["case"], amplitude), {})
            if amplitude
            else null.setdefault(part["case"], {})
        )
        entry.setdefault("p", []).extend(part["p"])
        entry.setdefault("z", []).extend(part["z"])
        entry.setdefault("replicates", set()).add(part["replicates"])
    return null, power


def _size_lines(null: dict[str, dict]) -> list[str]:
    lines = [
        "| case | records | replicates | α = 0.05 | α = 0.01 | α = 0.001 | KS p-value |",
        "|---|---|---|---|---|---|---|",
    ]
    for name, case in CASES.items():
        if name not in null:
            continue
        p = np.asarray(null[name]["p"])
        cells = []
        for level in LEVELS:
            k = int(np.sum(p <= level))
            low, high = clopper_pearson(k, len(p))
            cells.append(f"{k} = {k / len(p):.4f} [{low:.4f}, {high:.4f}]")
        ks = float(stats.kstest(p, "uniform").pvalue)
        counts = "/".join(str(r) for r in sorted(null[name]["replicates"]))
        lines.append(f"| {case.description} | {len(p)} | {counts} | {' | '.join(cells)} | {ks:.3g} |")
    return lines


def _power_lines(power: dict[tuple[str, float], dict]) -> list[str]:
    lines = [
        "| case | warm-up amplitude | records | named, bootstrap reference | named, N(0, 1) reference | "
        "median z |",
        "|---|---|---|---|---|---|",
    ]
    for (name, amplitude), entry in sorted(power.items()):
        p, z = np.asarray(entry["p"]), np.asarray(entry["z"])
        normal = 2.0 * stats.norm.sf(np.abs(z))
        named, plain = int(np.sum(p <= LOOP_TEST_LEVEL)), int(np.sum(normal <= LOOP_TEST_LEVEL))
        description = CASES[name].description
        lines.append(
            f"| {description} | {amplitude:g} | {len(p)} | {named}/{len(p)} | {plain}/{len(p)} | "
            f"{float(np.median(z)):.2f} |"
        )
    return lines


def write() -> str:
    null, power = _parts()
    lines = [
        "<!-- generated by benchmarks/bench_trend_reference.py --write — do not edit -->",
        "# Trend statistic: size of the studentized bootstrap reference on whole simulated records",
        "",
        (__doc__ or "").split("\n\n")[1].replace("\n", " "),
        "",
        "Rejections at each level with the 95 % Clopper–Pearson interval; KS: the Kolmogorov–Smirnov test of"
        " the records' p-values against U(0, 1).",
        "",
        *_size_lines(null),
        "",
        "## Power at the loop's rate",
        "",
        f"A warm-up e^{{−t/τ_c}} of the given amplitude added to the records; named when p is at most the"
        f" warm-up detector's per-test rate in the loop's first iteration ({LOOP_TEST_LEVEL:.3g}: its share"
        f" of α = 0.01, Bonferroni over 8 time constants and 2 axes). Here τ_c is known (the loop scans it),"
        f" and the N(0, 1) reference of the same z (which ignores the uncertainty of θ̂) is shown beside.",
        "",
        *_power_lines(power),
    ]
    return "\n".join(lines) + "\n"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--case", choices=sorted(CASES))
    parser.add_argument("--records", type=int, default=100)
    parser.add_argument("--first-seed", type=int, default=0)
    parser.add_argument("--replicates", type=int, default=200)
    parser.add_argument("--amplitude", type=float, default=0.0, help="warm-up amplitude added (rad/s)")
    parser.add_argument("--write", action="store_true")
    args = parser.parse_args()
    if args.write:
        DOCUMENT.write_text(write())
        print(DOCUMENT.read_text())
        return
    if args.case is None:
        parser.error("--case is required unless --write")
    print(run(CASES[args.case], args.records, args.first_seed, args.replicates, args.amplitude))


if __name__ == "__main__":
    main()
