"""Exact covariance of the Earth-rate estimate of any rotation scheme, for every record length at once.

The estimate Ω̂ of :mod:`carousel_theory.rotation_schemes` is linear in each gyro's error process:
component j gets ``Σ_t W[j, g, t] x_{g,t}`` from gyro g. For records of n samples (the first n of the
scheme) write ``U[j, t] = R_t[j, g] [t used]`` (so W = U/n_used), ``S_j(n) = Σ_{t<n} U[j, t]`` and
``P_j(i) = Σ_{t<i} U[j, t]``. With unit driving variance (TIM 2014 §II; multiply by the gyro's
per-sample variance) the covariance of components j and l is, before dividing by n_used²:

- bias, eq. (1) (a random constant per gyro):  ``S_j(n) S_l(n)``;
- white noise:  ``Σ_{t<n} U[j, t] U[l, t]``;
- rate random walk, eq. (2): ``Σ_{i<n} (S_j(n) − P_j(i)) (S_l(n) − P_l(i))``
  ``= n S_j S_l − S_j Σ_{i<n} P_l(i) − S_l Σ_{i<n} P_j(i) + Σ_{i<n} P_j(i) P_l(i)``
  — the suffix-sum form ``Σ_i (Σ_{t≥i} w_t)²`` of :func:`carousel_theory.propagation.weighted_sum_variance`
  expanded so that every n comes from cumulative sums: one O(n_max) pass for all lengths;
- 1/f noise, eq. (3): :func:`carousel_theory.propagation.weighted_sums_covariance` of the first n
  columns (one FFT, O(n log n), per length).

No (kN)×(kN) matrix is formed; the gyros' processes are independent of each other.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from carousel_theory._validation import check_positive_integer, check_positive_real
from carousel_theory.fitting import NoiseModel
from carousel_theory.propagation import weighted_sums_covariance
from carousel_theory.rotation_schemes import SchemePattern

__all__ = ["PROCESS_TERMS", "EstimateCovariance", "estimate_covariances", "unit_covariances"]

_QUARTER_TURN = np.array([[0.0, -1.0], [1.0, 0.0]])

#: The error processes whose covariances are reported, in this order.
PROCESS_TERMS = ("bias", "white", "rrw", "flicker")


@dataclass(frozen=True)
class EstimateCovariance:
    """Covariance of Ω̂ (rad/s)² after ``length`` samples, split by error process.

    Each matrix is (components × components), components being the base-frame axes x, y (and z).
    """

    length: int
    used: int
    bias: np.ndarray
    white: np.ndarray
    rrw: np.ndarray
    flicker: np.ndarray

    def total(self) -> np.ndarray:
        """The sum over processes (they are independent)."""
        return self.bias + self.white + self.rrw + self.flicker


def _sums_up_to(values: np.ndarray, lengths: np.ndarray) -> np.ndarray:
    """Σ_{t<n} values[..., t] for each n of the increasing, distinct ``lengths`` (segment sums, then a
    cumulative sum over the few segments: no array of n prefix sums is written)."""
    starts = np.concatenate([[0], lengths[:-1]])
    return np.cumsum(np.add.reduceat(values[..., : lengths[-1]], starts, axis=-1), axis=-1)


def _prefix_covariances(U: np.ndarray, lengths: np.ndarray) -> dict[str, np.ndarray]:
    """Unnormalised bias, white and RRW covariances for every length; shape (len(lengths), c, c)."""
    distinct, position = np.unique(lengths, return_inverse=True)
    U = U[:, : distinct[-1]]
    P = np.concatenate([np.zeros((U.shape[0], 1)), np.cumsum(U[:, :-1], axis=1)], axis=1)  # P(i) = Σ_{t<i}
    S_n = _sums_up_to(U, distinct)
    Q_n = _sums_up_to(P, distinct)
    c = U.shape[0]
    white = np.empty((c, c, distinct.shape[0]))
    squares = np.empty_like(white)
    for a in range(c):
        for b in range(a, c):
            white[a, b] = white[b, a] = _sums_up_to(U[a] * U[b], distinct)
            squares[a, b] = squares[b, a] = _sums_up_to(P[a] * P[b], distinct)
    outer = S_n[:, np.newaxis, :] * S_n[np.newaxis, :, :]
    rrw = (
        distinct * outer
        - S_n[:, np.newaxis, :] * Q_n[np.newaxis, :, :]
        - Q_n[:, np.newaxis, :] * S_n[np.newaxis, :, :]
        + squares
    )
    return {
        name: np.moveaxis(value, 2, 0)[position]
        for name, value in (("bias", outer), ("white", white), ("rrw", rrw))
    }


def _check_lengths(lengths: Any) -> np.ndarray:
    values = [check_positive_integer("length", value) for value in np.atleast_1d(lengths).tolist()]
    return np.asarray(values, dtype=np.int64)


def unit_covariances(
    pattern: SchemePattern, lengths: Any, gyro: int, d: float | None = None
) -> dict[str, np.ndarray]:
    """Covariances of Ω̂ from gyro ``gyro`` (0, 1, 2 = x, y, z) with unit driving variance, per process.

    Returns a dict process → array of shape (len(lengths), c, c), already divided by n_used²; the
    1/f entry is present only when ``d`` is given. Each length n uses the first n samples of the pattern.
    """
    lengths = _check_lengths(lengths)
    if lengths.max() > pattern.used.shape[0]:
        raise ValueError(f"lengths: must not exceed the pattern's {pattern.used.shape[0]} samples")
    U = pattern.rotations[:, : pattern.components, gyro].T * pattern.used
    counts = np.cumsum(pattern.used)[lengths - 1].astype(np.float64)
    if np.any(counts == 0):
        raise ValueError(f"lengths={lengths.tolist()!r}: a record must use at least one sample")
    scale = (1.0 / counts**2)[:, np.newaxis, np.newaxis]
    result = {name: value * scale for name, value in _prefix_covariances(U, lengths).items()}
    if d is not None:
        result["flicker"] = (
            np.stack([weighted_sums_covariance(U[:, :n], "flicker", d) for n in lengths.tolist()]) * scale
        )
    return result


def _per_gyro(
    pattern: SchemePattern, lengths: np.ndarray, models: list[NoiseModel]
) -> list[tuple[NoiseModel, dict[str, np.ndarray]]]:
    """(noise model, unit covariances) of each gyro that enters the estimate.

    About the vertical the y gyro's weights are J times the x gyro's (J = [[0, −1], [1, 0]]), so its
    covariances are J C Jᵀ of the x gyro's whenever both have the same 1/f order (or none); the z gyro
    never enters the horizontal estimate.
    """
    planar = pattern.components == 2 and bool(np.all(pattern.rotations[:, 2, 2] == 1.0))
    result: list[tuple[NoiseModel, dict[str, np.ndarray]]] = []
    for gyro in range(2 if planar else 3):
        model = models[min(gyro, len(models) - 1)]
        order = _order(model)
        if planar and gyro == 1 and order == _order(result[0][0]):
            unit = {name: _QUARTER_TURN @ value @ _QUARTER_TURN.T for name, value in result[0][1].items()}
        else:
            unit = unit_covariances(pattern, lengths, gyro, order)
        result.append((model, unit))
    return result


def _order(model: NoiseModel) -> float | None:
    return model.flicker_d if model.flicker_variance > 0 else None


def estimate_covariances(
    pattern: SchemePattern,
    lengths: Any,
    noise: Sequence[NoiseModel],
    bias_variance: float = 0.0,
) -> list[EstimateCovariance]:
    """The covariance of Ω̂ after each record length, for per-gyro noise models (gyros x, y, z).

    ``noise`` holds one :class:`carousel_theory.fitting.NoiseModel` per gyro (per-sample variances;
    a shorter sequence repeats its last model); ``bias_variance`` is the variance (rad/s)² of each
    gyro's turn-on bias, the random constant of TIM 2014 eq. (1).
    """
    lengths = _check_lengths(lengths)
    bias_variance = float(check_positive_real("bias_variance", bias_variance, allow_zero=True))
    models = list(noise)
    if not models or not all(isinstance(model, NoiseModel) for model in models):
        raise TypeError(
            f"noise={noise!r}: must be a non-empty sequence of carousel_theory.fitting.NoiseModel"
        )
    c = pattern.components
    totals = {name: np.zeros((lengths.shape[0], c, c)) for name in PROCESS_TERMS}
    for model, unit in _per_gyro(pattern, lengths, models):
        variances = {
            "bias": bias_variance,
            "white": model.white_variance,
            "rrw": model.rrw_variance,
            "flicker": model.flicker_variance,
        }
        for name in unit:
            totals[name] += variances[name] * unit[name]
    counts = np.cumsum(pattern.used)[lengths - 1]
    return [
        EstimateCovariance(int(n), int(count), *(totals[name][index] for name in PROCESS_TERMS))
        for index, (n, count) in enumerate(zip(lengths.tolist(), counts.tolist(), strict=True))
    ]
