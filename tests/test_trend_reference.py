"""The studentized trend statistic's bootstrap reference: its pieces against exact forms, and its size on
whole simulated records (the check a reference that mis-studentizes the observed statistic fails)."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
import pytest
from conftest import Z_MONTE_CARLO
from scipy import stats

from carousel_theory.closed_loop.calibration import long_tau_start, octave_allan
from carousel_theory.closed_loop.flicker_blocks import flicker_block_factor
from carousel_theory.closed_loop.linear_statistics import difference_weights
from carousel_theory.closed_loop.residual_model import (
    FittedNoise,
    ModelTerms,
    ResidualFit,
    covariance_product,
    fit_residual_model,
    fit_units,
    noise_variances,
    simulate_block_sum_draws,
    statistic_units,
)
from carousel_theory.closed_loop.studentized import (
    BoundaryReference,
    _active_sets,
    _normal_mass,
    boundary_grid,
    boundary_reference,
    octave_products,
    trend_reference,
)
from carousel_theory.noise_model import NoiseModel
from carousel_theory.processes import covariance_matrix
from carousel_theory.propagation import weighted_sums_covariance
from carousel_theory.simulate import sample_noise

RATE = 100.0


@pytest.mark.parametrize(("d", "block", "count"), [(0.5, 4, 16), (0.3, 7, 9), (0.5, 1, 20), (0.8, 32, 12)])
def test_flicker_block_sums_have_the_exact_covariance_of_block_sums(d, block, count):
    """Cov(S_i, S_j) = Σ_l A_{i−l}·A_{j−l} of the factor equals the covariance of the block sums of the
    samples (propagation.weighted_sums_covariance, block indicator rows), to rounding."""
    factor = flicker_block_factor(d, block, count)
    produced = np.array(
        [
            [sum(factor[i - lag] @ factor[j - lag] for lag in range(min(i, j) + 1)) for j in range(count)]
            for i in range(count)
        ]
    )
    exact = weighted_sums_covariance(np.kron(np.eye(count), np.ones(block)), "flicker", d)
    assert np.max(np.abs(produced - exact)) <= 1e-12 * np.max(np.abs(exact))


def test_block_sum_draws_have_the_model_covariance():
    """4000 draws of white + walk + 1/f block sums: the sample covariance of two blocks against the
    exact one (dense covariance of the samples summed over the blocks), within Z_MONTE_CARLO of the
    standard error of a sample covariance."""
    block, count, draws = 4, 6, 4000
    model = NoiseModel(RATE, white_variance=2.0, rrw_variance=0.3, flicker_variance=0.7, flicker_d=0.5)
    sums = simulate_block_sum_draws(FittedNoise(model), block * count, block, draws, np.random.default_rng(3))
    n = block * count
    dense = 2.0 * covariance_matrix("white", n) + 0.3 * covariance_matrix("rrw", n)
    dense = dense + 0.7 * covariance_matrix("flicker", n, d=0.5)
    indicators = np.kron(np.eye(count), np.ones(block))
    exact = indicators @ dense @ indicators.T
    produced = sums.T @ sums / draws
    error = np.sqrt((exact**2 + np.outer(np.diag(exact), np.diag(exact))) / draws)
    assert np.all(np.abs(produced - exact) <= Z_MONTE_CARLO * error)


def test_covariance_product_is_the_dense_covariance_times_the_weights():
    n = 60
    weights = np.random.default_rng(4).standard_normal(n)
    model = NoiseModel(RATE, white_variance=2.0, rrw_variance=0.3, flicker_variance=0.7, flicker_d=0.5)
    dense = (
        2.0 * covariance_matrix("white", n)
        + 0.3 * covariance_matrix("rrw", n)
        + 0.7 * covariance_matrix("flicker", n, d=0.5)
    )
    assert covariance_product(FittedNoise(model), weights) == pytest.approx(
        dense @ weights, rel=1e-10, abs=1e-12
    )


def test_octave_products_are_the_fitted_estimator_and_bilinear():
    """B(x, x) is the estimator the fit uses; B(x, y) = (A(x + y) − A(x − y))/4."""
    rng = np.random.default_rng(5)
    x, y = rng.standard_normal(4096), rng.standard_normal(4096)
    assert octave_products(x, x, 9, 1) == pytest.approx(octave_allan(x, 9, 1), rel=1e-12)
    polar = (octave_allan(x + y, 9, 1) - octave_allan(x - y, 9, 1)) / 4.0
    assert octave_products(x, y, 9, 1) == pytest.approx(polar, rel=1e-9, abs=1e-14)
    rows = np.vstack((x, y))
    assert octave_products(rows, y, 9, 1)[1] == pytest.approx(octave_allan(y, 9, 1), rel=1e-12)


@pytest.mark.parametrize(("rrw", "flicker"), [(1e-11, 0.0), (0.0, 0.0), (1e-11, 5e-8)])
def test_active_sets_reproduce_the_fitters_variance(rrw, flicker):
    """The fitter's non-negative GLS step by active sets gives V(θ̂) of the fit itself — with the walk
    fitted inside and (for a white record) at the boundary, where the active set matters."""
    model = NoiseModel(RATE, white_variance=3.6e-5, rrw_variance=rrw, flicker_variance=flicker)
    record = sample_noise(model, 60_000, rng=np.random.default_rng(7))
    fit = fit_residual_model(record, RATE, ModelTerms(flicker=bool(flicker)))
    weights = np.random.default_rng(7).standard_normal(60_000)
    sets, cholesky = _active_sets(fit, fit_units(fit, weights))
    produced = sets.variance(*sets.conditions(np.linalg.solve(cholesky, fit.observed)))
    expected = statistic_units(weights).variance(noise_variances(fit.noise))
    assert float(produced) == pytest.approx(expected, rel=1e-8)
    if not rrw and not flicker:
        assert fit.noise.model.rrw_variance == 0.0  # the boundary case is exercised


@dataclass(frozen=True)
class _Case:
    model: NoiseModel
    pilot: ResidualFit
    length: int
    block_weights: np.ndarray
    weights: np.ndarray
    centred: np.ndarray
    regressor_sums: np.ndarray


def _case(length: int, rrw: float, time_constant: float) -> _Case:
    """White + walk records of ``length`` samples, the warm-up's GLS weights on blocks of the first long τ
    (chosen under the true model and held fixed), and a pilot fit for the covariance across τ."""
    model = NoiseModel(RATE, white_variance=3.6e-5, rrw_variance=rrw)
    pilot = fit_residual_model(sample_noise(model, length, rng=np.random.default_rng(8)), RATE, ModelTerms())
    block = int(pilot.sizes[long_tau_start(pilot, length)])
    count = length // block
    regressor = np.exp(-np.arange(length) / RATE / time_constant)
    block_weights = difference_weights(FittedNoise(model), regressor, block) / block
    weights = np.zeros(length)
    weights[: count * block] = np.repeat(block_weights, block)
    sums = regressor[: count * block].reshape(count, block).sum(axis=1)
    return _Case(model, pilot, length, block_weights, weights, regressor - regressor.mean(), sums)


def _clopper_pearson_low(count: int, records: int) -> float:
    return float(stats.beta.ppf(0.025, count, records - count + 1)) if count else 0.0


def _rejections(case: _Case, records: int, level: float, confidence_level: float = 0.0) -> int:
    """Rejections at ``level`` over ``records`` whole records: each simulated sample by sample, the noise
    refitted on r = e − (L/I) g, z = L/√V(θ̂) and p from the bootstrap drawn from that fit (with a
    ``confidence_level``, the confidence-set p-value over the boundary nuisances)."""
    rng = np.random.default_rng(9)
    information = float(np.dot(case.block_weights, case.regressor_sums))
    rejected = 0
    for _ in range(records):
        record = sample_noise(case.model, case.length, rng=rng)
        projection = float(np.dot(case.weights, record))
        record -= (projection / information) * case.centred
        fit = fit_residual_model(record, RATE, ModelTerms(), reference=case.pilot)
        z = projection / math.sqrt(statistic_units(case.weights).variance(noise_variances(fit.noise)))
        if confidence_level:
            reference = boundary_reference(
                fit, case.length, case.block_weights, projection, confidence_level, case.regressor_sums, 100
            )
        else:
            reference = trend_reference(
                fit, case.length, case.block_weights, projection, case.regressor_sums, 100
            )
        rejected += reference.sf(z) <= level
    return rejected


def _assert_size(rejected: int, records: int, level: float) -> None:
    """Consistent with the level (the 95 % Clopper–Pearson interval reaches down to it) and not grossly
    conservative (at least half of it)."""
    assert _clopper_pearson_low(rejected, records) <= level
    assert rejected / records >= 0.5 * level


@pytest.mark.slow
def test_trend_reference_has_its_size_on_whole_records_with_the_walk_inside():
    """400 records of 2^15 samples, walk σ_q² = 1e-9 (4.5 GLS standard errors from 0, 91 % of V): the
    rate at 0.05 is consistent with the level. A rate of 0.137 (what a
    reference studentizing the observed statistic by a boundary-moved model's variance gave) fails."""
    records, level = 400, 0.05
    _assert_size(_rejections(_case(2**15, 1e-9, 20.0), records, level), records, level)


@pytest.mark.slow
@pytest.mark.xfail(
    strict=True,
    reason="a parametric bootstrap from a walk fitted at or near 0 is liberal (Andrews 2000): 0.077 "
    "[0.061, 0.095] at 0.05 on 1000 records (benchmarks/bench_trend_reference.py --case short_small_walk)",
)
def test_trend_reference_has_its_size_on_whole_records_with_a_walk_near_the_boundary():
    """400 records of 2^15 samples, walk σ_q² = 1e-12 (0.6 GLS se; fitted as 0 in about half of them):
    the case in which the earlier reference rejected 0.137 at 0.05, held to the same bounds."""
    records, level = 400, 0.05
    _assert_size(_rejections(_case(2**15, 1e-12, 20.0), records, level), records, level)


@pytest.mark.slow
def test_confidence_set_reference_is_not_liberal_with_a_walk_near_the_boundary():
    """The records of the case above (the plain bootstrap rejects 0.077 there), with the confidence-set
    p-value (γ = 1e-4): its 95 % Clopper–Pearson interval reaches down to the level. It is conservative
    on these records (9/1000 at 0.05 in benchmarks/bench_trend_reference.py --case
    short_small_walk_boundary), so only validity is held here, not the lower bound of _assert_size."""
    records, level = 400, 0.05
    rejected = _rejections(_case(2**15, 1e-12, 20.0), records, level, confidence_level=1e-4)
    assert _clopper_pearson_low(rejected, records) <= level


def test_normal_mass_is_the_gaussian_mass_of_the_rejected_set():
    """gap = x² − c² (rejected beyond c) gives Φ̄(c), up to the linear interpolation of the crossing; a
    gap positive everywhere gives 1/2, negative everywhere 0; two crossings give the mass between."""
    grid = np.arange(0.0, 12.01, 0.02)
    gaps = np.vstack(
        (grid**2 - 2.5**2, np.ones_like(grid), -np.ones_like(grid), -(grid - 1.0) * (grid - 2.0))
    )
    mass = _normal_mass(grid, gaps)
    assert mass[0] == pytest.approx(stats.norm.sf(2.5), rel=1e-3)
    assert mass[1] == pytest.approx(0.5, rel=1e-12)
    assert mass[2] == 0.0
    assert mass[3] == pytest.approx(stats.norm.cdf(2.0) - stats.norm.cdf(1.0), rel=1e-3)


def _white_fit(rrw: float, seed: int) -> ResidualFit:
    model = NoiseModel(RATE, white_variance=3.6e-5, rrw_variance=rrw)
    return fit_residual_model(sample_noise(model, 2**15, rng=np.random.default_rng(seed)), RATE, ModelTerms())


def test_boundary_grid_searches_a_walk_whose_interval_reaches_zero_and_holds_an_interior_one():
    """A walk near 0: the fit's own noise, then 0 and θ̂ + c se (c = Φ̄⁻¹(γ/2), one nuisance) where they
    differ from θ̂. A walk many standard errors from 0: the fit's own noise alone."""
    level = 1e-3
    near = _white_fit(1e-12, 11)
    grid = boundary_grid(near.noise, level)
    walk, error = near.noise.model.rrw_variance, near.noise.standard_errors["rrw_variance"]
    upper = walk + stats.norm.isf(level / 2) * error
    expected = [walk] + [value for value in (0.0, upper) if value != walk]
    assert [noise.model.rrw_variance for noise in grid] == pytest.approx(expected, rel=1e-12)
    assert grid[0] is near.noise
    inside = _white_fit(1e-8, 12)
    assert (
        inside.noise.model.rrw_variance
        > stats.norm.isf(level / 2) * inside.noise.standard_errors["rrw_variance"]
    )
    assert boundary_grid(inside.noise, level) == [inside.noise]


@pytest.mark.parametrize("level", [0.0, 1.0, -0.1, math.nan])
def test_boundary_grid_refuses_a_confidence_level_outside_zero_one(level):
    with pytest.raises(ValueError, match="confidence_level"):
        boundary_grid(_white_fit(1e-12, 11).noise, level)


def _boundary_case() -> tuple[BoundaryReference, float]:
    case = _case(2**15, 1e-12, 20.0)
    record = sample_noise(case.model, case.length, rng=np.random.default_rng(13))
    projection = float(np.dot(case.weights, record))
    record -= projection / float(np.dot(case.block_weights, case.regressor_sums)) * case.centred
    fit = fit_residual_model(record, RATE, ModelTerms(), reference=case.pilot)
    reference = boundary_reference(
        fit, case.length, case.block_weights, projection, 1e-4, case.regressor_sums, 50
    )
    return reference, projection


def test_boundary_reference_is_the_largest_grid_p_value_plus_gamma():
    """sf = max over the grid's references + γ, one reference per grid point (the fit's own walk first);
    the threshold is where the Bonferroni p-value equals α, and a per-test level not above γ is refused."""
    reference, _ = _boundary_case()
    assert len(reference.references) == len(reference.walks) >= 2
    assert min(reference.walks) == 0.0 and max(reference.walks) > reference.walks[0]  # 0 and the upper end
    for z in (0.5, 2.0, 3.5):
        expected = max(part.sf(z) for part in reference.references) + 1e-4
        assert reference.sf(z) == pytest.approx(min(expected, 1.0), rel=1e-12)
    threshold = reference.threshold(0.01, 4)
    assert 10 ** reference.log10_p(threshold, 4) == pytest.approx(0.01, rel=1e-3)
    with pytest.raises(ValueError, match="per-test level"):
        reference.threshold(4e-4, 4)


def test_a_generating_one_over_f_term_the_fit_lacks_enters_the_variance():
    """The fit has no 1/f term, so its statistic units leave the 1/f unit at 0 (no transform of twice the
    record's length); a generating model with a 1/f variance still gets V with its 1/f part, the same V as
    the units with the 1/f unit computed."""
    case = _case(2**15, 1e-11, 20.0)
    generating = replace(
        case.pilot.noise, model=replace(case.pilot.noise.model, flicker_variance=5e-8, flicker_d=0.5)
    )
    reference = trend_reference(
        case.pilot, case.length, case.block_weights, 0.0, case.regressor_sums, 20, generating
    )
    expected = statistic_units(case.weights, 0.5).variance(noise_variances(generating))
    assert fit_units(case.pilot, case.weights).flicker == 0.0
    assert reference.variance == pytest.approx(expected, rel=1e-12)
    assert expected > statistic_units(case.weights, 0.5, flicker=False).variance(noise_variances(generating))
