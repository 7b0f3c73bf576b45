"""Covariance of Allan-variance estimates across τ: the closed form against exact Fraction sums and the
dense O(n) computation, the finite lag sums against dense Toeplitz algebra, the 1/f truncation bound, and
a seeded Monte Carlo."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from conftest import GYRO_MODEL, Z_MONTE_CARLO
from scipy.linalg import toeplitz

from carousel_theory import tau_covariance
from carousel_theory.allan import allan_covariance, equivalent_degrees_of_freedom
from carousel_theory.lag_plan import PROVED_RULE, WEIGHTS_RULE
from carousel_theory.noise_model import NoiseModel
from carousel_theory.tau_covariance import (
    _finite_gram,
    allan_estimate_covariance,
    allan_estimate_variance,
)

INCREMENT_TAPS = {"white": {0: 2, 1: -1}, "rrw": {0: 1}, "quantization": {0: 6, 1: -4, 2: 1}}


def _difference_rows(m: int, length: int, starts: range) -> list[list[int]]:
    """Each cluster-sum difference as integer weights on the increments z_1 … z_{length−1}."""
    triangle = [min(k + 1, 2 * m - 1 - k) for k in range(2 * m - 1)]
    rows = []
    for s in starts:
        row = [0] * (length - 1)
        row[s : s + 2 * m - 1] = triangle
        rows.append(row)
    return rows


def _exact_pair_sum(term_a: str, term_b: str, m_i: int, m_j: int, length: int) -> int:
    """Σ_s Σ_r cov_a(d_{i,s}, d_{j,r}) cov_b(d_{i,s}, d_{j,r}) in integers (overlapping), by brute force."""
    rows_i = _difference_rows(m_i, length, range(length - 2 * m_i + 1))
    rows_j = _difference_rows(m_j, length, range(length - 2 * m_j + 1))

    def covariance(taps: dict[int, int], a: list[int], b: list[int]) -> int:
        return sum(
            a[p] * b[q] * taps.get(abs(p - q), 0)
            for p in range(len(a))
            if a[p]
            for q in range(max(0, p - 2), min(len(b), p + 3))
        )

    return sum(
        covariance(INCREMENT_TAPS[term_a], a, b) * covariance(INCREMENT_TAPS[term_b], a, b)
        for a in rows_i
        for b in rows_j
    )


@pytest.mark.parametrize(
    ("m_i", "m_j", "length"), [(1, 1, 9), (1, 3, 12), (2, 3, 14), (2, 5, 17), (3, 3, 10), (1, 4, 25)]
)
def test_closed_form_equals_exact_integer_sums(m_i, m_j, length):
    K_i, K_j = length - 2 * m_i + 1, length - 2 * m_j + 1
    ww, wr, rr, qq, qw, qr = _finite_gram(m_i, m_j, K_i, K_j)
    assert ww == _exact_pair_sum("white", "white", m_i, m_j, length)
    assert wr == _exact_pair_sum("white", "rrw", m_i, m_j, length)
    assert rr == _exact_pair_sum("rrw", "rrw", m_i, m_j, length)
    assert qq == _exact_pair_sum("quantization", "quantization", m_i, m_j, length)
    assert qw == _exact_pair_sum("quantization", "white", m_i, m_j, length)
    assert qr == _exact_pair_sum("quantization", "rrw", m_i, m_j, length)


MODELS = {
    "white": NoiseModel(sample_rate=1.0, white_variance=1.0),
    "rrw": NoiseModel(sample_rate=1.0, rrw_variance=1.0),
    "quantization": NoiseModel(sample_rate=1.0, quantization=0.3),
    "mixed": NoiseModel(sample_rate=1.0, white_variance=2.0, rrw_variance=0.01, quantization=0.1),
}


@pytest.mark.parametrize("estimator", ["overlapping", "non-overlapping"])
@pytest.mark.parametrize("name", sorted(MODELS))
def test_against_dense_computation(name, estimator):
    sizes = np.array([1, 2, 4, 8, 16, 32, 64])
    new = allan_estimate_covariance(MODELS[name], sizes, 200, estimator=estimator)
    dense = allan_covariance(MODELS[name], sizes, 200, estimator=estimator)
    np.testing.assert_allclose(new.covariance, dense, rtol=1e-11, atol=1e-15 * np.abs(dense).max())
    assert np.all(new.truncation_bound == 0)


def _dense_toeplitz(model: NoiseModel, sizes: np.ndarray, length: int, estimator: str) -> np.ndarray:
    covariance_z = toeplitz(model.increment_autocovariance(length - 1))
    rows = []
    for m in sizes:
        count = length - 2 * m + 1 if estimator == "overlapping" else length // m - 1
        starts = range(count) if estimator == "overlapping" else range(0, count * m, m)
        rows.append((np.array(_difference_rows(int(m), length, starts), dtype=float), int(m), count))
    result = np.empty((len(sizes), len(sizes)))
    for i, (A, m_i, K_i) in enumerate(rows):
        for j, (B, m_j, K_j) in enumerate(rows):
            cross = A @ covariance_z @ B.T
            result[i, j] = 2 * np.sum(cross * cross) / (4.0 * m_i**2 * m_j**2 * K_i * K_j)
    return result


LONG_MODELS = {
    "flicker-0.3": NoiseModel(sample_rate=1.0, flicker_variance=1.0, flicker_d=0.3),
    "flicker-0.8+white": NoiseModel(sample_rate=1.0, flicker_variance=1.0, flicker_d=0.8, white_variance=0.5),
    "ar2+rrw": NoiseModel(sample_rate=1.0, ar_variance=1.0, ar_coefficients=(0.6, -0.2), rrw_variance=0.01),
    "gauss-markov+white+quantization": NoiseModel(
        sample_rate=1.0, ar_variance=0.3, ar_coefficients=(0.95,), white_variance=1.0, quantization=0.2
    ),
    # τ_c = 200 samples: the AR modes' Gauss blocks start 32 lags from the breakpoints, within τ_c.
    "slow-gauss-markov+flicker": NoiseModel(
        sample_rate=1.0,
        ar_variance=1e-4,
        ar_coefficients=(0.995,),
        white_variance=1.0,
        flicker_variance=0.1,
        flicker_d=0.4,
    ),
}


@pytest.mark.parametrize("estimator", ["overlapping", "non-overlapping"])
@pytest.mark.parametrize("name", sorted(LONG_MODELS))
def test_lag_sums_against_dense_toeplitz(name, estimator):
    sizes = np.array([1, 2, 4, 8, 16])
    result = allan_estimate_covariance(LONG_MODELS[name], sizes, 120, estimator=estimator)
    dense = _dense_toeplitz(LONG_MODELS[name], sizes, 120, estimator)
    # AR: exact (bound 0); 1/f: within the reported truncation bound.
    assert np.all(np.abs(result.covariance - dense) <= result.truncation_bound + 1e-9 * np.abs(dense))
    if "flicker" not in name:
        assert np.all(result.truncation_bound == 0)


def _triangle(m: int) -> np.ndarray:
    return np.array([min(k + 1, 2 * m - 1 - k) for k in range(2 * m - 1)], dtype=np.float64)


def _direct_lag_sums(model: NoiseModel, sizes: np.ndarray, length: int) -> np.ndarray:
    """Σ_δ N c² over every lag of the record, c_ij(δ) = Σ_u W(u) γ_z(δ + u) with W = g_i ⋆ g_j by np.convolve
    (independent of the fourth sums and of the quadrature)."""
    gamma = model.increment_autocovariance(2 * length + 4)
    result = np.empty((len(sizes), len(sizes)))
    for i, m_i in enumerate(sizes.tolist()):
        for j, m_j in enumerate(sizes.tolist()):
            K_i, K_j = length - 2 * m_i + 1, length - 2 * m_j + 1
            weights = np.convolve(_triangle(m_i)[::-1], _triangle(m_j))  # W(u), u = −(2m_i − 2) …
            deltas = np.arange(-(K_i - 1), K_j)
            arguments = np.arange(deltas[0] - (2 * m_i - 2), deltas[-1] + 2 * m_j - 1)
            c = np.convolve(gamma[np.abs(arguments)], weights[::-1], mode="valid")
            counts = np.minimum(K_i - 1, K_j - 1 - deltas) - np.maximum(0, -deltas) + 1
            result[i, j] = np.dot(counts, c * c) / (2.0 * m_i**2 * m_j**2 * K_i * K_j)
    return result


@pytest.mark.parametrize(
    "sizes", [[1, 2, 4, 8, 16, 32, 64, 128, 256, 512, 1024], [3, 6, 12, 25, 50, 100, 700]]
)
@pytest.mark.parametrize("name", sorted(LONG_MODELS))
def test_lag_quadrature_against_every_lag_summed(name, sizes, monkeypatch):
    # 3200 samples: the far tails and the gaps between breakpoints are summed by Gauss blocks (and the 1/f
    # far tail by its Newton series); the error stays within the reported bound plus rounding. The
    # reference's own γ_z (a running product) is good to about 1e-11 at 6400 lags, which sets the margin;
    # tests/test_lag_quadrature.py holds the quadrature alone to its bound at 1e-13.
    monkeypatch.setattr(tau_covariance, "EVERY_LAG_LENGTH", 0)  # the quadrature, not the short-record sum
    sizes = np.array(sizes)
    result = allan_estimate_covariance(LONG_MODELS[name], sizes, 3200)
    reference = _direct_lag_sums(LONG_MODELS[name], sizes, 3200)
    scale = np.sqrt(np.outer(np.diag(reference), np.diag(reference)))
    assert np.all(np.abs(result.covariance - reference) <= result.truncation_bound + 1e-10 * scale)
    np.testing.assert_allclose(result.covariance, reference, rtol=1e-9)
    assert np.all(result.truncation_bound <= 1e-12 * scale)
    decreasing = allan_estimate_covariance(LONG_MODELS[name], sizes[::-1], 3200)
    np.testing.assert_array_equal(decreasing.covariance, result.covariance[::-1, ::-1])


@pytest.mark.parametrize("rule", [PROVED_RULE, WEIGHTS_RULE])
@pytest.mark.parametrize("d", [0.2, 0.5, 0.85])
def test_batched_quadrature_of_a_full_model_against_the_every_lag_engine(d, rule, monkeypatch):
    # White + RRW + 1/f + AR(2) at 24 000 samples, octave τ and one odd size: the quadrature evaluates all
    # 78 pairs together (rows with an owner index, H tabulated once). The reference is the short-record
    # engine: c by moving sums of γ_z at every lag, summed over every lag — no fourth sum, no blocks, no
    # batching. A pair whose rows were mixed up would be off by far more than the bound. Rounding margin as
    # in the test above: 1e-10 of √(C_ii C_jj) (reached, near 5e-11, only by the widest ratio m_j/m_i =
    # 1024 at d ≥ 0.85, where the nine-term sum loses about (m_j/m_i)² ulps and the reference's moving
    # sums of a slowly decaying γ_z lose as much). The fit's WEIGHTS_RULE is held to its stated accuracy,
    # 2·10⁻⁷ of the scale (measured up to 1.8·10⁻⁸ here); its proved bound is loose (up to 2·10⁻² of the
    # scale here) and is not required to be small.
    variances = {"white_variance": 0.5, "rrw_variance": 1e-6, "flicker_variance": 1.0, "ar_variance": 0.3}
    model = NoiseModel(sample_rate=1.0, flicker_d=d, ar_coefficients=(0.5, 0.2), **variances)
    sizes = np.array([1, 2, 3, 4, 8, 16, 32, 64, 128, 256, 512, 1024])
    length = 24_000
    reference = allan_estimate_covariance(model, sizes, length)
    assert np.all(reference.truncation_bound == 0)  # below EVERY_LAG_LENGTH: every lag, exactly
    monkeypatch.setattr(tau_covariance, "EVERY_LAG_LENGTH", 0)
    result = allan_estimate_covariance(model, sizes, length, rule=rule)
    scale = np.sqrt(np.outer(np.diag(reference.covariance), np.diag(reference.covariance)))
    error = np.abs(result.covariance - reference.covariance)
    assert np.all(error <= result.truncation_bound + 1e-10 * scale)
    assert np.all(error <= (1e-10 if rule == PROVED_RULE else 2e-7) * scale)
    if rule == PROVED_RULE:
        assert np.all(result.truncation_bound <= 1e-11 * scale)


FIT_MODELS = {
    "white + RRW + 1/f (d = 0.5) + Gauss–Markov 0.8": {"flicker_d": 0.5, "ar_coefficients": (0.8,)},
    "d = 0.05, Gauss–Markov 0.99": {"flicker_d": 0.05, "ar_coefficients": (0.99,)},
    "d = 0.3, AR(1) −0.6": {"flicker_d": 0.3, "ar_coefficients": (-0.6,)},
    "d = 0.6, AR(2) complex roots": {"flicker_d": 0.6, "ar_coefficients": (1.2, -0.5)},
}


@pytest.mark.parametrize("name", sorted(FIT_MODELS))
def test_weights_rule_gives_the_proved_rules_covariance_at_a_million_samples(name):
    # The fit's rule against the reported one at octave τ of 10⁶ samples at 100 Hz (GYRO_MODEL with
    # other orders d and AR coefficients): the same covariance to 2·10⁻⁷ of √(C_ii C_jj), the weights
    # rule's stated accuracy (measured: 8.0·10⁻⁸ at d = 0.05 beside φ = 0.99, 1.7·10⁻¹¹–9.4·10⁻⁹ for the
    # others; at d ≥ 0.75 both rules' rounding reaches 10⁻⁹–10⁻⁷ of the scale and the comparison against
    # every lag above holds them).
    model = replace(GYRO_MODEL, **FIT_MODELS[name])
    sizes, length = 2 ** np.arange(19), 1_000_000
    proved = allan_estimate_covariance(model, sizes, length).covariance
    weights = allan_estimate_covariance(model, sizes, length, bound=False, rule=WEIGHTS_RULE).covariance
    scale = np.sqrt(np.outer(np.diag(proved), np.diag(proved)))
    assert np.all(np.abs(weights - proved) <= 2e-7 * scale)


def test_covariance_without_the_bound_is_the_covariance_with_it():
    # bound=False (the fit's weights) skips the quadrature's error bound: the same covariance bit for bit,
    # NaN where the bound was not formed; the exact engine (white + RRW) keeps its zero bound.
    variances = {"white_variance": 0.5, "rrw_variance": 1e-6, "flicker_variance": 1.0, "ar_variance": 0.3}
    model = NoiseModel(sample_rate=1.0, flicker_d=0.3, ar_coefficients=(0.8,), **variances)
    sizes, length = 2 ** np.arange(15), 100_000
    with_bound = allan_estimate_covariance(model, sizes, length)
    without = allan_estimate_covariance(model, sizes, length, bound=False)
    np.testing.assert_array_equal(without.covariance, with_bound.covariance)
    assert np.all(np.isnan(without.truncation_bound))
    assert np.all(with_bound.truncation_bound >= 0)
    finite = NoiseModel(sample_rate=1.0, white_variance=0.5, rrw_variance=1e-6)
    exact = allan_estimate_covariance(finite, sizes, length, bound=False)
    np.testing.assert_array_equal(
        exact.covariance, allan_estimate_covariance(finite, sizes, length).covariance
    )
    assert np.all(exact.truncation_bound == 0)


def test_short_flicker_record_is_summed_over_every_lag():
    model = NoiseModel(sample_rate=1.0, flicker_variance=1.0, flicker_d=0.7)
    sizes = np.array([1, 2, 4])
    length = 900  # FLICKER_REACH·(m_i + m_j) lags would be shorter than the record: every lag is summed
    result = allan_estimate_covariance(model, sizes, length)
    dense = _dense_toeplitz(model, sizes, length, "overlapping")
    error = np.abs(result.covariance - dense)
    assert np.all(result.truncation_bound == 0)
    assert np.all(error <= result.truncation_bound + 1e-12 * np.abs(dense))
    assert np.all(result.covariance <= dense + 1e-12 * np.abs(dense))  # c² ≥ 0: truncation only drops mass


def test_edf_agrees_with_the_power_sum_formula_for_white_noise():
    model = NoiseModel(sample_rate=1.0, white_variance=1.0)
    sizes = np.array([1, 2, 4, 8, 32, 128])
    length = 1000
    edf = allan_estimate_covariance(model, sizes, length).edf
    expected = [
        equivalent_degrees_of_freedom("white", int(m), length - 2 * int(m) + 1, 1, length) for m in sizes
    ]
    np.testing.assert_allclose(edf, expected, rtol=1e-13)
    np.testing.assert_allclose(
        allan_estimate_variance(model, sizes, length),
        np.diag(allan_estimate_covariance(model, sizes, length).covariance),
    )


def test_cost_does_not_grow_with_the_record():
    # The same pair at n and 1000 n: A + B n (the pieces do not depend on n once n ≥ 2(m_i + m_j)).
    model = NoiseModel(sample_rate=1.0, white_variance=1.0, rrw_variance=1e-3)
    small = allan_estimate_covariance(model, np.array([4, 64]), 10_000).covariance
    large = allan_estimate_covariance(model, np.array([4, 64]), 10_000_000).covariance
    middle = allan_estimate_covariance(model, np.array([4, 64]), 5_005_000).covariance
    scaled = [c * (n - 7) * (n - 127) for c, n in ((small, 10_000), (middle, 5_005_000), (large, 10_000_000))]
    np.testing.assert_allclose(scaled[1][0, 1], (scaled[0][0, 1] + scaled[2][0, 1]) / 2, rtol=1e-12)


def _overlapping_allan(y: np.ndarray, m: int) -> np.ndarray:
    """Overlapping Allan variance of each row of ``y`` (an independent implementation by cumulative sums)."""
    cumulative = np.concatenate((np.zeros((len(y), 1)), np.cumsum(y, axis=1)), axis=1)
    window = cumulative[:, m:] - cumulative[:, :-m]
    difference = window[:, m:] - window[:, :-m]
    return np.mean(difference**2, axis=1) / (2.0 * m * m)


@pytest.mark.slow
def test_monte_carlo_covariance_of_estimates():
    rng = np.random.default_rng(20261123)
    model = NoiseModel(sample_rate=1.0, white_variance=1.0, rrw_variance=0.02)
    length, batches, batch = 64, 60, 10_000
    sizes = (1, 2, 4)
    values = []
    for _ in range(batches):
        y = rng.standard_normal((batch, length)) + np.cumsum(
            np.sqrt(0.02) * rng.standard_normal((batch, length)), axis=1
        )
        values.append(np.column_stack([_overlapping_allan(y, m) for m in sizes]))
    samples = np.concatenate(values)
    theory = allan_estimate_covariance(model, np.array(sizes), length).covariance
    for i, j in ((0, 0), (1, 1), (2, 2), (0, 1), (1, 2), (0, 2)):
        products = (samples[:, i] - samples[:, i].mean()) * (samples[:, j] - samples[:, j].mean())
        standard_error = products.std(ddof=1) / np.sqrt(len(samples))
        assert abs(products.mean() - theory[i, j]) <= Z_MONTE_CARLO * standard_error
        if (
            abs(i - j) <= 1
        ):  # a 2 % error would fail (the weak (1, 4) covariance is only checked for agreement)
            assert Z_MONTE_CARLO * standard_error <= 0.02 * abs(theory[i, j])


def test_bad_calls():
    with pytest.raises(ValueError, match="estimator='mixed'"):
        allan_estimate_covariance(MODELS["white"], [1, 2], 100, estimator="mixed")
    with pytest.raises(ValueError, match="no noise component"):
        allan_estimate_covariance(NoiseModel(sample_rate=1.0), [1, 2], 100)
    with pytest.raises(ValueError, match="must divide"):
        allan_estimate_covariance(MODELS["white"], [2, 3], 100, estimator="non-overlapping")


@pytest.mark.parametrize("function", [allan_estimate_covariance, allan_estimate_variance])
@pytest.mark.parametrize(
    ("sizes", "length", "error", "message"),
    [
        ([1, 64], 100, ValueError, r"m=64 is outside 1 … 50: a record of length=100"),
        ([0, 2], 100, ValueError, r"tau_samples=\[0, 2\]: every cluster size must be >= 1"),
        ([2.5], 100, TypeError, "cluster sizes must be integers"),
        ([float("nan")], 100, TypeError, "cluster sizes must be integers"),
        ([], 100, ValueError, "non-empty 1-D array"),
        ([[1, 2]], 100, ValueError, "non-empty 1-D array"),
        ([1, 2], 100.0, TypeError, r"length=100\.0: must be an integer"),
        ([1], 1, ValueError, "length=1: must be an integer >= 2"),
    ],
)
def test_cluster_sizes_the_record_cannot_hold_are_refused_by_name(function, sizes, length, error, message):
    with pytest.raises(error, match=message):
        function(MODELS["white"], sizes, length)


def test_the_largest_cluster_size_a_record_holds_is_accepted():
    # m = n/2: one overlapping term, one non-overlapping difference; Var = 2 σ_A⁴ for white noise
    for estimator in ("overlapping", "non-overlapping"):
        variance = allan_estimate_variance(MODELS["white"], [50], 100, estimator=estimator)
        assert variance[0] == pytest.approx(2.0 * MODELS["white"].allan_variance(np.array([50]))[0] ** 2)


def test_white_overlapping_closed_form_equals_the_engine():
    import sympy as sp

    from carousel_theory import symbols
    from carousel_theory.tau_covariance import WHITE_OVERLAPPING_ESTIMATE_VARIANCE

    for m, length in ((1, 4), (3, 11), (7, 40), (64, 1000), (1000, 10**7)):
        K = length - 2 * m + 1
        exact = WHITE_OVERLAPPING_ESTIMATE_VARIANCE.subs(
            {symbols.white_sample_variance: 1, symbols.cluster_size: m, symbols.difference_count: K}
        )
        gram = _finite_gram(m, m, K, K)[0]
        assert sp.Rational(2 * gram, 4 * m**4 * K**2) == exact
