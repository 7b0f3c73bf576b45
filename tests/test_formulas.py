"""The formula registry: names, metadata, exact / high-precision / float64 evaluation, bad input.

Expected values here are computed independently of the registry: by hand from the weight vectors
(small N), by Fraction sums, or by direct mpmath summation.
"""

from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import numpy as np
import pytest
import sympy as sp
from hypothesis import example, given
from hypothesis import strategies as st

from carousel_theory import formulas
from carousel_theory.formulas import FORMULAS, Formula, formula

STABLE_NAMES = {
    "rrw_average_cov": ("N", "a", "b"),
    "rrw_average_var": ("N", "k"),
    "rrw_carousel_var_sin": ("N",),
    "rrw_carousel_var_cos": ("N",),
    "rrw_carousel_var": ("N",),
    "rrw_carousel_cross": ("N",),
    "rrw_carousel_var_correlated": ("N", "rho"),
    "white_average_var": ("N",),
    "white_carousel_var": ("N", "var_x", "var_y"),
    "bias_carousel_residual": ("N",),
    "flicker_average_var": ("d", "N", "k"),
    "flicker_carousel_var": ("d", "N", "k"),
}

#: A valid exact argument set per formula (used by the generic tests below).
SAMPLE = {
    "bias_carousel_residual": {"N": 5},
    "bias_carousel_residual_cos": {"N": 1},
    "bias_carousel_residual_sin": {"N": 7},
    "flicker_average_var": {"d": Fraction(1, 2), "N": 4, "k": 3},
    "flicker_carousel_var": {"d": Fraction(1, 2), "N": 4, "k": 3},
    "heading_angle_bias": {"beta": Fraction(1, 100)},
    "heading_angle_walk_var": {"sigma_nu": Fraction(1, 1000), "n": 7},
    "heading_encoder_noise_var": {"sigma_e": Fraction(1, 10), "n": 5},
    "heading_scale_mismatch": {"k_x": Fraction(1, 1000), "k_y": Fraction(-1, 2000), "psi": Fraction(1, 3)},
    "indexing2_bias_var": {"N": 5, "k": 2},
    "indexing2_rrw_var": {"N": 5, "k": 2, "g": 3},
    "indexing2_white_var": {"N": 5, "k": 2},
    "indexing4_bias_var": {"N": 5, "k": 2},
    "indexing4_rrw_var": {"N": 5, "k": 2, "g": 3},
    "indexing4_white_var": {"N": 5, "k": 2},
    "rate_error_misalignment_wobble": {
        "epsilon": Fraction(1, 1000),
        "wobble": Fraction(1, 100),
        "omega_r": 3,
    },
    "rrw_average_cov": {"N": 5, "a": 2, "b": 4},
    "rrw_average_var": {"N": 5, "k": 3},
    "rrw_carousel_cov": {"N": 5, "a": 3, "b": 3},
    "rrw_carousel_cross": {"N": 5},
    "rrw_carousel_var": {"N": 5},
    "rrw_carousel_var_correlated": {"N": 5, "rho": Fraction(-1, 3)},
    "rrw_carousel_var_cos": {"N": 5},
    "rrw_carousel_var_sin": {"N": 5},
    "white_average_var": {"N": 5},
    "white_carousel_var": {"N": 5, "var_x": Fraction(1, 2), "var_y": 3},
}


def test_registry_has_the_stable_names_with_their_parameters():
    for name, parameters in STABLE_NAMES.items():
        assert FORMULAS[name].parameters == parameters
    assert list(FORMULAS) == sorted(FORMULAS)
    assert set(SAMPLE) == set(FORMULAS)


@pytest.mark.parametrize("name", sorted(FORMULAS))
def test_metadata_and_latex(name):
    entry = FORMULAS[name]
    assert isinstance(entry, Formula)
    assert entry.name == name
    assert entry.source.startswith("TIM 2014")
    assert entry.assumptions and entry.description
    assert isinstance(entry.latex(), str) and entry.latex()
    if entry.expression is not None:
        from carousel_theory import symbols

        allowed = {getattr(symbols, p) for p in entry.parameters}
        assert entry.expression.free_symbols <= allowed


def test_unknown_name_lists_the_known_ones():
    with pytest.raises(ValueError, match="rrw_carousel_var") as info:
        formula("rrw_carousel_variance")
    assert "no such formula" in str(info.value)


