"""The AR autocovariance as a sum of geometric modes, and its fourth sum in closed form at any argument.

Setting (:mod:`carousel_theory.noise_model`, :mod:`carousel_theory.increment_sums`). For an AR(p) process
y_t = Σ_j φ_j y_{t−j} + e_t at unit innovation variance whose characteristic polynomial
z^p − Σ_j φ_j z^{p−j} has distinct non-zero roots λ_i (|λ_i| < 1):

    γ(k) = Σ_i A_i λ_i^{|k|}   for every integer k.

The Yule–Walker recursion γ(k) = Σ_j φ_j γ(k − j) holds for k ≥ 1 and reaches back to γ(1 − p), so the
sequence γ(1 − p), γ(2 − p), … solves the homogeneous recursion and is a sum of the modes λ_i^k; the p
values γ(0 … p − 1) fix the A_i (a Vandermonde system). The increments z_t = y_t − y_{t−1} then have, for
|k| ≥ 1, γ_z(k) = 2γ(k) − γ(k − 1) − γ(k + 1) = Σ_i b_i λ_i^{|k|}, b_i = A_i (2 − λ_i − 1/λ_i).

Fourth sum. H(x) = Σ_k γ_z(k) R₃(x − k), R₃(y) = C(y + 3, 3) for y ≥ −3 and 0 below, equals, at every
integer x,

    H(x) = S · H_w(x) + Σ_i C_i λ_i^{|x + 2|},   H_w(x) = −max(x + 2, 0),
    S = 1/(1 − Σ_j φ_j)²,   C_i = b_i λ_i²/(1 − λ_i)⁴ = −A_i λ_i/(1 − λ_i)².

H_w is the fourth sum of white noise of unit variance (γ_z = 2, −1), and S = Σ_k γ(k) the long-run
variance: at long τ an AR term looks like white noise of variance S, and the modes are the correction,
which decays geometrically away from x = −2. Proof. For x ≤ −1 only k ≤ x < 0 contribute (R₃ vanishes at
−1, −2, −3): H(x) = Σ_{j≥0} γ_z(x − j) C(j + 3, 3) = Σ_i b_i λ_i^{−x} Σ_j C(j + 3, 3) λ_i^j =
Σ_i b_i λ_i^{−x}/(1 − λ_i)⁴, and −x = |x + 2| + 2 for x ≤ −2 (at x = −1 the two sides agree by the
next line). For x ≥ −3, R₃(x − k) = p(x − k) with p(y) = (y + 1)(y + 2)(y + 3)/6 except where x − k ≤ −4,
so H(x) = Σ_k γ_z(k) p(x − k) − Σ_{k ≥ x+4} γ_z(k) p(x − k). The first sum is the Taylor form
Σ_r (−1)^r M_r p^{(r)}(x)/r! with the moments M_r = Σ_k k^r γ_z(k): M_0 = 0 (γ_z sums differences),
M_1 = M_3 = 0 (γ_z even) and M_2 = Σ_k γ(k)(2k² − (k + 1)² − (k − 1)²) = −2S, so it is −S(x + 2). In the
second, p(−4 − j) = −C(j + 3, 3) and k ≥ 1, so it adds Σ_i b_i λ_i^{x+4}/(1 − λ_i)⁴ = Σ_i C_i λ_i^{x+2}.
∎ (At 50 digits in ``proofs/proof_ar_modal_fourth_sum.py``; :func:`fourth_sum_of_modes` is held to the
fourth cumulative sum of the truncated γ_z in the tests.)

Between the integers. The lag quadrature needs H at Gauss nodes: on each side of x = −2 the modal part
is continued analytically, G(j) = Re Σ_i C_i exp(j Log λ_i), j = |x + 2| (real at the integers, where it
is the sum above), whose p-th derivative is at most Σ_i |C_i| |Log λ_i|^p |λ_i|^j
(:func:`mode_derivative_bound`). A mode that turns faster than it decays (|arg λ_i| > −log|λ_i|: a
negative root, or a complex pair of high frequency) makes that bound useless for Gauss blocks while the
mode is alive; :attr:`ArModes.rough_reach` is how far from x = −2 such modes stay above
``AR_TRUNCATION`` (relative), and the quadrature sums every lag out to it.

When the roots are not well separated (a Vandermonde system too ill-conditioned to give A_i to about
1e-12), or a root is zero, :func:`ar_modes` returns None and the caller keeps the truncated γ_z.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from carousel_theory.noise_model import AR_TRUNCATION, ar_autocovariance

__all__ = ["ArModes", "ar_modes", "fourth_sum_of_modes", "mode_derivative_bound", "underflow_distance"]

#: The modes are kept when A_i reproduce γ(0 … 2p + 7) to this fraction of Σ|A_i| and Σ|A_i| ≤
#: ``_LARGEST_CANCELLATION`` · γ(0).
_RECONSTRUCTION = 1e-12
_LARGEST_CANCELLATION = 1e4
_CHECKED_LAGS = 8
#: exp(−746) rounds to 0 in double precision.
_UNDERFLOW = 746.0


@dataclass(frozen=True)
class ArModes:
    """The modes λ_i (complex), the weights C_i of the fourth sum (complex, unit innovation variance), the
    long-run variance S = 1/(1 − Σφ)², and how far the rough modes reach (module text)."""

    roots: np.ndarray
    weights: np.ndarray
    long_run_variance: float
    rough_reach: int

    @property
    def real(self) -> bool:
        """Every root real and positive: the modal sum is evaluated in real arithmetic."""
        return bool(np.all(self.roots.imag == 0) and np.all(self.roots.real > 0))


@functools.lru_cache(maxsize=64)
def ar_modes(coefficients: tuple[float, ...]) -> ArModes | None:
    """:class:`ArModes` of the AR coefficients, or None where the modal form is not accurate (module
    text)."""
    phi = np.asarray(coefficients, dtype=np.float64)
    if not len(phi) or phi[-1] == 0.0:
        return None
    roots = np.roots(np.concatenate(([1.0], -phi))).astype(np.complex128)
    if np.any(np.abs(roots) >= 1.0) or np.any(roots == 0.0):
        return None
    order = len(phi)
    gamma = ar_autocovariance(tuple(float(c) for c in coefficients), 2 * order + _CHECKED_LAGS)
    powers = roots[None, :] ** np.arange(len(gamma))[:, None]
    try:
        amplitudes = np.linalg.solve(powers[:order], gamma[:order].astype(np.complex128))
    except np.linalg.LinAlgError:
        return None
    magnitude = float(np.sum(np.abs(amplitudes)))
    error = float(np.max(np.abs(powers @ amplitudes - gamma)))
    if error > _RECONSTRUCTION * magnitude or magnitude > _LARGEST_CANCELLATION * float(gamma[0]):
        return None
    weights = -amplitudes * roots / (1.0 - roots) ** 2
    rough = np.abs(np.angle(roots)) > -np.log(np.abs(roots))
    reach = 0
    if np.any(rough):
        slowest = float(np.max(np.abs(roots[rough])))
        reach = order + 2 + int(math.log(AR_TRUNCATION) / math.log(slowest))
    return ArModes(roots, weights, 1.0 / (1.0 - float(np.sum(phi))) ** 2, reach)


def underflow_distance(modes: ArModes) -> float:
    """The j beyond which every |λ_i|^j rounds to 0 (j log|λ_i| < −746)."""
    return _UNDERFLOW / float(np.min(-np.log(np.abs(modes.roots))))


def fourth_sum_of_modes(modes: ArModes, distance: np.ndarray) -> np.ndarray:
    """G(j) = Re Σ_i C_i λ_i^j at j = |x + 2| ≥ 0, any real j (unit innovation variance). Where every
    |λ_i|^j is below the smallest double (j log|λ_i| < −746) the value is the 0 the exponentials give,
    without forming them."""
    j = np.asarray(distance, dtype=np.float64)
    result = np.zeros(j.shape)
    alive = j < underflow_distance(modes)
    points = j[alive]
    if modes.real:
        for root, weight in zip(modes.roots.real.tolist(), modes.weights.real.tolist(), strict=True):
            result[alive] += weight * np.exp(points * math.log(root))
        return result
    for root, weight in zip(modes.roots.tolist(), modes.weights.tolist(), strict=True):
        result[alive] += np.real(weight * np.exp(points * np.log(root)))
    return result


def mode_derivative_bound(modes: ArModes, distance: np.ndarray, order: int) -> np.ndarray:
    """Σ_i |C_i| |Log λ_i|^p |λ_i|^j / p! ≥ |G^{(p)}(j')|/p! for every j' ≥ j (module text)."""
    j = np.asarray(distance, dtype=np.float64)
    logs = np.log(modes.roots)
    scale = np.abs(modes.weights) * np.abs(logs) ** order / math.factorial(order)
    return np.exp(j[..., None] * np.log(np.abs(modes.roots))) @ scale
