"""What the detectors see: the residual of every axis under one model, with its fit — a plain data view.

:class:`ResidualView` holds arrays and fits and nothing else; the questions a detector asks of it (the
variance of a linear statistic, GLS weights, a refit, a nested fit) are the plain functions of
:mod:`carousel_theory.closed_loop.linear_statistics`. :func:`build_view` makes a view from a recording
and a :class:`ModelSpec` (the stochastic terms plus the effects fitted so far).
"""

from __future__ import annotations

import weakref
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from carousel_theory.closed_loop.residual_model import (
    ModelTerms,
    ResidualFit,
    fit_residual_model,
)
from carousel_theory.data import Recording
from carousel_theory.signal_checks import check_noise_signal

__all__ = [
    "FittedEffect",
    "ModelSpec",
    "ResidualView",
    "Residuals",
    "build_view",
    "local_median_replacement",
]


@dataclass(frozen=True)
class FittedEffect:
    """A fitted effect: deterministic signals to subtract per axis, samples to replace per axis (spikes),
    and/or stochastic terms to add to the model (``terms``)."""

    effect: str
    parameters: dict[str, Any]
    signals: dict[str, np.ndarray] = field(default_factory=dict)
    replaced: dict[str, np.ndarray] = field(default_factory=dict)
    terms: ModelTerms | None = None


@dataclass(frozen=True)
class ModelSpec:
    """The model of one iteration: its stochastic terms and the effects fitted so far."""

    terms: ModelTerms = field(default_factory=ModelTerms)
    fitted: tuple[FittedEffect, ...] = ()

    def with_effect(self, fitted: FittedEffect) -> ModelSpec:
        """This model with ``fitted`` added (its stochastic terms joined to the current ones)."""
        extra = fitted.terms or ModelTerms()
        terms = ModelTerms(
            ar_order=max(self.terms.ar_order, extra.ar_order), flicker=self.terms.flicker or extra.flicker
        )
        return ModelSpec(terms, (*self.fitted, fitted))


class Residuals(Mapping[str, np.ndarray]):
    """``cleaned[axis]`` minus the axis's fitted bias, made when asked: a long recording does not hold a
    second record-length array per axis. The array last made is handed out again (read-only) while its
    user still holds it, and freed when nobody does."""

    def __init__(self, cleaned: Mapping[str, np.ndarray], biases: Mapping[str, float]) -> None:
        self._cleaned = cleaned
        self._biases = dict(biases)
        self._last: tuple[str, weakref.ref[np.ndarray]] | None = None

    def __getitem__(self, axis: str) -> np.ndarray:
        held = self._last[1]() if self._last is not None and self._last[0] == axis else None
        if held is not None:
            return held
        residual = self.fresh(axis)
        residual.setflags(write=False)
        self._last = (axis, weakref.ref(residual))
        return residual

    def fresh(self, axis: str) -> np.ndarray:
        """The residual of ``axis`` in a new, writable array that nothing else holds (the same values as
        ``self[axis]``), for a caller that transforms it in place."""
        return np.subtract(self._cleaned[axis], self._biases[axis], dtype=np.float64)

    def __iter__(self) -> Iterator[str]:
        return iter(self._biases)

    def __len__(self) -> int:
        return len(self._biases)


@dataclass(frozen=True)
class ResidualView:
    """The residual of each axis under one model.

    ``cleaned`` is the recording with the fitted effects removed; ``residuals`` is ``cleaned`` minus the
    fitted bias (:class:`Residuals`, made per axis when asked); ``fits`` holds each axis's
    :class:`~carousel_theory.closed_loop.residual_model.ResidualFit`.
    """

    axes: tuple[str, ...]
    time: np.ndarray
    sample_rate: float
    temperature: np.ndarray | None
    spec: ModelSpec
    cleaned: dict[str, np.ndarray]
    residuals: Residuals = field(compare=False)
    fits: dict[str, ResidualFit]
    #: Fits of the same axes with other terms, made on demand (see linear_statistics.fit_with_terms).
    other_fits: dict[tuple[str, ModelTerms], ResidualFit] = field(
        default_factory=dict, compare=False, repr=False
    )


def local_median_replacement(x: np.ndarray, mask: np.ndarray, half_width: int = 7) -> np.ndarray:
    """x with the masked samples replaced by the median of the unmasked samples within ±half_width."""
    if not mask.any():
        return x
    result = x.copy()
    padded = np.pad(np.where(mask, np.nan, x), half_width, mode="edge")
    windows = np.lib.stride_tricks.sliding_window_view(padded, 2 * half_width + 1)
    where = np.flatnonzero(mask)
    selected = windows[where]
    # Inside a long flagged run (a bump) a window holds no unmasked sample: interpolate linearly there.
    empty = np.all(np.isnan(selected), axis=1)
    local = np.empty(len(where))
    if (~empty).any():
        local[~empty] = np.nanmedian(selected[~empty], axis=1)
    kept = np.flatnonzero(~mask)
    if empty.any():
        local[empty] = np.interp(where[empty], kept, x[kept]) if len(kept) else 0.0
    result[where] = local
    return result


def _cleaned_axis(values: np.ndarray, axis: str, fitted: tuple[FittedEffect, ...]) -> np.ndarray:
    mask = np.zeros(len(values), dtype=bool)
    for effect in fitted:
        if axis in effect.replaced:
            mask |= effect.replaced[axis]
    for effect in fitted:
        if axis in effect.signals:
            values = values - effect.signals[axis]
    return local_median_replacement(values, mask)


def build_view(recording: Recording, axes: tuple[str, ...], spec: ModelSpec) -> ResidualView:
    """The recording's axes with ``spec``'s effects removed, each fitted with ``spec``'s terms."""
    cleaned = {axis: _cleaned_axis(recording.rates[axis], axis, spec.fitted) for axis in axes}
    for axis in axes:  # e.g. a column that is nothing but spikes on a constant
        check_noise_signal(cleaned[axis], f"{recording.source}: column {axis!r} once its effects are removed")
    fits = {axis: fit_residual_model(cleaned[axis], recording.sample_rate, spec.terms) for axis in axes}
    residuals = Residuals(cleaned, {axis: fits[axis].bias for axis in axes})
    return ResidualView(
        axes, recording.time, recording.sample_rate, recording.temperature, spec, cleaned, residuals, fits
    )
