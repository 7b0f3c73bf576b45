"""What a fitted noise model's numbers mean, in words: model rejection, terms at a bound, the ARW read-off.

A :class:`carousel_theory.fitting.FitResult` carries the evidence; this module turns it into notices a
user reads beside the numbers (``fit`` prints them on stdout and writes them into ``--json`` and
``--markdown``):

``model_rejected``
    The GLS objective χ² of the fit exceeds its upper :data:`REJECTION_LEVEL` quantile on the fit's
    degrees of freedom. The standard errors assume the model, so they are too small; √(χ²/ν) is the
    usual scale factor (Birge ratio). What to try: a short-τ cut-off above the sensor's internal filter,
    a 1/f or autoregressive (Gauss–Markov) term, or the closed loop, which looks for the missing effect.
``term_at_bound``
    A driving variance held at zero by the non-negativity constraint: its standard error is undefined
    (the printed value is 0 with no error), and the notice names the likely cause and the remedy.
``weakly_determined``
    A fitted variance whose standard error exceeds :data:`WEAK_TERM_LEVEL` of it. Its error is a plug-in
    one (the covariance across τ at the estimate), which shrinks with the estimate, so the notice gives
    the interval by test inversion (:func:`carousel_theory.fitting.inverted_interval`; on seeded white +
    RRW records of 10⁶ samples it held the walk on 56 of 60, ±1.96 errors on 45 of 58:
    docs/fit_calibration.md).
``ar_correlation_long``
    The AR(1) (Gauss–Markov) coefficient was estimated from the record less its centred moving average of
    W samples (:func:`carousel_theory.autoregression.high_pass_window`), and its correlation time
    τ_c = −1/(f_s ln φ) exceeds W/:data:`AR_CORRELATION_FRACTION`: there the estimate is biased low
    (:mod:`carousel_theory.autoregression`, 12 records of 10⁶ samples at 100 Hz: at φ = 0.95, τ_c = W/51,
    the mean is within one standard deviation of φ; at φ = 0.99, τ_c = W/10, it is 0.977 with a spread of
    0.013), and the fit could not refine it by its χ² on the Allan variance (which it does there, and which
    removes the bias: :func:`carousel_theory.fitting.fit_observed`), so a rejected fit may be the
    coefficient's fault. The remedy is the known coefficient, given (``--ar-coefficients``).
``angle_random_walk_read_off``
    The textbook read-off of the angle random walk, σ_A(τ)·√τ at the octave τ nearest 1 s (IEEE Std
    952-1997 Annex C: the −1/2 line at τ = 1 s), differs from the fitted white noise by more than
    :data:`READ_OFF_TOLERANCE` and by more than the Allan variance's own interval at that τ: the
    read-off also counts every other term at that τ, and an internal filter bends the short-τ end of the
    curve below the −1/2 line.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from carousel_theory.autoregression import LONG_CORRELATION_FRACTION, correlation_is_long, high_pass_window
from carousel_theory.fitting import ALLAN_PROFILE, COMPONENT_OF_PARAMETER, FitResult
from carousel_theory.units import to_deg_per_sqrt_hour

__all__ = [
    "AR_CORRELATION_FRACTION",
    "READ_OFF_TOLERANCE",
    "REJECTION_LEVEL",
    "WEAK_TERM_LEVEL",
    "FitNotice",
    "angle_random_walk_read_off",
    "ar_correlation_notice",
    "bound_notices",
    "fit_notices",
    "read_off_notice",
    "rejection_notice",
    "weak_term_notices",
]

#: A fit whose χ² p-value is below this is reported as rejected.
REJECTION_LEVEL = 0.01
#: Relative difference between the fitted and the read-off angle random walk that is reported.
READ_OFF_TOLERANCE = 0.05
#: A fitted variance whose standard error exceeds this fraction of it is reported as weakly determined.
WEAK_TERM_LEVEL = 0.3
#: An estimated Gauss–Markov correlation time above W/this (W the AR estimator's high-pass window) is
#: reported when the fit could not refine it
#: (:data:`carousel_theory.autoregression.LONG_CORRELATION_FRACTION`).
AR_CORRELATION_FRACTION = LONG_CORRELATION_FRACTION


@dataclass(frozen=True)
class FitNotice:
    """One sentence-level finding about a fit: ``kind`` (see the module text) and the ``message``."""

    kind: str
    message: str


def rejection_notice(fit: FitResult) -> FitNotice | None:
    """The ``model_rejected`` notice when the fit's p-value is below :data:`REJECTION_LEVEL`, else None."""
    if fit.degrees_of_freedom <= 0 or not fit.p_value < REJECTION_LEVEL:
        return None
    components = fit.components
    tries = []
    if float(fit.allan.tau[fit.used][0]) < 1.0:
        tries.append("a short-τ cut-off above the sensor's internal filter (--tau-min 1)")
    if "flicker" not in components:
        tries.append("a 1/f term (add 'flicker' to --model)")
    if "ar" not in components:
        tries.append("a Gauss–Markov (autoregressive) term (add 'ar')")
    tries.append("`carousel-theory loop`, which looks for the missing effect")
    scale = math.sqrt(fit.chi_square / fit.degrees_of_freedom)
    message = (
        f"the model is rejected by its own χ² test (χ² = {fit.chi_square:.3g} on {fit.degrees_of_freedom} "
        f"degrees of freedom, p = {fit.p_value:.2g}): it does not explain the Allan variance within the "
        "estimates' uncertainty, so every standard error above assumes a model that does not hold and is "
        f"too small; multiply them by at least √(χ²/dof) = {scale:.3g}. Try " + "; ".join(tries) + "."
    )
    return FitNotice("model_rejected", message)


