"""The loop's input: arguments checked once, the recording made uniform, the axes chosen, and what the
data allow said in observations before any fit."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from carousel_theory._validation import check_positive_integer, check_positive_real
from carousel_theory.closed_loop.evaluation import MINIMUM_BINS
from carousel_theory.closed_loop.resample import uniform_resample
from carousel_theory.data import Recording
from carousel_theory.effects import detect_quantization
from carousel_theory.signal_checks import check_recording_signals

__all__ = ["LoopInput", "default_axes", "prepare"]


@dataclass(frozen=True)
class LoopInput:
    """The checked arguments of one run of the loop."""

    recording: Recording
    axes: tuple[str, ...]
    samples_per_revolution: int
    alpha: float
    maximum_iterations: int
    declared_flicker: bool
    observations: list[str]

    @property
    def angle(self) -> np.ndarray | None:
        return self.recording.angle if len(self.axes) == 2 else None


def _check_declared(declared: Sequence[str]) -> bool:
    declared = tuple(declared)
    unknown = sorted(set(declared) - {"white", "rrw", "flicker"})
    if unknown or not {"white", "rrw"} <= set(declared):
        raise ValueError(f"declared={declared!r}: must hold 'white' and 'rrw', optionally 'flicker'")
    return "flicker" in declared


def _check_alpha(alpha: Any) -> float:
    alpha = float(check_positive_real("alpha", alpha))
    if not alpha < 0.5:
        raise ValueError(f"alpha={alpha!r}: must be < 0.5")
    return alpha


def _quantization_notes(recording: Recording, axes: Sequence[str] | None) -> list[str]:
    """The lattice test needs the samples as recorded (averaging onto a uniform grid would hide it)."""
    notes = []
    for axis in (a for a in (axes or ("wx", "wy")) if a in recording.rates):
        lattice = detect_quantization(recording.rates[axis])
        if lattice["quantized"]:
            notes.append(
                f"quantization on {axis}: step {lattice['step']:.4g} rad/s, {lattice['levels']} levels "
                f"(noise q²/12 = {lattice['step'] ** 2 / 12:.3g} (rad/s)² is inside the white term)"
            )
    return notes


def default_axes(recording: Recording) -> tuple[str, ...]:
    """The axes the loop analyses when none are named: ``wx`` and ``wy`` when present, else every axis."""
    names = tuple(recording.rates)
    return ("wx", "wy") if {"wx", "wy"} <= set(names) else names


def _chosen_axes(recording: Recording, axes: Sequence[str] | None, N: int) -> tuple[str, ...]:
    chosen = default_axes(recording) if axes is None else tuple(axes)
    missing = [a for a in chosen if a not in recording.rates]
    if not chosen or missing:
        raise ValueError(f"axes={chosen!r}: not in the recording, which has {sorted(recording.rates)}")
    if len(chosen) > 2:
        raise ValueError(f"axes={chosen!r}: give one axis (averaging) or two (averaging and carouseling)")
    needed = MINIMUM_BINS * N
    if len(recording) < needed:
        raise ValueError(
            f"{recording.source}: {len(recording)} samples are too short for samples_per_revolution={N} "
            f"(needs at least {MINIMUM_BINS} bins, {needed} samples)"
        )
    return chosen


def _data_notes(recording: Recording, axes: tuple[str, ...]) -> list[str]:
    notes = []
    if len(axes) == 1:
        notes.append(
            f"one gyro axis ({axes[0]}): averaging analysis only; carouseling needs two perpendicular axes"
        )
    if recording.angle is not None and len(axes) == 2:
        span = float(np.ptp(np.unwrap(recording.angle)))
        notes.append(
            "phi column present: carouselled bins use the measured angles, one bin per revolution"
            if span >= 2.0 * np.pi
            else f"phi column spans {span:.3g} rad, less than one revolution: no carouselled bins, "
            "so no carousel metrics (averaging metrics only)"
        )
    if recording.temperature is None:
        notes.append("no temperature column: the temperature effect cannot be tested")
    elif float(np.ptp(recording.temperature)) == 0.0:
        notes.append("the temperature column is constant: no temperature effect can be tested")
    return notes


def prepare(
    recording: Any,
    samples_per_revolution: Any,
    axes: Sequence[str] | None,
    alpha: Any,
    maximum_iterations: Any,
    declared: Sequence[str],
) -> LoopInput:
    """Check the arguments of :func:`~carousel_theory.closed_loop.run_loop` and prepare the recording."""
    if not isinstance(recording, Recording):
        raise TypeError(f"recording={recording!r}: must be a carousel_theory.data.Recording")
    N = check_positive_integer("samples_per_revolution", samples_per_revolution, minimum=3)
    alpha = _check_alpha(alpha)
    maximum_iterations = check_positive_integer("maximum_iterations", maximum_iterations)
    flicker = _check_declared(declared)
    chosen = _chosen_axes(recording, axes, N)
    check_recording_signals(recording, chosen)  # as recorded, before any arithmetic on the values
    observations = [*recording.notes, *_quantization_notes(recording, axes)]
    if not recording.uniform:
        recording, note = uniform_resample(recording)
        observations.append(note)
        chosen = _chosen_axes(recording, axes, N)
    observations += _data_notes(recording, chosen)
    return LoopInput(recording, chosen, N, alpha, maximum_iterations, flicker, observations)
