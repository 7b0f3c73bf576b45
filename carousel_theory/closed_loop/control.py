"""The loop's control: fit, test, try the best-supported candidates, keep one, repeat, test the misfit.

One iteration k
    1. **Evaluate** the current model (:func:`carousel_theory.closed_loop.evaluation.evaluate`): every
       detector at its share of α (:mod:`carousel_theory.closed_loop.calibration`).
    2. **Try** the significant candidates, the three smallest p-values first: fit the effect
       (:data:`~carousel_theory.closed_loop.detectors.REMEDIES`), refit the noise model, evaluate again.
    3. **Keep** the first candidate for which the headline error drops, the noise model's Allan variance
       does not have to grow at any τ by more than 2 of its GLS standard errors to absorb what a
       deterministic effect leaves (:func:`~carousel_theory.closed_loop.residual_model.noise_growth`),
       and the effect explains its own evidence (:data:`~carousel_theory.closed_loop.detectors.VERIFIERS`
       no longer significant at the iteration's rate; for colored noise, whose real filters are not
       exactly AR(p ≤ 4), a 95 % drop of the evidence's −log p counts as "most of it").
    4. **Stop** when nothing is significant (``none`` if nothing was added) or every candidate is rejected
       (``unexplained``). At the end the Allan variance is tested against the final model by a parametric
       bootstrap; a misfit appends ``unexplained``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np

from carousel_theory.closed_loop.calibration import DEFAULT_ALPHA, detector_alpha, final_alpha, misfit_test
from carousel_theory.closed_loop.detection import Detection
from carousel_theory.closed_loop.detectors import REMEDIES, TESTED_EFFECTS, VERIFIERS
from carousel_theory.closed_loop.evaluation import HEADLINE_METRIC, Evaluation, evaluate
from carousel_theory.closed_loop.preparation import LoopInput, prepare
from carousel_theory.closed_loop.residual_model import ModelTerms, describe_noise, noise_growth
from carousel_theory.closed_loop.result import LoopResult, Step, Trial
from carousel_theory.closed_loop.view import FittedEffect, ModelSpec, build_view
from carousel_theory.data import Recording

__all__ = ["MAXIMUM_TRIALS", "run_loop"]

#: Candidates tried per iteration, from the smallest p-value.
MAXIMUM_TRIALS = 3


@dataclass(frozen=True)
class _Outcome:
    steps: list[Step]
    current: Evaluation
    effects: list[str]
    unexplained: bool


def _detector_count(spec: ModelSpec) -> int:
    return sum(1 for name in TESTED_EFFECTS if not (name == "flicker" and spec.terms.flicker))


def _evaluate(loop: LoopInput, spec: ModelSpec, iteration: int) -> Evaluation:
    """The model ``spec`` evaluated with the detectors at iteration ``iteration``'s rate."""
    view = build_view(loop.recording, loop.axes, spec)
    rate = detector_alpha(loop.alpha, iteration, _detector_count(spec))
    return evaluate(view, loop.samples_per_revolution, loop.angle, rate)


def _significant(current: Evaluation, kept: set[str] | frozenset[str]) -> list[Detection]:
    candidates = [d for name, d in current.detections.items() if name not in kept]
    if current.view.spec.terms.ar_order:
        candidates = [d for d in candidates if d.effect != "colored_noise"]
    return sorted((d for d in candidates if d.significant), key=lambda d: (d.log10_p, -d.statistic))


def _verdict(
    detection: Detection, verification: Detection, improved: bool, grown: list[str], rate: float
) -> tuple[bool, str]:
    explained = not verification.log10_p < np.log10(rate)
    # A real sensor's filter is not exactly AR(p ≤ 4): on long records the slope test stays significant
    # after a fit that removes nearly all of it; a ≥ 95 % drop of the evidence's −log p counts as "most".
    partial = (
        detection.effect == "colored_noise"
        and verification.log10_p > 0.05 * detection.log10_p
        and detection.log10_p < 0
    )
    if improved and (explained or partial) and not grown:
        return True, "added: explains its evidence" if explained else "added: explains most of its evidence"
    if not improved:
        return False, "rejected: the error did not drop"
    if grown:
        return False, "rejected: the noise model had to grow to absorb what it leaves (" + ", ".join(
            grown
        ) + ")"
    return False, "rejected: its own evidence remains (it does not explain the residual)"


