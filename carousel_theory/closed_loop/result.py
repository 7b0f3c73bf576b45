"""The loop's typed results: one :class:`Trial` per candidate tried, one :class:`Step` per iteration,
and the :class:`LoopResult`, whose :meth:`LoopResult.as_dict` is the JSON of ``carousel-theory loop``."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from carousel_theory.closed_loop.detection import Detection, json_value
from carousel_theory.closed_loop.evaluation import Evaluation

__all__ = ["LoopResult", "Step", "Trial"]


@dataclass(frozen=True)
class Trial:
    """One candidate effect added to the model, what the error and its own evidence did, and the verdict;
    ``companion`` is the effect added with it when the two mask each other (tested jointly)."""

    detection: Detection
    error_before: float
    error_after: float
    verification: Detection
    accepted: bool
    decision: str
    parameters: dict[str, Any]
    companion: Detection | None = None

    def as_dict(self) -> dict[str, Any]:
        return {
            "effect": self.detection.effect,
            "statistic": self.detection.statistic,
            "statistic_name": self.detection.statistic_name,
            "threshold": self.detection.threshold,
            "log10_p": self.detection.log10_p,
            "error_before": self.error_before,
            "error_after": self.error_after,
            "verification_statistic": self.verification.statistic,
            "verification_log10_p": self.verification.log10_p,
            "decision": self.decision,
            "parameters": self.parameters,
            "added_with": None if self.companion is None else self.companion.effect,
        }


@dataclass(frozen=True)
class Step:
    """One iteration (or the final misfit test): the error, every detection, the trials, the decision,
    the rate α each detector ran at, and the effect added (if any)."""

    iteration: int
    error: float
    decision: str
    detector_alpha: float
    detections: tuple[Detection, ...] = ()
    trials: tuple[Trial, ...] = ()
    added: Detection | None = None

    def as_dict(self) -> dict[str, Any]:
        result: dict[str, Any] = {
            "iteration": self.iteration,
            "error": self.error,
            "detector_alpha": self.detector_alpha,
            "detections": [d.as_dict() for d in self.detections],
            "tried": [t.as_dict() for t in self.trials],
            "decision": self.decision,
        }
        if self.added is not None:
            result["effect"] = self.added.effect
            result["statistic"] = self.added.statistic
        return result


@dataclass
class LoopResult:
    """What the loop found; :meth:`as_dict` is the JSON of ``carousel-theory loop --json``."""

    effects: list[str]
    metric: str
    error_before: float
    error_after: float
    model_before: dict[str, Any]
    model_after: dict[str, Any]
    metrics_before: dict[str, Any]
    metrics_after: dict[str, Any]
    steps: list[Step]
    fitted_effects: list[dict[str, Any]]
    observations: list[str]
    samples_per_revolution: int
    source: str
    axes: list[str]
    alpha: float
    evaluation_before: Evaluation | None = field(default=None, repr=False)
    evaluation_after: Evaluation | None = field(default=None, repr=False)

    def as_dict(self) -> dict[str, Any]:
        return json_value(
            {
                "source": self.source,
                "axes": self.axes,
                "samples_per_revolution": self.samples_per_revolution,
                "alpha": self.alpha,
                "effects": self.effects,
                "metric": self.metric,
                "error_before": self.error_before,
                "error_after": self.error_after,
                "model_before": self.model_before,
                "model_after": self.model_after,
                "metrics_before": self.metrics_before,
                "metrics_after": self.metrics_after,
                "fitted_effects": self.fitted_effects,
                "steps": [step.as_dict() for step in self.steps],
                "observations": self.observations,
            }
        )
