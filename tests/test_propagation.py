"""Variance of bin means and carouselled means, TIM 2014 §III, against dense products built here."""

from __future__ import annotations

from fractions import Fraction

import mpmath
import numpy as np
import pytest
import scipy.special
import sympy as sp
from conftest import functions_called_in, public_functions
from hypothesis import example, given, settings
from hypothesis import strategies as st

from carousel_theory import propagation
from carousel_theory.processes import covariance_matrix as propagation_covariance
from carousel_theory.propagation import (
    flicker_averaged_bin_variance,
    flicker_averaged_bin_variance_exact,
    flicker_bin_variances,
    flicker_bin_variances_high_precision,
    flicker_carouselled_bin_variance,
    repeated_weights_bin_variances,
    weighted_sum_variance,
    weighted_sums_covariance,
)
from carousel_theory.weights import carousel_weights_from_angles

ORDERS = [Fraction(1, 2), Fraction(1, 3)]
SIZES = [(N, k) for N in range(1, 13) for k in range(1, 5)]


def psi_from_gamma(d: Fraction, length: int) -> list[Fraction]:
    """ψ_j = Γ(j + d) / (Γ(j + 1) Γ(d)) of TIM 2014 eq. (3), from the Gamma form via SymPy (no recursion)."""
    out = []
    for j in range(length):
        value = sp.gammasimp(
            sp.gamma(j + sp.Rational(d.numerator, d.denominator))
            / (sp.gamma(j + 1) * sp.gamma(sp.Rational(d.numerator, d.denominator)))
        )
        out.append(Fraction(int(value.p), int(value.q)))
    return out


PSI = {d: psi_from_gamma(d, 48) for d in ORDERS}


def dense_variance(transfer, weights):
    """wᵀ T Tᵀ w for a dense lower-triangular transfer matrix T given as a list of rows."""
    size = len(weights)
    coefficients = [
        sum((transfer[t][i] * weights[t] for t in range(i, size)), 0 * weights[0]) for i in range(size)
    ]
    return sum((c * c for c in coefficients), 0 * weights[0])


def bin_vector(bin_weights, k, zero):
    N = len(bin_weights)
    return [zero] * ((k - 1) * N) + list(bin_weights)


# --- exact brute force: averaged 1/f and rate random walk, all N ≤ 12, k ≤ 4 -----------------------


@pytest.mark.parametrize("d", ORDERS, ids=str)
def test_flicker_averaged_equals_dense_fraction_product(d):
    """e_kᵀ F Fᵀ e_k with F the (kN)×(kN) Toeplitz matrix of ψ (TIM 2014 §III-D), exactly."""
    psi = PSI[d]
    for N, k in SIZES:
        size = k * N
        F = [[psi[t - i] if i <= t else Fraction(0) for i in range(size)] for t in range(size)]
        expected = dense_variance(F, bin_vector([Fraction(1, N)] * N, k, Fraction(0)))
        assert flicker_averaged_bin_variance_exact(d, N, k) == expected, (N, k)
        assert (
            weighted_sum_variance(bin_vector([Fraction(1, N)] * N, k, Fraction(0)), "flicker", d, exact=True)
            == expected
        )
        assert flicker_averaged_bin_variance(d, N, k) == pytest.approx(float(expected), rel=1e-14, abs=0)
        with mpmath.workdps(50):
            got = flicker_averaged_bin_variance(d, N, k, digits=50)
            assert (
                abs(got - mpmath.mpf(expected.numerator) / expected.denominator)
                <= mpmath.mpf(10) ** -49 * got
            )


