"""Synthetic gyro recordings: a declared noise model plus any set of undeclared effects.

A recording is built axis by axis as

    y_t = b + n_t + r_t + f_t + Σ_e s_e(t),

with b the constant bias (TIM 2014 eq. (1)), n_t white noise (§II-B), r_t the rate random walk of eq. (2),
f_t the 1/f noise of eq. (3), and s_e the signals of the undeclared effects of
:mod:`carousel_theory.effects` (a warm-up transient, a temperature-driven bias, spikes, …). An effect
that filters the white noise (``colored_noise``) replaces n_t by its filtered version, and
``quantization`` rounds the final output. Every random number comes from the ``rng`` argument (a
``numpy.random.Generator``), so one seed gives one recording, bit for bit.

Besides the catalogue, :data:`OUTSIDE_CATALOGUE` holds signals that no catalogue effect describes
(a sawtooth), used to check that the closed loop says "unexplained" rather than a wrong name.
"""

from __future__ import annotations

import inspect
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from carousel_theory._validation import check_positive_integer, check_positive_real, check_real
from carousel_theory.data import RESERVED_COLUMN_NAMES, Recording, recording_from_arrays
from carousel_theory.effects import CATALOGUE, check_effect_parameters
from carousel_theory.noise_model import NoiseModel, ar_decay_lags
from carousel_theory.processes import sample_flicker, sample_rate_random_walk, sample_white
from carousel_theory.units import (
    flicker_variance_from_bias_instability,
    from_arcseconds,
    from_microradians,
    rrw_variance_from_rate_random_walk,
    white_variance_from_angle_random_walk,
)

__all__ = [
    "MAX_SIMULATED_SAMPLES",
    "OUTSIDE_CATALOGUE",
    "Datasheet",
    "Injection",
    "default_temperature_profile",
    "parse_injection",
    "sample_noise",
    "samples_for_duration",
    "simulate_recording",
    "write_recording",
]


def sample_noise(model: NoiseModel, length: int, *, rng: np.random.Generator) -> np.ndarray:
    """One axis of ``length`` samples of ``model``: b + white + RRW (eq. (2), r_0 = 0) + 1/f (eq. (3),
    started at t = 1) + quantization (f_s (a_t − a_{t−1}), a white angle error of variance Q²) + the AR term
    started in its stationary state (a burn-in until the slowest root's envelope is below
    :data:`carousel_theory.noise_model.AR_TRUNCATION`)."""
    from scipy.signal import lfilter

    length = check_positive_integer("length", length, minimum=1)
    if not isinstance(model, NoiseModel):
        raise TypeError(f"model={model!r}: must be a NoiseModel")
    if not isinstance(rng, np.random.Generator):
        raise TypeError(f"rng={rng!r}: must be a numpy.random.Generator")
    y = np.full(length, float(model.bias))
    if model.white_variance:
        y += sample_white(length, rng=rng, variance=float(model.white_variance))
    if model.rrw_variance:
        y += sample_rate_random_walk(length, rng=rng, variance=float(model.rrw_variance))
    if model.flicker_variance:
        flicker = sample_flicker(length, rng=rng, d=float(model.flicker_d))
        y += np.sqrt(float(model.flicker_variance)) * flicker
    if model.quantization:
        angle = float(model.quantization) * rng.standard_normal(length + 1)
        y += float(model.sample_rate) * np.diff(angle)
    if model.ar_variance:
        phi = np.asarray(model.ar_coefficients, dtype=np.float64)
        burn = ar_decay_lags(tuple(model.ar_coefficients)) + len(phi) if len(phi) else 0
        innovations = np.sqrt(float(model.ar_variance)) * rng.standard_normal(length + burn)
        y += lfilter([1.0], np.concatenate(([1.0], -phi)), innovations)[burn:]
    return y


