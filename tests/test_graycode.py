"""Tests of carousel_theory.graycode (TIM 2014 §IV) against the paper's printed values and against
independent brute-force constructions in exact ``Fraction`` arithmetic."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import sympy as sp
from conftest import Z_MONTE_CARLO
from hypothesis import example, given
from hypothesis import strategies as st

from carousel_theory import graycode
from carousel_theory.graycode import (
    allan_estimator_variance,
    allan_variance_exact,
    allan_variance_statistic,
    covariance_entry,
    deterministic_sequence,
    gray_code,
    gray_column,
    gray_matrix,
    innovation_index,
    mvue_variance,
    mvue_variance_estimate,
    overlapping_allan_variance_exact,
    pseudoinverse,
    sequence,
    sequence_coefficients,
    sequence_from_innovations,
)

HALF = Fraction(1, 2)


# ---------------------------------------------------------------------------------------------
# Independent brute force: Algorithm 1, eq. (22) and the column rule of K, literally, in Fractions
# ---------------------------------------------------------------------------------------------


def brute_a(length: int) -> list[Fraction]:
    """a_k of eq. (22) by its recurrence."""
    a: list[Fraction] = []
    for k in range(1, length + 1):
        a.append(-HALF if k == 1 else HALF if k == 2 else -a[k - 3])
    return a


def brute_kron_ones(vector: list, count: int) -> list:
    """vector ⊗ 1_count (each element repeated ``count`` times)."""
    return [value for value in vector for _ in range(count)]


def brute_algorithm_1(n: int, x: list | None = None) -> list:
    """Algorithm 1, with a_{1…2^i} x_i added at step i (Table II) when x is given."""
    x = x if x is not None else [1] * n
    v = [-HALF * x[0], HALF * x[0]]
    for i in range(2, n + 1):
        a = brute_a(2**i)
        v = [w + ak * x[i - 1] for w, ak in zip(brute_kron_ones(v, 2), a, strict=True)]
    return v


def brute_k(n: int) -> list[list[Fraction]]:
    """K row by row: column i is a_{1…2^i} ⊗ 1_{2^{n−i}}."""
    columns = [brute_kron_ones(brute_a(2**i), 2 ** (n - i)) for i in range(1, n + 1)]
    return [list(row) for row in zip(*columns, strict=True)]


def brute_matmul(left, right):
    return [
        [sum(a * b for a, b in zip(row, col, strict=True)) for col in zip(*right, strict=True)]
        for row in left
    ]


def brute_transpose(matrix):
    return [list(row) for row in zip(*matrix, strict=True)]


def brute_difference_matrix(n: int, m: int) -> list[list[Fraction]]:
    """A of eq. (28)-(29): row j takes the mean of bin j + 1 minus the mean of bin j, τ = 2^m."""
    tau, bins = 2**m, 2 ** (n - m)
    rows = []
    for j in range(bins - 1):
        row = [Fraction(0)] * 2**n
        for t in range(tau):
            row[j * tau + t] = Fraction(-1, tau)
            row[(j + 1) * tau + t] = Fraction(1, tau)
        rows.append(row)
    return rows


# ---------------------------------------------------------------------------------------------
# The paper's printed values (TIM 2014 Tables I-II, eq. (24), (27), (30), (31)), typed from the paper
# ---------------------------------------------------------------------------------------------


def test_table_one_sequences():
    assert list(deterministic_sequence(2)) == [-1, 0, 1, 0]  # S_4, Table I and the text
    assert [Fraction(v) for v in deterministic_sequence(3)] == [
        Fraction(-3, 2),
        -HALF,
        HALF,
        -HALF,
        HALF,
        Fraction(3, 2),
        HALF,
        -HALF,
    ]  # S_8, Table I


def test_equation_22_coefficients_and_period_four():
    assert list(sequence_coefficients(8)) == [-0.5, 0.5, 0.5, -0.5, -0.5, 0.5, 0.5, -0.5]  # a_{1…8}, Table I
    assert [Fraction(v) for v in sequence_coefficients(40)] == brute_a(40)


def test_equation_24_matrix():
    assert gray_matrix(2).tolist() == [[-0.5, -0.5], [-0.5, 0.5], [0.5, 0.5], [0.5, -0.5]]


def test_table_two_stochastic_sequence():
    x1, x2 = 3.0, -7.0  # R_4 = [−x1/2 − x2/2, −x1/2 + x2/2, x1/2 + x2/2, x1/2 − x2/2]
    assert list(sequence_from_innovations([x1, x2])) == [
        -x1 / 2 - x2 / 2,
        -x1 / 2 + x2 / 2,
        x1 / 2 + x2 / 2,
        x1 / 2 - x2 / 2,
    ]


def test_equation_27_and_30_and_31():
    K = gray_matrix(2)
    assert (K @ K.T).tolist() == [[0.5, 0, -0.5, 0], [0, 0.5, 0, -0.5], [-0.5, 0, 0.5, 0], [0, -0.5, 0, 0.5]]
    A = np.array([[-1, 1, 0, 0], [0, -1, 1, 0], [0, 0, -1, 1]])
    assert (A @ K @ K.T @ A.T).tolist() == [[1, 0, -1], [0, 1, 0], [-1, 0, 1]]
    assert pseudoinverse(2).tolist() == [[-0.5, -0.5, 0.5, 0.5], [-0.5, 0.5, 0.5, -0.5]]


def test_standard_gray_code_table_sixteen_by_four():
    # the reflected Gray code of 0 … 15 (Flajolet and Ramshaw, Table 1), most significant bit first
    codes = ["0000", "0001", "0011", "0010", "0110", "0111", "0101", "0100",
             "1100", "1101", "1111", "1110", "1010", "1011", "1001", "1000"]  # fmt: skip
    expected = [[int(bit) for bit in code] for code in codes]
    assert (gray_matrix(4) + 0.5).tolist() == expected
    assert [gray_code(r) for r in range(16)] == [int(code, 2) for code in codes]


# ---------------------------------------------------------------------------------------------
# Two ways: the package against the brute force, exactly
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("n", range(2, 8))
def test_algorithm_and_matrix_against_brute_force(n):
    assert [Fraction(v) for v in deterministic_sequence(n)] == brute_algorithm_1(n)
    assert [[Fraction(v) for v in row] for row in gray_matrix(n)] == brute_k(n)
    # eq. (32): S = K 1, and S + n/2 counts the ones of the Gray code
    assert [sum(row) for row in brute_k(n)] == brute_algorithm_1(n)
    assert [v + Fraction(n, 2) for v in brute_algorithm_1(n)] == [
        gray_code(r).bit_count() for r in range(2**n)
    ]


@pytest.mark.parametrize("n", range(2, 7))
def test_covariance_closed_form_against_dense_product(n):
    K = brute_k(n)
    covariance = brute_matmul(K, brute_transpose(K))
    S = brute_algorithm_1(n)
    for r in range(2**n):
        for s in range(2**n):
            assert covariance[r][s] == covariance_entry(n, r, s) == -S[r ^ s] / 2
    assert all(covariance[r][r] == Fraction(n, 4) for r in range(2**n))


@pytest.mark.parametrize("n", range(2, 7))
def test_pseudoinverse_against_brute_force_and_penrose(n):
    K = brute_k(n)
    gram = brute_matmul(brute_transpose(K), K)
    assert gram == [[Fraction(2**n, 4) if i == j else 0 for j in range(n)] for i in range(n)]
    Kf = gray_matrix(n)
    pinv = pseudoinverse(n)
    assert np.array_equal(pinv @ Kf, np.eye(n))  # exact: powers of two
    assert np.array_equal(Kf @ pinv @ Kf, Kf)
    assert np.array_equal(pinv @ Kf @ pinv, pinv)
    assert np.array_equal((Kf @ pinv).T, Kf @ pinv)
    np.testing.assert_allclose(pinv, np.linalg.pinv(Kf), rtol=0, atol=1e-12)


@pytest.mark.parametrize("n", range(2, 7))
def test_bin_differences_and_allan_variance_against_brute_force(n):
    K = brute_k(n)
    for m in range(n):
        A = brute_difference_matrix(n, m)
        AK = brute_matmul(A, K)
        # corrected eq. (23): each difference is ±x_i for exactly one i
        for j, row in enumerate(AK, start=1):
            nonzero = [i for i, value in enumerate(row, start=1) if value != 0]
            assert nonzero == [innovation_index(n, m, j)]
            assert abs(row[nonzero[0] - 1]) == 1
        # E σ_A² = tr(A K Kᵀ Aᵀ) / (2(M − 1)), any zero-mean unit-variance x
        expected = sum(value * value for row in AK for value in row) / Fraction(2 * len(A))
        assert allan_variance_exact(n, m, 1) == expected == HALF
        assert allan_variance_exact(n, m, Fraction(3, 2)) == expected * Fraction(9, 4)
        # eq. (21): the deterministic S
        S = brute_algorithm_1(n)
        assert all(abs(sum(a * s for a, s in zip(row, S, strict=True))) == 1 for row in A)
        assert allan_variance_statistic(deterministic_sequence(n), 2**m) == 0.5


@pytest.mark.parametrize("n", range(2, 6))
def test_estimator_variances_against_gaussian_quadratic_forms(n):
    """For Gaussian x, Var(xᵀQx) = 2 tr(Q²): the Allan estimator 2σ_A² has Q = (AK)ᵀ(AK)/(M − 1)."""
    K = brute_k(n)
    for m in range(n):
        AK = brute_matmul(brute_difference_matrix(n, m), K)
        Q = [[value / (len(AK)) for value in row] for row in brute_matmul(brute_transpose(AK), AK)]
        trace_q_squared = sum(Q[i][j] * Q[j][i] for i in range(n) for j in range(n))
        assert allan_estimator_variance(n, m, 1) == 2 * trace_q_squared
        assert allan_estimator_variance(n, m, 2) == 32 * trace_q_squared
    # MVUE ‖K⁺R‖²/n = ‖x‖²/n: Q = I/n, 2 tr(Q²) = 2/n, strictly below every Allan estimator
    assert mvue_variance(n, 1) == Fraction(2, n)
    assert all(mvue_variance(n, 1) < allan_estimator_variance(n, m, 1) for m in range(n))


def test_closed_forms_accept_any_order_without_allocating():
    assert allan_variance_exact(200, 150, 1) == sp.Rational(1, 2)
    assert mvue_variance(200, 1) == sp.Rational(1, 100)
    assert covariance_entry(100, 0, 2**100 - 1) == Fraction(100 - 2 * 1, 4)  # g(2^100 − 1) = 2^99
    assert innovation_index(100, 0, 2**40) == 60


def test_exact_results_are_exact_and_float_results_are_float():
    assert allan_variance_exact(5, 1, sp.Rational(1, 3)) == sp.Rational(1, 18)
    assert isinstance(allan_variance_exact(5, 1, 0.5), float)
    assert allan_variance_exact(5, 1, 0.5) == 0.125
    assert allan_estimator_variance(3, 0, 1) == sp.Rational(2 * 9, 3 * 7)


# ---------------------------------------------------------------------------------------------
# Property-based, over n
# ---------------------------------------------------------------------------------------------


@given(n=st.integers(2, 14), data=st.data())
@example(n=2, data=None)
def test_columns_are_gray_bits_and_innovation_rule(n, data):
    r = data.draw(st.integers(0, 2**n - 1)) if data is not None else 3
    for i in range(1, n + 1):
        assert gray_column(n, i)[r] + 0.5 == (gray_code(r) >> (n - i)) & 1
    m = data.draw(st.integers(0, n - 1)) if data is not None else 0
    j = data.draw(st.integers(1, 2 ** (n - m) - 1)) if data is not None else 1
    i = innovation_index(n, m, j)
    # the only column whose bin mean changes between bins j and j + 1 (1-based) is column i
    tau = 2**m
    for column_number in range(1, n + 1):
        column = gray_column(n, column_number)
        change = column[j * tau : (j + 1) * tau].mean() - column[(j - 1) * tau : j * tau].mean()
        assert abs(change) == (1.0 if column_number == i else 0.0)


@given(n=st.integers(2, 12), x=st.lists(st.integers(-5, 5), min_size=12, max_size=12))
def test_sequence_from_innovations_is_K_times_x(n, x):
    innovations = np.array(x[:n], dtype=np.float64)
    assert np.array_equal(sequence_from_innovations(innovations, 2), 2 * gray_matrix(n) @ innovations)
    # K⁺ recovers x, so the MVUE is the mean of squares of x
    R = sequence_from_innovations(innovations)
    assert mvue_variance_estimate(R) == pytest.approx(float(np.mean(innovations**2)), rel=1e-12, abs=1e-12)


def test_same_noise_generator_and_hand_loop():
    """sequence(n, C, rng) draws x ~ N(0, I_n) from rng and returns C K x."""
    C, n = 1.7, 9
    R = sequence(n, C, rng=np.random.default_rng(2024))
    x = np.random.default_rng(2024).standard_normal(n)
    np.testing.assert_allclose(R, C * gray_matrix(n) @ x, rtol=1e-13, atol=1e-13)


# ---------------------------------------------------------------------------------------------
# Monte Carlo: the stochastic generator's Allan variance, with enough replicates that 2 % would fail
# ---------------------------------------------------------------------------------------------


def test_monte_carlo_allan_variance_of_generator_is_C_squared_over_two():
    n, C, replicates = 8, 1.3, 60_000
    rng = np.random.default_rng(20140806)
    octaves = (0, 3, 5)
    samples = np.stack([sequence(n, C, rng=rng) for _ in range(replicates)])  # replicates × 2^n
    statistics = np.empty((replicates, len(octaves)))
    for column, m in enumerate(octaves):
        means = samples.reshape(replicates, -1, 2**m).mean(axis=2)
        statistics[:, column] = np.sum(np.diff(means, axis=1) ** 2, axis=1) / (2 * (means.shape[1] - 1))
    theory = float(allan_variance_exact(n, 0, C))
    for column, m in enumerate(octaves):
        mean = statistics[:, column].mean()
        standard_error = statistics[:, column].std(ddof=1) / np.sqrt(replicates)
        assert 0.02 * theory > Z_MONTE_CARLO * standard_error, "too few replicates to detect a 2 % error"
        assert abs(mean - theory) <= Z_MONTE_CARLO * standard_error, (m, mean, theory)
        # and the variance of the estimator 2σ_A² against its closed form (Gaussian x)
        predicted = float(allan_estimator_variance(n, m, C))
        observed = np.var(2 * statistics[:, column], ddof=1)
        assert abs(observed - predicted) <= 0.05 * predicted


# ---------------------------------------------------------------------------------------------
# Bad input: one table for every public function
# ---------------------------------------------------------------------------------------------

RNG = np.random.default_rng(0)

INVALID_CALLS = [
    ("sequence-n-one", lambda: deterministic_sequence(1), ValueError, "n=1"),
    ("sequence-n-zero", lambda: deterministic_sequence(0), ValueError, "n=0"),
    ("sequence-n-float", lambda: deterministic_sequence(3.0), TypeError, "n=3.0"),
    ("sequence-n-bool", lambda: deterministic_sequence(True), TypeError, "n=True"),
    ("sequence-n-huge", lambda: deterministic_sequence(60), ValueError, "memory"),
    ("matrix-n-huge", lambda: gray_matrix(40), ValueError, "memory"),
    ("matrix-n-one", lambda: gray_matrix(1), ValueError, "n=1"),
    ("matrix-n-string", lambda: gray_matrix("4"), TypeError, "n='4'"),
    ("column-i-zero", lambda: gray_column(4, 0), ValueError, "i=0"),
    ("column-i-too-big", lambda: gray_column(4, 5), ValueError, "i=5"),
    ("random-no-rng", lambda: sequence(4, 1.0, rng=None), TypeError, "rng=None"),
    ("random-legacy-rng", lambda: sequence(4, 1.0, rng=np.random.RandomState(0)), TypeError, "rng="),
    ("random-C-zero", lambda: sequence(4, 0.0, rng=RNG), ValueError, "C=0.0"),
    ("random-C-nan", lambda: sequence(4, float("nan"), rng=RNG), ValueError, "C=nan"),
    ("random-n-huge", lambda: sequence(70, 1.0, rng=RNG), ValueError, "memory"),
    ("innovations-too-short", lambda: sequence_from_innovations([1.0]), ValueError, "x"),
    ("innovations-inf", lambda: sequence_from_innovations([1.0, np.inf]), ValueError, "x"),
    ("allan-m-negative", lambda: allan_variance_exact(4, -1), ValueError, "m=-1"),
    ("allan-m-too-big", lambda: allan_variance_exact(4, 4), ValueError, "m=4"),
    ("allan-C-negative", lambda: allan_variance_exact(4, 1, -1), ValueError, "C=-1"),
    ("allan-C-string", lambda: allan_variance_exact(4, 1, "1"), TypeError, "C='1'"),
    ("estimator-m-too-big", lambda: allan_estimator_variance(3, 3), ValueError, "m=3"),
    ("mvue-variance-n-one", lambda: mvue_variance(1), ValueError, "n=1"),
    ("statistic-tau-zero", lambda: allan_variance_statistic(np.zeros(8), 0), ValueError, "tau=0"),
    ("statistic-tau-too-big", lambda: allan_variance_statistic(np.zeros(8), 5), ValueError, "tau=5"),
    ("statistic-nan", lambda: allan_variance_statistic([0.0, np.nan, 1.0, 2.0], 1), ValueError, "y"),
    ("index-j-zero", lambda: innovation_index(4, 0, 0), ValueError, "j=0"),
    ("index-j-too-big", lambda: innovation_index(4, 2, 4), ValueError, "j=4"),
    ("covariance-row-out", lambda: covariance_entry(3, 8, 0), ValueError, "r=8"),
    ("covariance-col-negative", lambda: covariance_entry(3, 0, -1), ValueError, "s=-1"),
    ("pseudoinverse-n-one", lambda: pseudoinverse(1), ValueError, "n=1"),
    ("mvue-not-power-of-two", lambda: mvue_variance_estimate(np.zeros(6)), ValueError, "power of two"),
    ("mvue-length-two", lambda: mvue_variance_estimate(np.zeros(2)), ValueError, "n=1"),
    ("coefficients-length-zero", lambda: sequence_coefficients(0), ValueError, "length=0"),
    ("overlapping-m-too-big", lambda: overlapping_allan_variance_exact(3, 3), ValueError, "m=3"),
    ("overlapping-C-zero", lambda: overlapping_allan_variance_exact(3, 1, 0), ValueError, "C=0"),
]


@pytest.mark.parametrize(
    ("call", "error", "message"),
    [pytest.param(call, error, message, id=name) for name, call, error, message in INVALID_CALLS],
)
def test_invalid_calls(call, error, message):
    with pytest.raises(error, match=message.replace("(", r"\(").replace("[", r"\[")):
        call()


def test_invalid_table_covers_every_public_function():
    called = {name.split("-")[0] for name, *_ in INVALID_CALLS}
    aliases = {
        "sequence": "deterministic_sequence", "matrix": "gray_matrix", "column": "gray_column",
        "random": "sequence", "innovations": "sequence_from_innovations", "allan": "allan_variance_exact",
        "estimator": "allan_estimator_variance", "mvue": "mvue_variance_estimate", "statistic":
        "allan_variance_statistic", "index": "innovation_index", "covariance": "covariance_entry",
        "pseudoinverse": "pseudoinverse", "coefficients": "sequence_coefficients",
        "overlapping": "overlapping_allan_variance_exact",
    }  # fmt: skip
    covered = {aliases[name] for name in called} | {"mvue_variance"}
    functions = {name for name in graycode.__all__ if callable(getattr(graycode, name))}
    # gray_code works on any integer or integer array (no domain to violate)
    assert functions - covered == {"gray_code"}


def test_all_is_honest():
    assert sorted(graycode.__all__) == graycode.__all__
    for name in graycode.__all__:
        assert hasattr(graycode, name)