def test_rate_random_walk_bins_equal_dense_fraction_product():
    """Bin means of RRW through the cumulative-sum matrix R of TIM 2014 eq. (10)–(11), for k bins."""
    for N, k in SIZES:
        size = k * N
        R = [[Fraction(int(i <= t)) for i in range(size)] for t in range(size)]
        averaged = bin_vector([Fraction(1, N)] * N, k, Fraction(0))
        expected = dense_variance(R, averaged)
        assert weighted_sum_variance(averaged, "rrw", exact=True) == expected
        assert repeated_weights_bin_variances(np.full(N, 1 / N), "rrw", k)[-1] == pytest.approx(
            float(expected), rel=1e-14
        )
        assert weighted_sum_variance(np.array(averaged, float), "rrw") == pytest.approx(
            float(expected), rel=1e-14
        )
        # white noise and bias of the same statistic
        assert weighted_sum_variance(averaged, "white", exact=True) == Fraction(1, N)
        assert weighted_sum_variance(averaged, "bias", exact=True) == 1


# --- carouselled 1/f noise against mpmath dense products at 50 digits ------------------------------


@pytest.mark.parametrize("d", ORDERS, ids=str)
def test_flicker_carouselled_equals_dense_mpmath_product(d):
    psi = PSI[d]
    for N, k in SIZES:
        size = k * N
        with mpmath.workdps(60):
            F = [
                [
                    mpmath.mpf(psi[t - i].numerator) / psi[t - i].denominator if i <= t else mpmath.mpf(0)
                    for i in range(size)
                ]
                for t in range(size)
            ]
            zero = mpmath.mpf(0)
            sine = [mpmath.sinpi(mpmath.mpf(2 * u) / N) / N for u in range(1, N + 1)]
            cosine = [mpmath.cospi(mpmath.mpf(2 * u) / N) / N for u in range(1, N + 1)]
            expected = dense_variance(F, bin_vector(sine, k, zero)) + dense_variance(
                F, bin_vector(cosine, k, zero)
            )
        with mpmath.workdps(50):
            got = flicker_carouselled_bin_variance(d, N, k, digits=50)
            assert abs(got - expected) <= mpmath.mpf(10) ** -49 * expected, (N, k)
        with mpmath.workdps(20):
            got20 = flicker_carouselled_bin_variance(d, N, k, digits=20)
            assert abs(got20 - expected) <= mpmath.mpf(10) ** -19 * expected, (N, k)
        assert flicker_carouselled_bin_variance(d, N, k) == pytest.approx(float(expected), rel=1e-13), (N, k)


# --- large N: high precision against direct summation ----------------------------------------------


@pytest.mark.parametrize("digits", [50, 25])
def test_averaged_high_precision_against_binomial_closed_form_at_N_10_thousand(digits):
    """Ψ_M = Σ_{j≤M} ψ_j = binomial(M + d, M) (a Gamma ratio, evaluated by mpmath, no recursion)."""
    N, d = 10_000, Fraction(1, 2)
    with mpmath.workdps(digits + 10):
        half = mpmath.mpf(1) / 2
        expected = mpmath.fsum(mpmath.binomial(j + half, j) ** 2 for j in range(N)) / N**2
    with mpmath.workdps(digits):
        got = flicker_averaged_bin_variance(d, N, 1, digits=digits)
        assert abs(got - expected) <= mpmath.mpf(10) ** (1 - digits) * expected
    assert flicker_averaged_bin_variance(0.5, N, 1) == pytest.approx(float(expected), rel=1e-12)


@pytest.mark.parametrize("digits", [50, 30])
def test_carouselled_high_precision_against_direct_summation(digits):
    """g_j = Σ_u s_u ψ_{u−N+j} summed term by term (no recursion in h) for N = 300, k = 2."""
    N, k, d = 300, 2, Fraction(1, 3)
    with mpmath.workdps(digits + 10):
        third = mpmath.mpf(1) / 3
        psi = [mpmath.gammaprod([j + third], [j + 1, third]) for j in range(k * N)]
        sine = [mpmath.sinpi(mpmath.mpf(2 * u) / N) / N for u in range(1, N + 1)]
        cosine = [mpmath.cospi(mpmath.mpf(2 * u) / N) / N for u in range(1, N + 1)]
        total = mpmath.mpf(0)
        for j in range(k * N):
            lowest = max(1, N - j)  # ψ of negative index is zero
            terms = [psi[u - N + j] for u in range(lowest, N + 1)]
            total += (
                mpmath.fdot(sine[lowest - 1 :], terms) ** 2 + mpmath.fdot(cosine[lowest - 1 :], terms) ** 2
            )
    with mpmath.workdps(digits):
        got = flicker_carouselled_bin_variance(d, N, k, digits=digits)
        assert abs(got - total) <= mpmath.mpf(10) ** (1 - digits) * total


