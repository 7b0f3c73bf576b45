"""Notices beside a fit's numbers (issue 12 point 2, issue 13 point 11): a rejected model says what that
means and what to try, a term held at zero says so with its likely cause, and the fitted ARW is compared
with the textbook 1-s read-off when a filter bends the short-τ end."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from conftest import Z_MONTE_CARLO

from carousel_theory.autoregression import HIGH_ORDER, short_noise_estimate
from carousel_theory.fit_diagnostics import (
    AR_CORRELATION_FRACTION,
    READ_OFF_TOLERANCE,
    WEAK_TERM_LEVEL,
    angle_random_walk_read_off,
    ar_correlation_notice,
    fit_notices,
    read_off_notice,
    rejection_notice,
    weak_term_notices,
)
from carousel_theory.fitting import ALLAN_PROFILE, fit_noise_model
from carousel_theory.noise_model import NoiseModel
from carousel_theory.simulate import sample_noise

RATE = 100.0


def filtered_sensor(samples: int = 100_000, seed: int = 3) -> np.ndarray:
    """White noise through a 4-sample moving average (an internal filter) plus 1/f noise."""
    rng = np.random.default_rng(seed)
    filtered = np.convolve(6e-3 * rng.standard_normal(samples + 3), np.ones(4) / 4, mode="valid")
    flicker = NoiseModel(sample_rate=RATE, flicker_variance=1e-9, flicker_d=0.5)
    return filtered + sample_noise(flicker, samples, rng=rng)


@pytest.fixture(scope="module")
def sensor() -> np.ndarray:
    return filtered_sensor()


@pytest.fixture(scope="module")
def white_rrw_all_tau(sensor):
    return fit_noise_model(sensor, RATE, ("white", "rrw"))


def test_issue13_white_held_at_zero_is_reported_with_cause_and_remedy(sensor):
    fit = fit_noise_model(sensor, RATE, ("white", "rrw", "flicker"))
    assert "white_variance" in fit.at_bound  # the failure of issue 13 point 11, reproduced
    messages = [n.message for n in fit_notices(fit) if n.kind == "term_at_bound"]
    white = next(m for m in messages if m.startswith("white_variance"))
    assert "held at zero" in white and "no standard error" in white
    assert "--tau-min" in white and "'ar'" in white and "1/f term (order d = " in white


def test_rejected_model_says_what_it_means_and_what_to_try(white_rrw_all_tau):
    fit = white_rrw_all_tau
    assert fit.p_value < 0.01
    notice = rejection_notice(fit)
    assert notice is not None and notice.kind == "model_rejected"
    scale = math.sqrt(fit.chi_square / fit.degrees_of_freedom)
    assert f"√(χ²/dof) = {scale:.3g}" in notice.message
    for advice in ("too small", "--tau-min 1", "'flicker'", "'ar'", "carousel-theory loop"):
        assert advice in notice.message


def test_arw_read_off_at_the_octave_tau_nearest_one_second(sensor, white_rrw_all_tau):
    tau, value, low, high = angle_random_walk_read_off(white_rrw_all_tau)
    assert tau == 1.28  # 128 samples at 100 Hz: the octave τ nearest 1 s
    m = 128  # the overlapping Allan variance at m, written out
    angle = np.concatenate(([0.0], np.cumsum(sensor))) / RATE
    avar = np.mean((angle[2 * m :] - 2 * angle[m:-m] + angle[: -2 * m]) ** 2) / (2 * tau**2)
    assert value == pytest.approx(math.sqrt(avar * tau) * 180 / math.pi * 60, rel=1e-9)
    assert low < value < high


def test_arw_read_off_notice_when_the_filter_bends_the_short_tau_end(white_rrw_all_tau):
    notice = read_off_notice(white_rrw_all_tau)
    assert notice is not None
    fitted = white_rrw_all_tau.model.angle_random_walk_deg_per_sqrt_hour()
    _, read, low, high = angle_random_walk_read_off(white_rrw_all_tau)
    assert abs(read - fitted) > READ_OFF_TOLERANCE * fitted and not low <= fitted <= high
    assert f"{fitted:.3g} °/√h" in notice.message and f"{read:.3g} °/√h" in notice.message
    assert "internal filter" in notice.message and "--tau-min 1" in notice.message


def test_a_model_that_holds_gives_no_notice():
    model = NoiseModel(sample_rate=RATE, white_variance=1e-6, rrw_variance=1e-11)
    y = sample_noise(model, 100_000, rng=np.random.default_rng(21))
    fit = fit_noise_model(y, RATE, ("white", "rrw"))
    assert fit.p_value >= 0.01 and not fit.at_bound
    assert fit_notices(fit) == []


def test_a_weakly_determined_walk_is_reported_with_its_interval_by_test_inversion():
    model = NoiseModel(sample_rate=RATE, white_variance=3.6e-5, rrw_variance=1e-14)
    fit = fit_noise_model(sample_noise(model, 1_000_000, rng=np.random.default_rng(3)), RATE)
    relative = fit.standard_errors["rrw_variance"] / fit.model.rrw_variance
    assert relative > WEAK_TERM_LEVEL  # the walk is known to about 80 % on this record
    (notice,) = weak_term_notices(fit)  # the white noise, known to 0.2 %, gives none
    low, high = fit.interval("rrw_variance", method="inverted")
    assert notice.kind == "weakly_determined" and notice.message.startswith("rrw_variance")
    assert f"standard error {relative:.0%}" in notice.message and f"{low:.3g} … {high:.3g}" in notice.message
    assert notice in fit_notices(fit)


def _gauss_markov_record(phi: float) -> np.ndarray:
    """white + AR(1) of coefficient φ, long-run AR variance 10⁻⁴, 2·10⁵ samples at 100 Hz."""
    truth = NoiseModel(
        sample_rate=RATE, white_variance=3.6e-5, ar_variance=1e-4 * (1 - phi) ** 2, ar_coefficients=(phi,)
    )
    return sample_noise(truth, 200_000, rng=np.random.default_rng(41))


def _gauss_markov_fit(phi: float, **options):
    """:func:`_gauss_markov_record` fitted as white + AR."""
    return fit_noise_model(_gauss_markov_record(phi), RATE, ("white", "ar"), **options)


def test_a_long_gauss_markov_correlation_is_refined_by_the_allan_variance():
    # τ_c = 1 s at 100 Hz against the estimator's 10-s window: the record's estimate (high-order
    # Yule–Walker) is biased low and its model is rejected; the fit refines φ by its χ² and is not.
    slow = _gauss_markov_fit(0.99)
    assert slow.ar_estimator == ALLAN_PROFILE and ALLAN_PROFILE in slow.method
    (phi,), (error,) = slow.model.ar_coefficients, slow.ar_coefficient_errors
    assert abs(phi - 0.99) <= Z_MONTE_CARLO * error
    assert slow.p_value > 0.01
    record = short_noise_estimate(_gauss_markov_record(0.99), RATE, 4)
    assert record.coefficients[0] < phi - Z_MONTE_CARLO * error  # biased low, by more than the spread
    held = _gauss_markov_fit(0.99, ar_coefficients=record.coefficients)
    assert held.p_value < 1e-4
    assert ar_correlation_notice(slow) is None  # refined: nothing to report
    short = _gauss_markov_fit(0.8)  # τ_c = 4.5 samples: the record's estimate is kept
    assert short.ar_estimator == HIGH_ORDER


def test_a_long_estimated_gauss_markov_correlation_time_is_reported_when_not_refined():
    # W = 1001 samples at 100 Hz: τ_c above 50 samples (φ above 0.98) kept as the record's estimate is
    # reported (the fit refines it unless its χ² does not fall), a short one is not, and a given
    # coefficient never is.
    slow = _gauss_markov_fit(0.99)
    kept = replace(slow, ar_estimator=HIGH_ORDER)
    (phi,) = kept.model.ar_coefficients
    assert -1.0 / math.log(phi) > 1001 / AR_CORRELATION_FRACTION
    notices = [n for n in fit_notices(kept) if n.kind == "ar_correlation_long"]
    assert len(notices) == 1 and f"φ = {phi:.4g}" in notices[0].message
    assert "--ar-coefficients" in notices[0].message
    assert ar_correlation_notice(_gauss_markov_fit(0.8)) is None
    assert ar_correlation_notice(_gauss_markov_fit(0.99, ar_coefficients=(0.99,))) is None


@pytest.mark.parametrize(
    ("coefficients", "message"),
    [
        ((1.2,), r"ar_coefficients=\(1.2,\): must describe a stationary"),
        ((0.5, 0.6), r"ar_coefficients=\(0.5, 0.6\): must describe a stationary"),
        ((float("nan"),), r"ar_coefficients\[0\]=nan: must be a number, not NaN"),
        ((), r"ar_coefficients=\(\): must hold at least one"),
    ],
)
def test_given_ar_coefficients_must_be_finite_and_stationary(coefficients, message):
    with pytest.raises(ValueError, match=message):
        _gauss_markov_fit(0.8, ar_coefficients=coefficients)
