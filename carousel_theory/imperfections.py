"""Imperfections of a real rotation scheme and the error each adds to the Earth-rate estimate.

TIM 2014 §VI assumes "negligible scale factor errors, uniform sensor sampling and carouseling rate, and
precise knowledge of the instantaneous carouseling angle" and leaves the sensitivity to their
violation as future work. Here the rotation is about the vertical (the schemes of
:mod:`carousel_theory.rotation_schemes` other than two-axis), with nominal angle φ⁰_t and:

- true angle φ_t = φ⁰_t + w_t, where w is a periodic rate wobble — the table rate is
  φ̇ = ω⁰ (1 + a cos(h φ⁰ + ϕ₀)), so w = (a/h)(sin(h φ⁰ + ϕ₀) − sin ϕ₀) — plus, optionally, a random
  angle walk w_t = Σ_{s≤t} ν_s (rate noise, ν ~ N(0, σ_ν²));
- gyro g measures ``(1 + k_g) cos ε_g [R(φ_t)ᵀ E]_g + sin ε_g (φ̇_t + Ω sin L) + b_g + noise``: scale
  factor error k_g and a tilt ε_g of its sensing axis toward the rotation axis, which couples the table
  rate itself into the output (a constant rate acts as a bias and cancels; a varying one does not);
- the demodulation angle is the encoder's φ̂_t = φ_t + β + quantisation error + e_t (bias β, step q,
  white noise e_t ~ N(0, σ_e²)), or the nominal φ⁰_t when the angle is not measured. Sampling-time
  jitter τ_t ~ N(0, σ_τ²) of an unmeasured angle is an angle error φ̇⁰_t τ_t.

The estimate is Ω̂ = (1/n) Σ_used R(φ̂_t) ω_t. Its systematic error δ is computed exactly (one pass,
all deterministic imperfections together); the random angle errors add a covariance computed exactly
from Gaussian moments (E[cos e] = e^{−σ²/2}, Var sin e = (1 − e^{−2σ²})/2, E[sin w_s sin w_t] =
e^{−(V_s+V_t)/2} sinh Cov(w_s, w_t)), each at the nominal pattern (their interactions with the other
imperfections are of higher order and not included; a random angle walk that the encoder measures
is harmless to first order and is not propagated). Leading-order heading errors are SymPy
expressions below (:data:`LEADING_ORDER`), with their derivatives from :func:`sensitivity`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

import numpy as np
import sympy as sp

from carousel_theory import closed_forms as cf
from carousel_theory._validation import check_positive_integer, check_positive_real, check_real
from carousel_theory.heading import EARTH_RATE, check_latitude
from carousel_theory.rotation_schemes import SchemePattern
from carousel_theory.symbols import n, sigma_e

__all__ = [
    "LEADING_ORDER",
    "ImperfectionEffect",
    "Imperfections",
    "imperfection_effect",
    "sensitivity",
]

# --- leading-order heading errors (SymPy, radians) ---------------------------------------------------

_Omega, _L, _B = sp.Symbol("Omega", positive=True), sp.Symbol("L", real=True), sp.Symbol("B", real=True)

#: Leading-order heading errors: name → (expression, kind: "variance" (rad²) or "bias" (rad), meaning).
#: Ω is the Earth rate (substitute :data:`carousel_theory.heading.EARTH_RATE`), L the latitude (rad).
#: The registry's forms (:mod:`carousel_theory.closed_forms`) are used where they exist.
LEADING_ORDER: dict[str, tuple[sp.Expr, str, str]] = {
    "angle_bias": (
        cf.HEADING_ANGLE_BIAS,
        "bias",
        "encoder offset β: Ω̂ = R(β)E exactly, the heading moves by −β",
    ),
    "angle_noise": (
        cf.HEADING_ENCODER_NOISE_VARIANCE,
        "variance",
        "encoder white noise σ_e over n used samples: Var(sin e)/n, exact cross-track variance / |E|²",
    ),
    "angle_noise_bias_coupling": (
        _B**2 * (1 - sp.exp(-(sigma_e**2))) / (n * (_Omega * sp.cos(_L)) ** 2),
        "variance",
        "encoder noise also modulates each gyro's bias (random, standard deviation B): "
        "B²(1 − e^{−σ_e²})/(n|E|²), |E| = Ω cos L",
    ),
    "rate_noise": (
        cf.HEADING_ANGLE_WALK_VARIANCE,
        "variance",
        "unmeasured angle random walk (σ_ν per sample): the heading error is the mean of the walk, "
        "the RRW average variance of TIM 2014 eq. (15)",
    ),
    "misalignment_wobble": (
        cf.RATE_ERROR_MISALIGNMENT_WOBBLE / (_Omega * sp.cos(_L)),
        "bias",
        "tilt ε of one gyro toward the rotation axis and a once-per-turn rate wobble of relative size a at "
        "rate ω_r, demodulated at the nominal angle: |δ| = sin ε · a ω_r / 2, the largest heading error over "
        "the wobble's phase (with the measured angle, Σ φ̇ cos φ̂ Δt ≈ ∮ cos φ dφ = 0: the coupling cancels)",
    ),
    "scale_mismatch": (
        cf.HEADING_SCALE_MISMATCH,
        "bias",
        "unequal scale factors k_x, k_y under static averaging or 2-position indexing (each component from "
        "one gyro); zero for carouseling and 4-position indexing, where each component averages both",
    ),
}


def sensitivity(name: str, parameter: str) -> sp.Expr:
    """d(leading-order heading error)/d(parameter) for an entry of :data:`LEADING_ORDER` (SymPy)."""
    if name not in LEADING_ORDER:
        raise ValueError(f"name={name!r}: must be one of {sorted(LEADING_ORDER)}")
    expression = LEADING_ORDER[name][0]
    symbol = {s.name: s for s in expression.free_symbols}.get(parameter)
    if symbol is None:
        names = sorted(s.name for s in expression.free_symbols)
        raise ValueError(f"parameter={parameter!r}: must be one of {names} for {name!r}")
    return sp.diff(expression, symbol)


# --- the imperfections of one set-up -----------------------------------------------------------------


@dataclass(frozen=True)
class Imperfections:
    """Sizes of the imperfections (all zero: the ideal scheme). Angles in rad, times in s."""

    angle_bias: float = 0.0
    angle_noise: float = 0.0
    angle_quantization: float = 0.0
    measured_angles: bool = True
    rate_wobble: float = 0.0
    wobble_harmonic: int = 1
    wobble_phase: float = 0.0
    rate_noise: float = 0.0
    timing_jitter: float = 0.0
    scale_factor_x: float = 0.0
    scale_factor_y: float = 0.0
    misalignment_x: float = 0.0
    misalignment_y: float = 0.0

    def __post_init__(self) -> None:
        for item in fields(self):
            value = getattr(self, item.name)
            if item.name == "measured_angles":
                if not isinstance(value, bool):
                    raise TypeError(f"measured_angles={value!r}: must be True or False")
            elif item.name == "wobble_harmonic":
                check_positive_integer("wobble_harmonic", value)
            elif item.name in (
                "angle_noise",
                "angle_quantization",
                "rate_wobble",
                "rate_noise",
                "timing_jitter",
            ):
                check_positive_real(item.name, value, allow_zero=True)
            else:
                check_real(item.name, value)

    def is_ideal(self) -> bool:
        return self == Imperfections(measured_angles=self.measured_angles)


@dataclass(frozen=True)
class ImperfectionEffect:
    """What the imperfections add to (Ω̂_x, Ω̂_y): a systematic error δ (rad/s) and a covariance (rad/s)²."""

    bias: np.ndarray
    covariance: np.ndarray


def _rotation(angles: np.ndarray) -> np.ndarray:
    """R(φ) stacked, shape (n, 2, 2)."""
    cosine, sine = np.cos(angles), np.sin(angles)
    return np.stack([np.stack([cosine, -sine], -1), np.stack([sine, cosine], -1)], -2)


def _nominal(pattern: SchemePattern, sample_rate: float) -> tuple[np.ndarray, np.ndarray]:
    """Unwrapped nominal angle φ⁰_t and nominal rate φ̇⁰_t (rad/s, backward difference, φ⁰_0 = 0)."""
    if pattern.components != 2 or np.any(pattern.rotations[:, 2, 2] != 1.0):
        raise ValueError(
            "pattern: imperfections are modelled for rotations about the vertical only (not two-axis)"
        )
    angles = np.unwrap(np.arctan2(pattern.rotations[:, 1, 0], pattern.rotations[:, 0, 0]))
    rate = np.diff(angles, prepend=0.0) * sample_rate
    return angles, rate


def _systematic_error(
    pattern: SchemePattern, imperfections: Imperfections, earth_rate: np.ndarray, sample_rate: float
) -> np.ndarray:
    """δ = (1/n) Σ_used R(φ̂_t) ω_t − E for the deterministic imperfections, exactly."""
    nominal, nominal_rate = _nominal(pattern, sample_rate)
    a, h, phase = imperfections.rate_wobble, imperfections.wobble_harmonic, imperfections.wobble_phase
    true_angle = nominal + (a / h) * (np.sin(h * nominal + phase) - math.sin(phase))
    true_rate = nominal_rate * (1 + a * np.cos(h * nominal + phase))
    demodulation = (true_angle if imperfections.measured_angles else nominal) + imperfections.angle_bias
    step = imperfections.angle_quantization
    if step > 0 and imperfections.measured_angles:
        demodulation = step * np.round(demodulation / step)
    tilt = np.array([imperfections.misalignment_x, imperfections.misalignment_y])
    gain = (1 + np.array([imperfections.scale_factor_x, imperfections.scale_factor_y])) * np.cos(tilt)
    body = np.einsum("tji,j->ti", _rotation(true_angle), earth_rate[:2]) * gain
    body += np.sin(tilt) * (true_rate + earth_rate[2])[:, np.newaxis]
    used = pattern.used
    estimate = np.einsum("tij,tj->i", _rotation(demodulation[used]), body[used]) / used.sum()
    return estimate - earth_rate[:2]


def _angle_noise_covariance(
    pattern: SchemePattern, variances: np.ndarray, earth_rate: np.ndarray, bias_sigma: float
) -> np.ndarray:
    """Covariance of (1/n) Σ R(e_t) [E + R(φ_t) b] for independent e_t ~ N(0, variances_t), b ~ N(0, B² I)."""
    used = pattern.used
    v = variances[used]
    count = used.sum()
    variance_cos = (1 + np.exp(-2 * v)) / 2 - np.exp(-v)
    variance_sin = (1 - np.exp(-2 * v)) / 2
    along = np.outer(earth_rate[:2], earth_rate[:2])
    across_vector = np.array([earth_rate[1], -earth_rate[0]])
    across = np.outer(across_vector, across_vector)
    coupling = bias_sigma**2 * (variance_cos + variance_sin).sum() * np.eye(2)
    return (variance_cos.sum() * along + variance_sin.sum() * across + coupling) / count**2


def _rate_noise_covariance(pattern: SchemePattern, sigma: float, earth_rate: np.ndarray) -> np.ndarray:
    """Covariance of (1/n) Σ_used R(−w_t) E for the angle walk w_t = Σ_{s≤t} ν_s (unmeasured), exact."""
    used = pattern.used.astype(np.float64)
    t = np.arange(1, used.shape[0] + 1, dtype=np.float64)
    weight = used * np.exp(-(sigma**2) * t / 2)  # E-factor e^{−V_t/2}, V_t = σ² t
    suffix = np.cumsum(weight[::-1])[::-1]  # Σ_{s≥t}
    pairs = 2 * weight * suffix - weight**2  # Σ_{s,t: min(s,t) = m} weight_s weight_t, by m
    covariance = sigma**2 * t
    sum_sin = float(np.dot(pairs, np.sinh(covariance)))  # Σ_{s,t} E[sin w_s sin w_t]
    sum_cos = float(np.dot(pairs, np.cosh(covariance)))
    mean_cos = float(weight.sum())
    count = used.sum()
    variance_cos = (sum_cos - mean_cos**2) / count**2
    variance_sin = sum_sin / count**2
    along = np.outer(earth_rate[:2], earth_rate[:2])
    across_vector = np.array([earth_rate[1], -earth_rate[0]])
    return variance_cos * along + variance_sin * np.outer(across_vector, across_vector)


def imperfection_effect(
    pattern: SchemePattern,
    imperfections: Imperfections,
    latitude_deg: float,
    heading_deg: float = 0.0,
    sample_rate: float = 1.0,
    bias_sigma: float = 0.0,
) -> ImperfectionEffect:
    """The systematic error and the added covariance of (Ω̂_x, Ω̂_y) under ``imperfections``.

    The systematic error holds the deterministic imperfections exactly and the shortening E[cos e] of
    the random angle errors (whose product with the deterministic ones is neglected).

    ``bias_sigma`` (rad/s) is the standard deviation of each gyro's random turn-on bias, which the
    encoder noise modulates.
    """
    if not isinstance(imperfections, Imperfections):
        raise TypeError(f"imperfections={imperfections!r}: must be an Imperfections")
    latitude = math.radians(check_latitude(latitude_deg))
    heading = math.radians(float(check_real("heading", heading_deg)))
    sample_rate = float(check_positive_real("sample_rate", sample_rate))
    bias_sigma = float(check_positive_real("bias_sigma", bias_sigma, allow_zero=True))
    horizontal = EARTH_RATE * math.cos(latitude)
    earth_rate = np.array(
        [horizontal * math.cos(heading), -horizontal * math.sin(heading), EARTH_RATE * math.sin(latitude)]
    )
    bias = _systematic_error(pattern, imperfections, earth_rate, sample_rate)
    covariance = np.zeros((2, 2))
    _, nominal_rate = _nominal(pattern, sample_rate)
    variances = np.zeros(pattern.used.shape[0])
    if imperfections.measured_angles:
        variances += imperfections.angle_noise**2
    else:
        variances += (nominal_rate * imperfections.timing_jitter) ** 2
    walk: np.ndarray = np.zeros_like(variances)
    if imperfections.rate_noise > 0 and not imperfections.measured_angles:
        covariance += _rate_noise_covariance(pattern, imperfections.rate_noise, earth_rate)
        walk = imperfections.rate_noise**2 * np.arange(1, walk.shape[0] + 1)
    if np.any(variances > 0):
        covariance += _angle_noise_covariance(pattern, variances, earth_rate, bias_sigma)
    # a random angle error e shortens the mean by E[cos e] = e^{−Var e/2} (along E: no heading error)
    shrink = float(np.mean(np.exp(-(variances + walk)[pattern.used] / 2)))
    return ImperfectionEffect(bias=bias + (shrink - 1) * earth_rate[:2], covariance=covariance)