def test_float64_against_direct_convolution_at_N_10_thousand():
    """FFT path against numpy's direct (non-FFT) convolution, N = 10⁴, k = 2."""
    N, k, d = 10_000, 2, 0.5
    psi = propagation.fractional_coefficients(d, k * N)
    s, c = propagation.carousel_weights(N)
    direct_averaged = np.convolve(psi, np.full(N, 1 / N))[: k * N]
    direct_sine = np.convolve(psi, s[::-1])[: k * N]
    direct_cosine = np.convolve(psi, c[::-1])[: k * N]
    averaged = flicker_bin_variances(d, N, k, "averaged")
    carouselled = flicker_bin_variances(d, N, k, "carouselled")
    assert averaged[-1] == pytest.approx(np.sum(direct_averaged**2), rel=1e-12)
    assert carouselled[-1] == pytest.approx(np.sum(direct_sine**2) + np.sum(direct_cosine**2), rel=1e-11)
    assert averaged[0] == pytest.approx(np.sum(direct_averaged[:N] ** 2), rel=1e-12)


@pytest.mark.parametrize("n", [1, 2, 3, 7, 33, 100])
def test_flicker_weighted_sum_variance_equals_exact_gamma_sum(n):
    """The FFT 1/f variance of Σ w_t x_t (one zero-padded buffer for both transforms) against
    Σ_i (Σ_{t≥i} w_t ψ_{t−i})² in Fractions, ψ from the Gamma form, for integer weights of both signs."""
    d = Fraction(1, 2)
    weights = [int(w) for w in np.random.default_rng(n).integers(-9, 10, size=n)]
    psi = psi_from_gamma(d, n)
    exact = sum(
        (sum((Fraction(weights[t]) * psi[t - i] for t in range(i, n)), Fraction(0)) ** 2 for i in range(n)),
        Fraction(0),
    )
    got = weighted_sum_variance(np.array(weights, dtype=float), "flicker", d=0.5)
    assert got == pytest.approx(float(exact), rel=1e-12, abs=1e-12)


def test_all_bins_at_high_precision_equal_single_bins():
    for method, single in (
        ("averaged", flicker_averaged_bin_variance),
        ("carouselled", flicker_carouselled_bin_variance),
    ):
        with mpmath.workdps(40):
            every = flicker_bin_variances_high_precision(Fraction(2, 5), 7, 4, method, digits=40)
            assert len(every) == 4
            for k in range(1, 5):
                assert (
                    abs(every[k - 1] - single(Fraction(2, 5), 7, k, digits=40))
                    <= mpmath.mpf(10) ** -39 * every[k - 1]
                )


@pytest.mark.parametrize(("process", "d"), [("white", None), ("rrw", None), ("flicker", 0.3), ("bias", None)])
def test_covariance_of_several_statistics_equals_dense_product(process, d):
    """W Σ Wᵀ with the dense covariance of the process (processes.covariance_matrix), and the diagonal
    equal to weighted_sum_variance row by row."""
    W = np.random.default_rng(3).standard_normal((4, 60))
    got = weighted_sums_covariance(W, process, d)
    dense = W @ propagation_covariance(process, 60, d=d) @ W.T
    assert np.allclose(got, dense, rtol=1e-12, atol=1e-12 * np.abs(dense).max())
    assert np.allclose(np.diag(got), [weighted_sum_variance(row, process, d) for row in W], rtol=1e-12)


