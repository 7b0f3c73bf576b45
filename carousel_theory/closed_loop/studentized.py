"""The null distribution of a trend detector's studentized statistic, by parametric bootstrap.

A trend detector (warm-up, temperature, steps) computes a GLS linear statistic L = Σ w_t e_t of the
residual and studentizes it by the variance its fitted noise model gives, z = L / √V(θ̂) with
V(θ) = Σ_i θ_i u_i(w) (:func:`~carousel_theory.closed_loop.residual_model.statistic_variance_units`;
θ the short noise's long-run variance, the walk and the 1/f variance, TIM 2014 eqs. (2)–(3)). Given θ,
L is exactly N(0, V(θ)) under the model; the uncertainty of θ̂ is what makes z heavier-tailed than
N(0, 1), by a lot when a fitted 1/f term and the walk share the long τ (se(V̂)/V̂ of 0.5 and more on a
one-hour record). The reference of z is therefore drawn from the fitted model (a parametric bootstrap
of the studentized statistic, Efron & Tibshirani 1993 §12.5; Davison & Hinkley 1997 §5.2.1):

- each replicate k draws the Allan-variance vector of the fitted model at the fit's τ
  (:class:`~carousel_theory.closed_loop.calibration.AllanVarianceSampler`, the long τ exactly from block
  sums) and refits the same terms to it by the fitter's own non-negative GLS under the fit's covariance
  across τ, giving θ̂*_k and V*_k = V(θ̂*_k);
- the Gaussian part is integrated exactly (conditional Monte Carlo): given V*_k,
  P(|L*| ≥ c √V*_k) = 2Φ̄(c √(V*_k / V₀)), V₀ = V(θ̂) the variance of L in the bootstrap world, so
  p(c) = mean_k 2Φ̄(c √(V*_k / V₀)), smooth in c and accurate far in the tail from a few hundred
  replicates (a count of exceedances would need 1/p of them).

**L and the Allan variances.** L is linear and the Allan variances are quadratic in the same Gaussian
record: uncorrelated, not independent. The dependence is carried to first order exactly. Write
e = s √V₀ · u / V₀ + e⊥ with u = Σw (:func:`~carousel_theory.closed_loop.residual_model.covariance_product`),
s = L/√V₀ ~ N(0, 1) and e⊥ independent of s. The series the noise is fitted to is r = e (steps) or
r = e − (L/I) g for a regressor g refitted jointly (warm-up, temperature; I = Σ w_t g_t), i.e.
r = e⊥ + (s/√V₀) h with h = u or h = u − (V₀/I) g. The Allan variance is then
A(r) = A(e⊥) + (2s/√V₀) B(e⊥, h) + (s²/V₀) A(h), and E A(e⊥) = E A(e) − A(u)/V₀ exactly (A of a fixed
vector through the same estimator). The GLS map being linear (apart from its non-negativity), the
fitted variance is, to first order, V̂ = V̂⊥ + s² δ_h with V̂⊥ distributed as V*_k − δ_u, δ_x the V of
the GLS fit of A(x)/V₀. The rejection event s² V₀ ≥ c² (V*_k − δ_u + s² δ_h) then has the exact
conditional probability 2Φ̄(c √((V*_k − δ_u)⁺ / (V₀ − c² δ_h))) (0 when c² δ_h ≥ V₀: a statistic
whose variance grows with L² cannot pass √(V₀/δ_h)). What is left out is second order: the zero-mean
cross term B(e⊥, h), whose spread makes the test slightly liberal, and the variance A(e) has over A(e⊥),
which makes it slightly conservative. benchmarks/bench_loop_detection.py (section ``calibration``)
measures the size of every trend detector against whole simulated records.

**At the boundary.** A parametric bootstrap from a fit whose walk (or 1/f) variance is 0, or within
sampling error of 0, draws records in which that term is nearly always fitted as 0 again, and so
understates how far V(θ̂) can fall below V(θ) (Andrews 2000, Econometrica 68, 399: the bootstrap is
inconsistent at the boundary of the parameter space). The replicates are therefore drawn from the
fitted model with the walk and the 1/f variance each raised to at least BOUNDARY_ERRORS = 2 of its GLS
standard errors (the model is moved off the boundary by the amount the data cannot rule out; in the
interior, where a variance exceeds 2 standard errors, nothing changes); V₀ is then that model's
variance of L, and the observed z keeps V(θ̂). The rule is a choice, not a derivation: its effect on
the size is what the benchmark's calibration section measures.

The weights w are held at the observed fit's (as the 1/f detector holds its covariance across τ).
Replicates come from :func:`~carousel_theory.closed_loop.calibration.bootstrap_generator`, seeded by a
digest of the observed Allan variances and L, so a recording always gets the same decision.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from scipy import optimize, special, stats

from carousel_theory.closed_loop.calibration import (
    TREND_STREAM,
    AllanVarianceSampler,
    bootstrap_generator,
    octave_allan,
)
from carousel_theory.closed_loop.residual_model import (
    FittedNoise,
    ResidualFit,
    covariance_product,
    noise_variances,
    statistic_variance_units,
)
from carousel_theory.fitting import COMPONENT_OF_PARAMETER, generalized_least_squares
from carousel_theory.noise_model import term_allan_variance

__all__ = [
    "BOUNDARY_ERRORS",
    "REPLICATES",
    "SQUARE_GRID",
    "AllanRefit",
    "StudentizedReference",
    "allan_of_vector",
    "off_boundary",
    "studentized_reference",
]

#: Bootstrap replicates of the fitted variance per test.
REPLICATES = 500
#: A walk or 1/f variance fitted below this many of its standard errors is raised to it in the model the
#: replicates are drawn from (module docstring).
BOUNDARY_ERRORS = 2.0
#: Largest |z| searched for a threshold.
_LARGEST_Z = 60.0


def allan_of_vector(values: np.ndarray, sizes: np.ndarray) -> np.ndarray:
    """The non-overlapping octave Allan variance of ``values`` at ``sizes`` (consecutive octaves), the
    estimator the fit uses (:func:`~carousel_theory.closed_loop.calibration.octave_allan`)."""
    block = int(sizes[0])
    count = len(values) // block
    sums = values[: count * block].reshape(count, block).sum(axis=1)
    return octave_allan(sums, len(sizes), block)


@dataclass(frozen=True)
class AllanRefit:
    """The GLS refit of an Allan-variance vector at the τ of a fit, with the same terms, its covariance
    across τ held, and the variance V(θ̂) of a linear statistic it implies: V = Σ_j θ̂_j c_j, c_j the
    statistic's unit variance of the variance parameter j (the AR innovation variance scaled to its
    long-run value)."""

    design: np.ndarray
    cholesky: np.ndarray
    coefficients: np.ndarray

    @classmethod
    def from_fit(cls, fit: ResidualFit, unit_variances: dict[str, float]) -> AllanRefit:
        model = fit.noise.model
        ar = model.ar_coefficients
        gain = 1.0 / (1.0 - sum(ar)) ** 2 if ar else 1.0
        columns, coefficients = [], []
        for parameter in fit.result.parameters:
            component = COMPONENT_OF_PARAMETER[parameter]
            columns.append(term_allan_variance(component, fit.sizes, model.flicker_d, ar_coefficients=ar))
            name = "flicker_variance" if component == "flicker" else "rrw_variance"
            if component in ("white", "ar"):
                name = "long_run_white_variance"
            coefficients.append(unit_variances.get(name, 0.0) * (gain if component == "ar" else 1.0))
        cholesky = np.linalg.cholesky(np.asarray(fit.result.tau_covariance, dtype=np.float64))
        return cls(np.column_stack(columns), cholesky, np.array(coefficients))

    def variance(self, allan: np.ndarray) -> float:
        """V(θ̂) of the non-negative GLS fit of ``allan`` (the fitter's own least-squares step)."""
        theta, _, _ = generalized_least_squares(self.design, allan, self.cholesky)
        return float(np.dot(theta, self.coefficients))

    def linear_variance(self, allan: np.ndarray) -> float:
        """V of the unconstrained GLS fit of ``allan``: the first-order (linear) part of the fit."""
        whitened = np.linalg.solve(self.cholesky, self.design)
        theta = np.linalg.lstsq(whitened, np.linalg.solve(self.cholesky, allan), rcond=None)[0]
        return float(np.dot(theta, self.coefficients))


#: Values of s² = L²/V₀ at which each replicate's fitted variance is evaluated (module docstring); the
#: tail the loop's tests use lies at s² ≈ 16 … 50.
SQUARE_GRID = (0.0, 9.0, 25.0, 49.0, 100.0)


@dataclass(frozen=True)
class StudentizedReference:
    """The bootstrap reference of z = L/√V(θ̂) (module docstring): ``profiles[k, i]`` is replicate k's
    fitted variance over V₀ = ``variance`` when s² = L²/V₀ = SQUARE_GRID[i], linear between the grid
    points and beyond the last two."""

    variance: float
    profiles: np.ndarray

    @property
    def dependence(self) -> float:
        """The median over replicates of d(V̂/V₀)/d(s²) across the grid: how much the fitted variance
        grows with L² (0 when L and the Allan variances were independent)."""
        grid = np.asarray(SQUARE_GRID)
        return float(np.median((self.profiles[:, -1] - self.profiles[:, 0]) / (grid[-1] - grid[0])))

    def _crossing(self, z: float) -> np.ndarray:
        """Per replicate, the least s² with s² ≥ z² V̂(s)/V₀ (∞ when the profile never allows it)."""
        grid, square = np.asarray(SQUARE_GRID), z * z
        gap = grid[np.newaxis, :] - square * self.profiles  # s² − z² V̂/V₀ at the grid, < 0 at s² = 0
        reached = gap >= 0.0
        first = np.where(reached.any(axis=1), reached.argmax(axis=1), len(grid))
        crossing = np.full(len(gap), np.inf)
        inside = (first > 0) & (first < len(grid))
        rows, upper = np.flatnonzero(inside), first[inside]
        low, high = gap[rows, upper - 1], gap[rows, upper]
        crossing[rows] = grid[upper - 1] + (grid[upper] - grid[upper - 1]) * (-low / (high - low))
        slope = (gap[:, -1] - gap[:, -2]) / (grid[-1] - grid[-2])
        beyond = (first == len(grid)) & (slope > 0.0)
        crossing[beyond] = grid[-1] - gap[beyond, -1] / slope[beyond]
        crossing[first == 0] = 0.0
        return crossing

    def log_sf(self, z: float) -> float:
        """log P*(|z*| ≥ |z|) = log mean_k 2Φ̄(√s²_k), s²_k replicate k's crossing point."""
        crossing = self._crossing(abs(z))
        finite = crossing[np.isfinite(crossing)]
        if not len(finite):
            return -math.inf
        terms = math.log(2.0) + stats.norm.logsf(np.sqrt(finite))
        return float(special.logsumexp(terms)) - math.log(len(crossing))

    def log10_p(self, z: float, tests: int) -> float:
        """log10 of the p-value of |z|, Bonferroni over ``tests``."""
        return min(0.0, (math.log(max(tests, 1)) + self.log_sf(z)) / math.log(10.0))

    def threshold(self, alpha: float, tests: int) -> float:
        """The |z| at which the Bonferroni p-value is ``alpha`` (∞ when none reaches it)."""
        target = math.log(alpha / max(tests, 1))
        if self.log_sf(_LARGEST_Z) > target:
            return math.inf
        return float(optimize.brentq(lambda z: self.log_sf(z) - target, 0.0, _LARGEST_Z, xtol=1e-6))


def off_boundary(noise: FittedNoise) -> FittedNoise:
    """``noise`` with the walk and the 1/f variance each raised to at least BOUNDARY_ERRORS of its GLS
    standard errors (module docstring); unchanged where they are already above."""
    errors, model = noise.standard_errors, noise.model

    def raised(name: str) -> float:
        value, error = float(getattr(model, name)), errors.get(name, math.nan)
        return max(value, BOUNDARY_ERRORS * error) if math.isfinite(error) else value

    walk, flicker = raised("rrw_variance"), raised("flicker_variance")
    if (walk, flicker) == (model.rrw_variance, model.flicker_variance):
        return noise
    return replace(noise, model=replace(model, rrw_variance=walk, flicker_variance=flicker))


def studentized_reference(
    noise: FittedNoise,
    fit: ResidualFit,
    length: int,
    weights: np.ndarray,
    projection: float,
    regressor: np.ndarray | None = None,
) -> StudentizedReference:
    """The bootstrap reference of L/√V(θ̂) for ``weights`` under ``noise``, the variances refitted as
    ``fit`` was (its terms, τ and covariance across τ); ``regressor`` g when the noise was refitted on the
    residual minus the fitted (L/I) g, else None (module docstring)."""
    fitted_flicker = "flicker_variance" in fit.result.parameters
    unit_variances = statistic_variance_units(noise, weights, flicker=fitted_flicker)
    generating = off_boundary(noise)
    values = noise_variances(generating)
    variance = sum(values[name] * unit for name, unit in unit_variances.items())
    refit = AllanRefit.from_fit(fit, unit_variances)
    sampler = AllanVarianceSampler.from_model(generating, fit, length)
    rng = bootstrap_generator(TREND_STREAM, [fit.observed, np.array([projection, variance])])
    direction = covariance_product(generating, weights)
    shift = allan_of_vector(direction, fit.sizes) / variance
    if regressor is not None:
        direction -= (variance / float(np.dot(weights, regressor))) * regressor
    tilt = allan_of_vector(direction, fit.sizes) / variance
    profiles = np.empty((REPLICATES, len(SQUARE_GRID)))
    for k in range(REPLICATES):
        base = sampler.draw(rng) - shift
        profiles[k] = [refit.variance(base + square * tilt) for square in SQUARE_GRID]
    return StudentizedReference(variance, profiles / variance)