@dataclass(frozen=True)
class Datasheet:
    """Noise figures as a gyro datasheet states them, in IEEE Std 952's units (0 = term absent).

    Attributes
    ----------
    angle_random_walk : float
        ARW N in °/√h (white rate noise; σ_A²(τ) = N²/τ).
    bias_instability : float
        B in °/h (1/f rate noise; flat σ_A = √(2 ln 2/π)·B = 0.664·B), simulated as the 1/f term of
        TIM 2014 eq. (3) at d = 1/2.
    rate_random_walk : float
        RRW K in °/h/√h (σ_A²(τ) = K²τ/3).
    quantization : float
        Angle quantization Q in ``quantization_unit`` (σ_A²(τ) = 3Q²/τ²).
    quantization_unit : str
        ``"urad"`` (µrad, default) or ``"arcsec"``.
    """

    angle_random_walk: float = 0.0
    bias_instability: float = 0.0
    rate_random_walk: float = 0.0
    quantization: float = 0.0
    quantization_unit: str = "urad"

    def noise_model(self, sample_rate: float, bias: float = 0.0) -> NoiseModel:
        """The per-sample model at ``sample_rate`` Hz (:mod:`carousel_theory.units`' inverse conversions)."""
        if self.quantization_unit not in ("urad", "arcsec"):
            raise ValueError(f"quantization_unit={self.quantization_unit!r}: must be 'urad' or 'arcsec'")
        to_radians = from_microradians if self.quantization_unit == "urad" else from_arcseconds
        if not (math.isfinite(self.quantization) and self.quantization >= 0):
            raise ValueError(f"quantization={self.quantization!r}: must be a finite number >= 0")
        return NoiseModel(
            sample_rate=float(check_positive_real("sample_rate", sample_rate)),
            bias=bias,
            white_variance=white_variance_from_angle_random_walk(self.angle_random_walk, sample_rate),
            rrw_variance=rrw_variance_from_rate_random_walk(self.rate_random_walk, sample_rate),
            flicker_variance=flicker_variance_from_bias_instability(self.bias_instability),
            flicker_d=0.5,
            quantization=to_radians(self.quantization),
        )


def _sawtooth(time: np.ndarray, amplitude: float = 1e-3, period: float = 60.0) -> np.ndarray:
    """A zero-mean sawtooth of peak-to-peak ``amplitude`` and the given period (s): a slow ramp that
    resets every period. Harmonics at every multiple of 1/period, so no single sinusoid explains it."""
    phase = np.mod(time / period, 1.0)
    return amplitude * (phase - 0.5)


#: Signals outside the effect catalogue: name → (function(time, **parameters), default parameters).
OUTSIDE_CATALOGUE: dict[str, tuple[Any, dict[str, float]]] = {
    "sawtooth": (_sawtooth, {"amplitude": 1e-3, "period": 60.0}),
}


@dataclass(frozen=True)
class Injection:
    """One undeclared effect to add: a catalogue name (or a name of :data:`OUTSIDE_CATALOGUE`) and its
    parameters (missing ones take the effect's defaults)."""

    name: str
    parameters: Mapping[str, float] = field(default_factory=dict)


def parse_injection(text: str) -> Injection:
    """Parse ``"name"`` or ``"name:key=value,key=value"`` (the command-line form) into an Injection."""
    if not isinstance(text, str) or not text.strip():
        raise ValueError(f"effect={text!r}: must be 'name' or 'name:key=value,...'")
    name, _, rest = text.strip().partition(":")
    parameters: dict[str, float] = {}
    for item in filter(None, (part.strip() for part in rest.split(","))):
        key, equals, value = item.partition("=")
        if not equals:
            raise ValueError(f"effect={text!r}: parameter {item!r} must have the form key=value")
        try:
            parameters[key.strip()] = float(value)
        except ValueError:
            raise ValueError(
                f"effect={text!r}: parameter {key.strip()!r}={value!r} must be a number"
            ) from None
    injection = Injection(name.strip(), parameters)
    _resolved_parameters(injection)
    return injection


def _injection(effect: Injection | str) -> Injection:
    return parse_injection(effect) if isinstance(effect, str) else effect


