"""The AR autocovariance as geometric modes and its fourth sum in closed form (carousel_theory.ar_modes).

- H = S·H_w + Σ C_i λ_i^{|x+2|} against the fourth cumulative sum of the truncated γ_z
  (:func:`carousel_theory.increment_sums.finite_fourth_sum`, no modes), at every integer within the
  truncation reach, for real, negative, complex and mixed roots and τ_c up to 1000 samples;
- AR(1) in closed form: S = 1/(1 − φ)², C = −φ/((1 − φ)²(1 − φ²)) (from γ(k) = φ^|k|/(1 − φ²));
- the derivative bound against 30-digit derivatives of the analytic continuation between the integers;
- roots that are repeated or zero fall back to the truncated γ_z; modes that turn faster than they decay
  keep their reach of exact lags, smooth ones none, so that the lag quadrature's exact lags do not grow
  with the correlation time.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

from carousel_theory.ar_modes import ar_modes, fourth_sum_of_modes, mode_derivative_bound
from carousel_theory.increment_sums import finite_fourth_sum
from carousel_theory.lag_quadrature import REACH_STEP, LagModel, PairBatch
from carousel_theory.noise_model import NoiseModel, ar_increment_reach, increment_autocovariance

COEFFICIENTS = [
    (0.3,),
    (0.8,),
    (0.999,),
    (-0.5,),
    (0.6, -0.2),  # a complex pair
    (0.5, 0.2),  # a positive and a negative root
    (0.3, 0.2, 0.1),  # a positive root and a complex pair
    (1.2, -0.5, 0.1),
]


@pytest.mark.parametrize("coefficients", COEFFICIENTS)
def test_modal_fourth_sum_is_the_fourth_sum_of_the_truncated_autocovariance(coefficients):
    modes = ar_modes(coefficients)
    assert modes is not None
    reach = ar_increment_reach(coefficients)
    gamma = increment_autocovariance("ar", reach + 1, ar_coefficients=coefficients)
    x = np.arange(-reach - 12, reach + 12)
    direct = finite_fourth_sum(gamma, x, total=0.0)
    white = -np.maximum(x + 2, 0)
    modal = modes.long_run_variance * white + fourth_sum_of_modes(modes, np.abs(x + 2.0))
    # Both carry the rounding of sums of values up to max|H| (the truncated tail is below 1e-17 of γ(0)).
    assert np.max(np.abs(modal - direct)) <= 1e-11 * np.max(np.abs(direct))


@pytest.mark.parametrize("phi", [0.1, 0.5, 0.8, 0.95, 0.999])
def test_first_order_modes_in_closed_form(phi):
    modes = ar_modes((phi,))
    assert modes is not None
    assert modes.roots == pytest.approx([phi], rel=1e-15)
    assert modes.long_run_variance == pytest.approx(1.0 / (1.0 - phi) ** 2, rel=1e-14)
    expected = -phi / ((1.0 - phi) ** 2 * (1.0 - phi**2))
    assert modes.weights.real[0] == pytest.approx(expected, rel=1e-11)
    assert modes.rough_reach == 0


@pytest.mark.parametrize("coefficients", [(0.6, -0.2), (0.5, 0.2), (0.9,)])
@pytest.mark.parametrize("distance", [3.3, 17.5, 60.25])
def test_derivative_bound_holds_between_the_integers(coefficients, distance):
    modes = ar_modes(coefficients)
    assert modes is not None
    order = 12
    with mpmath.workdps(30):
        roots = [mpmath.mpc(complex(r)) for r in modes.roots]
        weights = [mpmath.mpc(complex(w)) for w in modes.weights]

        def continued(j):
            terms = (w * mpmath.exp(j * mpmath.log(r)) for r, w in zip(roots, weights, strict=True))
            return mpmath.re(mpmath.fsum(terms))

        for step in (0.0, 0.5, 2.0):  # the bound at j holds for every j' ≥ j
            derivative = abs(mpmath.diff(continued, mpmath.mpf(distance) + step, order))
            bound = float(mode_derivative_bound(modes, np.array([distance]), order)[0])
            assert float(derivative) / math.factorial(order) <= bound * (1 + 1e-12)
        value = continued(mpmath.mpf(distance))
        assert float(value) == pytest.approx(
            float(fourth_sum_of_modes(modes, np.array([distance]))[0]), rel=1e-12
        )


@pytest.mark.parametrize("coefficients", [(1.6, -0.64), (0.5, 0.0), (0.0,)])
def test_repeated_or_zero_roots_keep_the_truncated_autocovariance(coefficients):
    assert ar_modes(coefficients) is None
    model = NoiseModel(sample_rate=1.0, white_variance=1.0, ar_variance=0.5, ar_coefficients=coefficients)
    lag_model = LagModel.of(model)
    assert lag_model.modes is None
    # The truncated γ_z's reach, rounded up to a multiple of REACH_STEP lags when it exceeds 3.
    reach = max(3, ar_increment_reach(coefficients))
    assert lag_model.reach == (reach if reach == 3 else -(-reach // REACH_STEP) * REACH_STEP)
    assert lag_model.reach >= ar_increment_reach(coefficients)


def test_rough_modes_keep_their_reach_and_smooth_ones_none():
    negative = ar_modes((-0.9,))
    assert negative is not None
    assert negative.rough_reach == ar_increment_reach((-0.9,))
    slow = ar_modes((0.999,))
    assert slow is not None and slow.rough_reach == 0
    model = NoiseModel(sample_rate=1.0, white_variance=1.0, ar_variance=0.5, ar_coefficients=(-0.9,))
    assert LagModel.of(model).reach >= negative.rough_reach


def test_exact_lags_do_not_grow_with_the_correlation_time():
    length = 200_000
    sizes = [2**k for k in range(16)]
    terms = [length - 2 * m + 1 for m in sizes]
    pairs = [(sizes[i], sizes[j], terms[i], terms[j]) for j in range(len(sizes)) for i in range(j + 1)]
    counts = []
    for coefficients in [(), (0.5,), (0.99,), (0.9999,)]:
        model = NoiseModel(
            sample_rate=1.0,
            white_variance=1.0,
            flicker_variance=0.1,
            flicker_d=0.4,
            ar_variance=0.5 if coefficients else 0.0,
            ar_coefficients=coefficients,
        )
        lag_model = LagModel.of(model)
        batch = PairBatch.of(pairs, lag_model.reach)
        counts.append((len(batch.lags), len(batch.nodes)))
    assert len(set(counts)) == 1