def test_bins_of_unequal_length_with_measured_angles():
    """Revolutions of 5, 7 and 6 samples at non-uniform angles (as in the field test, TIM 2014 Fig. 12):
    the covariance of the three carouselled rate-random-walk estimates, both gyros, against dense matrices."""
    lengths = [5, 7, 6]
    rng = np.random.default_rng(12)
    n = sum(lengths)
    sine_rows, cosine_rows = np.zeros((3, n)), np.zeros((3, n))
    start = 0
    for row, length in enumerate(lengths):
        angles = np.sort(rng.uniform(0, 2 * np.pi, length))
        s, c = carousel_weights_from_angles(angles)
        sine_rows[row, start : start + length], cosine_rows[row, start : start + length] = s, c
        start += length
    got = weighted_sums_covariance(sine_rows, "rrw") + weighted_sums_covariance(cosine_rows, "rrw")
    R = np.tril(np.ones((n, n)))
    expected = sine_rows @ R @ R.T @ sine_rows.T + cosine_rows @ R @ R.T @ cosine_rows.T
    np.testing.assert_allclose(got, expected, rtol=1e-12)


def test_uniform_carouselled_rrw_bins_are_uncorrelated():
    """TIM 2014 eq. (17): with 1ᵀs = 0 the carouselled RRW bins are uncorrelated with equal variances."""
    N, bins = 16, 3
    s, _ = propagation.carousel_weights(N)
    W = np.zeros((bins, bins * N))
    for row in range(bins):
        W[row, row * N : (row + 1) * N] = s
    covariance = weighted_sums_covariance(W, "rrw")
    assert np.max(np.abs(covariance - np.diag(np.diag(covariance)))) <= 1e-15
    assert np.allclose(np.diag(covariance), covariance[0, 0], rtol=1e-13)


# --- properties --------------------------------------------------------------------------------------


@given(N=st.integers(1, 10**6), k=st.integers(1, 40))
@example(N=1, k=1)
@example(N=10**6, k=2)
@example(N=2, k=40)
def test_rate_random_walk_average_matches_sum_of_squares_formula(N, k):
    """Var of the k-th RRW bin mean = (k−1)N + Σ_{i=1}^{N} i²/N² (TIM 2014 eq. (15) generalised),
    written here independently; the package value comes from cumulative sums."""
    expected = (k - 1) * N + Fraction(2 * N**3 + 3 * N**2 + N, 6 * N**2)
    got = repeated_weights_bin_variances(np.full(N, 1.0 / N), "rrw", k)
    assert got[-1] == pytest.approx(float(expected), rel=1e-9)
    if N * k <= 2 * 10**6:
        vector = np.zeros(N * k)
        vector[(k - 1) * N :] = 1.0 / N
        assert weighted_sum_variance(vector, "rrw") == pytest.approx(float(expected), rel=1e-9)


@given(
    d=st.floats(0.01, 0.99),
    N=st.integers(1, 3000),
    k=st.integers(1, 4),
    method=st.sampled_from(["averaged", "carouselled"]),
)
@example(d=0.5, N=1, k=1, method="carouselled")
@example(d=0.999, N=2, k=4, method="carouselled")
@example(d=0.001, N=3000, k=4, method="averaged")
def test_bin_variances_equal_variance_of_zero_padded_weights(d, N, k, method):
    """All bins from one cumulative sum == each bin as a separate weighted sum over t = 1 … kN."""
    bins = [np.full(N, 1.0 / N)] if method == "averaged" else list(propagation.carousel_weights(N))
    expected = 0.0
    for weights in bins:
        vector = np.zeros(N * k)
        vector[(k - 1) * N :] = weights
        expected += weighted_sum_variance(vector, "flicker", d)
    got = flicker_bin_variances(d, N, k, method)
    assert got[-1] == pytest.approx(expected, rel=1e-10, abs=1e-15)
    assert np.all(np.diff(got) >= -1e-15 * got[-1])  # each bin adds squares: never decreases