def _resolved_parameters(injection: Injection) -> dict[str, float]:
    if not isinstance(injection, Injection):
        raise TypeError(f"effects: {injection!r} must be an Injection (or a 'name:key=value' string)")
    if injection.name in OUTSIDE_CATALOGUE:
        defaults = OUTSIDE_CATALOGUE[injection.name][1]
        unknown = sorted(set(injection.parameters) - set(defaults))
        if unknown:
            raise ValueError(
                f"effect {injection.name!r}: unknown parameters {unknown}; known: {sorted(defaults)}"
            )
        merged = {**defaults, **{k: float(check_real(k, v)) for k, v in injection.parameters.items()}}
        return merged
    if injection.name not in CATALOGUE or injection.name == "none":
        known = sorted(set(CATALOGUE) - {"none"}) + sorted(OUTSIDE_CATALOGUE)
        raise ValueError(f"effect={injection.name!r}: unknown effect; known: {known}")
    return check_effect_parameters(injection.name, injection.parameters)


def default_temperature_profile(time: np.ndarray) -> np.ndarray:
    """A smooth, deterministic temperature history in °C: 25 °C plus a 0.5 K ramp over the record and a
    0.8 K oscillation of period 0.6 × the record length (no exponential part, so that a temperature
    effect is not confused with a warm-up transient by construction)."""
    span = float(time[-1] - time[0]) if len(time) > 1 else 1.0
    relative = (time - time[0]) / span
    return 25.0 + 0.5 * relative + 0.8 * np.sin(2.0 * np.pi * relative / 0.6 + 0.3)


def _check_size_rate_generator(
    samples: Any, sample_rate: Any, rng: Any, max_samples: int
) -> tuple[int, float]:
    samples = check_positive_integer("samples", samples, minimum=2)
    _check_sample_budget(samples, 1, max_samples)
    sample_rate = float(check_positive_real("sample_rate", sample_rate))
    if not isinstance(rng, np.random.Generator):
        raise TypeError(f"rng={rng!r}: must be a numpy.random.Generator (np.random.default_rng(seed))")
    return samples, sample_rate


#: Most samples per axis :func:`simulate_recording` makes unless ``max_samples`` raises the limit:
#: 10⁸ samples (11.6 days at 100 Hz) of 2 axes, time and temperature are 3.2 GB as float64.
MAX_SIMULATED_SAMPLES = 10**8
#: Names an axis may not take: the readers' reserved columns, and the keywords of ``numpy.savez``,
#: which would swallow the column (``allow_pickle``) or collide with the file argument.
_FORBIDDEN_AXIS_NAMES = RESERVED_COLUMN_NAMES | frozenset(inspect.signature(np.savez).parameters)


def samples_for_duration(
    duration: Any, sample_rate: Any, *, columns: int = 4, max_samples: int = MAX_SIMULATED_SAMPLES
) -> int:
    """The number of samples of ``duration`` s at ``sample_rate`` Hz, refused above ``max_samples``.

    ``columns`` (the axes plus time and temperature) only enters the memory estimate in the message.
    """
    duration = float(check_positive_real("duration", duration))
    sample_rate = float(check_positive_real("sample_rate", sample_rate))
    product = duration * sample_rate
    if not math.isfinite(product):
        raise ValueError(f"duration={duration!r} at sample_rate={sample_rate!r}: the sample count overflows")
    samples = round(product)
    _check_sample_budget(samples, columns, max_samples)
    return samples


def _check_sample_budget(samples: int, columns: int, max_samples: int) -> None:
    max_samples = check_positive_integer("max_samples", max_samples)
    if samples > max_samples:
        raise ValueError(
            f"samples={samples}: more than max_samples={max_samples} (about "
            f"{samples * columns * 8 / 1e9:.3g} GB for {columns} float64 column{'s' * (columns > 1)}); "
            "raise max_samples (--max-samples) if the machine has the memory"
        )