# ---------------------------------------------------------------------------------------------
# Exact values worked by hand from the weight vectors
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("name", "values", "expected"),
    [
        # N = 4: s = (1, 0, −1, 0)/4, Rᵀs = (0, −1, −1, 0)/4; c = (0, −1, 0, 1)/4, Rᵀc = (0, 0, 1, 1)/4
        ("rrw_carousel_var_sin", {"N": 4}, sp.Rational(1, 8)),
        ("rrw_carousel_var_cos", {"N": 4}, sp.Rational(1, 8)),
        ("rrw_carousel_var", {"N": 4}, sp.Rational(1, 4)),
        ("rrw_carousel_cross", {"N": 4}, sp.Rational(-1, 16)),
        ("rrw_carousel_var_correlated", {"N": 4, "rho": 1}, sp.Rational(1, 4) + sp.Rational(1, 8)),
        # N = 2: s = 0, c = (−1/2, 1/2), Rᵀc = (0, 1/2)
        ("rrw_carousel_var_sin", {"N": 2}, 0),
        ("rrw_carousel_var", {"N": 2}, sp.Rational(1, 4)),
        ("rrw_carousel_var_correlated", {"N": 2, "rho": -1}, sp.Rational(1, 4)),
        ("rrw_carousel_cross", {"N": 1}, 0),
        # N = 1: one sample per bin, the bin is the RRW sample itself: Cov(r_a, r_b) = min(a, b)
        ("rrw_carousel_cov", {"N": 1, "a": 3, "b": 5}, 3),
        ("rrw_carousel_cov", {"N": 6, "a": 3, "b": 5}, 0),
        # averaging, N = 2: (r_1 + r_2)/2 = q_1 + q_2/2 and (r_3 + r_4)/2 = q_1 + q_2 + q_3 + q_4/2,
        # so Var_1 = 5/4, Var_2 = 2 + 5/4, Cov = 1 + 1/2
        ("rrw_average_var", {"N": 2, "k": 1}, sp.Rational(5, 4)),
        ("rrw_average_var", {"N": 2, "k": 2}, sp.Rational(13, 4)),
        ("rrw_average_cov", {"N": 2, "a": 1, "b": 2}, sp.Rational(3, 2)),
        ("white_carousel_var", {"N": 4, "var_x": 2, "var_y": 6}, 1),  # (2·2/16) + (6·2/16)
        ("white_carousel_var", {"N": 2, "var_x": 2, "var_y": 6}, 3),  # cos weights ±1/2, sin weights 0
        ("white_carousel_var", {"N": 1, "var_x": 2, "var_y": 6}, 6),
        ("white_average_var", {"N": 8}, sp.Rational(1, 8)),
        ("bias_carousel_residual", {"N": 1}, 1),
        ("bias_carousel_residual", {"N": 2}, 0),
        ("bias_carousel_residual_sin", {"N": 1}, 0),
        # 1/f, d = 1/2, N = 2, k = 1: mean of f_1 = w_1 and f_2 = w_1/2 + w_2 is (3w_1/2 + w_2)/2
        ("flicker_average_var", {"d": Fraction(1, 2), "N": 2, "k": 1}, sp.Rational(13, 16)),
    ],
    ids=lambda value: (
        str(value) if not isinstance(value, dict) else ",".join(f"{k}={v}" for k, v in value.items())
    ),
)
def test_exact_values_by_hand(name, values, expected):
    assert sp.simplify(formula(name).exact(**values) - expected) == 0


def test_carousel_var_at_N_6_in_radicals():
    # N = 6: csc²(π/6) = 4, so the total is 4/12 = 1/3; cot(π/6) = √3, cross = −√3/24
    assert formula("rrw_carousel_var").exact(N=6) == sp.Rational(1, 3)
    assert sp.simplify(formula("rrw_carousel_cross").exact(N=6) + sp.sqrt(3) / 24) == 0


def test_flicker_carousel_has_no_exact_form():
    with pytest.raises(ValueError, match="no exact form"):
        formula("flicker_carousel_var").exact(d=Fraction(1, 2), N=4, k=1)


# ---------------------------------------------------------------------------------------------
# evaluate and numeric agree with exact, at 50 and 30 digits and in float64
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("digits", [50, 30])
@pytest.mark.parametrize("name", sorted(FORMULAS))
def test_evaluate_matches_exact_at_precision(name, digits):
    entry = FORMULAS[name]
    value = entry.evaluate(digits=digits, **SAMPLE[name])
    assert isinstance(value, mpmath.mpf)
    with mpmath.workdps(digits + 20):
        if name == "flicker_carousel_var":  # no exact form: compare with the 30-digit-deeper evaluation
            reference = entry.evaluate(digits=digits + 20, **SAMPLE[name])
        else:
            reference = mpmath.mpf(str(sp.N(entry.exact(**SAMPLE[name]), digits + 20)))
        assert abs(value - reference) <= mpmath.mpf(10) ** (1 - digits) * max(
            abs(reference), mpmath.mpf(1e-300)
        )


