"""False-alarm and detection rates of the closed loop: clean records of three lengths, single effects, pairs.

1. **False alarms.** Clean recordings of the declared model (bias + white + rate random walk, 100 Hz, two
   axes) of 300 s, 1 h and 10,000 s: how often the loop ends with anything but ``none`` (its family-wise
   false-alarm rate, at most α = 0.01 by construction), with a 95 % Clopper–Pearson interval, and which
   test fired.
2. **Single effects** at 300 s: a ladder of amplitudes per catalogue effect, down to the detection limit.
3. **Pairs that mask each other**, at 1 h: a warm-up transient under 1/f noise, a temperature effect under
   a strong rate random walk; each effect alone at the same amplitude for reference.
4. **Outside the catalogue**: a sawtooth must give ``unexplained``, never a catalogue name.
5. **Single decisions** on clean records: the rejection rate of each trend detector and of the 1/f
   detector (bootstrap and former χ²₁ / F references) at a nominal level of 0.05, the coverage of the
   trend statistics' variance bound, and the 1/f detector's power under both references.

Writes docs/loop_detection_rates.md (deterministic for given arguments: seeded, no timings in the file;
the mean loop time per record length is printed).

    nice python benchmarks/bench_loop_detection.py --section clean --clean 40 100 40
    nice python benchmarks/bench_loop_detection.py --section calibration --calibration 500 60 --power-seeds 10
    nice python benchmarks/bench_loop_detection.py --section pairs --pair-seeds 10
    nice python benchmarks/bench_loop_detection.py --section effects --seeds 5
    python benchmarks/bench_loop_detection.py --write
"""

from __future__ import annotations

import argparse
import json
import time
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np
from scipy import stats

from carousel_theory.closed_loop import LoopResult, run_loop
from carousel_theory.progress import progress
from carousel_theory.simulate import simulate_recording

RATE, WHITE, WALK = 100.0, 3.6e-5, 1e-11
ALPHA = 0.01
CLEAN_DURATIONS = (300, 3600, 10_000)
SHORT = 30_000  # samples of the single-effect ladders (300 s)
HOUR = 360_000

#: effect → (parameter varied, amplitudes from strong to the detection limit, fixed parameters)
LADDERS: dict[str, tuple[str, list[float], str]] = {
    "warmup": ("amplitude", [1.2e-2, 8e-3, 5e-3, 3e-3], "time_constant=30"),
    "temperature": ("coefficient", [5e-3, 3e-3, 1.5e-3, 8e-4], ""),
    "steps": ("size", [4e-3, 3e-3, 2e-3, 1.5e-3], ""),
    "spikes": ("amplitude", [0.06, 0.045, 0.035, 0.03], "rate=2e-4"),
    "sinusoid": ("amplitude", [5e-4, 3e-4, 2e-4, 1.5e-4], "frequency=3.3"),
    "colored_noise": ("coefficient", [0.4, 0.1, 0.05, 0.03], ""),
    "flicker": ("variance", [1e-6, 3e-7, 1e-7, 5e-8], ""),
}


@dataclass(frozen=True)
class PairCase:
    """Effects injected together (and the random-walk level), and the effects the loop should name."""

    label: str
    effects: tuple[str, ...]
    expected: tuple[str, ...]
    rrw_variance: float = WALK


PAIRS = (
    PairCase(
        "warm-up (8e-3) under 1/f noise",
        ("warmup:amplitude=8e-3,time_constant=120", "flicker:variance=5e-8"),
        ("warmup", "flicker"),
    ),
    PairCase("warm-up (8e-3) alone", ("warmup:amplitude=8e-3,time_constant=120",), ("warmup",)),
    PairCase(
        "warm-up (4e-3) under 1/f noise",
        ("warmup:amplitude=4e-3,time_constant=120", "flicker:variance=5e-8"),
        ("warmup", "flicker"),
    ),
    PairCase("warm-up (4e-3) alone", ("warmup:amplitude=4e-3,time_constant=120",), ("warmup",)),
    PairCase("1/f noise alone", ("flicker:variance=5e-8",), ("flicker",)),
    PairCase(
        "temperature under a strong random walk (σ_q² = 1e-10)",
        ("temperature:coefficient=5e-3",),
        ("temperature",),
        rrw_variance=1e-10,
    ),
)