def _check_axis_names(axes: Any) -> None:
    """Refuse axis names a written file could not hold as gyro columns."""
    if isinstance(axes, str) or not axes or not all(isinstance(a, str) and a for a in axes):
        raise TypeError(f"axes={axes!r}: must be a non-empty sequence of axis names")
    for axis in axes:
        if not axis.isidentifier():
            raise ValueError(f"axes={axes!r}: {axis!r} must be an identifier (letters, digits, underscores)")
        if axis.lower() in _FORBIDDEN_AXIS_NAMES:
            raise ValueError(
                f"axes={axes!r}: {axis!r} is reserved (for time, temperature, angle, sample rate or a "
                f"numpy.savez keyword: {', '.join(sorted(_FORBIDDEN_AXIS_NAMES))}); choose another "
                "name, e.g. wx"
            )
    if len({axis.lower() for axis in axes}) != len(axes):
        raise ValueError(f"axes={axes!r}: names must be distinct (ignoring case)")


def _axis_biases(axes: Sequence[str], bias: float | Mapping[str, float]) -> dict[str, float]:
    _check_axis_names(axes)
    if isinstance(bias, Mapping):
        missing = [a for a in axes if a not in bias]
        if missing:
            raise ValueError(f"bias={bias!r}: no value for axes {missing}")
        return {a: float(check_real(f"bias[{a!r}]", bias[a])) for a in axes}
    return {a: float(check_real("bias", bias)) for a in axes}


def _temperature_column(temperature: Any, time: np.ndarray, resolved: list) -> np.ndarray | None:
    if isinstance(temperature, str):
        if temperature != "auto":
            raise ValueError(f"temperature={temperature!r}: must be 'auto', None or an array")
        column: np.ndarray | None = default_temperature_profile(time)
    elif temperature is None:
        column = None
    else:
        column = np.asarray(temperature, dtype=np.float64)
        if column.shape != time.shape or not np.all(np.isfinite(column)):
            raise ValueError(f"temperature: must be {len(time)} finite values in °C")
    if column is None and any(name == "temperature" for name, _ in resolved):
        raise ValueError("effects: a 'temperature' effect needs a temperature column (temperature='auto')")
    return column


def _simulate_axis(
    declared: NoiseModel,
    bias: float,
    time: np.ndarray,
    temperature: np.ndarray | None,
    resolved: list,
    rng: np.random.Generator,
) -> np.ndarray:
    """One axis: white noise (through any noise filter), bias, the rest of ``declared``
    (:func:`sample_noise`), additive, then output effects."""
    samples = len(time)
    white = (
        sample_white(samples, rng=rng, variance=declared.white_variance)
        if declared.white_variance
        else np.zeros(samples)
    )
    # Effects that filter the white noise act on it before it joins the other components.
    for name, parameters in resolved:
        if name in CATALOGUE and CATALOGUE[name].kind == "noise_filter":
            white = CATALOGUE[name].inject(white, time, temperature, rng, parameters)
    # The rest of the declared model (RRW, 1/f) comes from the one sampler of a NoiseModel.
    signal = bias + white + sample_noise(replace(declared, bias=0.0, white_variance=0.0), samples, rng=rng)
    for name, parameters in resolved:
        if name in OUTSIDE_CATALOGUE:
            signal = signal + OUTSIDE_CATALOGUE[name][0](time, **parameters)
        elif CATALOGUE[name].kind == "additive":
            signal = signal + CATALOGUE[name].inject(np.zeros(samples), time, temperature, rng, parameters)
    # Output effects (rounding) act last, on the complete signal.
    for name, parameters in resolved:
        if name in CATALOGUE and CATALOGUE[name].kind == "output":
            signal = CATALOGUE[name].inject(signal, time, temperature, rng, parameters)
    return signal