def _bound_cause(fit: FitResult, term: str) -> str:
    """Likely cause and remedy of ``term`` held at zero."""
    tau_used = fit.allan.tau[fit.used]
    if term == "white":
        taker = (
            f"the 1/f term (order d = {fit.model.flicker_d:.2f}, near white noise at small d)"
            if fit.model.flicker_variance > 0
            else "the other terms"
        )
        return (
            "the short-τ end of the Allan deviation does not follow the white-noise slope −1/2 (an internal "
            f"filter correlates neighbouring samples), and {taker} takes its place. Fit above the filter "
            "with --tau-min (e.g. 1 s), or model the correlation with 'ar' instead of 'white'"
        )
    if term == "rrw":
        return (
            f"no +1/2 slope is resolved up to the longest fitted τ ({tau_used[-1]:.4g} s); read the 0 as "
            "'below detection'. Drop 'rrw' from --model or use a longer recording"
        )
    if term == "flicker":
        return "no flat part beyond the other terms is resolved. Drop 'flicker' from --model"
    if term == "quantization":
        return (
            f"no −1 slope is resolved at the shortest fitted τ ({tau_used[0]:.4g} s). Drop 'quantization' "
            "or lower --tau-min"
        )
    return "the short-τ correlation is not resolved in the fitted τ range. Drop 'ar' from --model"


def bound_notices(fit: FitResult) -> list[FitNotice]:
    """A ``term_at_bound`` notice for each driving variance held at zero."""
    notices = []
    for parameter in fit.at_bound:
        term = COMPONENT_OF_PARAMETER.get(parameter, parameter)
        notices.append(
            FitNotice(
                "term_at_bound",
                f"{parameter} is held at zero, the bound of its range: its value 0 has no standard error "
                "and the other terms' errors assume it absent. Likely cause: "
                + _bound_cause(fit, term)
                + ".",
            )
        )
    return notices


def weak_term_notices(fit: FitResult) -> list[FitNotice]:
    """A ``weakly_determined`` notice for each fitted variance (not held at zero) whose standard error
    exceeds :data:`WEAK_TERM_LEVEL` of it, with its 95 % interval by test inversion."""
    notices = []
    for parameter in fit.parameters:
        if parameter not in COMPONENT_OF_PARAMETER or parameter in fit.at_bound:
            continue
        value, error = fit.value(parameter), fit.standard_errors[parameter]
        if not error > WEAK_TERM_LEVEL * value:
            continue
        low, high = fit.interval(parameter, method="inverted")
        unit = "rad²" if parameter == "quantization_squared" else "(rad/s)²"
        notices.append(
            FitNotice(
                "weakly_determined",
                f"{parameter} is weakly determined (standard error {error / value:.0%} of {value:.3g} "
                f"{unit}); its 95 % interval by test inversion is {low:.3g} … {high:.3g} {unit}. The "
                "± error is taken at the estimate and understates the spread when the estimate is low.",
            )
        )
    return notices


