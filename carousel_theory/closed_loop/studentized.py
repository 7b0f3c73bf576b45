"""The null distribution of a trend statistic studentized by its refitted noise model (parametric bootstrap).

A trend detector computes a GLS linear statistic L = Σ w_t e_t of the residual e and studentizes it by
the variance its fitted noise model gives, z = L / √V(θ̂), V(θ) = Σ_i θ_i u_i(w)
(:class:`~carousel_theory.closed_loop.residual_model.StatisticUnits`; θ the short noise's long-run
variance, the walk and the 1/f variance, TIM 2014 eqs. (2)–(3)). θ̂ is the fitter's non-negative GLS fit
of the Allan variance of r = e (no regressor) or r = e − (L/I) g (a regressor g refitted jointly,
I = Σ w_t g_t). Given θ, L ~ N(0, V(θ)); but θ̂ is estimated from the same record, and L and the Allan
variances are dependent (uncorrelated, both functions of one Gaussian record), so the reference of z is
drawn from the fitted model θ̂ itself (a parametric bootstrap; Davison & Hinkley 1997 §5.2.1), with the
observed z formed with V(θ̂) of the actual fit and the same map from record to z in every replicate.

**The exact structure.** Under a model θ with covariance Σ, write u = Σ w, V = wᵀ u and
e = (L/V) u + e⊥, e⊥ independent of L. Then r = e⊥ + (L/V) h with h = u − (V/I) g (h = u without a
regressor), and the Allan variance is A(r) = A(e⊥) + 2 (L/V) B(e⊥, h) + (L/V)² A(h): A(e⊥) quadratic and
B(e⊥, h) linear in e⊥, both drawn from one draw of e⊥. Each replicate k draws the record's block sums at
the first long τ (``block`` samples, the weights constant over these blocks) from θ̂ exactly
(:func:`~carousel_theory.closed_loop.residual_model.simulate_block_sum_draws`), forms L*, e⊥* = e* − (L*/V) u
and, *for every value of L*, the Allan variance A(r*(L)) at the long τ exactly, refits θ̂*(L) by the
fitter's non-negative GLS step under the fit's covariance across τ, and so knows the whole set
R_k(t) = {L : |L| > t √V(θ̂*(L))}. The Gaussian part is integrated exactly: P(|z*| > t) = mean_k P(L ∈ R_k(t)),
L ~ N(0, V) independent of e⊥*. The set is found on a grid of x = L/√V over [−X, X] (crossings
interpolated linearly), X = GRID_LIMIT where 2Φ̄(X) < 1e-32; the non-negative GLS solution at each x
is the one active set that satisfies the Kuhn–Tucker conditions (each is a quadratic in x).

**Short τ.** The Allan variances at τ with more than LONG_TAU_TERMS differences are drawn Gaussian given
the long ones (:class:`~carousel_theory.closed_loop.calibration.AllanVarianceSampler`) and held at their
value for the drawn L*: the part of L in them, (L/V)² A(h) and 2 (L/V) B(e⊥, h) at τ of a few samples, is of
relative size t²/n and t/√n against sampling errors of √(2/n) — left out. Whole simulated records
measure what these choices cost (benchmarks/bench_trend_reference.py, tests/test_trend_reference.py).

**At the boundary.** Drawn from θ̂ itself, the reference is that of a world whose walk (or 1/f) variance
is the fitted one; when the data cannot tell that variance from 0, θ̂ is 0 in about half the records and
the bootstrap is not consistent there (Andrews 2000, Econometrica 68, 399): the replicates' refitted
walk can only err upwards, while the record's erred downwards. ``generating`` lets the replicates be
drawn from another model (a walk raised off the boundary); the observed z keeps V(θ̂) of the actual fit.
What either choice does to the size is measured on whole records (benchmarks/bench_trend_reference.py):
drawn from θ̂, the reference rejects 0.077 [0.061, 0.095] at 0.05 on short records (327.68 s) with a walk
of 0.6 GLS standard errors; drawn from quantiles of a truncated-normal confidence distribution of the
walk, 0.028 (KS p 0.0036).

**A confidence-set p-value over the boundary nuisances** (:func:`boundary_reference`). The reference
p*(ν) is a function of the nuisance ν it is drawn from, and only ν near its boundary is at fault. With
γ a stated share of the test's level, C_γ a (1 − γ) confidence set for ν and
p = sup_{ν ∈ C_γ} p*(ν) + γ, P(p ≤ α) ≤ α + o(1) at every true ν, on or off the boundary: on the event
ν ∈ C_γ, p ≥ p*(ν_true) + γ, and p*(ν_true) is the reference drawn from the true nuisance (Berger & Boos
1994, JASA 89, 1012; Silvapulle 1996, JASA 91, 1690, who applies it to parameters on a boundary; the
same device, with a bootstrap inside, in McCloskey 2017, J. Econometrics 200, 17). The nuisances are the
walk and 1/f variances the fit carries (BOUNDARY_PARAMETERS); C_γ is the product of their Wald intervals
θ̂_j ± c se_j cut at 0, c = Φ̄⁻¹(γ / 2m) for m of them (Bonferroni). A nuisance whose interval stays
clear of 0 is interior, where the parametric bootstrap is first-order consistent (Andrews 2000 concerns
the boundary only) and z is nearly pivotal: it is held at θ̂. For each nuisance whose interval reaches 0,
the sup is taken on a stated grid — the interval's ends (0 and θ̂_j + c se_j) with the others at θ̂, and
θ̂ itself — not over the whole set: p*(ν) is monotone in the walk in the cases measured (replicates from
a walk at 0 are too light-tailed, from a raised walk nearly N(0, 1)-to-t-like), and the grid is what is
measured. Each point gets its own replicates, so the max is also biased upward by their Monte Carlo
error (conservative). What this costs and buys is measured on whole records
(benchmarks/bench_trend_reference.py, the ``_boundary`` cases; docs/trend_reference_size.md): on the
short records above, with γ = 1e-4, 9 of 1000 rejected at 0.05 and none at 0.01 — valid, and
conservative there, where the upper end of the walk's interval lies some 4 standard errors above a walk
the record cannot see; on the masked warm-up (4e-3 under 1/f 5e-8, 1 h), with γ a tenth of the loop's
per-test rate 4.07e-5, 85 of 100 records named against 90 by the bootstrap from θ̂ alone. On any record
the p-value is at least that of the bootstrap from θ̂ plus γ (θ̂ is a grid point, drawn with the same
replicates), so it rejects no record that one keeps.

The weights are held fixed (they are chosen from a fit, and so depend on the record through its Allan
variance, which is left out). Replicates come from
:func:`~carousel_theory.closed_loop.calibration.bootstrap_generator`, seeded by a digest of the observed
Allan variances and L, so a recording always gets the same decision.
"""

