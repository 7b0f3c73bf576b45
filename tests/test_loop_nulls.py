"""The 1/f decision's null distribution: the sequential Monte Carlo test has its stated size, the
bootstrap statistic is the loop's nested-fit statistic, and the Allan-variance draws have the law of
whole simulated records."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from conftest import Z_MONTE_CARLO
from scipy import stats

from carousel_theory.closed_loop.calibration import (
    FLICKER_STREAM,
    MISFIT_STREAM,
    AllanVarianceSampler,
    bootstrap_generator,
    octave_allan,
    sequential_monte_carlo_p,
)
from carousel_theory.closed_loop.linear_statistics import nested_chi_square
from carousel_theory.closed_loop.noise_detectors import FlickerDetector, NestedAllanStatistic
from carousel_theory.closed_loop.residual_model import ModelTerms
from carousel_theory.closed_loop.view import ModelSpec, build_view
from carousel_theory.simulate import sample_noise, simulate_recording

RATE, WHITE = 100.0, 3.6e-5


def _view(samples: int, effects=(), seed: int = 5, rrw_variance: float = 1e-11):
    """A two-axis view of the declared model (bias + white + walk) plus ``effects``, fitted as declared."""
    noise = {"bias": 0.01, "white_variance": WHITE, "rrw_variance": rrw_variance}
    rng = np.random.default_rng(seed)
    recording = simulate_recording(samples, RATE, rng=rng, effects=list(effects), **noise)
    return build_view(recording, ("wx", "wy"), ModelSpec())


@pytest.mark.parametrize("alpha", [0.05, 0.03, 0.2])
def test_sequential_monte_carlo_p_rejects_with_probability_one_over_b_plus_one(alpha):
    """For a continuous statistic and exchangeable draws, P(no replicate reaches T) = 1/(B + 1) with
    B = ⌈1/α⌉ − 1, so the size is 1/(B + 1) ≤ α; 200,000 seeded tests resolve it to a few per cent
    of itself (far below a 2-point error of the rate)."""
    rng = np.random.default_rng(17)
    trials = 200_000
    budget = math.ceil(1.0 / alpha) - 1
    size = 1.0 / (budget + 1)
    rejections = 0
    for _ in range(trials):
        p_value, _ = sequential_monte_carlo_p(rng.random, rng.random(), alpha)
        rejections += p_value <= alpha
    standard_error = math.sqrt(size * (1 - size) / trials)
    assert size <= alpha
    assert Z_MONTE_CARLO * standard_error < 0.1 * size  # a 10 % error of the size would fail
    assert abs(rejections / trials - size) <= Z_MONTE_CARLO * standard_error


def test_sequential_monte_carlo_p_stops_at_the_first_exceedance_and_otherwise_draws_b():
    draws = iter([0.1, 0.2, 0.9, 0.3])
    assert sequential_monte_carlo_p(lambda: next(draws), 0.5, 0.01) == (1.0 / 3.0, 3)
    p_value, drawn = sequential_monte_carlo_p(lambda: 0.0, 0.5, 0.01)
    assert (p_value, drawn) == (pytest.approx(1.0 / 100.0, rel=1e-15), 99)


def test_nested_statistic_is_the_loops_nested_fit_statistic():
    """On the observed Allan variance the bootstrap statistic equals Δχ²/max(1, χ²/ν) of the loop's
    own nested fits (fitting.fit_observed under the reference covariance), with and without 1/f noise."""
    for effects in ([], ["flicker:variance=3e-7"]):
        view = _view(30_000, effects)
        for axis in view.axes:
            without, _ = nested_chi_square(view, axis, flicker=False)
            with_flicker, dof = nested_chi_square(view, axis, flicker=True)
            expected = max(0.0, without - with_flicker) / max(1.0, with_flicker / dof)
            statistic = NestedAllanStatistic.from_fit(view.fits[axis])
            assert statistic.dof == dof
            assert statistic(view.fits[axis].observed) == pytest.approx(expected, rel=1e-9, abs=1e-12)


def test_octave_allan_of_the_samples_is_the_fitted_estimator():
    view = _view(30_000)
    fit = view.fits["wx"]
    assert int(fit.sizes[0]) == 1
    computed = octave_allan(view.cleaned["wx"], len(fit.sizes), 1)
    assert computed == pytest.approx(fit.observed, rel=1e-12)


def test_allan_variance_draws_have_the_law_of_whole_simulated_records():
    """1500 draws of the sampler (long τ from block sums, short τ Gaussian given them) against 1500
    whole records of the fitted model through the same estimator: every τ's mean and variance agree
    within Z_MONTE_CARLO standard errors, and the 1/f statistic's distribution passes a two-sample
    Kolmogorov–Smirnov test at the suite's two-sided level."""
    samples, count = 30_000, 1500
    view = _view(samples, rrw_variance=1e-10)
    fit = view.fits["wx"]
    assert fit.noise.model.rrw_variance > 0
    sampler = AllanVarianceSampler.from_fit(fit, samples)
    assert 0 < sampler.first < len(fit.sizes)
    statistic = NestedAllanStatistic.from_fit(fit)
    rng = np.random.default_rng(23)
    drawn = np.array([sampler.draw(rng) for _ in range(count)])
    whole = np.array(
        [
            octave_allan(sample_noise(fit.noise.model, samples, rng=rng), len(fit.sizes), 1)
            for _ in range(count)
        ]
    )
    spread = np.sqrt((drawn.var(axis=0) + whole.var(axis=0)) / count)
    assert np.all(np.abs(drawn.mean(axis=0) - whole.mean(axis=0)) <= Z_MONTE_CARLO * spread)
    # Each τ's spread: log of the variance ratio, standard error from the fourth moments
    # (se² of log s² is (κ − 1)/n, κ the kurtosis); a short-τ variance off by a factor two gives z ≈ 12.
    kurtosis = [stats.kurtosis(values, axis=0, fisher=False) for values in (drawn, whole)]
    log_ratio = np.log(drawn.var(axis=0) / whole.var(axis=0))
    assert np.all(np.abs(log_ratio) <= Z_MONTE_CARLO * np.sqrt((kurtosis[0] - 1 + kurtosis[1] - 1) / count))
    level = 2.0 * float(stats.norm.sf(Z_MONTE_CARLO))
    result = stats.ks_2samp([statistic(a) for a in drawn], [statistic(a) for a in whole])
    assert result.pvalue > level