#: How each decision's null distribution is obtained (what the false-alarm rates below test).
NULL_DISTRIBUTIONS = [
    "## The null distribution of each decision",
    "",
    "| decision | statistic | reference under the fitted model |",
    "|---|---|---|",
    "| spikes | max robust abs z about the running median | normal tail, Bonferroni over samples and axes "
    "(the robust scale's bias is removed; tests/test_effects.py checks the tail at 3σ) |",
    "| warm-up, temperature | GLS linear statistic L = Σ w_t e_t (weights constant over blocks of the first "
    "long τ), studentized z = L/√V(θ̂) by the noise refitted jointly with the regressor | parametric "
    "bootstrap from the refitted model, every replicate refitted by the fitter's non-negative GLS step "
    "(L–Allan-variance dependence exact, the Gaussian part of L integrated exactly; "
    "carousel_theory/closed_loop/studentized.py); the walk and 1/f variances whose (1 − γ) interval "
    "reaches 0 are searched over the interval's ends and the estimate and γ = 0.1 × the per-test rate is "
    "added (Berger & Boos 1994, Silvapulle 1996): the bootstrap from a walk fitted at 0 is liberal "
    "(Andrews 2000). Size and power on whole records: docs/trend_reference_size.md |",
    "| steps | GLS linear statistic L = Σ w_t e_t | exactly Gaussian given the noise "
    "variances; the variance is taken at its upper (1 − γ) confidence bound V̂ + Φ̄⁻¹(γ) se(V̂) from the "
    "fitter's GLS covariance (delta method) and γ = 0.1 × the detector's rate is added to the p-value "
    "(Berger & Boos 1994). The bound's coverage is asymptotic, and is measured below: se(V̂) is evaluated "
    "at the fitted variances, so it shrinks with V̂ and the bound is exceeded more often than γ on long "
    "records (first order: Φ(−z_γ / (1 + z_γ r)), r = se/V); on 300 s records it is very wide |"
    "| sinusoid | max periodogram ordinate / (model spectrum × median level) | exact: an Exp(1) ordinate "
    "over the median of a block of Exp(1) ordinates (Rényi's representation), Bonferroni over ordinates |",
    "| colored noise | log ratio of the median whitened ordinates at 10 % and 42 % of f_s | ratio of "
    "medians of independent Exp(1) ordinates (every third ordinate), exact cumulant generating function, "
    "Lugannani–Rice tail (relative error O(1/M), M in the thousands) |",
    "| 1/f noise | Δχ²/max(1, χ²/ν) of the nested GLS Allan-variance fits (same covariance across τ) | "
    "sequential parametric bootstrap from the fitted model without 1/f: Allan-variance vectors drawn "
    "(long τ exactly from block sums, short τ — more than 2000 differences — Gaussian given the long ones "
    "with the model's covariance), both fits redone per replicate, Besag–Clifford stopping, Bonferroni "
    "over axes (carousel_theory/closed_loop/noise_detectors.py); replaces the χ²₁ / F(1, ν) reference |",
    "| final misfit | largest abs z of the Allan variance over τ and axes | short τ (> 2000 differences): "
    "χ²_ν; long τ: sequential parametric bootstrap from the fitted model, exact size "
    "(carousel_theory/closed_loop/calibration.py) |",
    "",
    "Both bootstraps draw their replicates from a generator seeded with a digest of the observed values "
    "(calibration.bootstrap_generator): a recording always gets the same decision, and different recordings "
    "independent replicates. With one fixed stream every recording would meet the same critical value, and "
    "the size over recordings would be that of one draw rather than 1/(B + 1).",
    "",
]


@dataclass
class CleanTally:
    runs: int = 0
    alarms: int = 0
    outcomes: Counter = field(default_factory=Counter)
    fired: Counter = field(default_factory=Counter)
    seconds: float = 0.0


def _recording(samples: int, effects: list[str] | tuple[str, ...], seed: int, rrw_variance: float = WALK):
    return simulate_recording(
        samples,
        RATE,
        rng=np.random.default_rng(seed),
        bias=0.01,
        white_variance=WHITE,
        rrw_variance=rrw_variance,
        effects=list(effects),
    )


def clopper_pearson(successes: int, trials: int, level: float = 0.95) -> tuple[float, float]:
    """The exact binomial (Clopper–Pearson) interval of a rate."""
    tail = (1.0 - level) / 2.0
    low = 0.0 if successes == 0 else float(stats.beta.ppf(tail, successes, trials - successes + 1))
    high = 1.0 if successes == trials else float(stats.beta.ppf(1 - tail, successes + 1, trials - successes))
    return low, high


def _what_fired(result: LoopResult) -> list[str]:
    if result.effects == ["none"]:
        return []
    fired = [d.effect for d in result.steps[0].detections if d.significant]
    last = result.steps[-1]
    if last.decision.startswith("unexplained: the Allan variance"):
        fired.append("final misfit test")
    return fired or [last.decision]