def _noise_grown(loop: LoopInput, current: Evaluation, candidate: Evaluation) -> list[str]:
    grown = []
    new_flicker = candidate.view.spec.terms.flicker and not current.view.spec.terms.flicker
    for axis in loop.axes:
        before, after = current.view.fits[axis], candidate.view.fits[axis]
        grown += [f"{axis} {change}" for change in noise_growth(before, after, new_flicker=new_flicker)]
    return grown


def _joint_term(current: Evaluation, fitted: FittedEffect, rate: float) -> Detection | None:
    """The 1/f term a deterministic effect was detected jointly with, as a named effect when its own
    test (on the residual without the effect) is significant at ``rate``."""
    if fitted.terms is None or not fitted.terms.flicker or current.view.spec.terms.flicker:
        return None
    flicker = current.detections.get("flicker")
    detection = current.detections[fitted.effect]
    p_value = float(detection.details.get("competing_flicker_p", 1.0))
    if flicker is None or not p_value < rate:
        return None
    return replace(flicker, log10_p=math.log10(max(p_value, 1e-300)), significant=True)


def _explains(name: str, evaluation: Evaluation, rate: float) -> bool:
    return not VERIFIERS[name].detect(evaluation.view, rate).log10_p < math.log10(rate)


def _companion(
    loop: LoopInput, current: Evaluation, candidate: Evaluation, detection: Detection, trial: _Trying
) -> tuple[Detection, Evaluation] | None:
    """Effects that mask each other, tested jointly: when removing ``detection``'s effect explains its
    evidence but reveals another effect (significant only now, at the next iteration's rate) and so does
    not lower the error by itself, the two are added together and kept if together they lower the
    error and each explains its own evidence."""
    revealed = _significant(candidate, trial.kept | {detection.effect})
    if not revealed:
        return None
    companion = revealed[0]
    fitted = REMEDIES[companion.effect].fit(candidate.view, companion, trial.rate)
    joint = _evaluate(loop, candidate.view.spec.with_effect(fitted), trial.iteration + 1)
    together = all(_explains(name, joint, trial.rate) for name in (detection.effect, companion.effect))
    return (companion, joint) if together and joint.headline < current.headline else None


@dataclass(frozen=True)
class _Trying:
    iteration: int
    rate: float
    kept: frozenset[str]


def _try(
    loop: LoopInput, current: Evaluation, detection: Detection, trying: _Trying
) -> tuple[Trial, Evaluation]:
    """Add ``detection``'s effect to the current model, evaluate, and judge it."""
    remedy = REMEDIES[detection.effect]
    fitted = remedy.fit(current.view, detection, trying.rate)
    candidate = _evaluate(loop, current.view.spec.with_effect(fitted), trying.iteration + 1)
    verification = VERIFIERS[detection.effect].detect(candidate.view, trying.rate)
    grown = [] if remedy.stochastic else _noise_grown(loop, current, candidate)
    improved = candidate.headline < current.headline
    accepted, decision = _verdict(detection, verification, improved, grown, trying.rate)
    companion = _joint_term(current, fitted, trying.rate) if accepted else None
    if not accepted and not improved and not grown and _explains(detection.effect, candidate, trying.rate):
        joint = _companion(loop, current, candidate, detection, trying)
        if joint is not None:
            companion, candidate = joint
            accepted, decision = True, f"added with {companion.effect}: together they explain their evidence"
    trial = Trial(
        detection,
        current.headline,
        candidate.headline,
        verification,
        accepted,
        decision,
        fitted.parameters,
        companion,
    )
    return trial, candidate


def _iterate(
    loop: LoopInput, current: Evaluation, iteration: int, kept: set[str]
) -> tuple[Step, Evaluation | None]:
    """One iteration: the step it records and the new evaluation (None when the loop stops)."""
    rate = detector_alpha(loop.alpha, iteration, len(current.detections))
    detections = tuple(d for name, d in current.detections.items() if name not in kept)
    significant = _significant(current, kept)
    if not significant:
        return Step(iteration, current.headline, "nothing significant remains", rate, detections), None
    trials = []
    trying = _Trying(iteration, rate, frozenset(kept))
    for detection in significant[:MAXIMUM_TRIALS]:
        trial, candidate = _try(loop, current, detection, trying)
        trials.append(trial)
        if trial.accepted:
            step = Step(
                iteration,
                current.headline,
                f"added {detection.effect}" + (f" and {trial.companion.effect}" if trial.companion else ""),
                rate,
                detections,
                tuple(trials),
                detection,
            )
            return step, candidate
    decision = "unexplained: no candidate explains the significant evidence"
    return Step(iteration, current.headline, decision, rate, detections, tuple(trials)), None


