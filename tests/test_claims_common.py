"""The identity decision shared by the claim checks: a SymPy remainder is a refutation only with a
counterexample (an exact nonzero rational, or a value above 10⁻⁴⁰ at 50 and 70 digits); when neither
simplification nor a sample point decides, the check fails instead of refuting."""

from __future__ import annotations

import pytest
import sympy as sp

from carousel_theory.claim import Claim, Status, Verdict
from carousel_theory.claims import _common as common
from carousel_theory.report import run_checks

N = sp.Symbol("N", integer=True, positive=True)
x = sp.Symbol("x", real=True)


def test_an_identity_is_zero():
    assert common.simplifies_to_zero(sp.sin(x) ** 2 + sp.cos(x) ** 2 - 1)
    assert common.simplifies_to_zero(sp.Matrix([[0, sp.cos(x) ** 2 + sp.sin(x) ** 2 - 1]]))


def test_a_polynomial_remainder_has_an_exact_counterexample():
    assert not common.simplifies_to_zero(N**2 - N)
    assert common.counterexample(N**2 - N) == "N = 2: 2 (exact)"


def test_a_transcendental_remainder_is_decided_at_fifty_digits():
    assert not common.simplifies_to_zero(sp.sin(x) - x)
    # sin(1/3) − 1/3 = −0.006138636537… (the first sample point of a real symbol)
    assert common.counterexample(sp.sin(x) - x) == "x = 1/3: -0.00613863653718 (at 50 digits)"


def test_a_zero_that_simplify_cannot_reach_is_undecided(monkeypatch):
    # A simplifier that stops short of zero: the remainder vanishes at every sample point, so it is
    # not a counterexample, and the decision is neither proof nor refutation.
    monkeypatch.setattr(common.sp, "simplify", lambda expression: expression)
    remainder = sp.sin(x) ** 2 + sp.cos(x) ** 2 - 1
    assert common.counterexample(remainder) is None
    with pytest.raises(common.UndecidedIdentityError, match="no sample point is nonzero"):
        common.simplifies_to_zero(remainder)


def test_an_undecided_check_is_reported_as_failed_not_refuted(monkeypatch):
    monkeypatch.setattr(common.sp, "simplify", lambda expression: expression)

    def check() -> Verdict:
        if common.simplifies_to_zero(sp.sin(x) ** 2 + sp.cos(x) ** 2 - 1):
            return Verdict(Status.PROVED, "identity")
        return Verdict(Status.REFUTED, "remainder")

    (checked,) = run_checks([Claim("TIM2014-test-undecided", "TIM2014", "nowhere", "an identity", check)])
    assert checked.verdict.status is Status.FAILED
    assert "UndecidedIdentityError" in checked.verdict.evidence