def simulate_recording(
    samples: int,
    sample_rate: float,
    *,
    rng: np.random.Generator,
    bias: float | Mapping[str, float] = 0.0,
    white_variance: float = 1e-6,
    rrw_variance: float = 0.0,
    flicker_variance: float = 0.0,
    flicker_d: float = 0.5,
    quantization: float = 0.0,
    axes: Sequence[str] = ("wx", "wy"),
    effects: Sequence[Injection | str] = (),
    temperature: Any = "auto",
    samples_per_revolution: int | None = None,
    max_samples: int = MAX_SIMULATED_SAMPLES,
) -> Recording:
    """A recording of ``samples`` samples at ``sample_rate`` Hz from a declared model plus effects.

    Parameters
    ----------
    samples, sample_rate, max_samples, rng
        Length and rate (Hz) of the recording (more than ``max_samples`` samples are refused); ``rng``,
        the only source of randomness.
    bias
        Constant bias b (rad/s) of TIM 2014 eq. (1), one value or one per axis.
    white_variance, rrw_variance, flicker_variance, flicker_d, quantization
        Per-sample variances (rad/s)² of white noise, of the rate-random-walk increments (eq. (2)) and of
        the 1/f driving noise (eq. (3), order ``flicker_d``); angle quantization Q (rad), a white angle
        error differenced into the rate. Each axis gets independent draws. :meth:`Datasheet.noise_model`
        gives them from datasheet figures (°/√h, °/h, °/h/√h, µrad or arcsec).
    axes, effects
        Names of the gyro axes; undeclared effects, :class:`Injection` objects or ``"name:key=value,..."``.
    temperature
        ``"auto"``: the :func:`default_temperature_profile` column (present even without a temperature
        effect, so that a clean recording also has one); ``None``: no column; or an array of °C.
    samples_per_revolution
        When given, a ``phi`` column of a uniform rotation with this many samples per revolution,
        φ_i = 2π i / N (TIM 2014 eq. (6)); the rates stay those of a static sensor.
    """
    samples, sample_rate = _check_size_rate_generator(samples, sample_rate, rng, max_samples)
    biases = _axis_biases(axes, bias)
    resolved = [(i.name, _resolved_parameters(i)) for i in map(_injection, effects)]
    time = np.arange(samples, dtype=np.float64) / sample_rate
    temperature_column = _temperature_column(temperature, time, resolved)
    declared = NoiseModel(
        sample_rate, 0, white_variance, rrw_variance, flicker_variance, flicker_d, quantization
    )
    rates = {
        axis: _simulate_axis(declared, biases[axis], time, temperature_column, resolved, rng) for axis in axes
    }
    angle = _uniform_rotation(samples, samples_per_revolution)
    return recording_from_arrays(
        rates,
        time=time,
        sample_rate=sample_rate,
        temperature=temperature_column,
        angle=angle,
        source=f"simulated ({', '.join(name for name, _ in resolved) or 'none'})",
    )


def _uniform_rotation(samples: int, samples_per_revolution: int | None) -> np.ndarray | None:
    """φ_i = 2π i / N (TIM 2014 eq. (6)), or None."""
    if samples_per_revolution is None:
        return None
    per_revolution = check_positive_integer("samples_per_revolution", samples_per_revolution, 3)
    return 2.0 * np.pi * (np.arange(1, samples + 1) % per_revolution) / per_revolution


def write_recording(recording: Recording, path: str | Path) -> Path:
    """Write a recording as CSV (header ``t,<axes>[,temp][,phi]``) or NPZ (the same keys plus ``fs``),
    chosen by the extension of ``path``. Refuses to overwrite a directory."""
    if not isinstance(recording, Recording):
        raise TypeError(f"recording={recording!r}: must be a carousel_theory.data.Recording")
    if not isinstance(path, (str, Path)):
        raise TypeError(f"path={path!r}: must be a str or pathlib.Path")
    path = Path(path)
    if path.is_dir():
        raise ValueError(f"{path}: is a directory; give a file name ending in .csv or .npz")
    columns: dict[str, np.ndarray] = {"t": recording.time, **recording.rates}
    if recording.temperature is not None:
        columns["temp"] = recording.temperature
    if recording.angle is not None:
        columns["phi"] = recording.angle
    suffix = path.suffix.lower()
    if suffix == ".npz":
        # numpy's stub types **kwds as the allow_pickle flag; the keys are array names here.
        np.savez(path, fs=np.float64(recording.sample_rate), **columns)  # type: ignore[arg-type]
    elif suffix == ".csv":
        # %.17g round-trips float64: reading the file back gives the same numbers bit for bit.
        np.savetxt(
            path,
            np.column_stack(list(columns.values())),
            fmt="%.17g",
            delimiter=",",
            header=",".join(columns),
            comments="",
        )
    else:
        raise ValueError(f"{path}: unknown extension {path.suffix!r}; must be .csv or .npz")
    return path
