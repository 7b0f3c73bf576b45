"""Claims of TIM 2014 §I–§III, eq. (26) and the §V set-up: the cheap checks detect a wrong statement
when fed a perturbed one, and the helpers are checked two ways (every status is pinned in
tests/test_claims_status.py)."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import sympy as sp

from carousel_theory.claim import Status
from carousel_theory.claims import _common as common
from carousel_theory.claims import (
    tim2014_sec1_introduction,
    tim2014_sec2_error_processes,
    tim2014_sec3_carouseling,
    tim2014_sec4_constant_allan_variance,
    tim2014_sec5ab_simulations,
    tim2014_sec5c_static_test,
)

# --- the checks detect a wrong statement ---------------------------------------------------------


def test_estimator_check_refutes_a_wrong_sign():
    assert tim2014_sec3_carouseling._check_estimator(sign_x=1).status is Status.REFUTED
    assert tim2014_sec3_carouseling._check_estimator(sign_y=-1).status is Status.REFUTED


def test_partition_check_refutes_a_wrong_lower_left_block():
    assert tim2014_sec3_carouseling._check_partition(range(1, 4), lower_left=2).status is Status.REFUTED
    assert tim2014_sec3_carouseling._check_partition(range(1, 4), lower_left=0).status is Status.REFUTED


def test_eq15_check_refutes_a_wrong_ones_term():
    assert (
        tim2014_sec3_carouseling._check_eq15_block_expansion(range(2, 4), ones_block_cube=2).status
        is Status.REFUTED
    )


def test_quantization_check_accepts_inputs_that_give_no_correlated_error():
    # integer inputs are quantized without error: nothing to refute there
    verdict = tim2014_sec2_error_processes._check_quantization_white(
        constant=Fraction(0), ramp_step=Fraction(1)
    )
    assert verdict.status is Status.VERIFIED


def test_thermal_check_refutes_whiteness_beyond_kt_over_h():
    assert tim2014_sec2_error_processes._check_thermal_white(frequency=1e13).status is Status.REFUTED


def test_flicker_name_check_refutes_one_over_f_at_other_orders():
    assert tim2014_sec1_introduction._check_flicker_name(order=Fraction(1, 4)).status is Status.REFUTED
    assert tim2014_sec1_introduction._check_flicker_name(order=Fraction(3, 4)).status is Status.REFUTED


def test_integer_ratio_check_refutes_when_the_ratio_is_an_integer():
    verdict = tim2014_sec3_carouseling._check_integer_ratio_needed(
        samples=8, samples_per_revolution=Fraction(8)
    )
    assert verdict.status is Status.REFUTED


def test_covariance_identity_check_refutes_the_two_by_two_for_three_columns():
    assert tim2014_sec4_constant_allan_variance._check_covariance_identity(order=3).status is Status.REFUTED


def test_simulation_setup_check_refutes_a_wrong_case_count():
    assert tim2014_sec5ab_simulations._check_rrw_simulation_setup(printed_cases=2000).status is Status.REFUTED
    assert tim2014_sec5ab_simulations._check_rrw_simulation_setup(realisations=1000).status is Status.REFUTED


def test_flicker_allan_check_refutes_a_constant_allan_variance_at_other_orders():
    assert (
        tim2014_sec4_constant_allan_variance._check_flicker_allan_constant(order=0.25).status
        is Status.REFUTED
    )
    assert (
        tim2014_sec4_constant_allan_variance._check_flicker_allan_constant(order=0.75).status
        is Status.REFUTED
    )


def test_averages_correlation_by_brute_force():
    # Corr of the two bin means from dense R_2 (Fractions), N = 3: Cov = 2, V_1 = 14/9, V_2 = 14/9 + 3
    n = 3
    walk = [[Fraction(int(u <= t)) for u in range(2 * n)] for t in range(2 * n)]  # R_2 rows
    first = [sum(walk[t][u] for t in range(n)) / n for u in range(2 * n)]
    second = [sum(walk[t][u] for t in range(n, 2 * n)) / n for u in range(2 * n)]
    covariance = sum(p * q for p, q in zip(first, second, strict=True))
    variances = (sum(p * p for p in first), sum(q * q for q in second))
    assert (covariance, variances) == (Fraction(2), (Fraction(14, 9), Fraction(41, 9)))
    evidence = tim2014_sec3_carouseling._check_averages_correlated(n_value=3).evidence
    expected = sp.N(2 / sp.sqrt(sp.Rational(14, 9) * sp.Rational(41, 9)), 6)
    assert f"{expected} at N = 3" in evidence


def test_earth_rate_numbers_by_hand():
    # 7.292115e-5 rad/s · cos 61.5° ≈ 3.48e-5 rad/s; over one hour ≈ 0.1253 rad ≈ 7.18°
    evidence = tim2014_sec5c_static_test._check_zero_true_rate().evidence
    horizontal = 7.292115e-5 * np.cos(np.radians(61.5))
    assert f"{horizontal:.2e}".replace("e-05", "e-5") + " rad/s" in evidence  # mpmath writes e-5
    assert f"{np.degrees(horizontal * 3600):.3g}°" in evidence
    # carouselled white bin: (3e-5 + 1e-5)/(2·200) = 1e-7 (rad/s)², σ = 3.16e-4 rad/s
    assert "σ = 0.000316 rad/s" in evidence


def test_x_rrw_crossing_by_hand():
    # σ_WN²/τ = σ_q² τ/3 at τ = √(3 · 3e-7 / 3e-10) = √3000 s
    assert f"{np.sqrt(3000):.1f} s" in tim2014_sec5c_static_test._check_x_rrw_slope().evidence


# --- the helpers, two ways -----------------------------------------------------------------------


@pytest.mark.parametrize("size", [1, 2, 5])
def test_cumulative_sum_matrices_equal_numpy_lower_triangles(size):
    assert np.array_equal(
        np.array(common.cumulative_sum_matrix(size), dtype=int), np.tril(np.ones((size, size)))
    )
    assert np.array_equal(
        np.array(tim2014_sec3_carouseling._partitioned_matrix(size), dtype=int),
        np.tril(np.ones((2 * size, 2 * size))),
    )


def testconditional_rrw_covariances_of_the_walk_by_hand():
    # r_4 = r_3 + q_4 and r_3 = r_2 + q_3: given r_2, Cov(r_3, r_4) = Var q_3 = 1; r_1 is in the past
    assert common.conditional_rrw_covariance(6, (3, 4), (2,)) == 1
    assert common.conditional_rrw_covariance(6, (3, 1), (2,)) == 0
    # given both neighbours r_2 and r_4, r_3 is a bridge value, independent of r_5
    assert common.conditional_rrw_covariance(6, (3, 5), (2, 4)) == 0
    # conditional variance of r_3 given r_2, r_4: the Brownian-bridge value 1·1/2
    assert common.conditional_rrw_covariance(6, (3, 3), (2, 4)) == sp.Rational(1, 2)


def test_quantization_helpers_on_hand_values():
    assert tim2014_sec2_error_processes._quantization_errors(
        [Fraction(1, 3), Fraction(1, 2), Fraction(-7, 10)]
    ) == [
        Fraction(-1, 3),
        Fraction(1, 2),
        Fraction(-3, 10),
    ]
    assert tim2014_sec2_error_processes._centred_autocorrelation([Fraction(1), Fraction(-1)] * 3, 1) == -1
    assert tim2014_sec2_error_processes._centred_autocorrelation([Fraction(2)] * 4, 1) == 0
    moments = tim2014_sec2_error_processes._dithered_error_moments()
    assert all(not moment.free_symbols for moment in moments)


def test_dithered_error_is_uniform_by_exact_enumeration():
    # x = 3/10 with dither on a grid of 10 000 midpoints of [−1/2, 1/2): the error takes each grid value once
    steps = 10_000
    dithers = [Fraction(2 * index + 1, 2 * steps) - Fraction(1, 2) for index in range(steps)]
    x = Fraction(3, 10)
    errors = sorted(tim2014_sec2_error_processes._round_to_step(x + u) - (x + u) for u in dithers)
    expected = sorted(Fraction(2 * index + 1, 2 * steps) - Fraction(1, 2) for index in range(steps))
    assert errors == expected