def run_clean(
    counts: dict[int, int], stored: Callable[[int, CleanTally], None] | None = None, first_seed: int = 0
) -> dict[int, CleanTally]:
    """Clean records of each duration, seeds ``first_seed`` onwards; ``stored`` is called after every
    record (a partial run keeps its counts)."""
    tallies = {}
    for duration, count in counts.items():
        tally = CleanTally()
        for seed in progress(range(first_seed, first_seed + count), label=f"clean {duration} s"):
            started = time.monotonic()
            result = run_loop(_recording(int(duration * RATE), [], 10_000 + seed))
            tally.seconds += time.monotonic() - started
            tally.runs += 1
            tally.alarms += result.effects != ["none"]
            tally.outcomes[", ".join(result.effects)] += 1
            tally.fired.update(_what_fired(result))
            if stored is not None:
                stored(duration, tally)
        tallies[duration] = tally
        print(
            f"clean {duration} s: {tally.alarms}/{tally.runs}, "
            f"mean loop time {tally.seconds / max(count, 1):.1f} s"
        )
    return tallies


def run_ladders(seeds: int) -> list[tuple]:
    rows = []
    cases = [(name, value) for name, (_, values, _) in LADDERS.items() for value in values]
    for name, value in progress(cases, label="single effects"):
        parameter, _, fixed = LADDERS[name]
        text = f"{name}:{parameter}={value:g}" + (f",{fixed}" if fixed else "")
        named = wrong = unexplained = drops = 0
        for seed in range(seeds):
            result = run_loop(_recording(SHORT, [text], 20_000 + seed))
            named += name in result.effects
            wrong += any(e not in (name, "none", "unexplained") for e in result.effects)
            unexplained += "unexplained" in result.effects
            drops += result.error_after < result.error_before
        rows.append((name, parameter, value, fixed, named, wrong, unexplained, drops))
    return rows


def run_pairs(
    seeds: int, stored: Callable[[list], None] | None = None, cases: list[int] | None = None
) -> list[tuple[PairCase, dict[str, int], int, int, int]]:
    """Each pair case (or those of index ``cases``) on ``seeds`` 1 h records; ``stored`` is called after
    every record with the rows so far (case, named counts, all named, other name, records)."""
    rows: list[tuple[PairCase, dict[str, int], int, int, int]] = []
    for case in progress([PAIRS[i] for i in cases] if cases else PAIRS, label="pairs"):
        named = dict.fromkeys(case.expected, 0)
        both = other = 0
        for seed in range(seeds):
            result = run_loop(_recording(HOUR, case.effects, 40_000 + seed, case.rrw_variance))
            for name in case.expected:
                named[name] += name in result.effects
            both += all(name in result.effects for name in case.expected)
            other += any(e not in (*case.expected, "none", "unexplained") for e in result.effects)
            if stored is not None:
                stored([*rows, (case, dict(named), both, other, seed + 1)])
        rows.append((case, named, both, other, seeds))
    return rows


def run_outside(seeds: int) -> Counter:
    outcome: Counter = Counter()
    for seed in range(seeds):
        result = run_loop(_recording(SHORT, ["sawtooth:amplitude=3e-3,period=20"], 30_000 + seed))
        if any(e not in ("none", "unexplained") for e in result.effects):
            outcome["a catalogue name"] += 1
        else:
            outcome["unexplained" if "unexplained" in result.effects else "none"] += 1
    return outcome


# --- calibration of single decisions (the detectors' own rates at a nominal level) ----------------------

#: Nominal level at which the detectors' own rejection rates on clean records are counted (large enough
#: that a 2-point excess shows in a few thousand records).
NOMINAL = 0.05
#: Confidence levels at which the coverage of the trend statistics' variance bound is counted.
COVERAGE_GAMMAS = (0.1, 0.05, 0.01, 0.001)
#: Seeds of the calibration records (apart from the loop's).
CALIBRATION_SEED = 50_000


def _asymptotic_flicker_log_p(view: Any, axis: str) -> float:
    """The 1/f decision's former reference: Δχ²/max(1, χ²/ν) to χ²₁, or F(1, ν) when χ²/ν > 1."""
    from carousel_theory.closed_loop.linear_statistics import nested_chi_square
    from carousel_theory.closed_loop.residual_model import nested_statistic

    without, _ = nested_chi_square(view, axis, flicker=False)
    with_flicker, dof = nested_chi_square(view, axis, flicker=True)
    dof = max(dof, 1)
    statistic = nested_statistic(without, with_flicker, dof)
    if with_flicker / dof > 1.0:
        return float(stats.f.logsf(statistic, 1, dof))
    return float(stats.chi2.logsf(statistic, 1))


def _asymptotic_flicker_rejects(view: Any, alpha: float) -> bool:
    tests = len(view.axes)
    return any(_asymptotic_flicker_log_p(view, axis) < np.log(alpha / tests) for axis in view.axes)