@pytest.mark.parametrize("name", sorted(FORMULAS))
def test_numeric_matches_evaluate(name):
    entry = FORMULAS[name]
    values = {p: (float(v) if isinstance(v, Fraction) else v) for p, v in SAMPLE[name].items()}
    result = entry.numeric(**values)
    assert isinstance(result, float)
    assert math.isclose(result, float(entry.evaluate(**SAMPLE[name])), rel_tol=1e-13, abs_tol=1e-15)


def test_evaluate_at_50_digits_against_direct_summation():
    n = 997
    with mpmath.workdps(70):
        sine_tail = cosine_tail = total = mpmath.mpf(0)
        for j in range(n, 0, -1):
            sine_tail += mpmath.sin(2 * mpmath.pi * j / n) / n
            cosine_tail += mpmath.cos(2 * mpmath.pi * j / n) / n
            total += sine_tail**2 + cosine_tail**2
    value = formula("rrw_carousel_var").evaluate(digits=50, N=n)
    assert abs(value - total) <= mpmath.mpf(10) ** -49 * total


def test_numeric_broadcasts_and_survives_huge_N():
    N = np.array([[3], [10], [10**9]])
    rho = np.array([-1.0, 0.0, 0.5, 1.0])
    result = formula("rrw_carousel_var_correlated").numeric(N=N, rho=rho)
    assert result.shape == (3, 4)
    for row, n in enumerate(N[:, 0]):
        for column, r in enumerate(rho):
            expected = float(formula("rrw_carousel_var_correlated").evaluate(N=int(n), rho=float(r)))
            assert math.isclose(result[row, column], expected, rel_tol=1e-12)
    # (N + 1)(2N + 1) overflows int64 beyond N ≈ 2·10⁹: numeric works in float64
    big = formula("rrw_average_var").numeric(N=np.array([10**12]), k=np.array([3]))
    assert math.isclose(big[0], float(formula("rrw_average_var").evaluate(N=10**12, k=3)), rel_tol=1e-14)


@given(n=st.integers(min_value=2, max_value=10**12), correlation=st.fractions(min_value=-1, max_value=1))
@example(n=2, correlation=Fraction(1))
@example(n=3, correlation=Fraction(-1))
def test_correlated_variance_is_positive_and_between_the_extremes(n, correlation):
    entry = formula("rrw_carousel_var_correlated")
    value = entry.evaluate(digits=30, N=n, rho=correlation)
    low = entry.evaluate(digits=30, N=n, rho=-1)
    high = entry.evaluate(digits=30, N=n, rho=1)
    with mpmath.workdps(40):  # compare at a precision above the 30 digits of the values
        slack = mpmath.mpf(10) ** -25 * high
        assert 0 < low <= value + slack
        assert value <= high + slack


# ---------------------------------------------------------------------------------------------
# Bad input: one table covering every public function
# ---------------------------------------------------------------------------------------------


