"""``carousel-theory formula``: listing, exact and decimal output, JSON, exact parsing of --set, errors."""

from __future__ import annotations

import json

import mpmath
import pytest
import sympy as sp

from carousel_theory.cli import main
from carousel_theory.cli.formula import parse_exact_number
from carousel_theory.formulas import FORMULAS


def run(capsys, *argv):
    status = main(["formula", *argv])
    captured = capsys.readouterr()
    return status, captured.out, captured.err


def test_list_names_every_formula(capsys):
    status, out, _ = run(capsys, "--list")
    assert status == 0
    for name in FORMULAS:
        assert name in out


def test_list_json(capsys):
    status, out, _ = run(capsys, "--list", "--json")
    assert status == 0
    entries = json.loads(out)["formulas"]
    assert [e["name"] for e in entries] == sorted(FORMULAS)
    by_name = {e["name"]: e for e in entries}
    assert by_name["rrw_average_cov"]["parameters"] == ["N", "a", "b"]
    assert by_name["flicker_carousel_var"]["closed_form"] is False


def test_json_value_exact_and_digits(capsys):
    status, out, _ = run(capsys, "rrw_carousel_var", "--set", "N=6", "--json", "--digits", "25")
    assert status == 0
    result = json.loads(out)
    assert result["name"] == "rrw_carousel_var"
    assert sp.sympify(result["exact"]) == sp.Rational(1, 3)  # csc²(π/6)/12 = 4/12
    assert result["value"] == "0." + "3" * 25
    assert result["digits"] == 25
    assert result["parameters"] == {"N": "6"}


def test_decimal_input_is_read_exactly(capsys):
    # rho = 0.3 must be 3/10 exactly: the exact form then has the coefficient 3/10 · 1/(2N)
    status, out, _ = run(capsys, "rrw_carousel_var_correlated", "--set", "N=4", "--set", "rho=0.3", "--json")
    assert status == 0
    result = json.loads(out)
    # N = 4: total 1/4, cross −1/16: 1/4 + 2 · (3/10) · (1/16) = 1/4 + 3/80 = 23/80
    assert sp.sympify(result["exact"]) == sp.Rational(23, 80)
    with mpmath.workdps(60):
        assert mpmath.mpf(result["value"]) == mpmath.mpf(23) / 80


def test_value_has_the_requested_significant_digits(capsys):
    status, out, _ = run(capsys, "rrw_carousel_var_sin", "--set", "N=1e9", "--json", "--digits", "40")
    assert status == 0
    result = json.loads(out)
    mantissa = result["value"].split("e")[0].replace(".", "").replace("-", "").lstrip("0")
    assert len(mantissa) == 40
    with mpmath.workdps(60):
        reference = (3 * mpmath.csc(mpmath.pi / 10**9) ** 2 - 2) / (8 * 10**9)
        assert abs(mpmath.mpf(result["value"]) - reference) <= mpmath.mpf(10) ** -38 * reference


def test_exact_only_text(capsys):
    status, out, _ = run(capsys, "rrw_average_cov", "--set", "N=2", "--set", "a=1", "--set", "b=2", "--exact")
    assert status == 0
    assert out.strip() == "rrw_average_cov(N=2, a=1, b=2) = 3/2"


def test_flicker_exact_null_unless_asked(capsys):
    arguments = ["flicker_average_var", "--set", "d=1/2", "--set", "N=2", "--set", "k=1", "--json"]
    status, out, _ = run(capsys, *arguments)
    assert status == 0 and json.loads(out)["exact"] is None
    status, out, _ = run(capsys, *arguments, "--exact")
    assert status == 0 and json.loads(out)["exact"] == "13/16"  # (9/4 + 1)/4, by hand


def test_exact_flag_prints_the_exact_value_to_fifty_digits(capsys):
    # 13/16 = 0.8125 is exact in binary, so use a value that is not: d = 1/3, N = 4, k = 2.
    arguments = ["flicker_average_var", "--set", "d=1/3", "--set", "N=4", "--set", "k=2", "--exact", "--json"]
    status, out, _ = run(capsys, *arguments)
    result = json.loads(out)
    assert status == 0
    exact = sp.Rational(result["exact"])
    with mpmath.workdps(70):
        expected = mpmath.nstr(mpmath.mpf(exact.p) / exact.q, 50, strip_zeros=False)
    assert result["value"] == expected  # every one of the 50 digits, not a float's binary expansion


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        pytest.param(["no_such_formula"], "no such formula", id="unknown-name"),
        pytest.param([], "NAME is required", id="no-name"),
        pytest.param(["--list", "rrw_carousel_var"], "--list takes no NAME", id="list-with-name"),
        pytest.param(["rrw_carousel_var", "--set", "N"], "KEY=VALUE", id="set-without-equals"),
        pytest.param(
            ["rrw_carousel_var", "--set", "N=abc"], "must be an integer, a fraction", id="set-not-a-number"
        ),
        pytest.param(["rrw_carousel_var", "--set", "N=nan"], "must be an integer, a fraction", id="set-nan"),
        pytest.param(["rrw_carousel_var", "--set", "N=3", "--set", "N=4"], "given twice", id="set-twice"),
        pytest.param(["rrw_carousel_var", "--set", "N=5/2"], "N=5/2", id="non-integer-N"),
        pytest.param(["rrw_carousel_var", "--set", "N=0"], "N=0", id="N-zero"),
        pytest.param(["rrw_carousel_var", "--set", "N=1"], "rrw_carousel_cov", id="N-one-not-carouselled"),
        pytest.param(["rrw_carousel_var"], "missing", id="missing-parameter"),
        pytest.param(["rrw_carousel_var", "--set", "N=4", "--set", "M=2"], "unknown", id="unknown-parameter"),
        pytest.param(
            ["rrw_average_cov", "--set", "N=4", "--set", "a=0", "--set", "b=1"], "a=0", id="bin-zero"
        ),
        pytest.param(
            ["rrw_carousel_var_correlated", "--set", "N=4", "--set", "rho=3/2"],
            "rho=3/2",
            id="rho-out-of-range",
        ),
        pytest.param(["rrw_carousel_var", "--set", "N=4", "--digits", "0"], "--digits=0", id="digits-zero"),
        pytest.param(
            ["flicker_carousel_var", "--set", "d=1/2", "--set", "N=4", "--set", "k=1", "--exact"],
            "no exact form",
            id="flicker-carousel-exact",
        ),
        pytest.param(
            ["flicker_average_var", "--set", "d=1", "--set", "N=4", "--set", "k=1"],
            "d=1",
            id="d-out-of-range",
        ),
    ],
)
def test_bad_input_exits_2_with_a_message(capsys, argv, message):
    status, out, err = run(capsys, *argv)
    assert status == 2
    assert message in err
    assert out == ""


@pytest.mark.parametrize(
    ("text", "expected"),
    [("200", 200), ("1/2", sp.Rational(1, 2)), ("0.3", sp.Rational(3, 10)), ("1e6", 10**6), ("-1", -1)],
)
def test_parse_exact_number(text, expected):
    assert parse_exact_number("x", text) == expected
