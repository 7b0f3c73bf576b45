"""Cost estimates for exact, high-precision and long evaluations, and the budget that refuses them.

Some evaluations grow without bound in their arguments: the 1/f bin variances of TIM 2014 §III-D
take k·N recursion steps at the working precision (or an FFT of length k·N in float64, or k·N exact
rational terms whose sizes grow with the index), a closed form at D digits costs about D^2.5 in
pure-Python mpmath, and a Monte Carlo figure costs a fixed time per realisation. Before such work
starts, its cost is estimated and compared with a stated budget (:data:`DEFAULT_BUDGET_SECONDS` of
estimated time, :data:`DEFAULT_BUDGET_BYTES` of memory); beyond it the evaluation is refused with a
one-line message naming the value, the rule and the estimate, unless the caller passes
``force=True`` (``--force`` on the command line).

The time constants were measured on a 2-core machine with mpmath's pure-Python backend (no gmpy2);
an estimate is right within a small factor, which is all a refusal needs: the refused cases are
orders of magnitude over the budget.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = [
    "DEFAULT_BUDGET_BYTES",
    "DEFAULT_BUDGET_SECONDS",
    "EvaluationBudgetError",
    "EvaluationCost",
    "check_budget",
    "closed_form_cost",
    "exact_flicker_cost",
    "float_flicker_cost",
    "growing_kalman_cost",
    "high_precision_flicker_cost",
    "monte_carlo_cost",
]

#: Estimated seconds an evaluation may take before it is refused (unless forced).
DEFAULT_BUDGET_SECONDS = 60.0
#: Estimated memory an evaluation may allocate before it is refused (unless forced): 4 GiB.
DEFAULT_BUDGET_BYTES = 4 * 1024**3

# Measured constants (seconds): one step of the high-precision 1/f recursion costs about
# _STEP_BASE + _STEP_PER_DIGIT · D^1.6 at D working digits; a closed form at D digits about
# _CLOSED_FORM · D^2.5 (SymPy evalf of csc(π/N) at 9000 digits: 0.12 s, at 20000: 1.1 s); the
# float64 FFT path about _FFT_PER_SAMPLE per sample of length k·N, with _FFT_BYTES_PER_SAMPLE of
# memory; the exact rational sum about _EXACT · (kN)^2.5 for d = 1/2 (kN = 3000: 1.1 s, 6000: 6.4 s).
_STEP_BASE = 3.0e-5
_STEP_PER_DIGIT = 2.0e-9
_STEP_BYTES_PER_DIGIT = 0.5
_STEP_BYTES_BASE = 120.0
_CLOSED_FORM = 2.0e-11
_CLOSED_FORM_BASE = 5.0e-3
_FFT_PER_SAMPLE = 4.5e-7
_FFT_BYTES_PER_SAMPLE = 64.0
_EXACT = 2.3e-9
_EXACT_EXPONENT = 2.5
# The growing-state Kalman filter over T = n + h states: about _KALMAN · T³ seconds (T = 1000: 0.40 s,
# 2000: 3.5 s) and a T × T covariance of float64.
_KALMAN = 4.4e-10


@dataclass(frozen=True)
class EvaluationCost:
    """An estimate of one evaluation's cost: what is evaluated, the rule that makes it grow, the
    amount of work, and the estimated time (seconds) and memory (bytes)."""

    what: str
    rule: str
    work: str
    seconds: float
    bytes: float = 0.0

    def describe(self) -> str:
        """``what: work (rule), estimated … s and … of memory``, on one line."""
        memory = f" and {_format_bytes(self.bytes)} of memory" if self.bytes else ""
        return f"{self.what}: {self.work} ({self.rule}), estimated {_format_seconds(self.seconds)}{memory}"


class EvaluationBudgetError(ValueError):
    """An evaluation whose estimated cost exceeds the budget; pass ``force=True`` to run it anyway."""


def _format_seconds(seconds: float) -> str:
    if seconds < 120:
        return f"{seconds:.2g} s"
    if seconds < 2 * 3600:
        return f"{seconds / 60:.3g} min"
    if seconds < 2 * 86400:
        return f"{seconds / 3600:.3g} h"
    return f"{seconds / 86400:.3g} days"


def _format_bytes(size: float) -> str:
    for unit, scale in (("TB", 1e12), ("GB", 1e9), ("MB", 1e6)):
        if size >= scale:
            return f"{size / scale:.3g} {unit}"
    return f"{size / 1e3:.3g} kB"


def _format_count(count: float) -> str:
    """An exact integer below 10⁶, else a rounded power of ten (1.0e+12)."""
    return f"{int(count)}" if count < 10**6 else f"{count:.2g}"


def check_budget(
    cost: EvaluationCost,
    *,
    force: bool = False,
    budget_seconds: float | None = None,
    budget_bytes: float | None = None,
) -> None:
    """Raise :class:`EvaluationBudgetError` when ``cost`` exceeds the budget and ``force`` is False.

    The budget defaults to :data:`DEFAULT_BUDGET_SECONDS` and :data:`DEFAULT_BUDGET_BYTES`.
    """
    if not isinstance(force, bool):
        raise TypeError(f"force={force!r}: must be True or False")
    budget_seconds = DEFAULT_BUDGET_SECONDS if budget_seconds is None else budget_seconds
    budget_bytes = DEFAULT_BUDGET_BYTES if budget_bytes is None else budget_bytes
    if force or (cost.seconds <= budget_seconds and cost.bytes <= budget_bytes):
        return
    limit = f"{_format_seconds(budget_seconds)}"
    if cost.bytes > budget_bytes:
        limit += f" / {_format_bytes(budget_bytes)}"
    raise EvaluationBudgetError(
        f"{cost.describe()}, over the budget of {limit}: refused; pass force=True (command line: --force) "
        "to run it anyway"
    )


def closed_form_cost(what: str, digits: int) -> EvaluationCost:
    """A closed form evaluated by SymPy ``evalf`` at ``digits`` significant digits: about D^2.5."""
    working = digits + 10
    return EvaluationCost(
        what,
        "a closed form at D digits costs about D^2.5",
        f"D = {working} working digits",
        _CLOSED_FORM_BASE + _CLOSED_FORM * working**2.5,
    )


def high_precision_flicker_cost(what: str, steps: int, digits: int) -> EvaluationCost:
    """The 1/f recursion of :mod:`carousel_theory.propagation`: k·N steps at ``digits`` + guard digits."""
    working = digits + 12 + len(str(steps))
    per_step = _STEP_BASE + _STEP_PER_DIGIT * working**1.6
    return EvaluationCost(
        what,
        "the 1/f bin variance takes k·N recursion steps at the working precision",
        f"k·N = {_format_count(steps)} steps at {working} digits",
        steps * per_step,
        steps * (_STEP_BYTES_BASE + _STEP_BYTES_PER_DIGIT * working),
    )


def float_flicker_cost(what: str, length: int) -> EvaluationCost:
    """The float64 1/f bin variances: FFT convolutions of total length Σ k_max·N."""
    return EvaluationCost(
        what,
        "the float64 1/f bin variances take an FFT of length k·N",
        f"k·N = {_format_count(length)} samples",
        _FFT_PER_SAMPLE * length,
        _FFT_BYTES_PER_SAMPLE * length,
    )


def exact_flicker_cost(what: str, steps: int, order_denominator: int) -> EvaluationCost:
    """The exact rational 1/f bin variance: k·N terms whose sizes grow with the index, about (kN)^2.5.

    The coefficients ψ_j of a rational order p/q have denominators near q^j j!, so a larger q makes
    every term longer; the estimate scales with (log2 q + log2 kN)/(1 + log2 kN), 1 for d = 1/2.
    """
    steps = max(int(steps), 1)
    size = math.log2(steps + 1)
    scale = (math.log2(max(order_denominator, 2)) + size) / (1 + size)
    return EvaluationCost(
        what,
        "the exact 1/f bin variance takes k·N rational terms of growing size, about (kN)^2.5 work",
        f"k·N = {_format_count(steps)} exact terms",
        _EXACT * scale * steps**_EXACT_EXPONENT,
    )


def monte_carlo_cost(what: str, realisations: int, seconds_per_realisation: float) -> EvaluationCost:
    """A Monte Carlo of ``realisations`` independent draws at a measured time per draw."""
    return EvaluationCost(
        what,
        f"each realisation takes about {seconds_per_realisation * 1e3:.2g} ms",
        f"{_format_count(realisations)} realisations",
        realisations * seconds_per_realisation,
    )


def growing_kalman_cost(what: str, states: int) -> EvaluationCost:
    """The growing-state Kalman filter of SJ 2012 §IV-A over ``states`` = n + h samples: O(T³) time and a
    T × T covariance."""
    return EvaluationCost(
        what,
        "O((n + h)³) time, O((n + h)²) memory",
        f"n + h = {_format_count(states)} states",
        _KALMAN * float(states) ** 3,
        8.0 * (float(states) + 1.0) ** 2,
    )
