"""Claims of SJ 2012 §I (introduction): the constant bias and its angle error, calibration of
bias plus white noise by a long record, the Allan variance of 1/f noise, and the Fig. 1 reading.
"""

from __future__ import annotations

import math

import numpy as np
import sympy as sp

from carousel_theory.allan import (
    flicker_allan_variance,
)
from carousel_theory.claim import Claim, Status, Verdict
from carousel_theory.claims._common import figure_1_not_public, simplifies_to_zero
from carousel_theory.propagation import weighted_sum_variance

__all__ = ["CLAIMS"]

FLICKER_TAUS = (1, 2, 4, 8, 16, 32, 64, 128)


FLICKER_LENGTH = 2**14


def _check_flicker_allan_constant() -> Verdict:
    values = flicker_allan_variance(0.5, np.array(FLICKER_TAUS), FLICKER_LENGTH)
    plateau = 2 * math.log(2) / math.pi  # continuous 1/f with one-sided density σ_w²/(π f): 2 ln 2 h
    first = values[0]
    long = values[FLICKER_TAUS.index(16) :]
    spread = float(np.max(np.abs(long / plateau - 1)))
    if abs(first / plateau - 1) > 0.1 and spread < 0.01:
        return Verdict(
            Status.QUALIFIED,
            "Asymptotically, not exactly: the expected Allan variance of (3) at d = 1/2 (σ_w² = 1, "
            f"{FLICKER_LENGTH} samples) is "
            + ", ".join(f"{value:.4f}" for value in values)
            + f" at τ = {', '.join(map(str, FLICKER_TAUS))}; it tends to 2 ln 2/π = {plateau:.4f} (within "
            f"{100 * spread:.2f} % for τ ≥ 16), while τ = 1 is {first:.4f}, "
            f"{100 * (first / plateau - 1):.0f} % "
            "above the limit.",
            corrected="the Allan variance of 1/f noise tends to a constant (2 ln 2/π σ_w² at d = 1/2) as τ "
            "grows; it is constant only for τ long against the sampling interval",
        )
    return Verdict(Status.REFUTED, f"values {values.tolist()} do not approach {plateau:.4f}")


def _check_bias_integrates_linearly() -> Verdict:
    bias, time, s = sp.symbols("b t s", positive=True)
    angle = sp.integrate(bias, (s, 0, time))
    samples = sp.Symbol("k", integer=True, positive=True)
    discrete = sp.summation(bias, (sp.Symbol("i", integer=True, positive=True), 1, samples))
    if simplifies_to_zero(angle - bias * time) and simplifies_to_zero(discrete - bias * samples):
        return Verdict(
            Status.PROVED,
            "∫_0^t b ds = b·t (and Σ_{i≤k} b = k·b in discrete time): a constant rate bias gives an angle "
            "error growing linearly in time.",
        )
    return Verdict(Status.REFUTED, f"integral {angle}, sum {discrete}")


def _prediction_error_variance(process: str, calibration: int, lag: int) -> float:
    """Var(x_{n+lag} − mean(x_1 … x_n)) for a process of TIM 2014 §II, unit driving variance."""
    weights = np.zeros(calibration + lag)
    weights[:calibration] = -1.0 / calibration
    weights[-1] = 1.0
    return weighted_sum_variance(weights, process, 0.5 if process == "flicker" else None)


def _check_bias_white_calibration() -> Verdict:
    sizes = (10, 100, 1000)
    # Bias + white: the calibration mean misses b by the mean of the white samples, Var σ²/n → 0.
    white = [weighted_sum_variance(np.full(n, 1.0 / n), "white") for n in sizes]
    # 1/f (d = 1/2): the error of the calibration mean as a prediction n samples later does not vanish.
    flicker = [_prediction_error_variance("flicker", n, n) for n in sizes]
    exact_white = all(abs(value - 1.0 / n) < 1e-15 for value, n in zip(white, sizes, strict=True))
    if exact_white and min(flicker) > 1.0 and flicker[-1] > flicker[0]:
        return Verdict(
            Status.VERIFIED,
            "Bias + white noise (σ² = 1): the calibration mean's error variance is 1/n = "
            + ", ".join(f"{value:.3g}" for value in white)
            + f" for n = {', '.join(map(str, sizes))}, → 0. With 1/f noise (d = 1/2, σ_w² = 1) the variance "
            "of x_{2n} − mean(x_1 … x_n) is "
            + ", ".join(f"{value:.4f}" for value in flicker)
            + ": it grows with n instead of vanishing (the nonstationarity of §I–§II).",
        )
    return Verdict(Status.REFUTED, f"white {white}, flicker {flicker}")


CLAIMS: list[Claim] = [
    Claim(
        "SJ2012-sec1-flicker-allan-constant",
        "SJ2012",
        "§I (Voss [15])",
        "The Allan variance of 1/f noise is constant.",
        _check_flicker_allan_constant,
    ),
    Claim(
        "SJ2012-sec1-fig1-temperature-trend",
        "SJ2012",
        "§I, Fig. 1",
        "The Allan variance of the MEMS gyro without temperature control shows an increasing trend at long "
        "averaging times.",
        figure_1_not_public("increasing trend without temperature control"),
    ),
    Claim(
        "SJ2012-sec1-constant-bias-linear-angle-error",
        "SJ2012",
        "§I",
        "Any constant bias error in the angular rate is integrated into a linearly increasing angle error.",
        _check_bias_integrates_linearly,
    ),
    Claim(
        "SJ2012-sec1-bias-white-calibrated-by-long-record",
        "SJ2012",
        "§I, §II",
        "If the gyro error were a constant bias and white noise only, a long record with known input would "
        "calibrate the bias out; the nonstationary 1/f component causes problems with plain averaging.",
        _check_bias_white_calibration,
    ),
]
