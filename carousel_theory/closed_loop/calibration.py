"""How the loop spends its false-alarm rate α, and the null distribution of its final misfit test.

**The split of α (Bonferroni).** A run of the loop makes a sequence of decisions: in iteration k every
testable detector is asked whether its effect is present, and at the end the Allan variance is asked
whether it still misfits the model. The loop's family-wise false-alarm rate is bounded by the sum of the
rates of all these tests, so α is split in advance:

- the final misfit test gets α/4;
- iteration k gets (3α/4) · 6/(π² k²) (Σ_k 6/(π² k²) = 1), shared equally among the J_k detectors
  tested in it: each detector runs at (3α/4) · 6/(π² k² J_k), and is itself family-wise over its own scan
  and the axes (Bonferroni).

On a clean record the loop can name something only in iteration 1 or in the final test, so its
false-alarm rate is at most (3α/4) · 6/π² + α/4 ≈ 0.71 α; on a record with effects, the rate of naming
anything beyond them is at most α. A decision that an added effect "explains its own evidence" uses the
rate of the iteration in which it was added.

**The final misfit test.** Each Allan-variance estimate of the final fit is standardised by its
χ²_ν distribution (ν the equivalent degrees of freedom of the fitted model) into a z-value.

- *Short τ* (more than LONG_TAU_TERMS squared differences averaged): the estimate is a sum of thousands
  of terms and χ²_ν with the Satterthwaite ν describes it well; the largest |z| of these points, over
  τ and axes, gets the Bonferroni p-value of the normal tail.
- *Long τ* (the few points with 7 to LONG_TAU_TERMS differences): the estimates are far from χ²_ν,
  correlated across τ, and the fitted parameters rest on them, so no asymptotic reference is used. The
  null distribution of the largest |z| of these points is taken from the fitted model by a parametric
  bootstrap: each replicate draws the block sums of every axis from the fitted model exactly
  (:func:`~carousel_theory.closed_loop.residual_model.simulate_block_sums`), computes the same Allan
  variances and z-values against the *fitted* curve, and p = (1 + #{T* ≥ T}) / (B + 1) is exact-size for
  B + 1 exchangeable draws (Davison & Hinkley 1997, §4.2). The observed curve was fitted to the observed
  points, which pulls its z-values towards 0: the test is conservative for the estimation of the
  parameters. B = ⌈1/α'⌉ − 1 with α' the level of this half (the smallest B at which p can reach α'),
  the model being rejected when no replicate reaches T; the replicates are drawn sequentially and stopped
  at the first T* ≥ T, which makes p > α' certain (Besag & Clifford 1991). The size of a Monte Carlo
  test does not depend on B; B sets its power and the Monte Carlo error of p: at α = 0.01, α' = α/8 and
  B = 799, a p-value of exactly α' is estimated with standard error √(α'(1 − α')/B) ≈ α' (so the
  decision at the threshold is a coin flip), and a true p of α'/10 is rejected with probability
  (1 − α'/10)^B ≈ 0.90.

Each half runs at half the final test's rate (Bonferroni); the reported p is 2 min(p_short, p_long).

**Shared by the 1/f detector.** The same sequential test (:func:`sequential_monte_carlo_p`) refers the
1/f detector's nested-fit statistic to replicates of the whole Allan-variance vector of the fitted model
(:class:`AllanVarianceSampler`: the long τ exactly from block sums, the short τ Gaussian given them).
Every bootstrap draws from its own generator (:func:`bootstrap_generator`), seeded with BOOTSTRAP_SEED, a
stream number per test and a digest of the observed values rounded to DIGEST_BITS significant bits: a
recording gets the same replicates on any numerical platform, and different recordings get independent
ones. The rounding is what makes the first true across machines: a change in the last bits of an
observed value (another summation order in NumPy or BLAS, another CPU's kernels) leaves the digest and
the replicates as they were, unless a value sits within those bits of a rounding midpoint (a chance of
about 2^(DIGEST_BITS − 52) per last-bit change). The decisions then differ across platforms only where a
statistic sits within rounding of its threshold. The digest matters: with one fixed
stream the critical value (the largest of the B replicates) would be the same draw for every recording,
and the test's size over recordings would be one minus that draw's quantile, a random number of mean
1/(B + 1) but as likely as not far from it (at B = 39, 9 of 43 clean one-hour records rejected at a
nominal 0.05).
"""

