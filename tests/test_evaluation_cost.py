"""Unbounded evaluations are refused before any work, with their cost; ``force`` runs them anyway.

One regression test per case found by the fuzzing pass (named after it), plus the budget's own rules.
"""

from __future__ import annotations

import json
import sys
from fractions import Fraction

import mpmath
import numpy as np
import pytest

from carousel_theory import evaluation_cost
from carousel_theory.cli import main
from carousel_theory.evaluation_cost import (
    EvaluationBudgetError,
    EvaluationCost,
    check_budget,
    closed_form_cost,
    exact_flicker_cost,
    float_flicker_cost,
    high_precision_flicker_cost,
)
from carousel_theory.figures import write_figures
from carousel_theory.formulas import formula


def refused(capsys, *argv):
    """Run the command; return its one-line error after checking that it was refused."""
    status = main(list(argv))
    captured = capsys.readouterr()
    assert status == 2, captured
    assert captured.out == ""
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1, lines
    return lines[0]


def test_formula_flicker_carousel_var_at_N_1e12_is_refused_with_its_cost(capsys):
    message = refused(
        capsys, "formula", "flicker_carousel_var", "--set", "d=1/2", "--set", "N=1e12", "--set", "k=1"
    )
    assert "flicker_carousel_var(d=1/2, N=1000000000000, k=1) at 50 digits" in message
    assert "k·N = 1e+12 steps" in message and "estimated" in message and "days" in message
    assert "--force" in message


def test_formula_flicker_average_var_at_N_1e9_k_1000_is_refused_with_its_cost(capsys):
    message = refused(
        capsys, "formula", "flicker_average_var", "--set", "d=1/2", "--set", "N=1e9", "--set", "k=1000"
    )
    assert "flicker_average_var(d=1/2, N=1000000000, k=1000)" in message
    assert "recursion steps" in message and "over the budget of 60 s" in message


def test_formula_exact_at_N_2000_k_100_is_refused_with_its_cost(capsys):
    message = refused(
        capsys,
        "formula",
        "flicker_average_var",
        "--set",
        "d=1/2",
        "--set",
        "N=2000",
        "--set",
        "k=100",
        "--exact",
    )
    assert "flicker_average_var(d=1/2, N=2000, k=100) exactly: k·N = 200000 exact terms" in message
    assert " h," in message  # hours, not seconds


def test_figures_with_a_billion_realisations_is_refused_before_writing(tmp_path, capsys):
    out = tmp_path / "figures"
    message = refused(capsys, "figures", "--realisations", "1000000000", "--out", str(out))
    assert "1e+09 realisations" in message and "estimated" in message and "--force" in message
    assert not out.exists()


def test_figures_without_monte_carlo_ignore_the_realisations(tmp_path):
    written = write_figures(tmp_path, realisations=10**9, only=["tim2014_fig3"])
    assert [path.name for path in written] == ["tim2014_fig3.png"]


def test_evaluate_at_a_million_digits_is_refused_with_its_cost():
    with pytest.raises(
        EvaluationBudgetError, match=r"rrw_carousel_var\(N=7\) at 1000000 digits: D = 1000010"
    ):
        formula("rrw_carousel_var").evaluate(digits=10**6, N=7)


def test_numeric_of_flicker_at_N_1e12_is_refused_before_allocating():
    with pytest.raises(EvaluationBudgetError, match=r"k·N = 1e\+12 samples.*TB of memory"):
        formula("flicker_carousel_var").numeric(d=0.5, N=10**12, k=1)


def test_digits_5000_pass_the_int_string_limit(capsys):
    """5000 digits of csc²(π/7)/14, past Python's 4300-digit int-string limit, against mpmath directly."""
    status = main(["formula", "rrw_carousel_var", "--set", "N=7", "--digits", "5000", "--json"])
    captured = capsys.readouterr()
    assert status == 0, captured.err
    limit = sys.get_int_max_str_digits()
    sys.set_int_max_str_digits(0)
    try:
        value = json.loads(captured.out)["value"]
        with mpmath.workdps(5020):
            expected = mpmath.csc(mpmath.pi / 7) ** 2 / 14
            assert abs(mpmath.mpf(value) - expected) <= expected * mpmath.mpf(10) ** -4999
    finally:
        sys.set_int_max_str_digits(limit)
    assert sys.get_int_max_str_digits() == limit  # the command restored the limit