def angle_random_walk_read_off(fit: FitResult) -> tuple[float, float, float, float]:
    """(τ, σ_A(τ)·√τ, its interval low, high) in °/√h at the octave τ of the data nearest 1 s (IEEE Std 952
    Annex C read-off); the interval is the Allan variance's own at that τ."""
    tau = np.asarray(fit.allan.tau)
    nearest = int(np.argmin(np.abs(np.log(tau))))
    at = float(tau[nearest])
    low, value, high = (
        to_deg_per_sqrt_hour(math.sqrt(float(array[nearest]) * at))
        for array in (fit.allan.ci_low, fit.allan.avar, fit.allan.ci_high)
    )
    return at, value, low, high


def read_off_notice(fit: FitResult) -> FitNotice | None:
    """The ``angle_random_walk_read_off`` notice when the fitted ARW lies outside the read-off's interval
    and differs from it by more than :data:`READ_OFF_TOLERANCE` (relative); None without a fitted
    white-noise term."""
    if "white_variance" not in fit.parameters or fit.model.white_variance <= 0:
        return None
    fitted = fit.model.angle_random_walk_deg_per_sqrt_hour()
    tau, read, low, high = angle_random_walk_read_off(fit)
    if low <= fitted <= high or abs(read - fitted) <= READ_OFF_TOLERANCE * fitted:
        return None
    first = float(fit.allan.tau[fit.used][0])
    advice = (
        f"fitting from τ = {first:.3g} s lets the bent short-τ end pull the white-noise level; fit above the "
        "filter (--tau-min 1) to read it where the slope is −1/2"
        if first < 1.0
        else f"the fit separates the white noise from the other terms over τ ≥ {first:.3g} s"
    )
    return FitNotice(
        "angle_random_walk_read_off",
        f"the angle random walk of the fit, {fitted:.3g} °/√h, differs from the textbook read-off "
        f"σ_A(τ)·√τ at τ = {tau:.3g} s, {read:.3g} °/√h: the read-off counts every term at that τ and "
        "assumes the white-noise slope −1/2 holds there, while a sensor's internal filter bends the "
        f"short-τ end of the curve; {advice}.",
    )


def ar_correlation_notice(fit: FitResult) -> FitNotice | None:
    """The ``ar_correlation_long`` notice for an AR(1) coefficient estimated from the record whose
    correlation time exceeds W/:data:`AR_CORRELATION_FRACTION` and which the fit did not refine by its χ²
    (:data:`carousel_theory.fitting.ALLAN_PROFILE`), else None."""
    coefficients = tuple(fit.model.ar_coefficients)
    rate = float(fit.model.sample_rate)
    estimated = fit.ar_estimator not in ("", "given", ALLAN_PROFILE)
    if not estimated or not correlation_is_long(coefficients, rate):
        return None
    window = high_pass_window(rate)
    samples = -1.0 / math.log(coefficients[0])
    message = (
        f"the Gauss–Markov coefficient φ = {coefficients[0]:.4g} (τ_c = {samples / rate:.3g} s) was "
        f"estimated from the record less its {window / rate:.3g}-s moving average; with τ_c above "
        f"{window / rate / AR_CORRELATION_FRACTION:.3g} s that estimate is biased low (at τ_c = 1 s against "
        "a 10-s window, φ = 0.99 came out 0.977 on average), which can alone make the model fail its χ² "
        "test. If the correlation time is known (the sensor's filter), give the coefficient: "
        "--ar-coefficients exp(−1/(f_s τ_c))."
    )
    return FitNotice("ar_correlation_long", message)


def fit_notices(fit: FitResult) -> list[FitNotice]:
    """Every notice about ``fit``: rejection first, then terms at a bound, weakly determined terms, a long
    estimated Gauss–Markov correlation time, then the ARW read-off."""
    notices = [
        rejection_notice(fit),
        *bound_notices(fit),
        *weak_term_notices(fit),
        ar_correlation_notice(fit),
        read_off_notice(fit),
    ]
    return [notice for notice in notices if notice is not None]