def _coverage_misses(view: Any, axis: str) -> dict[str, list[int]]:
    """For the weights of a middle step, a warm-up (τ_c = T/20) and the temperature column, chosen under
    the fit: is V(θ) above the upper bound V̂ + Φ̄⁻¹(γ) se(V̂) at each γ of COVERAGE_GAMMAS?"""
    from carousel_theory.closed_loop.linear_statistics import exponential_regressor, gls_weights, step_scan
    from carousel_theory.closed_loop.residual_model import (
        FittedNoise,
        statistic_variance,
        statistic_variance_error,
    )
    from carousel_theory.noise_model import NoiseModel

    true = FittedNoise(NoiseModel(RATE, white_variance=WHITE, rrw_variance=WALK))
    span = float(view.time[-1] - view.time[0])
    weights = {
        "steps": step_scan(view, axis).middle_weights,
        "warmup": gls_weights(view, axis, exponential_regressor(view, span / 20.0)),
        "temperature": gls_weights(view, axis, view.temperature),
    }
    misses = {}
    for name, w in weights.items():
        spread = statistic_variance_error(view.fits[axis].noise, w)
        truth = statistic_variance(true, w)
        misses[name] = [
            int(spread.variance + float(stats.norm.isf(g)) * spread.standard_error < truth)
            for g in COVERAGE_GAMMAS
        ]
    return misses


def _calibration_record(samples: int, seed: int) -> dict[str, Any]:
    from carousel_theory.closed_loop.detectors import DETECTORS
    from carousel_theory.closed_loop.view import ModelSpec, build_view

    recording = _recording(samples, [], CALIBRATION_SEED + seed)
    view = build_view(recording, ("wx", "wy"), ModelSpec())
    rejected = {name: bool(DETECTORS[name].detect(view, NOMINAL).significant) for name in TREND_AND_FLICKER}
    rejected["flicker (χ²₁ / F reference)"] = _asymptotic_flicker_rejects(view, NOMINAL)
    return {"rejected": rejected, "misses": _coverage_misses(view, "wx")}


TREND_AND_FLICKER = ("steps", "warmup", "temperature", "flicker")


def run_calibration(counts: dict[int, int], stored: Callable[[dict], None], first_seed: int = 0) -> None:
    """Clean records of each duration, seeds ``first_seed`` onwards: each detector's rejections at NOMINAL
    (1/f by both references) and the coverage misses of the variance bound; stored after every record."""
    tallies: dict[str, Any] = {}
    for duration, count in counts.items():
        tally = tallies.setdefault(str(duration), {"runs": 0, "rejected": Counter(), "misses": {}})
        for seed in progress(range(first_seed, first_seed + count), label=f"calibration {duration} s"):
            record = _calibration_record(int(duration * RATE), seed)
            tally["runs"] += 1
            tally["rejected"].update(name for name, value in record["rejected"].items() if value)
            for name, misses in record["misses"].items():
                total = tally["misses"].setdefault(name, [0] * len(COVERAGE_GAMMAS))
                tally["misses"][name] = [a + b for a, b in zip(total, misses, strict=True)]
            stored(tallies)


def _power_row(variance: float, samples: int, seeds: int, alpha: float) -> list:
    from carousel_theory.closed_loop.detectors import DETECTORS
    from carousel_theory.closed_loop.view import ModelSpec, build_view

    new = old = 0
    for seed in range(seeds):
        recording = _recording(samples, [f"flicker:variance={variance:g}"], 20_000 + seed)
        view = build_view(recording, ("wx", "wy"), ModelSpec())
        new += DETECTORS["flicker"].detect(view, alpha).significant
        old += _asymptotic_flicker_rejects(view, alpha)
    return [samples / RATE, variance, seeds, new, old]


def run_flicker_power(seeds: int) -> list[list]:
    """The 1/f detector alone at its first-iteration rate, bootstrap vs the former asymptotic reference,
    on the records of the single-effect ladder (300 s, same seeds) and at the pair cases' 1/f level (1 h)."""
    from carousel_theory.closed_loop.calibration import detector_alpha
    from carousel_theory.closed_loop.detectors import TESTED_EFFECTS

    alpha = detector_alpha(ALPHA, 1, len(TESTED_EFFECTS))
    cases = [(SHORT, v) for v in LADDERS["flicker"][1]] + [(HOUR, 5e-8), (HOUR, 2e-8)]
    return [_power_row(v, n, seeds, alpha) for n, v in progress(cases, label="1/f power")]


def _rate_cell(count: int, runs: int) -> str:
    low, high = clopper_pearson(count, runs)
    return f"{count}/{runs} = {count / runs:.3f} [{low:.3f}, {high:.3f}]"


