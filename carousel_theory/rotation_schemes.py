"""Rotation schemes of a gyro unit and the demodulation weights each one gives (beyond TIM 2014).

TIM 2014 treats one scheme, continuous carouseling with an integer number N of samples per
revolution (§III, eqs. (5)–(6), (13)). A MEMS north finder can instead average statically, carousel
at any rate, index between P positions with dwell and transition times (maytagging), follow a
measured angle profile, or turn a three-gyro unit about two axes. Every one of them is described
here by the attitude R_t of the gyro unit at each sample t = 1 … n (body → base frame) and by the
set of samples it uses.

The gyro triad measures ``ω_t = R_tᵀ Ω + b + e_t`` (Ω the Earth rate in the base frame, b the
gyro biases, e_t the noise processes of TIM 2014 §II), and the estimate of Ω is the demodulated
mean ``Ω̂ = (1/n_used) Σ_{t used} R_t ω_t`` — TIM 2014 eq. (6) generalised: for a rotation by φ_t
about the vertical its second component is ``(1/n) Σ (ω_x sin φ_t + ω_y cos φ_t)``, the first
``(1/n) Σ (ω_x cos φ_t − ω_y sin φ_t)``. Because ``R_t R_tᵀ = I`` the Earth rate is recovered
exactly at every sample, whatever the pattern; the bias leaves ``(1/n_used) Σ R_t b``, which is
zero exactly when the pattern's attitudes average to a matrix with zero columns (whole revolutions,
whole indexing cycles). Component j of Ω̂ weights gyro g with ``W[j, g, t] = R_t[j, g]/n_used``;
these weights are what :mod:`carousel_theory.scheme_variance` propagates.

Schemes count in samples. :func:`parse_scheme` turns the text of ``carousel-theory design``
(``static``, ``carousel:N=200``, ``carousel:period=2``, ``indexing:positions=4,dwell=10,transition=1``,
``two-axis:N=200``) into a scheme at a given sample rate.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from carousel_theory._validation import check_finite_array, check_positive_integer, check_positive_real

__all__ = [
    "Carousel",
    "Indexing",
    "MeasuredProfile",
    "SchemePattern",
    "Static",
    "TwoAxisCarousel",
    "demodulation_weights",
    "parse_scheme",
    "scheme_label",
]


@dataclass(frozen=True)
class SchemePattern:
    """The attitude of the unit at samples t = 1 … n and which samples the estimate uses.

    Attributes
    ----------
    rotations : numpy.ndarray, shape (n, 3, 3)
        R_t, body → base frame.
    used : numpy.ndarray of bool, shape (n,)
        Samples entering the estimate (transition samples of indexing may be dropped).
    components : int
        How many components of Ω the scheme estimates: 2 (horizontal, one rotation axis) or 3.
    """

    rotations: np.ndarray
    used: np.ndarray
    components: int


def _rotations_about_vertical(angles: np.ndarray) -> np.ndarray:
    """R_z(φ) for each φ: the gyros x, y turn in the horizontal plane, the z gyro stays vertical."""
    rotations = np.zeros((angles.shape[0], 3, 3))
    cosine, sine = np.cos(angles), np.sin(angles)
    rotations[:, 0, 0], rotations[:, 0, 1] = cosine, -sine
    rotations[:, 1, 0], rotations[:, 1, 1] = sine, cosine
    rotations[:, 2, 2] = 1.0
    return rotations


def _planar(angles: np.ndarray, used: np.ndarray | None = None) -> SchemePattern:
    mask = np.ones(angles.shape[0], dtype=bool) if used is None else used
    return SchemePattern(_rotations_about_vertical(angles), mask, 2)


@dataclass(frozen=True)
class Static:
    """No rotation: the plain average of TIM 2014 eq. (12) for each gyro; the biases stay in the estimate."""

    def cycle_length(self) -> int | None:
        return None

    def pattern(self, length: int) -> SchemePattern:
        length = check_positive_integer("length", length)
        return _planar(np.zeros(length))


@dataclass(frozen=True)
class Carousel:
    """Continuous rotation about the vertical, φ_t = 2π t / N (TIM 2014 eq. (13) for integer N).

    ``samples_per_revolution`` may be any real N ≥ 2; for a non-integer N a record never holds whole
    revolutions and the biases leak into the estimate (see :func:`demodulation_weights`).
    """

    samples_per_revolution: float

    def __post_init__(self) -> None:
        value = check_positive_real("samples_per_revolution", self.samples_per_revolution)
        if value < 2:
            raise ValueError(f"samples_per_revolution={value!r}: must be >= 2 (at least two samples a turn)")

    def cycle_length(self) -> int | None:
        value = float(self.samples_per_revolution)
        return int(value) if value.is_integer() else None

    def pattern(self, length: int) -> SchemePattern:
        length = check_positive_integer("length", length)
        t = np.arange(1, length + 1, dtype=np.float64)
        value = float(self.samples_per_revolution)
        if value.is_integer():  # exact multiples of π/2 where TIM 2014 §III-D needs them
            turns = np.mod(np.arange(1, length + 1), int(value)) / value
            return _planar(2 * np.pi * turns)
        return _planar(2 * np.pi * t / value)


@dataclass(frozen=True)
class Indexing:
    """P-position indexing (maytagging): dwell at φ_p = 2π p / P, then turn to the next position.

    One cycle is P × (``dwell`` samples at rest + ``transition`` samples turning at a constant rate by
    2π/P). Transition samples are dropped from the estimate unless ``use_transitions``; then they
    enter at their own angles φ_p + (2π/P) j/(transition + 1), j = 1 … transition.
    """

    positions: int
    dwell: int
    transition: int = 0
    use_transitions: bool = False

    def __post_init__(self) -> None:
        positions = check_positive_integer("positions", self.positions, minimum=2)
        dwell = _check_dwell(self.dwell)
        transition = check_positive_integer("transition", self.transition, minimum=0)
        object.__setattr__(self, "positions", positions)
        object.__setattr__(self, "dwell", dwell)
        object.__setattr__(self, "transition", transition)

    def cycle_length(self) -> int:
        return self.positions * (self.dwell + self.transition)

    def _one_cycle(self) -> tuple[np.ndarray, np.ndarray]:
        step = 2 * np.pi / self.positions
        turning = np.arange(1, self.transition + 1) / (self.transition + 1)
        angles, used = [], []
        for position in range(self.positions):
            angles += [np.full(self.dwell, position * step), (position + turning) * step]
            used += [np.ones(self.dwell, dtype=bool), np.full(self.transition, self.use_transitions)]
        return np.concatenate(angles), np.concatenate(used)

    def pattern(self, length: int) -> SchemePattern:
        length = check_positive_integer("length", length)
        angles, used = self._one_cycle()
        repeats = -(-length // angles.shape[0])
        return _planar(np.tile(angles, repeats)[:length], np.tile(used, repeats)[:length])


def _check_dwell(value: Any) -> int:
    if isinstance(value, (int, np.integer)) and not isinstance(value, bool) and value < 1:
        raise ValueError(f"dwell={value!r}: must be at least one sample (a dwell shorter than one sample)")
    return check_positive_integer("dwell", value)


@dataclass(frozen=True)
class MeasuredProfile:
    """A measured angle profile φ_1 … φ_m (rad) about the vertical, repeated if the record is longer.

    ``used`` optionally marks the samples that enter the estimate (default: all).
    """

    angles: tuple[float, ...]
    used: tuple[bool, ...] | None = None

    @classmethod
    def from_array(cls, angles: Any, used: Any = None) -> MeasuredProfile:
        values = check_finite_array("angles", angles)
        mask = None if used is None else tuple(bool(v) for v in np.asarray(used).ravel())
        if mask is not None and len(mask) != values.shape[0]:
            raise ValueError(f"used: must have one entry per angle ({values.shape[0]}), got {len(mask)}")
        return cls(tuple(float(v) for v in values), mask)

    def cycle_length(self) -> int:
        return len(self.angles)

    def pattern(self, length: int) -> SchemePattern:
        length = check_positive_integer("length", length)
        angles = np.asarray(self.angles)
        used = np.ones(angles.shape[0], dtype=bool) if self.used is None else np.asarray(self.used)
        repeats = -(-length // angles.shape[0])
        return _planar(np.tile(angles, repeats)[:length], np.tile(used, repeats)[:length])


@dataclass(frozen=True)
class TwoAxisCarousel:
    """Two-axis carouseling of a three-gyro unit: turn about the vertical, flip upside down each turn.

    R_t = R_z(2π t/N) F_c, where F_c is the identity in even revolutions and the 180° turn about the
    base x axis, diag(1, −1, −1), in odd ones. Over two revolutions the attitudes average to the zero
    matrix, so all three biases cancel, and Ω̂ estimates all three Earth-rate components (the
    vertical one through the flips, like 2-position indexing of the z gyro).
    """

    samples_per_revolution: int

    def __post_init__(self) -> None:
        object.__setattr__(
            self,
            "samples_per_revolution",
            check_positive_integer("samples_per_revolution", self.samples_per_revolution, minimum=2),
        )

    def cycle_length(self) -> int:
        return 2 * self.samples_per_revolution

    def pattern(self, length: int) -> SchemePattern:
        length = check_positive_integer("length", length)
        N = self.samples_per_revolution
        index = np.arange(1, length + 1)
        rotations = _rotations_about_vertical(2 * np.pi * (np.mod(index, N) / N))
        flipped = ((index - 1) // N) % 2 == 1
        rotations[flipped] = rotations[flipped] @ np.diag([1.0, -1.0, -1.0])
        return SchemePattern(rotations, np.ones(length, dtype=bool), 3)


def demodulation_weights(pattern: SchemePattern) -> np.ndarray:
    """W[j, g, t] = R_t[j, g] [t used] / n_used: the weight of gyro g's sample t in component j of Ω̂.

    Shape (components, 3, n); gyros are x, y, z. TIM 2014 eq. (13) is the case R_t = R_z(2π t/N):
    component 1 weights the x gyro with s_t and the y gyro with c_t.
    """
    used = pattern.used
    count = int(used.sum())
    if count == 0:
        raise ValueError("pattern: uses no sample (every sample is a dropped transition sample)")
    weights = np.transpose(pattern.rotations[:, : pattern.components, :], (1, 2, 0)) * (used / count)
    return np.ascontiguousarray(weights)


# --- the scheme text of `carousel-theory design` ---------------------------------------------------

_KINDS = ("static", "carousel", "indexing", "two-axis", "profile")


def _options(text: str, body: str) -> dict[str, str]:
    options: dict[str, str] = {}
    for item in filter(None, (part.strip() for part in body.split(","))):
        key, separator, value = item.partition("=")
        if not separator or not key.strip() or not value.strip():
            raise ValueError(f"scheme={text!r}: option {item!r} must have the form KEY=VALUE")
        options[key.strip()] = value.strip()
    return options


def _number(text: str, key: str, value: str) -> float:
    try:
        number = float(value)
    except ValueError:
        raise ValueError(f"scheme={text!r}: {key}={value!r} must be a number") from None
    if not math.isfinite(number) or number < 0:
        raise ValueError(f"scheme={text!r}: {key}={value!r} must be a finite number >= 0")
    return number


def _refuse_unknown(text: str, options: dict[str, str], allowed: tuple[str, ...]) -> None:
    unknown = sorted(set(options) - set(allowed))
    if unknown:
        raise ValueError(f"scheme={text!r}: unknown option(s) {unknown}; allowed: {list(allowed)}")


def _samples(text: str, key: str, seconds: float, sample_rate: float) -> int:
    count = seconds * sample_rate
    if abs(count - round(count)) > 1e-9 * max(1.0, count):
        raise ValueError(
            f"scheme={text!r}: {key}={seconds!r} s is {count!r} samples at {sample_rate!r} Hz: "
            "must be a whole number of samples"
        )
    return round(count)


def _parse_carousel(text: str, options: dict[str, str], sample_rate: float, two_axis: bool) -> Any:
    _refuse_unknown(text, options, ("N", "period"))
    if len(options) != 1:
        raise ValueError(f"scheme={text!r}: give exactly one of N= (samples a turn) or period= (s a turn)")
    key, value = next(iter(options.items()))
    samples = _number(text, key, value) * (sample_rate if key == "period" else 1.0)
    if samples < 2:
        raise ValueError(f"scheme={text!r}: {key}={value} is {samples!r} samples a turn: must be >= 2")
    if two_axis:
        if not float(samples).is_integer():
            raise ValueError(f"scheme={text!r}: two-axis carouseling needs a whole number of samples a turn")
        return TwoAxisCarousel(int(samples))
    return Carousel(int(samples) if float(samples).is_integer() else samples)


def _parse_indexing(text: str, options: dict[str, str], sample_rate: float) -> Indexing:
    _refuse_unknown(text, options, ("positions", "dwell", "transition", "transitions"))
    if "positions" not in options or "dwell" not in options:
        raise ValueError(f"scheme={text!r}: indexing needs positions= and dwell= (seconds)")
    positions = _number(text, "positions", options["positions"])
    if not positions.is_integer() or positions < 2:
        raise ValueError(f"scheme={text!r}: positions={options['positions']!r} must be an integer >= 2")
    dwell_seconds = _number(text, "dwell", options["dwell"])
    if dwell_seconds * sample_rate < 1:
        raise ValueError(
            f"scheme={text!r}: dwell={options['dwell']} s is shorter than one sample at {sample_rate!r} Hz: "
            "must be at least one sample"
        )
    dwell = _samples(text, "dwell", dwell_seconds, sample_rate)
    transition = _samples(
        text, "transition", _number(text, "transition", options.get("transition", "0")), sample_rate
    )
    mode = options.get("transitions", "discard")
    if mode not in ("discard", "use"):
        raise ValueError(f"scheme={text!r}: transitions={mode!r} must be 'discard' or 'use'")
    return Indexing(int(positions), dwell, transition, mode == "use")


def _read_profile(text: str, path: Path) -> MeasuredProfile:
    """A measured angle profile from a .npy file or a text file with one angle (rad) a line (read only)."""
    if not path.is_file():
        raise ValueError(f"scheme={text!r}: file={str(path)!r} does not exist")
    try:
        angles = np.load(path, allow_pickle=False) if path.suffix == ".npy" else np.loadtxt(path, ndmin=1)
    except ValueError as error:
        raise ValueError(f"scheme={text!r}: file={str(path)!r} holds no column of angles ({error})") from None
    return MeasuredProfile.from_array(np.ravel(angles))


def parse_scheme(text: str, sample_rate: float) -> Any:
    """The scheme described by ``text`` at ``sample_rate`` Hz; ValueError naming the text otherwise.

    ``static``; ``carousel:N=200`` (samples a turn, any real ≥ 2) or ``carousel:period=2`` (s);
    ``indexing:positions=4,dwell=10,transition=1[,transitions=use]`` (seconds; transitions are
    dropped by default); ``two-axis:N=200`` or ``two-axis:period=2``; ``profile:file=PATH`` (measured
    angles in rad, one per sample, repeated when the record is longer).
    """
    if not isinstance(text, str):
        raise TypeError(f"scheme={text!r}: must be a string such as 'carousel:N=200'")
    sample_rate = float(check_positive_real("sample_rate", sample_rate))
    kind, _, body = text.strip().partition(":")
    if kind not in _KINDS:
        raise ValueError(f"scheme={text!r}: must start with one of {list(_KINDS)} (e.g. 'carousel:N=200')")
    options = _options(text, body)
    if kind == "static":
        _refuse_unknown(text, options, ())
        return Static()
    if kind == "indexing":
        return _parse_indexing(text, options, sample_rate)
    if kind == "profile":
        _refuse_unknown(text, options, ("file",))
        if "file" not in options:
            raise ValueError(
                f"scheme={text!r}: a profile needs file=PATH (.npy, or text with one angle in rad a line)"
            )
        return _read_profile(text, Path(options["file"]))
    return _parse_carousel(text, options, sample_rate, two_axis=kind == "two-axis")


def scheme_label(scheme: Any, sample_rate: float) -> str:
    """The scheme written back in the text of :func:`parse_scheme` (seconds at ``sample_rate``)."""
    if isinstance(scheme, Static):
        return "static"
    if isinstance(scheme, (Carousel, TwoAxisCarousel)):
        kind = "carousel" if isinstance(scheme, Carousel) else "two-axis"
        return f"{kind}:N={float(scheme.samples_per_revolution):g}"
    if isinstance(scheme, Indexing):
        label = (
            f"indexing:positions={scheme.positions},dwell={scheme.dwell / sample_rate:g},"
            f"transition={scheme.transition / sample_rate:g}"
        )
        return label + (",transitions=use" if scheme.use_transitions else "")
    return f"profile ({len(scheme.angles)} angles)"