from __future__ import annotations

import functools
import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from scipy import optimize, special, stats

from carousel_theory.closed_loop.calibration import (
    TREND_STREAM,
    AllanVarianceSampler,
    bootstrap_generator,
    long_tau_start,
)
from carousel_theory.closed_loop.residual_model import (
    FittedNoise,
    ResidualFit,
    StatisticUnits,
    covariance_product,
    fit_units,
    noise_variances,
    simulate_block_sum_draws,
    statistic_units,
)
from carousel_theory.fitting import COMPONENT_OF_PARAMETER
from carousel_theory.noise_model import term_allan_variance

__all__ = [
    "BOUNDARY_PARAMETERS",
    "CONFIDENCE_SHARE",
    "GRID_LIMIT",
    "GRID_STEP",
    "REPLICATES",
    "BoundaryReference",
    "TrendReference",
    "block_sums",
    "boundary_grid",
    "boundary_reference",
    "expand_block_weights",
    "model_curve",
    "octave_products",
    "trend_reference",
]

#: Bootstrap replicates per test.
REPLICATES = 400
#: The grid of x = L/√V runs over [−GRID_LIMIT, GRID_LIMIT] (2Φ̄(12) = 3.6e-33) in steps of GRID_STEP.
GRID_LIMIT = 12.0
GRID_STEP = 0.02
#: The variances whose fitted value may sit on its boundary 0 (module docstring).
BOUNDARY_PARAMETERS = ("rrw_variance", "flicker_variance")
#: The share γ/α of a test's level α spent on the confidence set of the boundary nuisances.
CONFIDENCE_SHARE = 0.1
#: Largest |z| searched for a threshold.
_LARGEST_Z = 60.0


