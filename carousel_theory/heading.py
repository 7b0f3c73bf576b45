"""Heading (north-finding) error from the covariance of the horizontal Earth-rate estimate.

At latitude L the Earth rate has the horizontal component Ω cos L (Ω = 7.292115·10⁻⁵ rad/s, WGS 84)
pointing north. With the base frame's x axis at heading ψ (clockwise from north, z up) the true
horizontal rate in base coordinates is ``E = Ω cos L (cos ψ, −sin ψ)``, and the heading estimate is
``ψ̂ = atan2(−Ê_y, Ê_x)`` (TIM 2014 §I: gyrocompassing, the application carouseling serves).

- Linearised: ∂ψ/∂E = (E_y, −E_x)/|E|², a vector across E of length 1/|E|, so
  ``σ_ψ² = Var(the component of Ê across E) / |E|²`` and a bias δ of Ê moves ψ̂ by (∂ψ/∂E)·δ.
- Exact: Ê is Gaussian (the estimate is linear in Gaussian processes), so ψ̂ has the projected-normal
  density ``f(θ) = e^{−C/2} / (2π √det Σ · A) · [1 + (B/√A) Φ(B/√A)/φ(B/√A)]`` with u = (cos θ, sin θ),
  A = uᵀΣ⁻¹u, B = uᵀΣ⁻¹μ, C = μᵀΣ⁻¹μ (μ, Σ: mean and covariance of (Ê_x, −Ê_y)); the root-mean-square
  error ``(∫ (θ − ψ)² f dθ)^{1/2}`` over θ − ψ ∈ (−π, π] comes by quadrature. A seeded Monte Carlo of
  atan2 checks it (:func:`heading_monte_carlo`).

The linearisation holds while the cross-track standard deviation is small next to |E|; it fails
(the errors wrap around ±180°, the RMS saturates near π/√3 ≈ 104°) as σ/|E| grows — see
:func:`linearisation_ratio` and ``docs/rotation_schemes.md``.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.integrate
import scipy.special

from carousel_theory._validation import check_finite_array, check_positive_integer, check_real

__all__ = [
    "EARTH_RATE",
    "HeadingError",
    "check_latitude",
    "heading_error",
    "heading_monte_carlo",
    "horizontal_earth_rate",
    "linearisation_ratio",
]

#: The Earth's rotation rate Ω (rad/s), WGS 84.
EARTH_RATE = 7.292115e-5


def check_latitude(latitude_deg: Any) -> float:
    """A latitude in degrees strictly between −90° and 90°; at ±90° the horizontal Earth rate vanishes."""
    value = float(check_real("latitude", latitude_deg))
    if abs(value) > 90:
        raise ValueError(f"latitude={latitude_deg!r}: must lie in [-90, 90] degrees")
    if abs(value) == 90:
        raise ValueError(
            f"latitude={latitude_deg!r}: must be strictly between -90 and 90 degrees "
            "(at a pole the horizontal Earth rate is zero and the heading is undefined)"
        )
    return value


def horizontal_earth_rate(latitude_deg: Any, heading_deg: Any = 0.0) -> np.ndarray:
    """E = Ω cos L (cos ψ, −sin ψ) in base coordinates (rad/s)."""
    latitude = math.radians(check_latitude(latitude_deg))
    heading = math.radians(float(check_real("heading", heading_deg)))
    magnitude = EARTH_RATE * math.cos(latitude)
    return magnitude * np.array([math.cos(heading), -math.sin(heading)])


@dataclass(frozen=True)
class HeadingError:
    """Heading error (rad) of a Gaussian horizontal Earth-rate estimate, linearised and exact.

    ``linearised_sigma``: √(gᵀΣg); ``linearised_bias``: g·δ; ``exact_rms`` and ``exact_mean``: root
    mean square and mean of the wrapped error ψ̂ − ψ under the projected-normal law (quadrature).
    """

    linearised_sigma: float
    linearised_bias: float
    exact_rms: float
    exact_mean: float

    def linearised_rms(self) -> float:
        """√(σ² + bias²) of the linearised error."""
        return math.hypot(self.linearised_sigma, self.linearised_bias)


def _check_covariance(covariance: Any) -> np.ndarray:
    matrix = check_finite_array("covariance", covariance, ndim=2)
    if matrix.shape != (2, 2) or not np.allclose(matrix, matrix.T, rtol=1e-12, atol=0):
        raise ValueError(f"covariance: must be a symmetric 2×2 matrix, got shape {matrix.shape}")
    if np.linalg.eigvalsh(matrix).min() <= 0:
        raise ValueError("covariance: must be positive definite (a zero variance leaves no heading error)")
    return matrix


def _angle_density(theta: np.ndarray, mean: np.ndarray, covariance: np.ndarray) -> np.ndarray:
    """The projected-normal density of the angle of a 2-D Gaussian (module docstring)."""
    inverse = np.linalg.inv(covariance)
    u = np.stack([np.cos(theta), np.sin(theta)])
    A = np.einsum("in,ij,jn->n", u, inverse, u)
    B = np.einsum("in,ij,j->n", u, inverse, mean)
    C = float(mean @ inverse @ mean)
    ratio = B / np.sqrt(A)
    # e^{−C/2}(1 + r Φ(r)/φ(r)) = e^{−C/2} + r √(2π) Φ(r) e^{(r² − C)/2}, with r² ≤ C (Cauchy–Schwarz):
    # no overflow of Φ/φ and no underflow of e^{−C/2} multiplying it
    body = math.exp(-C / 2) + ratio * math.sqrt(2 * math.pi) * scipy.special.ndtr(ratio) * np.exp(
        (ratio**2 - C) / 2
    )
    return body / (2 * math.pi * math.sqrt(np.linalg.det(covariance)) * A)


def heading_error(
    covariance: Any, latitude_deg: Any, heading_deg: Any = 0.0, bias: Any = (0.0, 0.0)
) -> HeadingError:
    """Heading error of Ê ~ N(E + bias, covariance) at latitude L and heading ψ, linearised and exact.

    Parameters
    ----------
    covariance
        2×2 covariance (rad/s)² of (Ê_x, Ê_y), e.g. ``EstimateCovariance.total()[:2, :2]``.
    latitude_deg, heading_deg
        L (strictly inside ±90°) and the true heading ψ of the base x axis, degrees.
    bias
        Systematic error δ (rad/s) of (Ê_x, Ê_y) from imperfections.
    """
    matrix = _check_covariance(covariance)
    offset = check_finite_array("bias", bias)
    if offset.shape != (2,):
        raise ValueError(f"bias={bias!r}: must hold 2 components")
    truth = horizontal_earth_rate(latitude_deg, heading_deg)
    gradient = np.array([truth[1], -truth[0]]) / float(truth @ truth)
    heading = math.radians(float(heading_deg))
    flip = np.diag([1.0, -1.0])  # ψ̂ is the angle of (Ê_x, −Ê_y)
    mean, covariance_flipped = flip @ (truth + offset), flip @ matrix @ flip
    scale = math.sqrt(float(gradient @ matrix @ gradient))
    centre = float(gradient @ offset)
    moments = [_wrapped_moment(power, heading, mean, covariance_flipped, centre, scale) for power in (1, 2)]
    return HeadingError(
        linearised_sigma=scale,
        linearised_bias=float(gradient @ offset),
        exact_rms=math.sqrt(moments[1]),
        exact_mean=moments[0],
    )


def _wrapped_moment(
    power: int, heading: float, mean: np.ndarray, covariance: np.ndarray, centre: float, scale: float
) -> float:
    """∫ e^power f(ψ + e) de over e ∈ (−π, π], split where the density is concentrated (centre ± 12 σ)."""

    def integrand(error: float) -> float:
        return error**power * float(_angle_density(np.array([heading + error]), mean, covariance)[0])

    edges = sorted({-math.pi, math.pi, *(min(max(centre + k * scale, -math.pi), math.pi) for k in (-12, 12))})
    return sum(
        scipy.integrate.quad(integrand, low, high, limit=400)[0] for low, high in itertools.pairwise(edges)
    )


def heading_monte_carlo(
    covariance: Any,
    latitude_deg: Any,
    *,
    rng: np.random.Generator,
    replicates: int,
    heading_deg: Any = 0.0,
    bias: Any = (0.0, 0.0),
) -> np.ndarray:
    """Wrapped heading errors ψ̂ − ψ ∈ (−π, π] of draws Ê ~ N(E + bias, covariance), through atan2."""
    if not isinstance(rng, np.random.Generator):
        raise TypeError(f"rng={rng!r}: must be a numpy.random.Generator, e.g. numpy.random.default_rng(seed)")
    replicates = check_positive_integer("replicates", replicates)
    matrix = _check_covariance(covariance)
    truth = horizontal_earth_rate(latitude_deg, heading_deg) + check_finite_array("bias", bias)
    draws = truth + rng.standard_normal((replicates, 2)) @ np.linalg.cholesky(matrix).T
    estimate = np.arctan2(-draws[:, 1], draws[:, 0])
    return np.angle(np.exp(1j * (estimate - math.radians(float(heading_deg)))))


def linearisation_ratio(relative_sigma: Any) -> float:
    """Exact RMS / linearised σ for an isotropic estimate with σ/|E| = ``relative_sigma`` (unbiased).

    1 in the small-noise limit; it falls below 1 as errors wrap (the exact RMS cannot exceed π).
    """
    value = float(check_real("relative_sigma", relative_sigma))
    if value <= 0:
        raise ValueError(f"relative_sigma={relative_sigma!r}: must be > 0")
    magnitude = EARTH_RATE * math.cos(math.radians(45.0))
    result = heading_error(np.eye(2) * (value * magnitude) ** 2, 45.0)
    return result.exact_rms / result.linearised_sigma