def _calls():
    cases = [
        ("formula-not-a-name", lambda: formula(3), TypeError, "name=3"),
        ("formula-unknown", lambda: formula("nope"), ValueError, "no such formula"),
    ]
    for name, values in SAMPLE.items():
        entry = FORMULAS[name]
        for method in ("exact", "evaluate", "numeric"):
            call = getattr(entry, method)
            cases.append((f"{name}-{method}-missing", lambda call=call: call(), TypeError, "missing"))
            cases.append(
                (f"{name}-{method}-unknown", lambda c=call, v=values: c(**v, sigma=1), TypeError, "unknown")
            )
            for parameter, bad, error, message in [
                ("N", 0, ValueError, "N=0"),
                ("N", 2.5, TypeError, "N=2.5"),
                ("N", float("nan"), TypeError, "N=nan"),
                ("a", 0, ValueError, "a=0"),
                ("b", -2, ValueError, "b=-2"),
                ("k", 0, ValueError, "k=0"),
                ("rho", Fraction(3, 2), ValueError, "rho="),
                ("rho", float("nan"), ValueError, "rho=nan"),
                ("var_x", -1, ValueError, "var_x=-1"),
                ("var_y", float("inf"), ValueError, "var_y=inf"),
                ("d", Fraction(3, 2), ValueError, "d="),
                ("d", 0, ValueError, "d=0"),
                ("n", 0, ValueError, "n=0"),
                ("sigma_e", -1, ValueError, "sigma_e=-1"),
                ("omega_r", 0, ValueError, "omega_r=0"),
                ("psi", float("nan"), ValueError, "psi=nan"),
            ]:
                if parameter in values:
                    bad_values = {**values, parameter: bad}
                    cases.append(
                        (
                            f"{name}-{method}-{parameter}={bad}",
                            lambda c=call, v=bad_values: c(**v),
                            error,
                            message,
                        )
                    )
        if entry.minimum_samples == 2:
            cases.append(
                (f"{name}-N=1", lambda e=entry, v=values: e.exact(**{**v, "N": 1}), ValueError, ">= 2")
            )
        float_values = {p: (0.5 if p in ("rho", "var_x", "d") else v) for p, v in values.items()}
        if float_values != values:
            cases.append(
                (f"{name}-exact-float", lambda e=entry, v=float_values: e.exact(**v), TypeError, "exact")
            )
        cases.append(
            (f"{name}-digits=0", lambda e=entry, v=values: e.evaluate(digits=0, **v), ValueError, "digits")
        )
        if "N" not in values:
            continue
        cases.append(
            (
                f"{name}-numeric-float-N-array",
                lambda e=entry, v=values: e.numeric(**{**v, "N": np.array([3.0, 4.0])}),
                TypeError,
                "integer array",
            )
        )
        cases.append(
            (
                f"{name}-numeric-N-array-zero",
                lambda e=entry, v=values: e.numeric(**{**v, "N": np.array([3, 0])}),
                ValueError,
                "N=0",
            )
        )
    cases.append(
        (
            "correlated-numeric-rho-array-out-of-range",
            lambda: formula("rrw_carousel_var_correlated").numeric(N=5, rho=np.array([0.5, 1.5])),
            ValueError,
            "rho=1.5",
        )
    )
    cases.append(
        (
            "correlated-numeric-rho-array-nan",
            lambda: formula("rrw_carousel_var_correlated").numeric(N=5, rho=np.array([np.nan])),
            ValueError,
            "rho=nan",
        )
    )
    return cases


@pytest.mark.parametrize(
    ("call", "error", "message"), [c[1:] for c in _calls()], ids=[c[0] for c in _calls()]
)
def test_invalid_calls(call, error, message):
    with pytest.raises(error, match=message):
        call()


def test_all_is_honest():
    for name in formulas.__all__:
        assert hasattr(formulas, name)


# --- 1/f entries: numeric through one FFT per (d, N) ---------------------------------------------


@pytest.mark.parametrize(
    ("name", "method"), [("flicker_average_var", "averaged"), ("flicker_carousel_var", "carouselled")]
)
def test_flicker_numeric_over_many_bins_is_the_propagation_fast_path(name, method):
    """The case of the issue: 1000 bins of TIM 2014 Fig. 5 (d = 1/2, N = 200) in one call."""
    from carousel_theory.propagation import flicker_bin_variances

    bins = np.arange(1, 1001)
    got = formula(name).numeric(d=0.5, N=200, k=bins)
    np.testing.assert_array_equal(got, flicker_bin_variances(0.5, 200, 1000, method))


@pytest.mark.parametrize("name", ["flicker_average_var", "flicker_carousel_var"])
def test_flicker_numeric_groups_mixed_orders_and_sizes_against_50_digits(name):
    d = np.array([[0.25], [0.5], [0.75]])
    N = np.array([1, 2, 5, 5])
    k = np.array([3, 1, 2, 4])
    got = formula(name).numeric(d=d, N=N, k=k)
    assert got.shape == (3, 4)
    for row in range(3):
        for column in range(4):
            expected = formula(name).evaluate(d=float(d[row, 0]), N=int(N[column]), k=int(k[column]))
            assert math.isclose(got[row, column], float(expected), rel_tol=1e-12), (row, column)


def test_flicker_carousel_var_at_one_sample_is_the_cosine_gyros_variance():
    """N = 1: the one weight is cos 2π = 1 on the y gyro, so bin k is f_k: Var = Σ_{j<k} ψ_j² (eq. (3))."""
    psi = [Fraction(1)]
    for j in range(1, 6):
        psi.append(psi[-1] * (j - 1 + Fraction(1, 2)) / j)
    for k in range(1, 7):
        expected = sum(p * p for p in psi[:k])
        assert math.isclose(
            formula("flicker_carousel_var").numeric(d=0.5, N=1, k=k), float(expected), rel_tol=1e-13
        )
        assert formula("flicker_average_var").exact(d=Fraction(1, 2), N=1, k=k) == sp.Rational(
            expected.numerator, expected.denominator
        )
