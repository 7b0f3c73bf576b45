"""Allan variance estimators, their confidence intervals, and the exact model Allan variances.

Checked against allantools (same input, 1e-12 relative), against a literal exact-rational transcription
of TIM 2014 eq. (20), against dense covariance matrices (brute force), and by seeded Monte Carlo.
"""

from __future__ import annotations

from fractions import Fraction

import allantools
import numpy as np
import pytest
import sympy as sp
from conftest import Z_MONTE_CARLO

from carousel_theory import allan
from carousel_theory.allan import (
    allan_variance,
    difference_covariance,
    equivalent_degrees_of_freedom,
    flicker_allan_variance,
    graycode_allan_variance,
    model_allan_variance,
    octave_cluster_sizes,
)
from carousel_theory.fitting import NoiseModel
from carousel_theory.processes import covariance_matrix, sample_flicker, sample_rate_random_walk


def _test_signals() -> dict[str, np.ndarray]:
    rng = np.random.default_rng(20140)
    n = 5000
    return {
        "white": rng.standard_normal(n),
        "white-with-bias": 7e-3 + 6e-3 * rng.standard_normal(n),
        "rrw": np.cumsum(rng.standard_normal(n)),
        "odd-length-mixed": rng.standard_normal(n + 37) + 0.05 * np.cumsum(rng.standard_normal(n + 37)),
    }


@pytest.mark.parametrize("name", list(_test_signals()))
@pytest.mark.parametrize(
    ("estimator", "peer"), [("overlapping", allantools.oadev), ("non-overlapping", allantools.adev)]
)
def test_equals_allantools(name, estimator, peer):
    y = _test_signals()[name]
    for taus in ("octave", np.array([0.03, 0.05, 0.11, 2.5, 16.0])):
        ours = allan_variance(y, 100.0, taus, estimator=estimator)
        tau, deviation, _, _ = peer(y, rate=100.0, data_type="freq", taus=ours.tau)
        np.testing.assert_array_equal(tau, ours.tau)
        np.testing.assert_allclose(ours.avar, deviation**2, rtol=1e-12, atol=0)


def _eq20_exact(values: list[Fraction], m: int) -> Fraction:
    """TIM 2014 eq. (20) transcribed literally in exact rationals."""
    M = len(values) // m
    means = [sum(values[j * m : (j + 1) * m], Fraction(0)) / m for j in range(M)]
    return sum(((means[j + 1] - means[j]) ** 2 for j in range(M - 1)), Fraction(0)) / (2 * (M - 1))


def _overlapping_exact(values: list[Fraction], m: int) -> Fraction:
    n = len(values)
    terms = [
        (sum(values[s + m : s + 2 * m], Fraction(0)) - sum(values[s : s + m], Fraction(0))) / m
        for s in range(n - 2 * m + 1)
    ]
    return sum((t * t for t in terms), Fraction(0)) / (2 * len(terms))


