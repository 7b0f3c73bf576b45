"""Weight vectors of the linear statistics of TIM 2014 §III: plain averaging and carouseling.

One bin (one carouseling revolution, or one averaging block) of N samples is reduced to a single
number by a weight vector:

- plain averaging, the integrator vector of eq. (12): ``1 = (1/N) [1 … 1]ᵀ``;
- carouseling, the coefficient vectors of eq. (13): ``s_i = sin(2π i/N) / N`` and
  ``c_i = cos(2π i/N) / N`` for i = 1 … N (sample i of the bin is taken at angle φ_i = 2π i/N).

Sign convention (eq. (5)–(6)): the carouselled estimate of the bin is
``ω̂ = Σ_i (−ω_x,i sin φ_i + ω_y,i cos φ_i) / N = −sᵀ ω_x + cᵀ ω_y``: the x gyro enters with the
weights −s and the y gyro with +c. The vectors returned here are s and c themselves (positive sine
and cosine), as printed in (13); the minus sign belongs to the estimator, and it does not change any
variance (Var(−sᵀx) = Var(sᵀx)).

For real rotations the angles are not uniform: :func:`carousel_weights_from_angles` gives
``s_i = sin φ_i / n``, ``c_i = cos φ_i / n`` for any measured angles φ_1 … φ_n of one bin.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from carousel_theory._validation import check_finite_array, check_positive_integer

__all__ = ["averaging_weights", "carousel_weights", "carousel_weights_from_angles", "unit_circle_points"]


def averaging_weights(N: int) -> np.ndarray:
    """The integrator vector of TIM 2014 eq. (12): N entries equal to 1/N."""
    N = check_positive_integer("N", N)
    return np.full(N, 1.0 / N)


def unit_circle_points(N: int) -> tuple[np.ndarray, np.ndarray]:
    """sin(2π i/N) and cos(2π i/N) for i = 1 … N, with the symmetries of the circle kept exactly.

    The angle is reduced with integers to a quadrant q and an offset θ = (π/2)(4i mod N)/N in
    [0, π/2) before any rounding, so that sin and cos vanish exactly at multiples of π/2 and, for
    even N, the entries i and i + N/2 are exact opposites in floating point too (the "N/2 pairs of
    opposite numbers" of TIM 2014 §III-D). ``np.sin(2π i/N)`` would give 1.2e-16 instead of 0 at
    i = N/2 and break both.
    """
    N = check_positive_integer("N", N)
    i = np.arange(1, N + 1, dtype=np.int64) % N
    quadrant, remainder = np.divmod(4 * i, N)
    theta = (np.pi / 2) * (remainder / N)
    sin_theta, cos_theta = np.sin(theta), np.cos(theta)
    # sin(qπ/2 + θ), cos(qπ/2 + θ) for q = 0, 1, 2, 3
    sine = np.choose(quadrant, [sin_theta, cos_theta, -sin_theta, -cos_theta])
    cosine = np.choose(quadrant, [cos_theta, -sin_theta, -cos_theta, sin_theta])
    return sine, cosine


def carousel_weights(N: int) -> tuple[np.ndarray, np.ndarray]:
    """The carouseling coefficient vectors (s, c) of TIM 2014 eq. (13), i = 1 … N.

    ``s_i = sin(2π i/N) / N``, ``c_i = cos(2π i/N) / N``; the estimate of one revolution is
    ``−sᵀ ω_x + cᵀ ω_y`` (eq. (5)–(6), see the module docstring for the sign).
    """
    sine, cosine = unit_circle_points(N)
    return sine / N, cosine / N


def carousel_weights_from_angles(phi: Any) -> tuple[np.ndarray, np.ndarray]:
    """Carouseling weights (s, c) for arbitrary per-sample rotation angles φ_1 … φ_n (rad) of one bin.

    ``s_i = sin φ_i / n``, ``c_i = cos φ_i / n``: the estimate of the bin is
    ``(1/n) Σ_i (−ω_x,i sin φ_i + ω_y,i cos φ_i) = −sᵀ ω_x + cᵀ ω_y`` (TIM 2014 eq. (5), averaged
    as in eq. (6) but at the measured angles instead of 2π i/N). With φ_i = 2π i/N this is
    :func:`carousel_weights` up to rounding.
    """
    angles = check_finite_array("phi", phi)
    n = angles.shape[0]
    return np.sin(angles) / n, np.cos(angles) / n