def _calibration_lines(tallies: dict[str, Any], power: list[list] | None) -> list[str]:
    names = [*TREND_AND_FLICKER, "flicker (χ²₁ / F reference)"]
    lines = [
        f"## Each decision's own rejection rate on clean records, at a nominal level of {NOMINAL:g}",
        "",
        "Each detector alone on the clean two-axis records (seeds from "
        f"{CALIBRATION_SEED}), at level {NOMINAL:g} family-wise over its scan and the axes; a valid test "
        f"rejects at most {NOMINAL:g} of them. Counts with the 95 % Clopper–Pearson interval. The 1/f "
        "detector is shown with its bootstrap reference (used) and with the former χ²₁ / F reference.",
        "",
        "| duration | records | " + " | ".join(names) + " |",
        "|---|---|" + "---|" * len(names),
    ]
    for duration, tally in sorted(tallies.items(), key=lambda item: int(item[0])):
        cells = [_rate_cell(tally["rejected"].get(name, 0), tally["runs"]) for name in names]
        lines.append(f"| {int(duration):g} s | {tally['runs']} | " + " | ".join(cells) + " |")
    lines += [
        "",
        "## Coverage of the trend statistics' variance bound",
        "",
        "How often the true variance V(θ) of a GLS statistic exceeds its upper bound V̂ + Φ̄⁻¹(γ) se(V̂) "
        "(rate, 95 % Clopper–Pearson), for the weights of a step in the middle, a warm-up with τ_c = T/20 "
        "and the temperature column, chosen under the fit of axis wx; a valid bound is exceeded at most γ "
        "of the time. The three rows agree: the white variance is estimated far more precisely than the "
        "walk's, so to first order each bound is exceeded when the walk's own bound σ̂_q² + Φ̄⁻¹(γ) se(σ̂_q²) "
        "is below σ_q², whatever the weights.",
        "",
        "| duration | weights | " + " | ".join(f"γ = {g:g}" for g in COVERAGE_GAMMAS) + " |",
        "|---|---|" + "---|" * len(COVERAGE_GAMMAS),
    ]
    for duration, tally in sorted(tallies.items(), key=lambda item: int(item[0])):
        for name, misses in tally["misses"].items():
            cells = [_rate_cell(m, tally["runs"]) for m in misses]
            lines.append(f"| {int(duration):g} s | {name} | " + " | ".join(cells) + " |")
    if power:
        lines += [
            "",
            "## Power of the 1/f detector alone, bootstrap vs the former asymptotic reference",
            "",
            "At its first-iteration rate in the loop (α split over 7 detectors), the same records for both.",
            "",
            "| duration | σ_f² | records | bootstrap reference | χ²₁ / F reference |",
            "|---|---|---|---|---|",
        ]
        for duration, variance, seeds, new, old in power:
            lines.append(f"| {duration:g} s | {variance:g} | {seeds} | {new}/{seeds} | {old}/{seeds} |")
    return [*lines, ""]


def _clean_lines(tallies: dict[int, CleanTally]) -> list[str]:
    lines = [
        "## False alarms on clean recordings (family-wise, the whole loop)",
        "",
        "| duration | records | loop named anything | rate | 95 % Clopper–Pearson | outcomes "
        "| tests that fired |",
        "|---|---|---|---|---|---|---|",
    ]
    for duration, tally in tallies.items():
        low, high = clopper_pearson(tally.alarms, tally.runs)
        outcomes = "; ".join(f"{k} {v}" for k, v in sorted(tally.outcomes.items()))
        fired = "; ".join(f"{k} {v}" for k, v in sorted(tally.fired.items())) or "—"
        lines.append(
            f"| {duration:g} s | {tally.runs} | {tally.alarms} | {tally.alarms / tally.runs:.3f} | "
            f"[{low:.4f}, {high:.4f}] | {outcomes} | {fired} |"
        )
    return [*lines, ""]


