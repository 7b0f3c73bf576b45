"""Tests of the fast structural checks (carousel_theory.graycode_properties), the ``graycode``
command and the §IV claims: brute force for small n, and checks that each structural check fails
on a corrupted input."""

from __future__ import annotations

import json
from fractions import Fraction

import pytest
from hypothesis import given
from hypothesis import strategies as st

from carousel_theory import graycode_properties
from carousel_theory.cli import main
from carousel_theory.graycode import gray_matrix, overlapping_allan_variance_exact
from carousel_theory.graycode_properties import PROPERTIES, _Workspace, check_order, check_up_to


@given(st.integers(2, 13))
def test_every_property_holds(n):
    assert check_order(n) == {prop.name: True for prop in PROPERTIES}


def test_check_up_to_reports_every_property():
    results = check_up_to(9, show_progress=False)
    assert [r.name for r in results] == [p.name for p in PROPERTIES]
    assert all(r.largest_verified == 9 and r.first_failure is None for r in results)


# --- brute force for small n: the quantities the fast checks reason about --------------------------


def brute_overlapping_expectation(n: int, m: int) -> Fraction:
    K = [[Fraction(float(v)) for v in row] for row in gray_matrix(n)]
    tau, length = 2**m, 2**n
    windows = length - 2 * tau + 1
    total = Fraction(0)
    for t in range(windows):
        for i in range(n):
            later = sum(K[t + tau + k][i] for k in range(tau)) / tau
            earlier = sum(K[t + k][i] for k in range(tau)) / tau
            total += (later - earlier) ** 2
    return total / (2 * windows)


@pytest.mark.parametrize("n", range(2, 7))
def test_overlapping_expectation_against_brute_force(n):
    for m in range(n):
        assert overlapping_allan_variance_exact(n, m) == brute_overlapping_expectation(n, m)
    if n >= 3:
        assert overlapping_allan_variance_exact(n, 1) != Fraction(1, 2)


@pytest.mark.parametrize("n", range(2, 7))
def test_stationarity_and_dyadic_structure_brute_force(n):
    K = gray_matrix(n)
    covariance = K @ K.T
    lags_constant = all(len({covariance[t, t + lag] for t in range(2**n - lag)}) == 1 for lag in range(2**n))
    assert lags_constant == (n == 2)
    # cov depends on r XOR s only
    for r in range(2**n):
        for s in range(2**n):
            assert covariance[r, s] == covariance[0, r ^ s]


def test_gray_code_sums_against_brute_force():
    n = 10
    gray_ones = [bin(r ^ (r >> 1)).count("1") for r in range(2**n)]
    binary_ones = [bin(r).count("1") for r in range(2**n)]
    G = B = 0
    for N in range(1, 2**n + 1):
        G += gray_ones[N - 1]
        B += binary_ones[N - 1]
        assert B <= G <= B + Fraction(2 * N, 5)
    assert check_order(n)["mcilroy-bounds"]


# --- each structural check can fail ------------------------------------------------------------------


def corrupted_workspace(n: int, column: int, row: int) -> _Workspace:
    work = _Workspace(n)
    columns = [c.copy() for c in work.columns]
    columns[column][row] *= -1
    work.__dict__["columns"] = columns  # replace the cached property
    return work


@pytest.mark.parametrize(
    "name",
    ["gray-matrix", "eq23-corrected", "gram", "covariance-columns", "overlapping"],
)
def test_checks_detect_a_flipped_entry_of_K(name):
    check = {prop.name: prop.check for prop in PROPERTIES}[name]
    assert check(_Workspace(5))
    assert not check(corrupted_workspace(5, column=2, row=5))


@pytest.mark.parametrize("name", ["ones-count", "eq21", "allan-of-S", "mcilroy-bounds"])
def test_checks_detect_a_changed_sequence(name):
    check = {prop.name: prop.check for prop in PROPERTIES}[name]
    work = _Workspace(5)
    assert check(work)
    changed = work.twice_sequence.copy()
    changed[7] += 2  # S[7] + 1
    work.__dict__["twice_sequence"] = changed
    assert not check(work)


def test_diagonal_check_detects_a_wrong_magnitude():
    work = _Workspace(4)
    columns = [c.copy() for c in work.columns]
    columns[1][3] = 3
    work.__dict__["columns"] = columns
    assert not {prop.name: prop.check for prop in PROPERTIES}["diagonal"](work)


def test_check_up_to_reports_a_failure(monkeypatch):
    def fails_from_five(work):
        return work.n < 5

    broken = tuple(
        type(prop)(prop.name, prop.statement, fails_from_five) if prop.name == "eq21" else prop
        for prop in PROPERTIES
    )
    monkeypatch.setattr(graycode_properties, "PROPERTIES", broken)
    results = {r.name: r for r in check_up_to(7, show_progress=False)}
    assert results["eq21"].largest_verified == 4 and results["eq21"].first_failure == 5
    assert results["gram"].largest_verified == 7


# --- command line ------------------------------------------------------------------------------------


def test_command_json(capsys):
    assert main(["graycode", "--check-up-to", "8", "--json"]) == 0
    payload = json.loads(capsys.readouterr().out)
    assert payload["up_to"] == 8 and payload["all_held"]
    assert {p["name"] for p in payload["properties"]} == {prop.name for prop in PROPERTIES}
    assert all(p["largest_n_verified"] == 8 for p in payload["properties"])


def test_command_table(capsys):
    assert main(["graycode", "--check-up-to", "5"]) == 0
    out = capsys.readouterr().out
    assert "all held for n = 2 … 5" in out and "covariance-columns" in out


@pytest.mark.parametrize(
    ("value", "message"), [("1", "up_to=1"), ("70", "memory")], ids=["too-small", "too-big"]
)
def test_command_rejects_bad_orders(value, message, capsys):
    assert main(["graycode", "--check-up-to", value]) == 2
    assert message in capsys.readouterr().err


INVALID_CALLS = [
    ("check-order-one", lambda: check_order(1), ValueError, "n=1"),
    ("check-order-float", lambda: check_order(4.0), TypeError, "n=4.0"),
    ("check-up-to-one", lambda: check_up_to(1), ValueError, "up_to=1"),
    ("check-up-to-string", lambda: check_up_to("9"), TypeError, "up_to='9'"),
    ("overlapping-m-too-big", lambda: overlapping_allan_variance_exact(3, 3), ValueError, "m=3"),
]


@pytest.mark.parametrize(
    ("call", "error", "message"), [pytest.param(c, e, m, id=name) for name, c, e, m in INVALID_CALLS]
)
def test_invalid_calls(call, error, message):
    with pytest.raises(error, match=message):
        call()


# --- claims --------------------------------------------------------------------------------------------


def test_derivation_document_is_deterministic_and_committed():
    from pathlib import Path

    from carousel_theory.derivations.tim2014_constant_allan_variance import DOCUMENT

    text = DOCUMENT.render()
    assert text == DOCUMENT.render()
    committed = Path(__file__).resolve().parents[1] / "derivations" / f"{DOCUMENT.name}.md"
    assert committed.read_text(encoding="utf-8") == text
