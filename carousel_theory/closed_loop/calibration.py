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

**The final misfit test: a parametric bootstrap.** The statistic is the largest |z| over τ and axes of
the Allan variance, each z the χ²_ν standardisation of one estimate. At the longest τ (8 to 15 clusters)
the estimates are far from χ²_ν with the Satterthwaite ν, they are correlated across τ, and the model's
parameters were fitted to the same points; a Bonferroni p-value from the normal tail is then not the
stated rate. The null distribution is instead taken from the fitted model itself: each replicate
simulates every axis from its fitted noise model (same length), refits it with the same terms and the
same weights, and recomputes the statistic; p = (1 + #{T* ≥ T}) / (B + 1) is exact-size for B + 1
exchangeable draws (Davison & Hinkley 1997, §4.2). B = 2⌈1/α_final⌉ − 1, so that p can reach
α_final/2; the replicates are drawn sequentially and stopped as soon as the count of T* ≥ T makes
p > α_final certain (Besag & Clifford 1991): on a well-fitting record that takes a handful.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from carousel_theory.closed_loop.residual_model import (
    ModelTerms,
    ResidualFit,
    allan_z_values,
    fit_residual_model,
    simulate_noise,
)

__all__ = [
    "DEFAULT_ALPHA",
    "FINAL_SHARE",
    "MisfitTest",
    "detector_alpha",
    "final_alpha",
    "iteration_alpha",
    "misfit_test",
]

#: Family-wise false-alarm rate of a whole run of the loop.
DEFAULT_ALPHA = 0.01
#: Share of α given to the final misfit test; the rest is spread over the iterations.
FINAL_SHARE = 0.25
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


def _largest_z(fits: dict[str, ResidualFit]) -> tuple[float, str, float]:
    best = (0.0, "", 0.0)
    for axis, fit in fits.items():
        z = allan_z_values(fit)
        if len(z) and float(np.max(np.abs(z))) > best[0]:
            index = int(np.argmax(np.abs(z)))
            best = (float(abs(z[index])), axis, float(z[index]))
    return best


def _replicate(
    fits: dict[str, ResidualFit], terms: ModelTerms, length: int, rng: np.random.Generator
) -> float:
    replicated = {}
    for axis, fit in fits.items():
        values = simulate_noise(fit.noise, length, rng)
        replicated[axis] = fit_residual_model(values, fit.noise.sample_rate, terms, edf_hint=fit.edf)
    return _largest_z(replicated)[0]


def misfit_test(
    cleaned: dict[str, np.ndarray], fits: dict[str, ResidualFit], terms: ModelTerms, alpha: float
) -> MisfitTest:
    """Parametric-bootstrap test of the Allan variance of every axis against the fitted model.

    ``cleaned`` are the axes with the fitted effects removed, ``fits`` their fits with ``terms``. The
    observed statistic is recomputed with the fit's weights held fixed, exactly as in the replicates."""
    sample_rate = next(iter(fits.values())).noise.sample_rate
    observed = {
        axis: fit_residual_model(cleaned[axis], sample_rate, terms, edf_hint=fit.edf)
        for axis, fit in fits.items()
    }
    statistic, axis, z = _largest_z(observed)
    length = len(next(iter(cleaned.values())))
    budget = math.ceil(1.0 / alpha) * 2 - 1  # p can reach alpha / 2
    allowed = math.floor(alpha * (budget + 1)) - 1  # p ≤ alpha ⟺ exceedances ≤ allowed
    rng = np.random.default_rng(BOOTSTRAP_SEED)
    exceedances, drawn = 0, 0
    while drawn < budget and exceedances <= allowed:
        exceedances += _replicate(fits, terms, length, rng) >= statistic
        drawn += 1
    # Stopped early: p > alpha for certain; report the sequential estimate (Besag & Clifford 1991).
    p_value = (1 + exceedances) / (budget + 1) if drawn == budget else min(1.0, exceedances / drawn)
    tests = sum(len(fit.sizes) for fit in fits.values())
    return MisfitTest(statistic, axis, z, tests, p_value, drawn, alpha)