def _ladder_lines(rows: list[tuple], seeds: int) -> list[str]:
    lines = [
        f"## Single effects at 300 s, {seeds} seeds per amplitude",
        "",
        "| effect | parameter | value | fixed | named | other catalogue name | unexplained | error dropped |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for name, parameter, value, fixed, named, wrong, unexplained, drops in rows:
        lines.append(
            f"| {name} | {parameter} | {value:g} | {fixed or '—'} | {named}/{seeds} | {wrong}/{seeds} | "
            f"{unexplained}/{seeds} | {drops}/{seeds} |"
        )
    return [*lines, ""]


def _injected(case: PairCase, effect: str) -> dict[str, float]:
    """The parameters of ``effect`` in the case's injections ({} when it is not injected)."""
    for text in case.effects:
        name, _, parameters = text.partition(":")
        if name == effect:
            return {k: float(v) for k, v in (item.split("=") for item in parameters.split(","))}
    return {}


def _known_variance_warmup_z(cases: list[PairCase]) -> dict[str, float]:
    """The z of each case's warm-up with the noise variances known (the injected white, walk and 1/f):
    A (wᵀg)/√V(w), g = e^{−t/τ_c}, w its GLS weights, V the exact variance under the injected noise —
    the warm-up's detection limit under that noise, without the uncertainty of fitted variances."""
    from carousel_theory.closed_loop.linear_statistics import exponential_regressor, gls_weights
    from carousel_theory.closed_loop.residual_model import FittedNoise, statistic_variance
    from carousel_theory.closed_loop.view import ModelSpec, build_view
    from carousel_theory.noise_model import NoiseModel

    view = build_view(_recording(HOUR, [], 40_000), ("wx",), ModelSpec())
    result = {}
    for case in cases:
        warmup = _injected(case, "warmup")
        if not warmup:
            continue
        flicker = _injected(case, "flicker").get("variance", 0.0)
        walk = NoiseModel(RATE, white_variance=WHITE, rrw_variance=case.rrw_variance)
        shape = exponential_regressor(view, warmup["time_constant"])
        weights = gls_weights(view, "wx", shape, FittedNoise(walk))
        model = replace(walk, flicker_variance=flicker)
        variance = statistic_variance(FittedNoise(model), weights)
        result[case.label] = warmup["amplitude"] * float(np.dot(weights, shape)) / float(np.sqrt(variance))
    return result


def _warmup_threshold(iteration: int) -> float:
    """|z| at which the warm-up (8 time constants × 2 axes) rejects with known variances, iteration k."""
    from carousel_theory.closed_loop.calibration import detector_alpha
    from carousel_theory.closed_loop.detectors import TESTED_EFFECTS

    detectors = len(TESTED_EFFECTS) - (iteration > 1)  # the 1/f detector leaves once 1/f is fitted
    return float(stats.norm.isf(detector_alpha(ALPHA, iteration, detectors) / (2 * 8 * 2)))


def _pair_rows(parts: Path) -> list[tuple]:
    """The stored pair cases (parts pairs*.json; a case stored twice counts with its most records), in
    the order of PAIRS."""
    best: dict[int, list] = {}
    for path in sorted(parts.glob("pairs*.json")):
        for index, *row in json.loads(path.read_text(encoding="utf-8")):
            if index not in best or row[-1] > best[index][-1]:
                best[index] = row
    return [(PAIRS[index], *best[index]) for index in sorted(best)]


def _pair_lines(rows: list) -> list[str]:
    known = _known_variance_warmup_z([case for case, *_ in rows])
    counts = sorted({row[-1] for row in rows})
    seeds_text = f"{counts[0]} seeds each" if len(counts) == 1 else "records per case as counted"
    lines = [
        f"## Effects that mask each other, 1 h records, {seeds_text}",
        "",
        "Warm-up and temperature statistics are computed with the competing stochastic term refitted jointly "
        "with the regressor (1/f noise for the warm-up, the rate random walk for the temperature), so the "
        "stochastic term fitted with the effect still in the data cannot hide it. The last column is the "
        "warm-up's z with the injected noise variances known, against the |z| at which it is named with "
        f"known variances in iteration 1 ({_warmup_threshold(1):.2f}) and 2 ({_warmup_threshold(2):.2f}): "
        "above them the warm-up is above its detection limit under that noise.",
        "",
        "| case | injected | σ_q² | each named | all named | another catalogue name | warm-up z, variances "
        "known |",
        "|---|---|---|---|---|---|---|",
    ]
    for case, named, both, other, seeds in rows:
        each = ", ".join(f"{name} {count}/{seeds}" for name, count in named.items())
        z = f"{known[case.label]:.1f}" if case.label in known else "—"
        lines.append(
            f"| {case.label} | {'; '.join(case.effects)} | {case.rrw_variance:g} | {each} | {both}/{seeds} | "
            f"{other}/{seeds} | {z} |"
        )
    return [*lines, "", *_masking_notes(rows, known)]


def _masking_notes(rows: list, known: dict[str, float]) -> list[str]:
    """A plain statement for each case whose warm-up is above its known-variance detection limit in
    both iterations yet named in fewer than half of the records."""
    notes = []
    for case, named, _, _, seeds in rows:
        z = known.get(case.label)
        if z is None or z <= _warmup_threshold(2) or 2 * named.get("warmup", 0) >= seeds:
            continue
        notes.append(
            f"**Not achieved — {case.label}:** the warm-up is named in {named['warmup']}/{seeds} records "
            f"although with the variances known its z ({z:.1f}) is above the limit of both iterations. The "
            "joint test loses it in the variance of its statistic, not in its projection: with a 1/f term "
            "in the noise model the statistic's variance is dominated by the fitted 1/f variance, whose "
            "standard error is a large fraction of it, and the upper confidence bound of that variance "
            "(the nuisance part of the p-value) then lowers z below the threshold; the 1/f term is named "
            "and the warm-up, tested again with 1/f in the model, stays below it."
        )
    return [*notes, ""] if notes else []


def _save(parts: Path, name: str, value: object) -> None:
    parts.mkdir(parents=True, exist_ok=True)
    (parts / f"{name}.json").write_text(json.dumps(value, indent=1), encoding="utf-8")


def _load(parts: Path, name: str) -> object:
    return json.loads((parts / f"{name}.json").read_text(encoding="utf-8"))


def _json_tally(tally: dict[str, Any]) -> dict[str, Any]:
    return {"runs": tally["runs"], "rejected": dict(tally["rejected"]), "misses": tally["misses"]}


def _summed_tally(first: dict[str, Any] | None, second: dict[str, Any]) -> dict[str, Any]:
    """Two stored calibration tallies of one duration (records from different seeds) as one."""
    if first is None:
        return second
    rejected = Counter(first["rejected"]) + Counter(second["rejected"])
    misses = {
        name: [a + b for a, b in zip(first["misses"][name], counts, strict=True)]
        for name, counts in second["misses"].items()
    }
    return {"runs": first["runs"] + second["runs"], "rejected": dict(rejected), "misses": misses}


def _clean_record(tally: CleanTally) -> list:
    return [tally.runs, tally.alarms, dict(tally.outcomes), dict(tally.fired)]


def run_section(section: str, args: argparse.Namespace) -> None:
    """Run one section and store its tallies as JSON in ``args.parts`` (so sections can run apart), as it
    goes: a section stopped early leaves the counts it reached, and the document shows those counts."""
    _save(
        args.parts,
        f"arguments_{section}" + (f"_from{args.first_seed}" if args.first_seed else ""),
        {
            "clean": args.clean,
            "seeds": args.seeds,
            "pair_seeds": args.pair_seeds,
            "calibration": args.calibration,
            "power_seeds": args.power_seeds,
        },
    )
    if section == "clean":
        counts = dict(zip(CLEAN_DURATIONS, args.clean, strict=True))
        for duration in args.durations or CLEAN_DURATIONS:
            # Records from a later seed go to their own part; the document sums the parts of a duration.
            name = f"clean_{duration}" + (f"_from{args.first_seed}" if args.first_seed else "")
            run_clean(
                {duration: counts[duration]},
                lambda _, tally, name=name: _save(args.parts, name, _clean_record(tally)),
                args.first_seed,
            )
    elif section == "calibration":
        counts = dict(zip((300, 3600), args.calibration, strict=True))
        suffix = f"_from{args.first_seed}" if args.first_seed else ""
        for duration, count in counts.items():
            if not count:
                continue
            run_calibration(
                {duration: count},
                lambda tallies, d=duration: _save(
                    args.parts, f"calibration_{d}{suffix}", {k: _json_tally(v) for k, v in tallies.items()}
                ),
                args.first_seed,
            )
        if args.power_seeds:
            _save(args.parts, "flicker_power", run_flicker_power(args.power_seeds))
    elif section == "pairs":
        run_pairs(
            args.pair_seeds,
            lambda rows: _save(
                args.parts,
                "pairs" + "".join(f"_{i}" for i in args.pair_cases or []),
                [[PAIRS.index(row[0]), *row[1:]] for row in rows],
            ),
            args.pair_cases,
        )
    else:
        _save(
            args.parts,
            "effects",
            {"ladders": run_ladders(args.seeds), "outside": dict(run_outside(args.seeds))},
        )


MISSING = "Not measured: this section did not finish in the run that wrote this document."


def _maybe(parts: Path, name: str) -> Any:
    return _load(parts, name) if (parts / f"{name}.json").exists() else None


def _document_sections(args: argparse.Namespace) -> list[str]:
    tallies = {}
    for duration in CLEAN_DURATIONS:
        for path in sorted(args.parts.glob(f"clean_{duration}.json")) + sorted(
            args.parts.glob(f"clean_{duration}_from*.json")
        ):
            runs, alarms, outcomes, fired = json.loads(path.read_text(encoding="utf-8"))
            tally = tallies.setdefault(duration, CleanTally())
            tally.runs += runs
            tally.alarms += alarms
            tally.outcomes.update(outcomes)
            tally.fired.update(fired)
    lines = _clean_lines(tallies)
    missing = [f"{d:g} s" for d in CLEAN_DURATIONS if d not in tallies]
    if missing:
        lines += [f"Clean records of {', '.join(missing)}: {MISSING[0].lower()}{MISSING[1:]}", ""]
    calibration: dict[str, Any] = {}
    for path in sorted(args.parts.glob("calibration_*.json")):
        for duration, tally in json.loads(path.read_text(encoding="utf-8")).items():
            calibration[duration] = _summed_tally(calibration.get(duration), tally)
    if calibration:
        lines += _calibration_lines(calibration, _maybe(args.parts, "flicker_power"))
    else:
        lines += ["## Each decision's own rejection rate on clean records", "", MISSING, ""]
    rows = _pair_rows(args.parts)
    if not rows:
        lines += ["## Effects that mask each other", "", MISSING, ""]
    else:
        lines += _pair_lines(rows)
    effects, used = _maybe(args.parts, "effects"), _maybe(args.parts, "arguments_effects")
    if effects is None:
        return [*lines, "## Single effects and outside the catalogue", "", MISSING, ""]
    seeds, outside = used["seeds"], Counter(effects["outside"])
    lines += _ladder_lines([tuple(row) for row in effects["ladders"]], seeds)
    lines += [
        f"## Outside the catalogue: sawtooth (peak-to-peak 3e-3 rad/s, period 20 s), {seeds} seeds at 300 s",
        "",
        ", ".join(f"{k} {outside.get(k, 0)}" for k in ("unexplained", "a catalogue name", "none")) + ".",
        "",
    ]
    return lines


def write_document(args: argparse.Namespace) -> None:
    """docs/loop_detection_rates.md from the stored sections (a section not stored is said to be missing)."""
    commands = (
        "Commands: `python benchmarks/bench_loop_detection.py --section clean --clean N300 N3600 N10000`, "
        "`... --section calibration --calibration N300 N3600 --power-seeds K`, "
        "`... --section pairs --pair-seeds K`, `... --section effects --seeds K`, then `... --write` "
        "(sections can run in parallel; a clean duration can be split over runs with `--durations D "
        "--first-seed S`, and the calibration's with `--first-seed S`; the counts used are in the tables)."
    )
    lines = [
        "<!-- generated by benchmarks/bench_loop_detection.py — do not edit -->",
        "# Closed loop: false-alarm and detection rates",
        "",
        f"Two axes at {RATE:g} Hz, declared model bias + white (σ² = {WHITE:g} (rad/s)² per sample) + rate "
        f"random walk (σ_q² = {WALK:g} per sample unless said), plus the undeclared effects named. The loop "
        f"runs at a family-wise false-alarm rate α = {ALPHA:g} for the whole run (every detector in every "
        "iteration and the final Allan-variance misfit test; the split is documented in "
        "carousel_theory/closed_loop/calibration.py).",
        "",
        commands,
        "",
        *NULL_DISTRIBUTIONS,
        *_document_sections(args),
    ]
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text("\n".join(lines), encoding="utf-8")
    print(f"wrote {args.out}")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--section", choices=("clean", "calibration", "pairs", "effects"), help="run one section"
    )
    parser.add_argument("--write", action="store_true", help="write the document from the stored sections")
    parser.add_argument(
        "--clean",
        type=int,
        nargs=3,
        default=[40, 100, 40],
        metavar=("N300", "N3600", "N10000"),
        help="clean records of 300 s, 1 h and 10,000 s",
    )
    parser.add_argument(
        "--durations",
        type=int,
        nargs="*",
        choices=CLEAN_DURATIONS,
        help="clean durations to run (default all)",
    )
    parser.add_argument(
        "--first-seed",
        type=int,
        default=0,
        help="first record's seed of the clean and calibration sections (to split a duration over runs)",
    )
    parser.add_argument(
        "--calibration",
        type=int,
        nargs=2,
        default=[2400, 400],
        metavar=("N300", "N3600"),
        help="clean records of 300 s and 1 h for the detectors' own rates and the bound's coverage",
    )
    parser.add_argument("--power-seeds", type=int, default=20, help="records per 1/f power case")
    parser.add_argument("--seeds", type=int, default=10, help="records per single effect and amplitude")
    parser.add_argument(
        "--pair-cases", type=int, nargs="*", help="indices of the pair cases to run (default all)"
    )
    parser.add_argument("--pair-seeds", type=int, default=10, help="records per pair case (1 h each)")
    parser.add_argument("--parts", type=Path, default=Path("benchmarks/loop_detection_parts"))
    parser.add_argument("--out", type=Path, default=Path("docs/loop_detection_rates.md"))
    args = parser.parse_args()
    started = time.monotonic()
    every = ["clean", "calibration", "pairs", "effects"]
    sections = [args.section] if args.section else ([] if args.write else every)
    for section in sections:
        run_section(section, args)
    if args.write or not args.section:
        write_document(args)
    print(f"done in {time.monotonic() - started:.0f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