@pytest.mark.slow
@settings(max_examples=20)  # each example costs up to 2·10⁶ terms
@given(d=st.floats(0.01, 0.99), N=st.integers(2, 10**6), k=st.integers(1, 2))
@example(d=0.5, N=10**6, k=2)
@example(d=0.99, N=2, k=1)
def test_large_N_against_independent_linear_time_sums(d, N, k):
    """O(kN) checks without FFT: averaged via Ψ_j = Γ(j+1+d)/(Γ(j+1)Γ(d+1)) (log-Gamma), carouselled via
    h_j = z̄^j Σ_{m≤j} z^m (ψ_m − ψ_{m−N}) (the recursion h_j = z̄ h_{j−1} + ψ_j − ψ_{j−N} unrolled)."""
    length = k * N
    j = np.arange(length)
    cumulative = np.exp(
        scipy.special.gammaln(j + 1 + d) - scipy.special.gammaln(j + 1) - scipy.special.gammaln(d + 1)
    )
    window = cumulative - np.concatenate([np.zeros(N), cumulative[:-N]])[:length]
    averaged = np.sum(window**2) / N**2
    assert flicker_bin_variances(d, N, k, "averaged")[-1] == pytest.approx(averaged, rel=1e-7)
    psi = np.diff(np.concatenate([[0.0], cumulative]))  # ψ_m = Ψ_m − Ψ_{m−1}
    psi[0] = 1.0
    step = psi - np.concatenate([np.zeros(N), psi[:-N]])[:length]
    angle = 2 * np.pi * (j % N) / N
    rotated = np.cumsum(step * np.exp(1j * angle))
    carouselled = np.sum(np.abs(rotated) ** 2) / N**2
    assert flicker_bin_variances(d, N, k, "carouselled")[-1] == pytest.approx(carouselled, rel=1e-6)


@given(d=st.fractions(Fraction(1, 100), Fraction(99, 100)), N=st.integers(1, 300), k=st.integers(1, 3))
@example(d=Fraction(1, 2), N=1, k=1)
def test_float64_agrees_with_high_precision(d, N, k):
    for function in (flicker_averaged_bin_variance, flicker_carouselled_bin_variance):
        with mpmath.workdps(30):
            reference = function(d, N, k, digits=30)
        assert function(d, N, k) == pytest.approx(float(reference), rel=1e-11)


def test_one_sample_bins_carousel_as_averaging():
    """N = 1: s = (sin 2π) = 0 and c = (cos 2π) = 1, so the carouselled bin is the plain sample."""
    for k in (1, 2, 5):
        assert flicker_carouselled_bin_variance(0.4, 1, k) == flicker_averaged_bin_variance(0.4, 1, k)


def test_scaling_of_weights():
    w = np.linspace(-1, 2, 50)
    for process, d in (("white", None), ("rrw", None), ("flicker", 0.3), ("bias", None)):
        assert weighted_sum_variance(3 * w, process, d) == pytest.approx(
            9 * weighted_sum_variance(w, process, d)
        )


# --- bad input ---------------------------------------------------------------------------------------