from __future__ import annotations

import hashlib
import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy import stats

from carousel_theory.closed_loop.residual_model import ResidualFit, chi_square_z, simulate_block_sums

__all__ = [
    "BOOTSTRAP_SEED",
    "DEFAULT_ALPHA",
    "DIGEST_BITS",
    "FINAL_SHARE",
    "FLICKER_STREAM",
    "LONG_TAU_TERMS",
    "MISFIT_STREAM",
    "TREND_STREAM",
    "AllanVarianceSampler",
    "MisfitTest",
    "bootstrap_generator",
    "detector_alpha",
    "final_alpha",
    "iteration_alpha",
    "long_tau_start",
    "misfit_test",
    "octave_allan",
    "sequential_monte_carlo_p",
]

#: Family-wise false-alarm rate of a whole run of the loop.
DEFAULT_ALPHA = 0.01
#: Share of α given to the final misfit test; the rest is spread over the iterations.
FINAL_SHARE = 0.25
#: Allan-variance points averaging more squared differences than this are referred to χ²_ν; the others
#: (the longest τ) to the parametric bootstrap.
LONG_TAU_TERMS = 2000
#: Seed of the bootstrap's generator: the loop is deterministic for a given recording.
BOOTSTRAP_SEED = 20140515


def iteration_alpha(alpha: float, iteration: int) -> float:
    """The share of α of iteration k = ``iteration`` (1, 2, …): (1 − FINAL_SHARE) α · 6/(π² k²)."""
    return (1.0 - FINAL_SHARE) * alpha * 6.0 / (math.pi**2 * iteration**2)


def detector_alpha(alpha: float, iteration: int, detectors: int) -> float:
    """The rate of each of ``detectors`` detectors in iteration k (Bonferroni within the iteration)."""
    return iteration_alpha(alpha, iteration) / max(detectors, 1)


def final_alpha(alpha: float) -> float:
    """The rate of the final Allan-variance misfit test."""
    return FINAL_SHARE * alpha


@dataclass(frozen=True)
class MisfitTest:
    """The final test: its statistic (largest |z| over τ and axes), where it is, the bootstrap p-value,
    how many replicates were drawn, and whether it rejects the model at ``alpha``."""

    statistic: float
    axis: str
    z: float
    tests: int
    p_value: float
    replicates: int
    alpha: float

    @property
    def rejects(self) -> bool:
        return self.p_value <= self.alpha


def octave_allan(block_sums: np.ndarray, levels: int, block: int) -> np.ndarray:
    """Non-overlapping Allan variance (TIM 2014 eq. (20)) at m = block · 2^k, k < levels, from the sums of
    ``block`` samples (pairwise sums give the longer clusters, as :mod:`carousel_theory.allan` does)."""
    result, sums = np.empty(levels), block_sums
    for level in range(levels):
        if level:
            count = len(sums) // 2
            sums = sums[: 2 * count : 2] + sums[1 : 2 * count : 2]
        differences = np.diff(sums)
        size = block * 2**level
        result[level] = np.dot(differences, differences) / (2.0 * size**2 * len(differences))
    return result


@dataclass(frozen=True)
class _LongTau:
    """The long-τ points of one axis: where they start in the fit, the block size, the fitted curve."""

    fit: ResidualFit
    first: int

    @property
    def block(self) -> int:
        return int(self.fit.sizes[self.first])

    def z(self, observed: np.ndarray) -> np.ndarray:
        fit, first = self.fit, self.first
        return chi_square_z(observed, fit.model[first:], fit.edf[first:])


def long_tau_start(fit: ResidualFit, length: int) -> int:
    """Index of the first point with at most LONG_TAU_TERMS differences."""
    terms = length // fit.sizes - 1
    long = np.flatnonzero(terms <= LONG_TAU_TERMS)
    return int(long[0]) if len(long) else len(fit.sizes)


