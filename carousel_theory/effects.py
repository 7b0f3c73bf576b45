"""The catalogue of effects that a declared gyro noise model (bias + white + rate random walk) lacks.

Each entry says, with a stable name, (1) how the effect is put into a synthetic recording, and in words
(2) how the closed loop detects it in the residual of a fitted model, (3) how it enters the model and (4)
how it is fitted or removed.

======================  ==========================================================================
name                    detection statistic (null: the fitted model; Bonferroni over the scan)
======================  ==========================================================================
``warmup``              max over time constants τ_c of |z| of the GLS amplitude of e^{−t/τ_c}
``temperature``         |z| of the GLS coefficient of the temperature column
``steps``               max over t₀ of |z| of the GLS estimate of a bias step after sample t₀
``spikes``              max robust |z| of the residual about its running median (trimmed scale)
``sinusoid``            max of the Hann periodogram / (model PSD × local median level), exact tail
``colored_noise``       log(median level 5–15 % f_s / median level 35–50 % f_s), exact median tails
``flicker``             F = Δχ²/dispersion of the Allan-variance fit when a 1/f (d = 1/2) term is added
``quantization``        lattice test: every sample an integer multiple of one step (an observation)
``none``                nothing significant
======================  ==========================================================================

How each effect is detected, fitted and removed by the closed loop lives with the loop
(:mod:`carousel_theory.closed_loop.detectors`); this module is what a recording generator and a reader
need: names, descriptions, injections and their parameters.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any, ClassVar

import numpy as np

from carousel_theory._validation import check_real

__all__ = [
    "CATALOGUE",
    "Effect",
    "check_effect_parameters",
    "detect_quantization",
]


#: The reference of the bias-step scan (closed_loop/detection.py).
_BOUNDED_REFERENCE = (
    "normal reference with the statistic's variance at its upper confidence bound (Berger–Boos)"
)
#: The reference of the joint warm-up and temperature statistics (closed_loop/studentized.py).
_STUDENTIZED_REFERENCE = (
    "z studentized by the joint refit, referred to a parametric bootstrap from the refitted model that "
    "refits every replicate; the walk and 1/f variances whose confidence interval reaches 0 are searched "
    "over it and its non-coverage added (Berger–Boos)"
)


class Effect:
    """Base class of a catalogue entry; see the module table."""

    name = "none"
    kind = "none"  # "additive", "noise_filter", "output", or "none"
    stochastic = False
    summary = ""
    detection = ""
    enters_model = ""
    removal = ""
    defaults: ClassVar[dict[str, float]] = {}

    def inject(
        self,
        signal: np.ndarray,
        time: np.ndarray,
        temperature: np.ndarray | None,
        rng: np.random.Generator,
        parameters: Mapping[str, float],
    ) -> np.ndarray:
        """Return ``signal`` with the effect put in (additive effects receive zeros and return the signal)."""
        raise NotImplementedError(f"effect {self.name!r} cannot be simulated")

    def describe(self) -> dict[str, str]:
        return {
            "name": self.name,
            "summary": self.summary,
            "detection": self.detection,
            "enters_model": self.enters_model,
            "removal": self.removal,
        }


# --- deterministic effects ----------------------------------------------------------------------------


class Warmup(Effect):
    name = "warmup"
    kind = "additive"
    summary = "exponential turn-on transient of the bias, A e^{−t/τ}"
    detection = (
        "max over 8 time constants (log-spaced, T/500 … T/4) of |z| of the GLS projection of the residual "
        "on e^{−t/τ}, the noise refitted jointly with the transient and with a 1/f term when the residual "
        "without the transient asks for one; "
        + _STUDENTIZED_REFERENCE
        + "; Bonferroni over the grid and the axes"
    )
    enters_model = (
        "a deterministic term A e^{−t/τ} added to the bias of each axis "
        "(with the 1/f term it was detected with)"
    )
    removal = "τ maximising the GLS fit on a fine grid around the detected one, A by GLS; subtracted"
    defaults: ClassVar[dict[str, float]] = {"amplitude": 2e-3, "time_constant": 120.0}

    def inject(self, signal, time, temperature, rng, parameters):
        return signal + parameters["amplitude"] * np.exp(-(time - time[0]) / parameters["time_constant"])


class Temperature(Effect):
    name = "temperature"
    kind = "additive"
    summary = "bias linear in the temperature column, k (T − T̄)"
    detection = (
        "|z| of the GLS projection of the residual on the temperature column, the noise (rate random walk "
        "included) refitted jointly with the regressor; " + _STUDENTIZED_REFERENCE + "; Bonferroni over axes"
    )
    enters_model = "a term k_axis (T_t − T̄) added to the bias of each axis (k in rad/s per °C)"
    removal = "k by generalised least squares on each axis; subtracted"
    defaults: ClassVar[dict[str, float]] = {"coefficient": 1.5e-3}

    def inject(self, signal, time, temperature, rng, parameters):
        if temperature is None:
            raise ValueError("effect 'temperature': the recording has no temperature column")
        return signal + parameters["coefficient"] * (temperature - temperature[0])


class Steps(Effect):
    name = "steps"
    kind = "additive"
    summary = "abrupt bias jumps (a bias step at time t₀)"
    detection = (
        "max over t₀ of |z| of the generalised-least-squares estimate of a bias step after block t₀ of the "
        "record's b-sample block means (b = ⌈n / GLS_BLOCKS⌉, closed_loop.linear_statistics) under white "
        "noise + rate random walk (all t₀ from one tridiagonal solve), sd from the whole fitted model; "
        + _BOUNDED_REFERENCE
        + "; Bonferroni over the n/b − 1 block boundaries and the axes"
    )
    enters_model = "a term h · 1[t ≥ t₀] added to the bias, for up to 5 jumps"
    removal = "each jump at the maximum |z|, its height by generalised least squares; subtracted; repeated"
    defaults: ClassVar[dict[str, float]] = {"size": 2e-3, "time": 0.6}  # time as a fraction of the record

    def inject(self, signal, time, temperature, rng, parameters):
        at = time[0] + parameters["time"] * (time[-1] - time[0])
        return signal + parameters["size"] * (time >= at)


class Sinusoid(Effect):
    name = "sinusoid"
    kind = "additive"
    summary = "a periodic disturbance A sin(2π f t + θ) (vibration, a mains pick-up)"
    detection = (
        "max over frequencies of the Hann periodogram divided by the fitted model's spectrum and by the "
        "local median level (/ln 2): an Exp(1) ordinate over the median of its block's Exp(1) ordinates "
        "under the model (exact tail, Rényi's representation); Bonferroni over the frequencies and the axes"
    )
    enters_model = "a deterministic term A sin(2π f t + θ) per axis, one frequency shared by the axes"
    removal = "frequency refined by maximising the exact periodogram near the peak; A, θ by least squares"
    defaults: ClassVar[dict[str, float]] = {"amplitude": 1e-3, "frequency": 0.37, "phase": 0.0}

    def inject(self, signal, time, temperature, rng, parameters):
        return signal + parameters["amplitude"] * np.sin(
            2 * np.pi * parameters["frequency"] * time + parameters["phase"]
        )


class Spikes(Effect):
    name = "spikes"
    kind = "additive"
    summary = "isolated outliers (shocks, bit errors, bumps)"
    detection = (
        "max over samples of the robust |z| of the residual about its 15-sample running median, scale from "
        "the central 99 %; threshold Φ⁻¹(1 − α/(2n·axes))"
    )
    enters_model = (
        "flagged samples (and their direct neighbours) are excluded: replaced by the running median"
    )
    removal = "replacement by the running median; the count and the largest |z| are reported"
    defaults: ClassVar[dict[str, float]] = {"amplitude": 0.05, "rate": 2e-4}

    def inject(self, signal, time, temperature, rng, parameters):
        n = len(time)
        count = max(1, round(parameters["rate"] * n))
        where = rng.choice(n, size=count, replace=False)
        signs = rng.choice((-1.0, 1.0), size=count)
        result = signal.copy()
        result[where] += signs * parameters["amplitude"]
        return result


# --- stochastic effects -------------------------------------------------------------------------------


class ColoredNoise(Effect):
    name = "colored_noise"
    kind = "noise_filter"
    stochastic = True
    summary = "short-correlated noise: white noise through a low-order filter (a sensor's internal low-pass)"
    detection = (
        "z of log(median whitened periodogram in 5–15 % of f_s / median in 35–50 % of f_s), whitened by "
        "the fitted model's spectrum; every third ordinate (independent Exp(1) under the model); tail of "
        "the ratio of the two medians from its exact cumulant generating function (saddlepoint)"
    )
    enters_model = (
        "the white noise becomes an autoregressive process of order p ≤ 4 (Yule–Walker), its long-run "
        "variance playing the white-noise level for bins and for the Allan variance at long τ"
    )
    removal = "the noise model is refitted on the prewhitened residual (innovations scaled by 1/(1 − Σa))"
    defaults: ClassVar[dict[str, float]] = {"coefficient": 0.5}

    def inject(self, signal, time, temperature, rng, parameters):
        from scipy.signal import lfilter

        a = float(parameters["coefficient"])
        if not -1 < a < 1:
            raise ValueError(f"colored_noise: coefficient={a!r}: must lie in (-1, 1)")
        return lfilter([1.0], [1.0, -a], signal)


class Flicker(Effect):
    name = "flicker"
    kind = "additive"
    stochastic = True
    summary = "1/f noise (bias instability), fractional integration of order d = 1/2 (TIM 2014 eq. (3))"
    detection = (
        "Δχ² / max(1, χ²/ν) of the GLS Allan-variance fits (octave τ, the model's covariance across τ) "
        "without and with a 1/f term; sequential parametric bootstrap of the Allan variance from the "
        "fitted model without it; Bonferroni over axes"
    )
    enters_model = "a 1/f component σ_f² (d = 1/2) in the noise model of each axis, fitted with the others"
    removal = "refit of the noise model with the 1/f term; nothing is subtracted"
    defaults: ClassVar[dict[str, float]] = {"variance": 1e-8, "d": 0.5}

    def inject(self, signal, time, temperature, rng, parameters):
        from carousel_theory.processes import sample_flicker

        return signal + sample_flicker(len(time), rng=rng, d=parameters["d"], variance=parameters["variance"])


class NoEffect(Effect):
    name = "none"
    summary = "the declared model fits: nothing significant remains"


class Quantization(Effect):
    name = "quantization"
    kind = "output"
    summary = "the output is a multiple of one step q (an ADC or a digital interface), noise q²/12 when fine"
    detection = (
        "lattice test: the smallest spacing q of the distinct values divides every sample to 1e-6 q and "
        "there are fewer than n/4 distinct values; an observation, reported, not added to the model"
    )
    enters_model = (
        "nothing: for a step much smaller than the noise, rounding adds white noise of variance q²/12 that "
        "the white term already absorbs"
    )
    removal = "none"
    defaults: ClassVar[dict[str, float]] = {"step": 8.7e-4}

    def inject(self, signal, time, temperature, rng, parameters):
        step = float(parameters["step"])
        if step <= 0:
            raise ValueError(f"quantization: step={step!r}: must be > 0")
        return np.round(signal / step) * step


def detect_quantization(values: np.ndarray) -> dict[str, Any]:
    """The lattice test of ``quantization``: {"quantized": bool, "step": q, "levels": count}."""
    x = np.asarray(values, dtype=np.float64)
    levels = np.unique(x)
    if len(levels) < 2 or len(levels) > max(2, len(x) // 4):
        return {"quantized": False, "step": 0.0, "levels": len(levels)}
    spacing = np.diff(levels)
    step = float(spacing.min())
    # A step at the rounding level of float64 is no lattice (averaged or converted data).
    if step <= 1e-9 * float(levels[-1] - levels[0]):
        return {"quantized": False, "step": 0.0, "levels": len(levels)}
    multiples = (levels - levels[0]) / step
    on_lattice = bool(
        np.all(np.abs(multiples - np.round(multiples)) < 1e-6 * max(1.0, np.abs(multiples).max()))
    )
    return {"quantized": on_lattice, "step": step if on_lattice else 0.0, "levels": len(levels)}


#: The catalogue, by stable name.
CATALOGUE: dict[str, Effect] = {
    effect.name: effect
    for effect in (
        NoEffect(),
        Flicker(),
        Warmup(),
        Temperature(),
        Spikes(),
        Sinusoid(),
        ColoredNoise(),
        Steps(),
        Quantization(),
    )
}


#: Ranges of the effect parameters that have one: (effect, parameter) → (test, the rule in words).
PARAMETER_RULES: dict[tuple[str, str], tuple[Callable[[float], bool], str]] = {
    ("warmup", "time_constant"): (lambda v: v > 0, "must be > 0 s"),
    ("steps", "time"): (lambda v: 0 <= v <= 1, "must be a fraction of the record in [0, 1]"),
    ("sinusoid", "frequency"): (lambda v: v > 0, "must be > 0 Hz"),
    ("spikes", "rate"): (lambda v: 0 < v <= 1, "must be a probability per sample in (0, 1]"),
    ("colored_noise", "coefficient"): (lambda v: -1 < v < 1, "must lie in (-1, 1) (a stationary AR(1))"),
    ("flicker", "variance"): (lambda v: v >= 0, "must be >= 0"),
    ("flicker", "d"): (lambda v: 0 < v < 1, "must lie in (0, 1)"),
    ("quantization", "step"): (lambda v: v > 0, "must be > 0"),
}


def check_effect_parameters(name: str, parameters: Mapping[str, Any]) -> dict[str, float]:
    """The effect's defaults overridden by ``parameters``, each a finite real; unknown keys refused."""
    if name not in CATALOGUE or name == "none":
        raise ValueError(f"effect={name!r}: unknown effect; known: {sorted(set(CATALOGUE) - {'none'})}")
    if not isinstance(parameters, Mapping):
        raise TypeError(f"parameters={parameters!r}: must be a mapping of parameter name to number")
    defaults = CATALOGUE[name].defaults
    unknown = sorted(set(parameters) - set(defaults))
    if unknown:
        raise ValueError(f"effect {name!r}: unknown parameters {unknown}; known: {sorted(defaults)}")
    merged = dict(defaults)
    for key, value in parameters.items():
        merged[key] = float(check_real(f"{name}.{key}", value))
        test, rule = PARAMETER_RULES.get((name, key), (lambda v: True, ""))
        if not test(merged[key]):
            raise ValueError(f"{name}:{key}={merged[key]!r}: {rule}")
    return merged