def test_flicker_detector_is_deterministic_and_finds_strong_flicker():
    view = _view(30_000, ["flicker:variance=1e-6"])
    first = FlickerDetector().detect(view, 1e-3)
    second = FlickerDetector().detect(view, 1e-3)
    assert first.as_dict() == second.as_dict()
    assert first.significant and first.details["replicates"] == 1999  # α/2 per axis
    assert first.log10_p == pytest.approx(math.log10(2.0 / 2000.0), rel=1e-12)
    clean = FlickerDetector().detect(_view(30_000, seed=6), 1e-3)
    assert not clean.significant


def test_flicker_detector_says_when_the_model_already_has_a_1f_term():
    view = _view(30_000)
    with_flicker = replace(view, spec=replace(view.spec, terms=ModelTerms(flicker=True)))
    detection = FlickerDetector().detect(with_flicker, 1e-3)
    assert not detection.testable and "already has a 1/f term" in detection.note


def test_digest_seeded_tests_have_their_size_across_recordings():
    """Each "recording" (a uniform statistic) seeds its own replicates from a digest of what it observed:
    over 40,000 recordings the rejection rate is 1/(B + 1), as for independent replicates (one fixed
    stream would give every recording the same critical value instead); the same values give the same
    stream."""
    rng = np.random.default_rng(29)
    trials, alpha = 40_000, 0.05
    size = 1.0 / math.ceil(1.0 / alpha)
    rejections = 0
    for _ in range(trials):
        observed = rng.random()
        replicates = bootstrap_generator(FLICKER_STREAM, [np.array([observed])])
        rejections += sequential_monte_carlo_p(replicates.random, observed, alpha)[0] <= alpha
    standard_error = math.sqrt(size * (1 - size) / trials)
    # Resolves ±10 % of the size (4.5 standard errors = 0.0049 at 0.05): enough to catch a fixed stream
    # (a rejection rate of 0.12 with this seed); the size itself is held to 1/(B + 1) by the
    # 200,000-trial test of sequential_monte_carlo_p.
    assert Z_MONTE_CARLO * standard_error < 0.1 * size
    assert abs(rejections / trials - size) <= Z_MONTE_CARLO * standard_error
    same = [bootstrap_generator(MISFIT_STREAM, [np.arange(3.0)]).random() for _ in range(2)]
    assert same[0] == same[1] != bootstrap_generator(FLICKER_STREAM, [np.arange(3.0)]).random()


def test_bootstrap_replicates_do_not_depend_on_the_last_bits_of_the_observed_values():
    # Another summation order or CPU changes the observed Allan variances in their last bits; the replicates
    # must stay those of the same recording, while a real change of the values draws other ones.
    observed = np.random.default_rng(8).lognormal(-20.0, 3.0, size=24)
    nudged = observed.copy()
    nudged[::2] = np.nextafter(nudged[::2], np.inf)
    nudged[1::3] = np.nextafter(np.nextafter(nudged[1::3], 0.0), 0.0)
    first = bootstrap_generator(FLICKER_STREAM, [observed]).random(4)
    np.testing.assert_array_equal(bootstrap_generator(FLICKER_STREAM, [nudged]).random(4), first)
    changed = observed.copy()
    changed[5] *= 1.0 + 1e-6
    assert not np.array_equal(bootstrap_generator(FLICKER_STREAM, [changed]).random(4), first)