def octave_products(x_sums: np.ndarray, y_sums: np.ndarray, levels: int, block: int) -> np.ndarray:
    """The bilinear octave Allan variance B(x, y) = Σ Δx̄ Δȳ / (2 (N − 1)) at m = block · 2^k, k < levels,
    from sums of ``block`` samples along the last axis (B(x, x) is the non-overlapping Allan variance,
    TIM 2014 eq. (20)); rows of ``x_sums`` against ``y_sums`` broadcast."""
    x, y = np.asarray(x_sums, dtype=np.float64), np.asarray(y_sums, dtype=np.float64)
    result = np.empty((*np.broadcast_shapes(x.shape[:-1], y.shape[:-1]), levels))
    for level in range(levels):
        if level:
            count = x.shape[-1] // 2
            x = x[..., : 2 * count : 2] + x[..., 1 : 2 * count : 2]
            y = y[..., : 2 * count : 2] + y[..., 1 : 2 * count : 2]
        size = block * 2**level
        products = np.sum(np.diff(x, axis=-1) * np.diff(y, axis=-1), axis=-1)
        result[..., level] = products / (2.0 * size**2 * (x.shape[-1] - 1))
    return result


@dataclass(frozen=True)
class _ActiveSets:
    """The non-negative GLS step of the fitter as a function of its (whitened, column-scaled) data y:
    for each active set S, θ_S = P_S y (0 off S), the Kuhn–Tucker gradient G_S y of the columns off S, and
    V = c_S · θ_S; a solution is the set with θ_S ≥ 0 and G_S y ≥ 0."""

    projections: np.ndarray  # (sets, p, K): rows off S are 0
    gradients: np.ndarray  # (sets, p, K): rows on S are 0
    units: np.ndarray  # (p,): V per unit of each scaled coefficient

    @classmethod
    def from_design(cls, whitened: np.ndarray, units: np.ndarray) -> _ActiveSets:
        scale = np.linalg.norm(whitened, axis=0)
        scale[scale == 0] = 1.0
        design = whitened / scale
        p, k = design.shape[1], design.shape[0]
        projections, gradients = [], []
        for size in range(p + 1):
            for active in itertools.combinations(range(p), size):
                projection = np.zeros((p, k))
                if active:
                    columns = design[:, list(active)]
                    projection[list(active)] = np.linalg.pinv(columns)
                gradient = design.T @ (design @ projection - np.eye(k))
                gradient[list(active)] = 0.0
                projections.append(projection)
                gradients.append(gradient)
        return cls(np.array(projections), np.array(gradients), units / scale)

    def conditions(self, data: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(θ_S, G_S y) of every active set for each row of ``data`` (…, K): (…, sets, p) each."""
        theta = np.einsum("spk,...k->...sp", self.projections, data)
        return theta, np.einsum("spk,...k->...sp", self.gradients, data)

    def variance(self, theta: np.ndarray, gradient: np.ndarray) -> np.ndarray:
        """V(θ̂) of the non-negative GLS fit from :meth:`conditions`: the active set with the least
        violation of the Kuhn–Tucker conditions (0 at the solution)."""
        violation = np.maximum(np.max(-theta, axis=-1), np.max(-gradient, axis=-1))
        chosen = np.argmin(violation, axis=-1)
        best = np.take_along_axis(theta, chosen[..., np.newaxis, np.newaxis], axis=-2)[..., 0, :]
        return best @ self.units


@dataclass(frozen=True)
class TrendReference:
    """The bootstrap reference of z = L/√V(θ̂) (module docstring): ``variance`` is V = V(θ̂) of the
    observed fit, and the rows of ``constant``, ``linear``, ``square`` the whitened Allan-variance vectors
    y_k(x) = constant_k + x linear_k + x² square_k of replicate k at L = x √V."""

    variance: float
    sets: _ActiveSets
    constant: np.ndarray
    linear: np.ndarray
    square: np.ndarray

    def ratio(self, x: np.ndarray) -> np.ndarray:
        """V(θ̂*_k(x √V)) / V for every replicate k (rows) and x (columns); θ_S and the Kuhn–Tucker
        gradients are quadratics in x, formed from their coefficients."""
        powers = (np.ones_like(x), x, x * x)
        theta = gradient = 0.0
        for power, data in zip(powers, (self.constant, self.linear, self.square), strict=True):
            part_theta, part_gradient = self.sets.conditions(data)
            shape = (1, len(x), 1, 1)
            theta = theta + part_theta[:, np.newaxis] * power.reshape(shape)
            gradient = gradient + part_gradient[:, np.newaxis] * power.reshape(shape)
        return self.sets.variance(np.asarray(theta), np.asarray(gradient)) / self.variance

    @functools.cached_property
    def _ratios(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The grid x ≥ 0 and :meth:`ratio` at x and at −x: they do not depend on z, so every z (a
        threshold search evaluates many) reuses them."""
        grid = np.arange(0.0, GRID_LIMIT + GRID_STEP / 2, GRID_STEP)
        return grid, self.ratio(grid), self.ratio(-grid)

    def sf(self, z: float) -> float:
        """P*(|z*| > |z|) = mean_k P(x ∈ R_k), x ~ N(0, 1) (module docstring)."""
        grid, *ratios = self._ratios
        total = np.zeros(len(self.constant))
        for ratio in ratios:
            gap = grid**2 - z * z * ratio  # > 0: rejected
            total += _normal_mass(grid, gap)
        return float(np.mean(total))

    def log10_p(self, z: float, tests: int) -> float:
        """log10 of the p-value of |z|, Bonferroni over ``tests``."""
        return _bonferroni_log10_p(self.sf(z), tests)

    def threshold(self, alpha: float, tests: int) -> float:
        """The |z| at which the Bonferroni p-value is ``alpha`` (∞ when none reaches it)."""
        return _threshold(self.sf, alpha / max(tests, 1))


def _bonferroni_log10_p(p: float, tests: int) -> float:
    return min(0.0, math.log10(max(tests, 1)) + math.log10(max(p, 1e-300)))


def _threshold(sf: Callable[[float], float], level: float) -> float:
    """The |z| where sf(z) = ``level`` (∞ when sf stays above it up to _LARGEST_Z)."""
    target = math.log(level)

    def excess(z: float) -> float:
        return math.log(max(sf(z), 1e-300)) - target

    if excess(_LARGEST_Z) > 0:
        return math.inf
    return float(optimize.brentq(excess, 0.0, _LARGEST_Z, xtol=1e-4))


def _normal_mass(grid: np.ndarray, gap: np.ndarray) -> np.ndarray:
    """Per row, the N(0, 1) mass of {x ≥ 0 : gap(x) > 0}, gap linear between the grid points; beyond the
    last point the sign of the last value holds. Whole intervals take the tail difference of their ends;
    only the intervals where gap changes sign evaluate the tail at the crossing."""
    tail = special.ndtr(-grid)
    low, high = gap[:, :-1], gap[:, 1:]
    whole = (low > 0) & (high > 0)
    mass = np.sum(np.where(whole, tail[:-1] - tail[1:], 0.0), axis=1)
    rows, columns = np.nonzero((low > 0) != (high > 0))
    below, above = low[rows, columns], high[rows, columns]
    left, right = grid[columns], grid[columns + 1]
    crossing = special.ndtr(-(left + (right - left) * below / (below - above)))
    part = np.where(below > 0, tail[columns] - crossing, crossing - tail[columns + 1])
    np.add.at(mass, rows, np.maximum(part, 0.0))
    return mass + np.where(gap[:, -1] > 0, tail[-1], 0.0)


def expand_block_weights(block_weights: np.ndarray, block: int, length: int) -> np.ndarray:
    """Per-sample weights of ``length`` samples, constant over blocks of ``block`` (0 past the last)."""
    expanded = np.zeros(length)
    expanded[: len(block_weights) * block] = np.repeat(block_weights, block)
    return expanded


def block_sums(values: np.ndarray, block: int) -> np.ndarray:
    """Sums of ``values`` over its whole blocks of ``block`` samples."""
    count = len(values) // block
    return values[: count * block].reshape(count, block).sum(axis=1)


def _active_sets(fit: ResidualFit, units: StatisticUnits) -> tuple[_ActiveSets, np.ndarray]:
    """The fitter's GLS step for ``fit`` (its parameters, τ and covariance across τ) with V per unit of
    each parameter (``units``, :func:`fit_units` of the statistic's weights); and the Cholesky factor
    of that covariance."""
    model = fit.noise.model
    ar = model.ar_coefficients
    gain = 1.0 / (1.0 - sum(ar)) ** 2 if ar else 1.0
    columns, per_unit = [], []
    for parameter in fit.result.parameters:
        component = COMPONENT_OF_PARAMETER[parameter]
        columns.append(term_allan_variance(component, fit.sizes, model.flicker_d, ar_coefficients=ar))
        per_unit.append(units.of_parameter(parameter) * (gain if component == "ar" else 1.0))
    cholesky = np.linalg.cholesky(np.asarray(fit.result.tau_covariance, dtype=np.float64))
    whitened = np.linalg.solve(cholesky, np.column_stack(columns))
    return _ActiveSets.from_design(whitened, np.array(per_unit)), cholesky


def model_curve(fit: ResidualFit, noise: FittedNoise) -> np.ndarray:
    """The Allan variance of ``noise`` at the τ of ``fit``, through the fit's own columns (its terms)."""
    model = noise.model
    columns = [
        getattr(model, parameter)
        * term_allan_variance(
            COMPONENT_OF_PARAMETER[parameter],
            fit.sizes,
            model.flicker_d,
            ar_coefficients=model.ar_coefficients,
        )
        for parameter in fit.result.parameters
    ]
    return np.sum(columns, axis=0)


def _allan_parts(
    fit: ResidualFit,
    length: int,
    sums: tuple[np.ndarray, np.ndarray],
    direction: np.ndarray,
    rng: np.random.Generator,
    curve: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(constant, linear, square) of the Allan-variance vectors of the replicates at L = x √V (unwhitened,
    module docstring): ``sums`` the block sums of e⊥* and of e* = e⊥* + (L*/V) u (rows: replicates),
    ``direction`` those of h / √V; the short τ are drawn given the long ones of e*, about ``curve``, the
    generating model's Allan variance."""
    first = long_tau_start(fit, length)
    block, levels = int(fit.sizes[first]), len(fit.sizes) - first
    orthogonal, whole = sums
    sampler = AllanVarianceSampler.from_fit(fit, length)
    long_e = octave_products(whole, whole, levels, block)
    short = curve[:first] + rng.standard_normal((len(whole), first)) @ sampler.short_factor.T
    short = short + (long_e - curve[first:]) @ sampler.regression.T
    zeros = np.zeros((len(whole), first))
    constant = np.hstack((short, octave_products(orthogonal, orthogonal, levels, block)))
    linear = np.hstack((zeros, 2.0 * octave_products(orthogonal, direction, levels, block)))
    square = np.concatenate((zeros[0], octave_products(direction, direction, levels, block)))
    return constant, linear, np.broadcast_to(square, constant.shape)


def trend_reference(
    fit: ResidualFit,
    length: int,
    block_weights: np.ndarray,
    projection: float,
    regressor_sums: np.ndarray | None = None,
    replicates: int = REPLICATES,
    generating: FittedNoise | None = None,
    units: StatisticUnits | None = None,
) -> TrendReference:
    """The bootstrap reference of L/√V(θ̂) (module docstring) for the weights ``block_weights`` (the
    per-sample weight on each block of ``fit.sizes[first]`` samples, ``first`` the first long τ) under
    ``fit``, the fit of r = e (``regressor_sums`` None) or of r = e − (L/I) g (``regressor_sums`` the
    block sums of g); ``projection`` is the observed L (it seeds the generator). The replicates are drawn
    from ``generating`` (default: the fit's own noise), refitted and studentized as ``fit`` was.
    ``units``, when given, are :func:`fit_units` of the expanded weights (a caller that has them spares
    the record-length transforms)."""
    first = long_tau_start(fit, length)
    if first >= len(fit.sizes):
        raise ValueError(f"length={length!r}: no long τ to draw the trend reference from")
    block = int(fit.sizes[first])
    weights = expand_block_weights(np.asarray(block_weights, dtype=np.float64), block, length)
    units = fit_units(fit, weights) if units is None else units
    sets, cholesky = _active_sets(fit, units)
    noise = fit.noise if generating is None else generating
    if noise.model.flicker_variance and not units.flicker:  # a generating 1/f term the fit lacks
        units = statistic_units(weights, noise.model.flicker_d)
    variance = units.variance(noise_variances(noise))
    covariance = block_sums(covariance_product(noise, weights), block)  # Cov(block sums, L)
    direction = covariance
    if regressor_sums is not None:
        direction = covariance - variance / float(np.dot(block_weights, regressor_sums)) * regressor_sums
    rng = bootstrap_generator(TREND_STREAM, [fit.observed, np.array([projection, variance])])
    whole = simulate_block_sum_draws(noise, length, block, replicates, rng)
    orthogonal = whole - np.outer(whole @ block_weights / variance, covariance)
    root = math.sqrt(variance)
    curve = fit.model if generating is None else model_curve(fit, noise)
    constant, linear, square = _allan_parts(fit, length, (orthogonal, whole), direction / root, rng, curve)
    whiten = np.linalg.inv(cholesky).T
    return TrendReference(variance, sets, constant @ whiten, linear @ whiten, square @ whiten)


@dataclass(frozen=True)
class BoundaryReference:
    """The confidence-set p-value over the boundary nuisances (module docstring): p = max_k p*_k + γ over
    the references drawn at the grid points ``walks``/``flickers`` (the generating walk and 1/f variance
    of each reference, in order), γ = ``confidence_level`` spent on the confidence set."""

    references: tuple[TrendReference, ...]
    walks: tuple[float, ...]
    flickers: tuple[float, ...]
    confidence_level: float

    def sf(self, z: float) -> float:
        """max_k P*_k(|z*| > |z|) + γ, at most 1."""
        return min(1.0, max(reference.sf(z) for reference in self.references) + self.confidence_level)

    def log10_p(self, z: float, tests: int) -> float:
        """log10 of the p-value of |z|, Bonferroni over ``tests``."""
        return _bonferroni_log10_p(self.sf(z), tests)

    def threshold(self, alpha: float, tests: int) -> float:
        """The |z| at which the Bonferroni p-value is ``alpha`` (∞ when none reaches it); γ must be below
        alpha/tests."""
        level = alpha / max(tests, 1)
        if not self.confidence_level < level:
            raise ValueError(
                f"alpha={alpha!r}, tests={tests!r}: the per-test level {level!r} must exceed the confidence"
                f" set's share γ = {self.confidence_level!r}"
            )
        return _threshold(self.sf, level)


def boundary_grid(noise: FittedNoise, confidence_level: float) -> list[FittedNoise]:
    """The grid of generating models (module docstring): the fit's own noise first, then for each
    variance of BOUNDARY_PARAMETERS whose (1 − γ) Bonferroni interval θ̂ ± c se reaches 0, its ends 0 and
    θ̂ + c se with the others at θ̂ (points equal to θ̂ left out)."""
    if not 0.0 < confidence_level < 1.0:
        raise ValueError(f"confidence_level={confidence_level!r}: γ must lie in (0, 1)")
    errors = noise.standard_errors
    nuisances = [name for name in BOUNDARY_PARAMETERS if name in errors]
    grid = [noise]
    if not nuisances:
        return grid
    width = float(stats.norm.isf(confidence_level / (2 * len(nuisances))))
    for name in nuisances:
        estimate, error = float(getattr(noise.model, name)), errors[name]
        if estimate - width * error > 0.0:
            continue
        for value in (0.0, estimate + width * error):
            if value != estimate:
                raised: dict[str, Any] = {name: value}
                grid.append(replace(noise, model=replace(noise.model, **raised)))
    return grid


def boundary_reference(
    fit: ResidualFit,
    length: int,
    block_weights: np.ndarray,
    projection: float,
    confidence_level: float,
    regressor_sums: np.ndarray | None = None,
    replicates: int = REPLICATES,
    units: StatisticUnits | None = None,
) -> BoundaryReference:
    """The confidence-set reference of L/√V(θ̂) (module docstring): :func:`trend_reference` drawn at
    each point of :func:`boundary_grid` of ``fit.noise`` with ``replicates`` each, γ =
    ``confidence_level``; the other arguments as for :func:`trend_reference` (the grid keeps the fit's
    1/f order, so one set of ``units``, when given, serves every point)."""
    grid = boundary_grid(fit.noise, confidence_level)
    references = tuple(
        trend_reference(
            fit,
            length,
            block_weights,
            projection,
            regressor_sums,
            replicates,
            None if i == 0 else noise,
            units,
        )
        for i, noise in enumerate(grid)
    )
    walks = tuple(float(noise.model.rrw_variance) for noise in grid)
    flickers = tuple(float(noise.model.flicker_variance) for noise in grid)
    return BoundaryReference(references, walks, flickers, confidence_level)
