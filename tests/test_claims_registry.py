"""The claims registry is well-formed, every claim module follows one convention, and
``carousel-theory check --check`` refuses a stale file; plus two-way checks of the numbers the
experiment claims of TIM 2014 compute."""

from __future__ import annotations

import ast
import importlib
import inspect
import pkgutil
import re
from fractions import Fraction

import mpmath
import pytest
import sympy as sp

from carousel_theory.claim import PAPERS, Claim, Status, Verdict
from carousel_theory.claims import _tim2014_static_model as static_model
from carousel_theory.claims import all_claims
from carousel_theory.claims import tim2014_renderings as renderings
from carousel_theory.cli import main

# --- the registry ---------------------------------------------------------------------------------


def test_every_claim_is_well_formed_and_ids_are_unique():
    claims = all_claims()  # refuses duplicate ids itself
    ids = [claim.id for claim in claims]
    assert len(ids) == len(set(ids))
    assert ids == sorted(ids)
    for claim in claims:
        assert isinstance(claim, Claim)
        assert claim.paper in PAPERS
        assert claim.id.startswith(claim.paper + "-")
        assert claim.location.strip() and claim.statement.strip(), claim.id
        assert callable(claim.check)


def test_claim_refuses_an_unknown_paper_and_a_mismatched_id():
    with pytest.raises(ValueError, match="paper='IEEE1999'"):
        Claim("IEEE1999-x", "IEEE1999", "§I", "a claim", lambda: Verdict(Status.VERIFIED, ""))
    with pytest.raises(ValueError, match="must start with the paper key"):
        Claim("SJ2012-x", "TIM2014", "§I", "a claim", lambda: Verdict(Status.VERIFIED, ""))


#: The claim modules, one per paper section (the renderings module holds the claims about the text of
#: TIM 2014 itself), and the id prefixes each one owns: no prefix belongs to two modules.
SECTION_MODULES = {
    "sj2012_sec1_introduction": ("SJ2012-sec1-",),
    "sj2012_sec3_noise_processes": (
        "SJ2012-eq1-",
        "SJ2012-eq2-",
        "SJ2012-eq3-",
        "SJ2012-eq4-",
        "SJ2012-sec3",
    ),
    "sj2012_sec4_predictors": ("SJ2012-eq6-", "SJ2012-eq7-", "SJ2012-eq8-", "SJ2012-sec4"),
    "sj2012_sec5_experiments": ("SJ2012-sec5", "SJ2012-table1-"),
    "tim2014_abstract_and_conclusions": ("TIM2014-abstract-", "TIM2014-secVI-"),
    "tim2014_renderings": ("TIM2014-render-",),
    "tim2014_sec1_introduction": ("TIM2014-secI-",),
    "tim2014_sec2_error_processes": (
        "TIM2014-eq1-",
        "TIM2014-eq2-",
        "TIM2014-eq3-",
        "TIM2014-secIIA-",
        "TIM2014-secIIB-",
        "TIM2014-secIIC-",
        "TIM2014-secIID-",
    ),
    "tim2014_sec3_carouseling": (
        *(f"TIM2014-eq{n}-" for n in range(4, 19)),
        "TIM2014-secIIIA-",
        "TIM2014-secIIIB-",
        "TIM2014-secIIIC-",
    ),
    "tim2014_sec3d_flicker_noise": ("TIM2014-eq19-", "TIM2014-secIIID-", "TIM2014-fig2-"),
    "tim2014_sec4_constant_allan_variance": (
        "TIM2014-alg1-",
        "TIM2014-table2-",
        "TIM2014-sec4-",
        *(f"TIM2014-eq{n}-" for n in range(20, 33)),
    ),
    "tim2014_sec5ab_simulations": ("TIM2014-secVA-", "TIM2014-secVB-"),
    "tim2014_sec5c_static_test": ("TIM2014-secVC-",),
    "tim2014_sec5d_field_test": ("TIM2014-secVD-",),
}


def _claim_modules():
    import carousel_theory.claims as package

    names = sorted(
        info.name for info in pkgutil.iter_modules(package.__path__) if not info.name.startswith("_")
    )
    return {name: importlib.import_module(f"carousel_theory.claims.{name}") for name in names}


def test_one_module_per_section_and_no_overlap():
    modules = _claim_modules()
    assert sorted(modules) == sorted(SECTION_MODULES)
    prefixes = [prefix for owned in SECTION_MODULES.values() for prefix in owned]
    assert not [p for p in prefixes for q in prefixes if p != q and p.startswith(q)], "overlapping prefixes"
    for name, module in modules.items():
        for claim in module.CLAIMS:
            assert claim.id.startswith(SECTION_MODULES[name]), f"{claim.id} does not belong in {name}"


@pytest.mark.parametrize("name", sorted(SECTION_MODULES))
def test_every_claim_module_follows_one_convention(name):
    """``__all__ = ["CLAIMS"]``; every function private (``_check_*`` and helpers); claims built with
    ``Claim(...)``; closed forms from the library, never from a derivation document."""
    module = importlib.import_module(f"carousel_theory.claims.{name}")
    source = inspect.getsource(module)
    tree = ast.parse(source)
    assert module.__all__ == ["CLAIMS"], name
    assert all(isinstance(claim, Claim) for claim in module.CLAIMS), name
    functions = [node.name for node in tree.body if isinstance(node, ast.FunctionDef)]
    assert [f for f in functions if not f.startswith("_")] == [], f"{name}: public functions"
    imported = [node.module or "" for node in ast.walk(tree) if isinstance(node, ast.ImportFrom)]
    assert not [m for m in imported if m.startswith("carousel_theory.derivations")], name
    assert not [
        m
        for m in imported
        if m.startswith("carousel_theory.claims.") and not m.split(".")[-1].startswith("_")
    ]
    assert not re.search(r"(?<!\w)_claim\(", source), f"{name}: claims are built with Claim(...)"