def _short_tau_log_p(fits: dict[str, ResidualFit], firsts: dict[str, int]) -> tuple[float, int, float, str]:
    """Bonferroni p-value of the largest |z| among the short-τ points (χ²_ν reference)."""
    best, best_axis, count = 0.0, "", 0
    for axis, fit in fits.items():
        z = chi_square_z(fit.observed[: firsts[axis]], fit.model[: firsts[axis]], fit.edf[: firsts[axis]])
        count += len(z)
        if len(z) and float(np.max(np.abs(z))) > abs(best):
            best, best_axis = float(z[np.argmax(np.abs(z))]), axis
    p = min(1.0, 2.0 * count * float(stats.norm.sf(abs(best)))) if count else 1.0
    return p, count, best, best_axis


def _long_statistic(parts: dict[str, _LongTau], observed: dict[str, np.ndarray]) -> tuple[float, str, float]:
    best = (0.0, "", 0.0)
    for axis, part in parts.items():
        z = part.z(observed[axis])
        if len(z) and float(np.max(np.abs(z))) > best[0]:
            best = (float(np.max(np.abs(z))), axis, float(z[np.argmax(np.abs(z))]))
    return best


#: Significant bits of the observed values that seed the bootstrap generators (module docstring).
DIGEST_BITS = 32

#: Stream numbers of the loop's Monte Carlo tests (the second word of their generators' seeds).
MISFIT_STREAM, FLICKER_STREAM, TREND_STREAM = 0, 1, 2


def bootstrap_generator(stream: int, observed: list[np.ndarray]) -> np.random.Generator:
    """The generator of one Monte Carlo test on one recording: seeded with BOOTSTRAP_SEED, ``stream`` and a
    128-bit BLAKE2b digest of the ``observed`` values the test is about, rounded to DIGEST_BITS significant
    bits (module docstring)."""
    digest = hashlib.blake2b(digest_size=16)
    for values in observed:
        mantissa, exponent = np.frexp(np.asarray(values, dtype=np.float64))
        digest.update(np.rint(np.ldexp(mantissa, DIGEST_BITS)).astype(np.int64).tobytes())
        digest.update(exponent.astype(np.int64).tobytes())
    words = np.frombuffer(digest.digest(), dtype=np.uint32)
    return np.random.default_rng([BOOTSTRAP_SEED, stream, *(int(word) for word in words)])


def sequential_monte_carlo_p(draw: Callable[[], float], statistic: float, alpha: float) -> tuple[float, int]:
    """Monte Carlo p-value of ``statistic`` at level ``alpha`` from replicates ``draw()`` of its null
    distribution, and how many were drawn (module docstring).

    B = ⌈1/α⌉ − 1 replicates at most, the smallest B at which p = (1 + #{T* ≥ T})/(B + 1) can reach α,
    exact-size for B + 1 exchangeable draws (Davison & Hinkley 1997, §4.2). With B + 1 = ⌈1/α⌉ a single
    exceedance already gives p ≥ 2/(B + 1) > α, so drawing stops at the first one; the p-value reported
    then is the sequential estimate h/l = 1/l, one exceedance in l draws (Besag & Clifford 1991), which
    is > α as well, so the decision is that of the full test.
    """
    budget = math.ceil(1.0 / alpha - 1e-9) - 1
    for drawn in range(1, budget + 1):
        if draw() >= statistic:
            return (2.0 / (budget + 1) if drawn == budget else 1.0 / drawn), drawn
    return 1.0 / (budget + 1), budget


def _bootstrap_p(
    parts: dict[str, _LongTau], statistic: float, length: int, alpha: float
) -> tuple[float, int]:
    """Sequential parametric-bootstrap p-value of the long-τ statistic (module docstring)."""
    rng = bootstrap_generator(MISFIT_STREAM, [part.fit.observed[part.first :] for part in parts.values()])

    def draw() -> float:
        replicate = {
            axis: octave_allan(
                simulate_block_sums(part.fit.noise, length, part.block, rng),
                len(part.fit.sizes) - part.first,
                part.block,
            )
            for axis, part in parts.items()
        }
        return _long_statistic(parts, replicate)[0]

    return sequential_monte_carlo_p(draw, statistic, alpha)