def test_estimators_equal_exact_rational_transcription():
    rng = np.random.default_rng(7)
    integers = rng.integers(-50, 50, size=61)
    values = [Fraction(int(v)) for v in integers]
    for estimator, reference in (("non-overlapping", _eq20_exact), ("overlapping", _overlapping_exact)):
        for taus in ("octave", [3.0, 5.0, 7.0, 20.0]):
            result = allan_variance(integers, 1.0, taus, estimator=estimator)
            for m, value in zip(result.samples_per_cluster, result.avar, strict=True):
                exact = reference(values, int(m))
                assert abs(Fraction(value) - exact) <= exact * Fraction(1, 10**14)
            assert list(result.clusters) == [61 // int(m) for m in result.samples_per_cluster]


def test_octave_sizes_stop_at_a_third_of_the_record():
    assert list(octave_cluster_sizes(3)) == [1]
    assert list(octave_cluster_sizes(24)) == [1, 2, 4, 8]
    assert list(octave_cluster_sizes(23)) == [1, 2, 4]


# --- exact model Allan variances ----------------------------------------------------------------


def _difference_weights(m: int, start: int, length: int) -> list[Fraction]:
    """Weights of ȳ_{next} − ȳ_{this} for the bins starting at ``start`` (0-based), over t = 1 … length."""
    weights = [Fraction(0)] * length
    for t in range(start, start + m):
        weights[t] -= Fraction(1, m)
    for t in range(start + m, start + 2 * m):
        weights[t] += Fraction(1, m)
    return weights


@pytest.mark.parametrize("m", [1, 2, 3, 5, 8])
def test_white_and_rrw_closed_forms_against_exact_covariance_sums(m):
    length = 2 * m + 3
    weights = _difference_weights(m, 1, length)
    white = sum((w * w for w in weights), Fraction(0)) / 2
    # Random walk from r_0 = 0: Var(Σ w_t r_t) = Σ_i (Σ_{t≥i} w_t)² (the covariance min(s, t)).
    suffix = [sum(weights[i:], Fraction(0)) for i in range(length)]
    rrw = sum((s * s for s in suffix), Fraction(0)) / 2
    substitutions = {sp.Symbol("m", integer=True, positive=True): m}
    assert allan.WHITE_ALLAN_VARIANCE.subs(substitutions).subs(
        sp.Symbol("sigma_WN^2", positive=True), 1
    ) == sp.Rational(white.numerator, white.denominator)
    assert allan.RRW_ALLAN_VARIANCE.subs(substitutions).subs(
        sp.Symbol("sigma_q^2", positive=True), 1
    ) == sp.Rational(rrw.numerator, rrw.denominator)
    model = NoiseModel(sample_rate=1.0, white_variance=1.0, rrw_variance=1.0)
    assert model_allan_variance(model, np.array([m]))[0] == pytest.approx(float(white + rrw), rel=1e-14)


@pytest.mark.parametrize("m", [1, 2, 4])
def test_quantization_closed_form_against_differenced_angle_noise(m):
    # Rate = (e_t − e_{t−1}) f_s with white e of variance Q²; the difference of means is a filter on e.
    sample_rate, Q = 4.0, 0.5
    taps = np.zeros(2 * m + 1)
    taps[[0, m, 2 * m]] = (1.0, -2.0, 1.0)
    expected = Q**2 * sample_rate**2 * float(np.dot(taps, taps)) / m**2 / 2
    model = NoiseModel(sample_rate=sample_rate, quantization=Q)
    assert model_allan_variance(model, np.array([m]))[0] == pytest.approx(expected, rel=1e-14)
    assert expected == pytest.approx(3 * Q**2 / (m / sample_rate) ** 2, rel=1e-14)


@pytest.mark.parametrize("d", [0.1, 0.45, 0.5, 0.8])
@pytest.mark.parametrize("estimator", ["non-overlapping", "overlapping"])
def test_flicker_against_dense_covariance(d, estimator):
    length = 26
    covariance = covariance_matrix("flicker", length, d=d)
    for m in (1, 2, 4, 8):
        starts = (
            range(0, (length // m - 1) * m, m)
            if estimator == "non-overlapping"
            else range(length - 2 * m + 1)
        )
        variances = []
        for start in starts:
            w = np.array([float(x) for x in _difference_weights(m, start, length)])
            variances.append(w @ covariance @ w)
        expected = np.mean(variances) / 2
        got = flicker_allan_variance(d, np.array([m]), length, estimator)[0]
        assert got == pytest.approx(expected, rel=1e-12)


def test_flicker_against_weighted_sum_variance():
    propagation = pytest.importorskip("carousel_theory.propagation")
    length, d, m = 64, 0.3, 4
    variances = [
        propagation.weighted_sum_variance(
            np.array([float(x) for x in _difference_weights(m, s, length)]), "flicker", d
        )
        for s in range(0, (length // m - 1) * m, m)
    ]
    assert flicker_allan_variance(d, np.array([m]), length)[0] == pytest.approx(
        np.mean(variances) / 2, rel=1e-12
    )


def test_graycode_delegation_against_gray_matrix():
    graycode = pytest.importorskip("carousel_theory.graycode")
    n = 5
    K = graycode.gray_matrix(n)
    covariance = K @ K.T
    for m in range(n - 1):
        size = 2**m
        variances = [
            np.array([float(x) for x in _difference_weights(size, s, 2**n)])
            @ covariance
            @ np.array([float(x) for x in _difference_weights(size, s, 2**n)])
            for s in range(0, 2**n - size, size)
        ]
        assert float(graycode_allan_variance(n, m)) == pytest.approx(np.mean(variances) / 2, rel=1e-14)


def test_model_allan_variance_is_the_mean_of_the_estimator():
    """Monte Carlo: white + RRW + 1/f, 400 seeded records; |mean − theory| ≤ Z·SE and 2 % > Z·SE."""
    rng = np.random.default_rng(2024)
    length, replicates, d = 4096, 400, 0.4
    model = NoiseModel(
        sample_rate=10.0, white_variance=1.0, rrw_variance=1e-3, flicker_variance=0.2, flicker_d=d
    )
    y = (
        rng.standard_normal((replicates, length))
        + sample_rate_random_walk(length, rng=rng, variance=1e-3, realisations=replicates)
        + sample_flicker(length, rng=rng, d=d, variance=0.2, realisations=replicates)
    )
    sizes = np.array([1, 3, 8])
    for estimator in ("non-overlapping", "overlapping"):
        estimates = np.array([allan_variance(row, 10.0, sizes / 10.0, estimator=estimator).avar for row in y])
        theory = model_allan_variance(model, sizes, length=length, estimator=estimator)
        mean = estimates.mean(axis=0)
        standard_error = estimates.std(axis=0, ddof=1) / np.sqrt(replicates)
        assert np.all(np.abs(mean - theory) <= Z_MONTE_CARLO * standard_error), (mean, theory)
        assert np.all(0.02 * theory > Z_MONTE_CARLO * standard_error)


# --- degrees of freedom and intervals -----------------------------------------------------------


def _dense_edf(covariance: np.ndarray, m: int, estimator: str) -> float:
    """2 E[Q]² / Var[Q] for Q = Σ_s d_s², with Var[Q] = 2 tr((AΣ)²) computed from dense matrices."""
    length = covariance.shape[0]
    starts = (
        range(0, (length // m - 1) * m, m) if estimator == "non-overlapping" else range(length - 2 * m + 1)
    )
    D = np.array([[float(x) for x in _difference_weights(m, s, length)] for s in starts])
    covariance_of_differences = D @ covariance @ D.T
    mean = np.trace(covariance_of_differences)
    variance = 2 * np.sum(covariance_of_differences**2)
    return 2 * mean**2 / variance


@pytest.mark.parametrize("noise", ["white", "rrw", "quantization"])
@pytest.mark.parametrize("estimator", ["non-overlapping", "overlapping"])
def test_edf_equals_dense_quadratic_form(noise, estimator):
    length = 40
    if noise == "white":
        covariance = np.eye(length)
    elif noise == "rrw":
        covariance = covariance_matrix("rrw", length)
    else:
        difference = np.eye(length + 1)[1:] - np.eye(length + 1)[:-1]
        covariance = difference @ difference.T
    for m in (1, 2, 3, 5, 13):
        terms = length - 2 * m + 1 if estimator == "overlapping" else length // m - 1
        stride = 1 if estimator == "overlapping" else m
        got = equivalent_degrees_of_freedom(noise, m, terms, stride, length)
        assert got == pytest.approx(_dense_edf(covariance, m, estimator), rel=1e-10)


def test_edf_white_non_overlapping_closed_form():
    # Adjacent differences correlate −1/2, so ν = K² / (K + (K − 1)/2) = 2K² / (3K − 1), exactly.
    for K in (1, 2, 10, 999):
        got = equivalent_degrees_of_freedom("white", 4, K, 4, 4 * (K + 1))
        assert got == pytest.approx(2 * K**2 / (3 * K - 1), rel=1e-13)


def test_edf_of_a_model_mixes_components():
    model = NoiseModel(sample_rate=2.0, white_variance=1.0, rrw_variance=0.01)
    covariance = np.eye(40) + 0.01 * covariance_matrix("rrw", 40)
    got = equivalent_degrees_of_freedom(model, 5, 31, 1, 40, sample_rate=2.0)
    assert got == pytest.approx(_dense_edf(covariance, 5, "overlapping"), rel=1e-10)


@pytest.mark.slow
@pytest.mark.parametrize("estimator", ["non-overlapping", "overlapping"])
def test_interval_coverage_is_nominal_for_white_noise(estimator):
    """3000 seeded white records: coverage of the 95 % intervals within Z·SE, and 2 % of 0.95 > Z·SE."""
    rng = np.random.default_rng(99)
    replicates, length, level = 3000, 1024, 0.95
    taus = np.array([1.0, 8.0, 64.0])
    covered = np.zeros(len(taus))
    for _ in range(replicates):
        result = allan_variance(rng.standard_normal(length), 1.0, taus, estimator=estimator, confidence=level)
        truth = 1.0 / taus
        covered += (result.ci_low <= truth) & (truth <= result.ci_high)
    coverage = covered / replicates
    standard_error = np.sqrt(level * (1 - level) / replicates)
    assert 0.02 * level > Z_MONTE_CARLO * standard_error
    assert np.all(np.abs(coverage - level) <= Z_MONTE_CARLO * standard_error), coverage


def test_interval_brackets_estimate_and_result_fields():
    rng = np.random.default_rng(5)
    result = allan_variance(rng.standard_normal(3000), 50.0, estimator="non-overlapping", noise="rrw")
    assert np.all(result.ci_low < result.avar) and np.all(result.avar < result.ci_high)
    np.testing.assert_array_equal(result.terms, 3000 // result.samples_per_cluster - 1)
    np.testing.assert_allclose(result.adev**2, result.avar)
    assert result.estimator == "non-overlapping" and result.noise == "rrw"


# --- invalid calls ------------------------------------------------------------------------------

_Y = np.arange(30, dtype=np.float64)
_MODEL = NoiseModel(sample_rate=1.0, white_variance=1.0)

INVALID = [
    ("y-nan", lambda: allan_variance([1.0, np.nan, 2.0, 3.0], 1.0), ValueError, "must be finite"),
    ("y-3d", lambda: allan_variance(np.zeros((3, 3, 3)), 1.0), ValueError, "1-dimensional"),
    ("y-short", lambda: allan_variance([1.0, 2.0], 1.0), ValueError, "at least 3 samples"),
    ("rate-zero", lambda: allan_variance(_Y, 0.0), ValueError, "sample_rate=0.0"),
    ("rate-string", lambda: allan_variance(_Y, "fast"), TypeError, "sample_rate='fast'"),
    ("estimator", lambda: allan_variance(_Y, 1.0, estimator="modified"), ValueError, "estimator='modified'"),
    ("taus-word", lambda: allan_variance(_Y, 1.0, "decade"), ValueError, "taus='decade'"),
    ("tau-fraction", lambda: allan_variance(_Y, 1.0, [1.5]), ValueError, "whole number of sample"),
    ("tau-zero", lambda: allan_variance(_Y, 1.0, [0.0]), ValueError, "whole number of sample"),
    ("tau-over-third", lambda: allan_variance(_Y, 1.0, [11.0]), ValueError, "longer than a third"),
    ("taus-unsorted", lambda: allan_variance(_Y, 1.0, [4.0, 2.0]), ValueError, "strictly increasing"),
    ("noise", lambda: allan_variance(_Y, 1.0, noise="pink"), ValueError, "noise='pink'"),
    ("confidence", lambda: allan_variance(_Y, 1.0, confidence=1.0), ValueError, "confidence=1.0"),
    ("model-type", lambda: model_allan_variance("white", np.array([1])), TypeError, "must be a NoiseModel"),
    ("tau-samples-float", lambda: model_allan_variance(_MODEL, np.array([1.5])), TypeError, "integers"),
    ("tau-samples-zero", lambda: model_allan_variance(_MODEL, np.array([0])), ValueError, ">= 1"),
    (
        "flicker-no-length",
        lambda: model_allan_variance(NoiseModel(1.0, flicker_variance=1.0), np.array([1])),
        ValueError,
        "length=None",
    ),
    ("flicker-d", lambda: flicker_allan_variance(1.0, np.array([1]), 10), ValueError, "d=1.0"),
    ("flicker-over-third", lambda: flicker_allan_variance(0.3, np.array([4]), 10), ValueError, "a third"),
    ("octave-length", lambda: octave_cluster_sizes(2), ValueError, "length=2"),
    ("graycode-n", lambda: graycode_allan_variance(1, 0), ValueError, "n=1"),
    (
        "model-estimator",
        lambda: model_allan_variance(_MODEL, [2], estimator="x"),
        ValueError,
        "estimator='x'",
    ),
    ("edf-m-zero", lambda: equivalent_degrees_of_freedom("white", 0, 10, 1, 100), ValueError, "m=0"),
    ("edf-terms-zero", lambda: equivalent_degrees_of_freedom("white", 2, 0, 1, 100), ValueError, "terms=0"),
    (
        "edf-stride-zero",
        lambda: equivalent_degrees_of_freedom("white", 2, 10, 0, 100),
        ValueError,
        "stride=0",
    ),
    ("edf-m-fraction", lambda: equivalent_degrees_of_freedom("white", 2.5, 10, 1, 100), TypeError, "m=2.5"),
    (
        "edf-m-long",
        lambda: equivalent_degrees_of_freedom("white", 60, 10, 1, 100),
        ValueError,
        "m=60.*m <= 50",
    ),
    ("difference-m-zero", lambda: difference_covariance("white", 0, np.arange(3), 100), ValueError, "m=0"),
    (
        "difference-nan-lag",
        lambda: difference_covariance("white", 2, np.array([np.nan]), 100),
        TypeError,
        "lags",
    ),
    (
        "difference-rate",
        lambda: difference_covariance("white", 2, np.arange(3), 100, 0.0),
        ValueError,
        "rate=0.0",
    ),
]


@pytest.mark.parametrize(("call", "error", "message"), [c[1:] for c in INVALID], ids=[c[0] for c in INVALID])
def test_invalid_calls(call, error, message):
    with pytest.raises(error, match=message):
        call()


def test_all_is_honest():
    for name in allan.__all__:
        assert hasattr(allan, name), name


@pytest.mark.parametrize("estimator", ["non-overlapping", "overlapping"])
def test_allan_covariance_equals_dense_quadratic_forms(estimator):
    """Cov(σ̂²_i, σ̂²_j) = 2 tr(A_i Σ A_j Σ) with dense matrices, white + RRW + quantization (exact filters)."""
    length = 48
    model = NoiseModel(sample_rate=2.0, white_variance=1.0, rrw_variance=0.05, quantization=0.3)
    difference = np.eye(length + 1)[1:] - np.eye(length + 1)[:-1]
    covariance = (
        np.eye(length)
        + 0.05 * covariance_matrix("rrw", length)
        + (0.3 * 2.0) ** 2 * difference @ difference.T
    )
    sizes = np.array([1, 2, 4, 8, 16])
    rows = []
    for m in sizes:
        starts = (
            range(0, (length // m - 1) * m, m)
            if estimator == "non-overlapping"
            else range(length - 2 * m + 1)
        )
        rows.append(np.array([[float(x) for x in _difference_weights(int(m), s, length)] for s in starts]))
    expected = np.array(
        [[2 * np.sum((a @ covariance @ b.T) ** 2) / (4 * len(a) * len(b)) for b in rows] for a in rows]
    )
    np.testing.assert_allclose(
        allan.allan_covariance(model, sizes, length, estimator=estimator), expected, rtol=1e-12
    )


def test_allan_covariance_of_flicker_is_close_to_dense():
    """The 1/f filter is cut and treated as stationary: within 5 % of the dense nonstationary value here."""
    length, d = 48, 0.3
    model = NoiseModel(sample_rate=1.0, flicker_variance=1.0, flicker_d=d)
    covariance = covariance_matrix("flicker", length, d=d)
    sizes = np.array([1, 2, 4, 8, 16])
    rows = [
        np.array(
            [[float(x) for x in _difference_weights(int(m), s, length)] for s in range(length - 2 * m + 1)]
        )
        for m in sizes
    ]
    expected = np.array(
        [[2 * np.sum((a @ covariance @ b.T) ** 2) / (4 * len(a) * len(b)) for b in rows] for a in rows]
    )
    np.testing.assert_allclose(allan.allan_covariance(model, sizes, length), expected, rtol=0.05)


@pytest.mark.parametrize("length", [3, 5, 4097, 16384 + 5, 2 * 16384 + 4100, 123_457])
def test_overlapping_octave_equals_allantools_across_chunk_boundaries(length):
    import allantools

    y = np.random.default_rng(length).standard_normal(length) + 0.3
    ours = allan_variance(y, 1.0)
    peer = allantools.oadev(y, rate=1.0, data_type="freq", taus=ours.tau)[1] ** 2
    np.testing.assert_allclose(ours.avar, peer, rtol=1e-12)


@pytest.mark.parametrize("coefficients", [(0.5,), (0.9,), (1.2, -0.5)])
def test_model_allan_variance_holds_the_ar_term(coefficients):
    """The AR term's Allan variance by the fourth sum (``model_allan_variance`` and ``NoiseModel``) against
    the O(m) variogram sum of its increment autocovariance, a second way."""
    from carousel_theory.noise_model import allan_variance_from_increments, increment_autocovariance

    model = NoiseModel(sample_rate=1.0, white_variance=0.3, ar_variance=2.0, ar_coefficients=coefficients)
    sizes = np.array([1, 2, 4, 16, 64])
    gamma = increment_autocovariance("ar", 2 * int(sizes.max()), ar_coefficients=coefficients)
    expected = 2.0 * allan_variance_from_increments(gamma, sizes) + 0.3 / sizes
    np.testing.assert_allclose(model_allan_variance(model, sizes), expected, rtol=1e-12)
    np.testing.assert_allclose(model.allan_variance(sizes), expected, rtol=1e-12)