def _run_iterations(loop: LoopInput, first: Evaluation) -> _Outcome:
    steps: list[Step] = []
    current, effects, kept = first, list[str](), set[str]()
    for iteration in range(1, loop.maximum_iterations + 1):
        step, candidate = _iterate(loop, current, iteration, kept)
        steps.append(step)
        if step.added is None:
            return _Outcome(steps, current, effects, step.decision.startswith("unexplained"))
        assert candidate is not None
        for added in (step.added, step.trials[-1].companion):
            if added is not None:
                effects.append(added.effect)
                kept.add(added.effect)
        current = candidate
    # The iteration budget ran out: whatever is still significant is unexplained.
    return _Outcome(steps, current, effects, bool(_significant(current, kept)))


def _final_steps(loop: LoopInput, outcome: _Outcome) -> list[Step]:
    """The final tests when the iterations ended explained: the Allan-variance misfit (parametric
    bootstrap) and, for an effect kept for "most of its evidence", whether its evidence remains at the
    rate of the iteration that added it."""
    current, number = outcome.current, len(outcome.steps) + 1
    rate = final_alpha(loop.alpha)
    view = current.view
    test = misfit_test(view.cleaned, view.fits, rate)
    if test.rejects:
        decision = (
            f"unexplained: the Allan variance of {test.axis} still misfits the model "
            f"(largest z = {test.z:.3g} "
            f"over {test.tests} τ and axes; parametric bootstrap p = {test.p_value:.3g} from "
            f"{test.replicates} replicates, α = {rate:.3g})"
        )
        return [Step(number, current.headline, decision, rate)]
    # An effect kept for "most of its evidence" is judged again, at the rate of its own iteration.
    for step in outcome.steps:
        partial = [t for t in step.trials if t.accepted and t.decision.endswith("most of its evidence")]
        for trial in partial:
            name = trial.detection.effect
            if VERIFIERS[name].detect(view, step.detector_alpha).significant:
                decision = f"unexplained: evidence of {name} remains after adding it"
                return [Step(number, current.headline, decision, step.detector_alpha)]
    return []


def run_loop(
    recording: Recording,
    *,
    samples_per_revolution: int = 200,
    axes: Sequence[str] | None = None,
    alpha: float = DEFAULT_ALPHA,
    maximum_iterations: int = 8,
    declared: Sequence[str] = ("white", "rrw"),
) -> LoopResult:
    """Run the closed loop on a static recording (see the module docstring).

    Parameters
    ----------
    recording
        A :class:`~carousel_theory.data.Recording`; irregular timestamps are bin-averaged onto a uniform
        grid first (said in ``observations``).
    samples_per_revolution
        N of the virtual carouseling (TIM 2014 §V-C uses 200); ignored for the carouselled bins when the
        recording has a ``phi`` column (one bin per measured revolution), still used for averaged bins.
    axes
        The gyro axes; default: ``wx`` and ``wy`` when present, else every axis (one axis: averaging only).
    alpha
        Family-wise false-alarm rate of the whole run (every detector in every iteration and the final
        misfit test; split as :mod:`carousel_theory.closed_loop.calibration` documents).
    maximum_iterations
        Upper bound on the number of effects added.
    declared
        The declared model: "white" and "rrw" always, "flicker" optionally.
    """
    loop = prepare(recording, samples_per_revolution, axes, alpha, maximum_iterations, declared)
    spec = ModelSpec(ModelTerms(flicker=loop.declared_flicker))
    before = _evaluate(loop, spec, 1)
    outcome = _run_iterations(loop, before)
    final = [] if outcome.unexplained else _final_steps(loop, outcome)
    effects = (
        [*outcome.effects, "unexplained"] if (outcome.unexplained or final) else outcome.effects or ["none"]
    )
    after = outcome.current
    return LoopResult(
        effects=effects,
        metric=HEADLINE_METRIC,
        error_before=before.headline,
        error_after=after.headline,
        model_before={axis: describe_noise(before.view.fits[axis].noise) for axis in loop.axes},
        model_after={axis: describe_noise(after.view.fits[axis].noise) for axis in loop.axes},
        metrics_before=before.metrics,
        metrics_after=after.metrics,
        steps=[*outcome.steps, *final],
        fitted_effects=[{"effect": f.effect, "parameters": f.parameters} for f in after.view.spec.fitted],
        observations=loop.observations,
        samples_per_revolution=loop.samples_per_revolution,
        source=loop.recording.source,
        axes=list(loop.axes),
        alpha=loop.alpha,
        evaluation_before=before,
        evaluation_after=after,
    )