@dataclass(frozen=True)
class AllanVarianceSampler:
    """Draws of the octave non-overlapping Allan variance of one axis at the τ of ``fit``, from its model.

    The long τ (at most LONG_TAU_TERMS differences, from index ``first`` on) come from block sums of the
    fitted model drawn exactly (:func:`~carousel_theory.closed_loop.residual_model.simulate_block_sums`,
    as in the final misfit test), through the same estimator. The short τ, each a mean of more than
    LONG_TAU_TERMS squared differences, are drawn Gaussian given the long ones: mean
    μ_S + C_SL C_LL⁻¹ (y_L − μ_L) and covariance C_SS − C_SL C_LL⁻¹ C_LS, with μ the fitted curve and C the
    fit's model-based covariance across τ, so that the pair has the model's first and second moments
    (the skewness of a mean of N > 2000 squared Gaussian differences, ≤ √(8/N) ≈ 0.06, is left out).
    A whole record is never simulated: the cost is O(length / block) per draw.
    """

    fit: ResidualFit
    length: int
    first: int
    regression: np.ndarray
    short_factor: np.ndarray

    @classmethod
    def from_fit(cls, fit: ResidualFit, length: int) -> AllanVarianceSampler:
        first = long_tau_start(fit, length)
        covariance = np.asarray(fit.result.tau_covariance, dtype=np.float64)
        short, long = slice(0, first), slice(first, len(fit.sizes))
        if first in (0, len(fit.sizes)):
            factor = np.linalg.cholesky(covariance[short, short]) if first else np.zeros((0, 0))
            return cls(fit, length, first, np.zeros((first, len(fit.sizes) - first)), factor)
        regression = np.linalg.solve(covariance[long, long], covariance[long, short]).T
        residual = covariance[short, short] - regression @ covariance[long, short]
        return cls(fit, length, first, regression, np.linalg.cholesky(0.5 * (residual + residual.T)))

    def draw(self, rng: np.random.Generator) -> np.ndarray:
        fit, first = self.fit, self.first
        long = np.empty(0)
        if first < len(fit.sizes):
            block = int(fit.sizes[first])
            sums = simulate_block_sums(fit.noise, self.length, block, rng)
            long = octave_allan(sums, len(fit.sizes) - first, block)
        short = fit.model[:first] + self.short_factor @ rng.standard_normal(first)
        if len(long):
            short = short + self.regression @ (long - fit.model[first:])
        return np.concatenate((short, long))


def misfit_test(cleaned: dict[str, np.ndarray], fits: dict[str, ResidualFit], alpha: float) -> MisfitTest:
    """Test of the Allan variance of every axis against the fitted model, at ``alpha``: short τ by the
    χ²_ν reference, long τ by a parametric bootstrap, each at α/2 (module docstring)."""
    length = len(next(iter(cleaned.values())))
    firsts = {axis: long_tau_start(fit, length) for axis, fit in fits.items()}
    p_short, count, z_short, axis_short = _short_tau_log_p(fits, firsts)
    parts = {axis: _LongTau(fit, firsts[axis]) for axis, fit in fits.items() if firsts[axis] < len(fit.sizes)}
    tests = count + sum(len(p.fit.sizes) - p.first for p in parts.values())
    if not parts:
        return MisfitTest(abs(z_short), axis_short, z_short, tests, p_short, 0, alpha)
    observed = {axis: part.fit.observed[part.first :] for axis, part in parts.items()}
    statistic, axis, z = _long_statistic(parts, observed)
    p_long, drawn = _bootstrap_p(parts, statistic, length, alpha / 2.0)
    p_value = min(1.0, 2.0 * min(p_short, p_long))
    if p_short < p_long:
        statistic, axis, z = abs(z_short), axis_short, z_short
    return MisfitTest(statistic, axis, z, tests, p_value, drawn, alpha)
