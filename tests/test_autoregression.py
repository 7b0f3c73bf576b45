"""AR coefficients of the short noise: Yule–Walker when the AR process is the whole short noise, the
high-order Yule–Walker equations when white noise lies beside it.

Seeded records of white + AR noise (the white variance nine times the AR innovation variance, as in the
fit benchmark): the high-order equations recover φ = 0.8 to 0.012 (about three standard deviations of
the estimator at 2·10⁵ samples, measured over 30 seeds: 0.004; a 2 % error, 0.016, breaks it) and the
order of an AR(2); plain Yule–Walker on the same record returns the coefficients of the sum (an ARMA
process), and a fit that uses them is rejected by its own χ² test while the fit with the high-order
coefficients is not. With both white noise and an AR term in the model the coefficients are whichever
of the two describes the record's autocovariance (white + AR): the high-order ones beside white noise, the
plain ones for white noise coloured as a whole by a short filter (a moving average over two samples,
where the high-order equations see no AR process); with the high-pass's offset added back the mean over
8 records of φ = 0.95 lies within 0.002 of it, where the uncorrected equations' mean lies below.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from carousel_theory.autoregression import (
    lag_products,
    short_noise_coefficients,
    yule_walker,
    yule_walker_beside_white,
)
from carousel_theory.fitting import FitOptions, fit_noise_model
from carousel_theory.noise_model import NoiseModel
from carousel_theory.simulate import sample_noise

Z = 4.0  # standard errors allowed to a fitted variance (as elsewhere in the fit's tests)


def _white_and_ar(coefficients: tuple[float, ...]) -> NoiseModel:
    return NoiseModel(
        sample_rate=100.0,
        white_variance=3.6e-5,
        rrw_variance=1e-14,
        ar_variance=4e-6,
        ar_coefficients=coefficients,
    )


def test_high_order_equations_recover_a_gauss_markov_coefficient_beside_white_noise():
    y = sample_noise(_white_and_ar((0.8,)), 200_000, rng=np.random.default_rng(21))
    coefficients = yule_walker_beside_white(y, 100.0, 4)
    assert len(coefficients) == 1
    assert coefficients[0] == pytest.approx(0.8, abs=0.012)
    plain = yule_walker(y, 100.0, 4)  # the sum's coefficients: several, the first far below 0.8
    assert len(plain) > 1 and plain[0] < 0.5


def test_high_order_equations_find_the_order_of_an_ar2_beside_white_noise():
    y = sample_noise(_white_and_ar((1.2, -0.5)), 1_000_000, rng=np.random.default_rng(22))
    coefficients = yule_walker_beside_white(y, 100.0, 4)
    assert len(coefficients) == 2
    # Standard deviations at 2·10⁵ samples over 30 seeds: 0.027 and 0.012; here five times as many samples.
    allowed = 4 * np.array([0.027, 0.012]) / np.sqrt(5)
    assert np.all(np.abs(np.array(coefficients) - (1.2, -0.5)) <= allowed), coefficients


def test_high_order_equations_find_nothing_in_white_noise():
    y = np.random.default_rng(23).standard_normal(200_000)
    assert yule_walker_beside_white(y, 100.0, 4) == ()


def test_a_constant_record_has_no_ar_coefficients():
    for estimator in (yule_walker, yule_walker_beside_white, short_noise_coefficients):
        assert estimator(np.full(5_000, 0.01), 100.0, 4) == ()


def test_white_and_ar_fit_is_not_rejected_and_recovers_both_variances():
    truth = _white_and_ar((0.8,))
    y = sample_noise(truth, 400_000, rng=np.random.default_rng(24))
    result = fit_noise_model(y, 100.0, ("white", "rrw", "ar"))
    assert len(result.model.ar_coefficients) == 1
    assert result.p_value > 1e-3
    for name in ("white_variance", "ar_variance"):
        error = result.standard_errors[name]
        assert abs(getattr(result.model, name) - getattr(truth, name)) <= Z * error
    # The same fit with plain Yule–Walker's coefficients (the sum's) is rejected by its χ² test.
    plain = fit_noise_model(y, 100.0, ("white", "rrw", "ar"), ar_coefficients=yule_walker(y, 100.0, 4))
    assert plain.p_value < 1e-6


@pytest.mark.parametrize("components", [("rrw", "ar"), ("white", "rrw", "ar")])
def test_ar_term_without_correlation_in_the_record_is_refused(components):
    y = 1e-3 * np.random.default_rng(25).standard_normal(100_000)
    with pytest.raises(ValueError, match=r"no short correlated noise.*fit without 'ar'"):
        fit_noise_model(y, 100.0, components)


def test_empty_ar_coefficients_are_refused():
    with pytest.raises(ValueError, match=r"ar_coefficients=\(\): must hold at least one"):
        FitOptions(components=("white", "ar"), ar_coefficients=())


def test_maximum_order_must_be_a_positive_integer():
    with pytest.raises((TypeError, ValueError), match="maximum_order"):
        yule_walker_beside_white(np.zeros(10), 100.0, 0)


def test_white_and_ar_model_takes_the_coefficients_that_describe_the_record():
    rng = np.random.default_rng(26)
    beside = sample_noise(_white_and_ar((0.8,)), 200_000, rng=rng)
    chosen = short_noise_coefficients(beside, 100.0, 4)
    assert len(chosen) == 1 and chosen[0] == pytest.approx(0.8, abs=0.012)  # not the sum's AR(4)
    innovations = rng.standard_normal(200_001)
    filtered = innovations[1:] + 0.4 * innovations[:-1]  # all the white noise behind a short filter
    plain = yule_walker(filtered, 100.0, 4)
    assert abs(yule_walker_beside_white(filtered, 100.0, 4)[0]) < 0.1  # no AR process past lag 1
    chosen = short_noise_coefficients(filtered, 100.0, 4)
    assert len(chosen) > 1 and chosen[0] == pytest.approx(plain[0], abs=0.01)  # plain Yule–Walker's kind
    result = fit_noise_model(filtered, 100.0, ("white", "rrw", "ar"))
    assert result.model.ar_coefficients == chosen
    assert result.p_value > 1e-3


def test_the_high_pass_offset_is_added_back_for_a_long_correlation_time():
    # φ = 0.95 (τ_c = 0.2 s at 100 Hz): the 10-s high-pass lowers the lag covariances by about 4 % of γ(0).
    truth = NoiseModel(
        sample_rate=100.0,
        white_variance=3.6e-5,
        rrw_variance=1e-14,
        ar_variance=2.5e-7,
        ar_coefficients=(0.95,),
    )
    rng = np.random.default_rng(27)
    records = [sample_noise(truth, 1_000_000, rng=rng) for _ in range(8)]
    corrected = [short_noise_coefficients(y, 100.0, 4) for y in records]
    uncorrected = [yule_walker_beside_white(y, 100.0, 4)[0] for y in records]
    assert all(len(c) == 1 for c in corrected)
    # Spread of one estimate over 12 records: 0.0018; the mean of 8 gets three of its standard errors.
    allowed = 3 * 0.0018 / np.sqrt(8)
    assert abs(np.mean([c[0] for c in corrected]) - 0.95) <= allowed
    assert np.mean(uncorrected) < 0.95 - allowed  # without the offset: biased low


def test_the_fit_benchmark_model_is_not_rejected():
    # White + RRW + 1/f + Gauss–Markov (benchmarks/bench_fit_vs_allantools.py): with plain Yule–Walker's
    # coefficients the fit's χ² was 700–800 on 14 degrees of freedom at 10⁶ samples.
    truth = replace(_white_and_ar((0.8,)), flicker_variance=1e-9, flicker_d=0.5)
    y = sample_noise(truth, 400_000, rng=np.random.default_rng(30))
    result = fit_noise_model(y, 100.0, ("white", "rrw", "flicker", "ar"))
    assert result.model.ar_coefficients[0] == pytest.approx(0.8, abs=0.012)
    assert result.p_value > 1e-3
    error = result.standard_errors["white_variance"]
    assert abs(result.model.white_variance - truth.white_variance) <= Z * error


@pytest.mark.parametrize("estimator", [yule_walker, short_noise_coefficients])
def test_an_order_the_record_cannot_carry_is_refused_at_once(estimator):
    record = np.random.default_rng(5).standard_normal(2000)
    with pytest.raises(ValueError, match=r"maximum_order=5000: a record of 2000 samples .* n/4 = 500"):
        estimator(record, 100.0, 5000)


@pytest.mark.parametrize("rate", [0.0, -1.0, float("nan")])
def test_the_high_pass_needs_a_sample_rate(rate):
    from carousel_theory.autoregression import high_pass_window

    with pytest.raises(ValueError, match="sample_rate="):
        high_pass_window(rate)


@given(
    length=st.integers(min_value=1, max_value=20_000),
    lags=st.integers(min_value=0, max_value=80),
    seed=st.integers(min_value=0, max_value=2**32 - 1),
)
def test_lag_products_by_gram_blocks_are_the_exact_integer_sums(length, lags, seed):
    # Integer samples below 2⁷: every product and partial sum is an integer below 2⁵³, so the Gram blocks'
    # sums are exact whatever their order, and equal to the lag products in Python integers. Lengths
    # shorter than a row, than a block, and with a partial last row; lags up to 80 (rows wider than 32).
    lags = min(lags, length - 1)
    samples = np.random.default_rng(seed).integers(-100, 100, length)
    values = [int(v) for v in samples]
    exact = [sum(values[i] * values[i + k] for i in range(length - k)) for k in range(lags + 1)]
    found = lag_products(samples.astype(np.float64), lags)
    np.testing.assert_array_equal(found, np.array(exact, dtype=float))


def test_lag_products_of_real_samples_equal_one_dot_per_lag_within_rounding():
    x = np.random.default_rng(7).standard_normal(300_001)
    direct = np.array([float(np.dot(x[: len(x) - k], x[k:])) for k in range(25)])
    bound = 1e-12 * float(np.dot(x, x))  # rounding of a sum of 3·10⁵ products, far below their spread
    assert np.all(np.abs(lag_products(x, 24) - direct) <= bound)