# --- carousel-theory check --check ---------------------------------------------------------------


@pytest.fixture
def few_claims(monkeypatch):
    """Run the command on three fast claims instead of the whole registry."""
    chosen = [c for c in renderings.CLAIMS if c.id.endswith(("table3", "wording", "algorithm1-loop"))]
    assert len(chosen) == 3
    monkeypatch.setattr("carousel_theory.cli.check.all_claims", lambda: chosen)
    return chosen


def test_check_mode_accepts_fresh_files_and_refuses_stale_ones(tmp_path, few_claims, capsys):
    assert main(["check", "--out", str(tmp_path)]) == 0
    markdown, json_file = tmp_path / "paper_check.md", tmp_path / "paper_check.json"
    assert markdown.exists() and json_file.exists()
    assert main(["check", "--check", "--out", str(tmp_path)]) == 0
    stale = markdown.read_text(encoding="utf-8").replace("verified", "proved", 1)
    markdown.write_text(stale, encoding="utf-8")
    capsys.readouterr()
    assert main(["check", "--check", "--out", str(tmp_path)]) == 1
    assert "out of date" in capsys.readouterr().out
    # --check writes nothing: the stale file is left as it was.
    assert markdown.read_text(encoding="utf-8") == stale


def test_check_mode_refuses_a_missing_file_and_a_status_regression(tmp_path, few_claims, capsys):
    assert main(["check", "--check", "--out", str(tmp_path)]) == 1  # nothing written yet
    assert main(["check", "--out", str(tmp_path)]) == 0
    json_file = tmp_path / "paper_check.json"
    json_file.write_text(
        json_file.read_text(encoding="utf-8").replace('"status": "verified"', '"status": "proved"'),
        encoding="utf-8",
    )
    capsys.readouterr()
    assert main(["check", "--check", "--out", str(tmp_path)]) == 1
    assert "proved -> verified" in capsys.readouterr().out


# --- two-way checks of the numbers behind the experiment claims -----------------------------------


def test_integrated_rrw_sum_matches_a_brute_force_sum_of_min():
    """Σ_{a,b} Cov(bin a, bin b) from the registry equals Σ_{s,t ≤ KN} min(s, t) / N² exactly."""
    total, N, K = static_model.averaged_rrw_sum_of_covariances()
    for samples in (1, 2, 3, 5):
        for bins in (1, 2, 3, 4):
            length = samples * bins
            brute = Fraction(
                sum(min(s, t) for s in range(1, length + 1) for t in range(1, length + 1)), samples**2
            )
            assert total.subs({N: samples, K: bins}) == sp.Rational(brute.numerator, brute.denominator)


def test_integrated_rrw_sum_has_the_continuous_limit():
    # Σ_{s,t ≤ M} min(s, t) = M(M + 1)(2M + 1)/6: the integrated RRW has variance σ_q² t³/3 in the limit.
    total, N, K = static_model.averaged_rrw_sum_of_covariances()
    M = K * N
    assert sp.simplify(total - M * (M + 1) * (2 * M + 1) / (6 * N**2)) == 0


def test_angle_standard_deviations_against_the_continuous_formulas():
    """σ² of the angle after t: white σ_WN² t (ARW) and RRW σ_q² t³/3, up to the O(1/M) discretisation."""
    sigma = static_model.angle_standard_deviations()
    t = static_model.DURATION
    for gyro in ("x", "y"):
        parameters = static_model.TABLE_III[gyro]
        white = mpmath.sqrt(mpmath.mpf(parameters["white"].numerator) / parameters["white"].denominator * t)
        rrw = mpmath.sqrt(mpmath.mpf(parameters["rrw"].numerator) / parameters["rrw"].denominator * t**3 / 3)
        assert abs(sigma[f"averaged {gyro}"]["white"] / white - 1) < 1e-12
        assert abs(sigma[f"averaged {gyro}"]["rrw"] / rrw - 1) < 1e-5
    # Carouselled white noise: each sample contributes (Δt)²(σx² sin² + σy² cos²), summing to the mean ARW.
    white_mean = (static_model.TABLE_III["x"]["white"] + static_model.TABLE_III["y"]["white"]) / 2
    expected = mpmath.sqrt(mpmath.mpf(white_mean.numerator) / white_mean.denominator * t)
    assert abs(sigma["carouselled"]["white"] / expected - 1) < 1e-12


def test_binomial_interval_against_scipy():
    scipy_stats = pytest.importorskip("scipy.stats")
    with mpmath.workdps(30):
        probability = mpmath.erfc(mpmath.sqrt(2))
        lowest, highest = static_model.binomial_interval(1800, probability, mpmath.mpf("0.99"))
        tail = static_model.binomial_tail_at_least(117, 1800, probability)
    reference = scipy_stats.binom(1800, float(probability))
    assert (lowest, highest) == (int(reference.ppf(0.005)), int(reference.isf(0.005)))
    assert abs(float(tail) / reference.sf(116) - 1) < 1e-9


def test_table_three_constants_match_the_rendering_transcriptions():
    parsed = [renderings._parse_scientific(cell) for cell in renderings.TABLE_III_ALTERNATIVE]
    for gyro, column in zip(("x", "y"), parsed, strict=True):
        parameters = static_model.TABLE_III[gyro]
        assert column == [parameters["white"], parameters["rrw"], parameters["bias_instability"]]