@pytest.mark.slow
def test_exact_value_longer_than_4300_digits_is_printed_in_full(capsys):
    """The exact 1/f variance for d = 1/3, N = 50, k = 64 has numerator and denominator of > 4300 digits."""
    status = main(
        ["formula", "flicker_average_var", "--set", "d=1/3", "--set", "N=50", "--set", "k=64", "--exact"]
    )
    captured = capsys.readouterr()
    assert status == 0, captured.err
    numerator, denominator = captured.out.split(" = ")[1].strip().split("/")
    assert len(numerator) > 4300 and len(denominator) > 4300
    limit = sys.get_int_max_str_digits()
    sys.set_int_max_str_digits(0)
    try:
        exact = Fraction(int(numerator), int(denominator))
    finally:
        sys.set_int_max_str_digits(limit)
    # The float64 FFT path is a second, independent way.
    floating = formula("flicker_average_var").numeric(d=1 / 3, N=50, k=64)
    assert abs(float(exact) - floating) <= 1e-11 * floating


def test_force_runs_what_the_budget_refuses(monkeypatch, capsys):
    monkeypatch.setattr(evaluation_cost, "DEFAULT_BUDGET_SECONDS", 1e-12)
    argv = ["formula", "flicker_carousel_var", "--set", "d=1/2", "--set", "N=4", "--set", "k=2"]
    assert "over the budget of 1e-12 s" in refused(capsys, *argv)
    assert main([*argv, "--force"]) == 0
    assert "flicker_carousel_var(d=1/2, N=4, k=2) ≈ " in capsys.readouterr().out
    entry = formula("flicker_carousel_var")
    with pytest.raises(EvaluationBudgetError):
        entry.numeric(d=0.5, N=4, k=2)
    assert (
        entry.numeric(d=0.5, N=4, k=2, force=True)
        == entry.numeric(d=0.5, N=4, k=np.array([1, 2]), force=True)[1]
    )
    with pytest.raises(EvaluationBudgetError):
        formula("flicker_average_var").exact(d=Fraction(1, 2), N=4, k=2)
    assert formula("flicker_average_var").exact(d=Fraction(1, 2), N=1, k=1, force=True) == 1


@pytest.mark.parametrize(
    "call, error, message",
    [
        pytest.param(
            lambda: formula("rrw_average_var").evaluate(N=3, k=1, force=1),
            TypeError,
            "force=1",
            id="force-int",
        ),
        pytest.param(
            lambda: formula("flicker_average_var").numeric(d=0.5, N=3, k=1, force="yes"),
            TypeError,
            "force='yes'",
            id="numeric-force-str",
        ),
        pytest.param(
            lambda: write_figures(".", realisations=1, only=["tim2014_fig3"], force=None),
            TypeError,
            "force=None",
            id="figures-force-none",
        ),
        pytest.param(
            lambda: check_budget(closed_form_cost("x", 50), force=0), TypeError, "force=0", id="check-force-0"
        ),
    ],
)
def test_invalid_calls(call, error, message):
    with pytest.raises(error, match=message):
        call()


def test_the_estimates_grow_with_the_work():
    assert closed_form_cost("x", 100).seconds < closed_form_cost("x", 10_000).seconds
    assert (
        high_precision_flicker_cost("x", 10, 50).seconds < high_precision_flicker_cost("x", 10, 5000).seconds
    )
    assert (
        high_precision_flicker_cost("x", 10, 50).seconds < high_precision_flicker_cost("x", 1000, 50).seconds
    )
    assert exact_flicker_cost("x", 100, 2).seconds < exact_flicker_cost("x", 100, 1000).seconds
    assert float_flicker_cost("x", 10).bytes < float_flicker_cost("x", 10**6).bytes


def test_the_message_is_one_line_with_value_rule_and_estimate():
    cost = EvaluationCost("f(N=3)", "the rule", "3 steps", seconds=7200.0, bytes=5e9)
    with pytest.raises(EvaluationBudgetError) as raised:
        check_budget(cost)
    assert str(raised.value) == (
        "f(N=3): 3 steps (the rule), estimated 2 h and 5 GB of memory, over the budget of 60 s / 4.29 GB: "
        "refused; pass force=True (command line: --force) to run it anyway"
    )
    check_budget(cost, force=True)
    check_budget(cost, budget_seconds=1e4, budget_bytes=1e10)