INVALID_CALLS = [
    ("covariance 1-D", lambda: weighted_sums_covariance([1.0, 2.0], "white"), ValueError, "2-dimensional"),
    ("covariance no d", lambda: weighted_sums_covariance([[1.0]], "flicker"), ValueError, "d=None"),
    (
        "covariance inf",
        lambda: weighted_sums_covariance([[1.0, np.inf]], "rrw"),
        ValueError,
        "must be finite",
    ),
    ("wsv unknown process", lambda: weighted_sum_variance([1.0], "pink"), ValueError, "process='pink'"),
    ("wsv flicker without d", lambda: weighted_sum_variance([1.0], "flicker"), ValueError, "d=None"),
    ("wsv rrw with d", lambda: weighted_sum_variance([1.0], "rrw", 0.5), ValueError, "d=0.5"),
    ("wsv nan weight", lambda: weighted_sum_variance([1.0, np.nan], "white"), ValueError, "index 1"),
    ("wsv empty", lambda: weighted_sum_variance([], "white"), ValueError, "at least 1"),
    (
        "wsv exact float",
        lambda: weighted_sum_variance([0.5], "white", exact=True),
        TypeError,
        "weights[0]=0.5",
    ),
    ("wsv exact float d", lambda: weighted_sum_variance([1], "flicker", 0.5, exact=True), TypeError, "d=0.5"),
    ("wsv exact not bool", lambda: weighted_sum_variance([1], "white", exact=1), TypeError, "exact=1"),
    ("repeated k_max=0", lambda: repeated_weights_bin_variances([1.0], "rrw", 0), ValueError, "k_max=0"),
    (
        "repeated d=1",
        lambda: repeated_weights_bin_variances([1.0], "flicker", 2, d=1),
        ValueError,
        "0 < d < 1",
    ),
    ("bins method", lambda: flicker_bin_variances(0.5, 4, 2, "median"), ValueError, "method='median'"),
    ("bins method type", lambda: flicker_bin_variances(0.5, 4, 2, None), TypeError, "method=None"),
    ("bins N float", lambda: flicker_bin_variances(0.5, 4.0, 2), TypeError, "N=4.0"),
    ("averaged k=0", lambda: flicker_averaged_bin_variance(0.5, 4, 0), ValueError, "k=0"),
    ("averaged d nan", lambda: flicker_averaged_bin_variance(float("nan"), 4, 1), ValueError, "NaN"),
    ("averaged digits=0", lambda: flicker_averaged_bin_variance(0.5, 4, 1, digits=0), ValueError, "digits=0"),
    ("carouselled N=0", lambda: flicker_carouselled_bin_variance(0.5, 0, 1), ValueError, "N=0"),
    ("carouselled d=0", lambda: flicker_carouselled_bin_variance(0, 4, 1), ValueError, "0 < d < 1"),
    (
        "carouselled digits float",
        lambda: flicker_carouselled_bin_variance(0.5, 4, 1, digits=5.0),
        TypeError,
        "digits=5.0",
    ),
    ("exact float d", lambda: flicker_averaged_bin_variance_exact(0.5, 4, 1), TypeError, "exact rational"),
    (
        "high precision digits=0",
        lambda: flicker_bin_variances_high_precision(0.5, 4, 2, digits=0),
        ValueError,
        "digits=0",
    ),
    (
        "high precision method",
        lambda: flicker_bin_variances_high_precision(0.5, 4, 2, "sum"),
        ValueError,
        "method='sum'",
    ),
    (
        "high precision k_max",
        lambda: flicker_bin_variances_high_precision(0.5, 4, -1),
        ValueError,
        "k_max=-1",
    ),
    (
        "exact k bool",
        lambda: flicker_averaged_bin_variance_exact(Fraction(1, 2), 4, True),
        TypeError,
        "k=True",
    ),
]


@pytest.mark.parametrize(
    ("call", "error", "fragment"), [c[1:] for c in INVALID_CALLS], ids=[c[0] for c in INVALID_CALLS]
)
def test_invalid_calls(call, error, fragment):
    with pytest.raises(error) as excinfo:
        call()
    assert fragment in str(excinfo.value)


def test_every_public_function_is_exported_and_covered_by_the_invalid_call_table():
    public = public_functions(propagation)
    assert public == set(propagation.__all__) - {"BIN_METHODS"}
    assert public <= functions_called_in(INVALID_CALLS)
