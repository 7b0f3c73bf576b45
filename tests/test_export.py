"""The exported formulas are the registry's: evaluated Python, compiled C, parsed JSON and compiled LaTeX
agree with it, and every export follows the registry's one N rule."""

from __future__ import annotations

import ctypes
import itertools
import json
import math
import shutil
import subprocess

import numpy as np
import pytest
import sympy as sp

from carousel_theory.cli import main
from carousel_theory.export import DEFAULT_HEADER_NAME, FORMATS, export_formulas, symbol_assumptions
from carousel_theory.formulas import FORMULAS

CLOSED = {name: entry for name, entry in FORMULAS.items() if entry.expression is not None}
OMITTED = sorted(name for name, entry in FORMULAS.items() if entry.expression is None)
RELATIVE = 1e-12

#: C compiler flags of a strict C99 build (TIM 2014 formulas pasted into embedded code).
STRICT_C99 = ["-std=c99", "-Wall", "-Wextra", "-pedantic", "-Werror"]

#: Values per parameter: every branch of the piecewise forms (N = 1, 2, ≥ 3; a = b and a ≠ b).
VALUES = {
    "N": (1, 2, 3, 7, 200),
    "a": (1, 3),
    "b": (1, 2, 3),
    "k": (1, 2, 5),
    "rho": (-0.5, 0.0, 0.75),
    "var_x": (0.0, 0.5, 2.0),
    "var_y": (1.5, 3.0),
    "g": (0, 1, 4),
    "n": (1, 7, 1000),
    "beta": (-0.01, 0.2),
    "sigma_e": (0.0, 0.1),
    "sigma_nu": (0.0, 1e-3),
    "k_x": (-1e-3, 0.0),
    "k_y": (0.0, 2e-3),
    "psi": (0.0, 0.7),
    "epsilon": (0.0, 1e-3),
    "wobble": (0.0, 0.01),
    "omega_r": (0.5, 3.0),
}


def points(name):
    entry = FORMULAS[name]
    for combination in itertools.product(*(VALUES[p] for p in entry.parameters)):
        values = dict(zip(entry.parameters, combination, strict=True))
        if values.get("N", entry.minimum_samples) >= entry.minimum_samples:
            yield values


def assert_close(got, expected, where):
    assert abs(got - expected) <= RELATIVE * max(abs(expected), 1e-300) or got == expected, where


def test_every_format_is_deterministic_and_marked_generated():
    for format in FORMATS:
        text = export_formulas(format)
        assert text == export_formulas(format)
        # The first line (JSON: its first key, "comment", on the second line).
        assert "do not edit" in "\n".join(text.splitlines()[:2])
        for name in FORMULAS:
            written = name.replace("_", r"\_") if format == "latex" else name
            assert written in text, (format, name)
    assert export_formulas("latex", fragment=True) == export_formulas("latex", fragment=True)


@pytest.mark.parametrize(
    "call, error",
    [
        pytest.param(lambda: export_formulas("xml"), ValueError, id="unknown-format"),
        pytest.param(lambda: export_formulas("JSON"), ValueError, id="format-is-case-sensitive"),
        pytest.param(lambda: export_formulas(None), TypeError, id="format-none"),
        pytest.param(lambda: export_formulas(1), TypeError, id="format-int"),
        pytest.param(lambda: export_formulas("c", fragment=True), ValueError, id="fragment-of-c"),
        pytest.param(lambda: export_formulas("latex", fragment=1), TypeError, id="fragment-int"),
        pytest.param(lambda: export_formulas("c", header_name=""), ValueError, id="header-name-empty"),
        pytest.param(lambda: export_formulas("c", header_name='a"b.h'), ValueError, id="header-name-quote"),
        pytest.param(lambda: symbol_assumptions("N"), AttributeError, id="assumptions-of-a-string"),
    ],
)
def test_invalid_calls(call, error):
    with pytest.raises(error):
        call()


def test_unknown_format_message_names_the_value_and_the_rule():
    with pytest.raises(ValueError, match=r"format='xml': must be one of \['c', 'c-header', 'json', 'latex',"):
        export_formulas("xml")


# --- Python ---------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def python_namespace():
    namespace: dict = {}
    exec(compile(export_formulas("python"), "<exported formulas>", "exec"), namespace)
    return namespace


@pytest.mark.parametrize("name", sorted(CLOSED))
def test_exported_python_matches_the_registry(python_namespace, name):
    function = python_namespace[name]
    entry = FORMULAS[name]
    for values in points(name):
        expected = entry.numeric(**values)
        got = function(**values)
        assert isinstance(got, float), (name, values)
        assert_close(got, expected, (name, values))
        assert_close(float(entry.evaluate(digits=30, **values)), got, (name, values))


@pytest.mark.parametrize("name", sorted(CLOSED))
def test_exported_python_is_vectorised_like_the_registry(python_namespace, name):
    """All points at once as arrays (and one parameter as a column) give the scalar values."""
    function = python_namespace[name]
    entry = FORMULAS[name]
    table = list(points(name))
    arrays = {p: np.array([values[p] for values in table]) for p in entry.parameters}
    got = function(**arrays)
    assert got.shape == (len(table),)
    for index, values in enumerate(table):
        assert_close(got[index], function(**values), (name, values))
    first = entry.parameters[0]
    column = {**table[0], first: arrays[first][:, np.newaxis]}
    grid = function(**column)
    assert grid.shape == (len(table), 1)
    np.testing.assert_allclose(grid, entry.numeric(**column), rtol=RELATIVE, atol=0)


def test_exported_python_documents_the_omissions(python_namespace):
    assert sorted(python_namespace["OMITTED"]) == OMITTED
    for name in OMITTED:
        assert name not in python_namespace
        assert "no closed form" in python_namespace["OMITTED"][name]


@pytest.mark.parametrize(
    "name, values, bad",
    [
        pytest.param("rrw_average_var", {"N": 2.5, "k": 1}, "N=2.5", id="non-integral-N"),
        pytest.param("rrw_average_var", {"N": 3, "k": 0}, "k=0", id="k-zero"),
        pytest.param("rrw_carousel_cov", {"N": 3, "a": np.array([1, -2]), "b": 1}, "a=-2", id="a-array"),
        pytest.param("white_average_var", {"N": float("nan")}, "N=nan", id="N-nan"),
    ],
)
def test_exported_python_refuses_what_the_registry_refuses(python_namespace, name, values, bad):
    with pytest.raises(ValueError, match=f"^{bad}: must be an integer >= 1$"):
        python_namespace[name](**values)


# --- C -------------------------------------------------------------------------------------------


def _compiler():
    compiler = shutil.which("cc") or shutil.which("gcc")
    if compiler is None:
        pytest.skip("no C compiler (cc or gcc) on PATH")
    return compiler


@pytest.fixture(scope="module")
def c_library(tmp_path_factory):
    compiler = _compiler()
    directory = tmp_path_factory.mktemp("exported_c")
    source, library = directory / "formulas.c", directory / "libformulas.so"
    source.write_text(export_formulas("c", header_name="formulas.h"), encoding="utf-8")
    (directory / "formulas.h").write_text(export_formulas("c-header"), encoding="utf-8")
    subprocess.run(
        [compiler, *STRICT_C99, "-shared", "-fPIC", "-O2", "-o", str(library), str(source), "-lm"],
        check=True,
        capture_output=True,
    )
    return ctypes.CDLL(str(library))


def _c_function(c_library, name):
    function = getattr(c_library, name)
    function.restype = ctypes.c_double
    function.argtypes = [ctypes.c_double] * len(FORMULAS[name].parameters)
    return function


@pytest.mark.parametrize("name", sorted(CLOSED))
def test_exported_c_matches_the_registry(c_library, name):
    entry = FORMULAS[name]
    function = _c_function(c_library, name)
    for values in points(name):
        got = function(*(float(values[p]) for p in entry.parameters))
        assert_close(got, entry.numeric(**values), (name, values))


def test_exported_c_is_strict_c99_without_m_pi_and_its_header_stands_alone(tmp_path):
    compiler = _compiler()
    source, header = export_formulas("c"), export_formulas("c-header")
    assert "M_PI" not in source + header
    assert source.isascii() and header.isascii()
    (tmp_path / DEFAULT_HEADER_NAME).write_text(header, encoding="utf-8")
    (tmp_path / "formulas.c").write_text(source, encoding="utf-8")
    user = tmp_path / "user.c"  # a user's file that includes the header twice and calls a formula
    user.write_text(
        f'#include "{DEFAULT_HEADER_NAME}"\n#include "{DEFAULT_HEADER_NAME}"\n'
        "int main(void) { return rrw_average_var(2.0, 2.0) == 3.25 ? 0 : 1; }\n",
        encoding="utf-8",
    )
    program = tmp_path / "user"
    subprocess.run(
        [compiler, *STRICT_C99, "-o", str(program), str(user), str(tmp_path / "formulas.c"), "-lm"],
        check=True,
        capture_output=True,
        cwd=tmp_path,
    )
    assert subprocess.run([str(program)], check=False).returncode == 0


def test_exported_c_omits_the_formulas_without_closed_form(c_library):
    text = export_formulas("c") + export_formulas("c-header")
    for name in OMITTED:
        assert f"double {name}(" not in text
        assert f" * {name}: no closed form" in text
        assert not hasattr(c_library, name)


def test_exported_c_returns_nan_outside_the_integer_rules(c_library):
    assert math.isnan(_c_function(c_library, "rrw_average_var")(2.5, 1.0))
    assert math.isnan(_c_function(c_library, "rrw_average_var")(3.0, 0.0))
    assert math.isnan(_c_function(c_library, "rrw_carousel_cov")(3.0, 1.0, float("nan")))


# --- one N rule, everywhere ----------------------------------------------------------------------


def _at_one_sample(name):
    entry = FORMULAS[name]
    return {p: (1 if p == "N" else VALUES[p][-1]) for p in entry.parameters}


@pytest.mark.parametrize("name", sorted(name for name, e in CLOSED.items() if "N" in e.parameters))
def test_one_N_rule_in_the_expression_the_evaluators_and_every_export(python_namespace, c_library, name):
    """At N = 1 either everything gives the same value or everything refuses it (C: NaN)."""
    entry = FORMULAS[name]
    values = _at_one_sample(name)
    exact_values = {p: (sp.Rational(v) if isinstance(v, float) else v) for p, v in values.items()}
    symbolic = entry.expression.subs({s: exact_values[s.name] for s in entry.expression.free_symbols})
    c_value = _c_function(c_library, name)(*(float(values[p]) for p in entry.parameters))
    document = {r["name"]: r for r in json.loads(export_formulas("json"))["formulas"]}[name]
    if entry.minimum_samples > 1:
        assert symbolic.is_finite is not True, symbolic  # no value below the minimum
        message = f"N=1: must be an integer >= {entry.minimum_samples} for {name}"
        for call in (entry.exact, entry.numeric, entry.evaluate, python_namespace[name]):
            with pytest.raises(ValueError, match=message):
                call(**(exact_values if call == entry.exact else values))
        assert math.isnan(c_value)
        assert document["sample_rule"].startswith(f"N must be an integer >= {entry.minimum_samples}")
        assert rf"N \geq {entry.minimum_samples}" in export_formulas("latex", fragment=True)
        return
    expected = entry.exact(**exact_values)
    assert sp.simplify(symbolic - expected) == 0
    assert entry.numeric(**values) == python_namespace[name](**values) == c_value == float(expected)
    assert document["sample_rule"] == "N must be an integer >= 1"


def test_carouselled_rrw_variance_at_N_1_is_undefined_but_its_cosine_form_is_one():
    """rrw_carousel_var at N = 1 would be Var(r_k) = k, different in every bin; cᵀRRᵀc with c = (1) is 1."""
    assert FORMULAS["rrw_carousel_var"].minimum_samples == 2
    assert FORMULAS["rrw_carousel_cov"].exact(N=1, a=3, b=3) == 3  # bin 3 alone: Var(r_3) = 3
    assert FORMULAS["rrw_carousel_var_cos"].exact(N=1) == 1
    assert FORMULAS["rrw_carousel_var_sin"].exact(N=1) == 0


# --- JSON ----------------------------------------------------------------------------------------


def test_json_round_trips_to_the_registry_expressions():
    document = json.loads(export_formulas("json"))
    symbols = {name: sp.Symbol(name, **facts) for name, facts in document["symbols"].items()}
    records = {record["name"]: record for record in document["formulas"]}
    assert list(records) == sorted(FORMULAS)
    for name, entry in FORMULAS.items():
        record = records[name]
        assert record["parameters"] == list(entry.parameters)
        if entry.expression is None:
            assert record["expression"] is None and "no closed form" in record["reason"]
            continue
        parsed = sp.sympify(record["expression"], locals=symbols)
        assert parsed == entry.expression or sp.simplify(parsed - entry.expression) == 0, name
        assert parsed.free_symbols == entry.expression.free_symbols, name


def test_symbol_assumptions_rebuild_the_registry_symbols():
    for entry in CLOSED.values():
        for symbol in entry.expression.free_symbols:
            assert sp.Symbol(symbol.name, **symbol_assumptions(symbol)) == symbol


# --- LaTeX ---------------------------------------------------------------------------------------


def test_latex_holds_every_expression_and_marks_the_omissions():
    for text in (export_formulas("latex"), export_formulas("latex", fragment=True)):
        assert text.isascii()
        assert text.count(r"\begin{equation") == len(FORMULAS)
        for entry in CLOSED.values():
            assert sp.latex(entry.expression) in text
        for name in OMITTED:
            assert f"% omitted: no closed form: {FORMULAS[name].description}" in text


def test_latex_fragment_is_only_equations_with_labels():
    text = export_formulas("latex", fragment=True)
    for command in (r"\documentclass", r"\begin{document}", r"\usepackage", r"\section"):
        assert command not in text
    for name in FORMULAS:
        assert rf"\label{{eq:carousel-theory:{name}}}" in text


def _pdflatex(directory, name):
    return subprocess.run(
        ["pdflatex", "-interaction=nonstopmode", "-halt-on-error", name],
        cwd=directory,
        capture_output=True,
        text=True,
        check=False,
    )


@pytest.mark.skipif(shutil.which("pdflatex") is None, reason="pdflatex is not installed (texlive-latex-base)")
def test_latex_document_and_fragment_compile_with_pdflatex(tmp_path):
    (tmp_path / "document.tex").write_text(export_formulas("latex"), encoding="ascii")
    (tmp_path / "fragment.tex").write_text(export_formulas("latex", fragment=True), encoding="ascii")
    (tmp_path / "host.tex").write_text(
        "\\documentclass{article}\n\\usepackage{amsmath}\n\\begin{document}\n"
        "See (\\ref{eq:carousel-theory:rrw_carousel_var}).\n\\input{fragment.tex}\n\\end{document}\n",
        encoding="ascii",
    )
    for name in ("document.tex", "host.tex"):
        result = _pdflatex(tmp_path, name)
        assert result.returncode == 0, result.stdout[-2000:]
        assert (tmp_path / name.replace(".tex", ".pdf")).stat().st_size > 0


# --- the command ---------------------------------------------------------------------------------


def test_command_writes_the_file_and_check_detects_a_stale_one(tmp_path, capsys):
    target = tmp_path / "formulas.json"
    assert main(["export", "--format", "json", "-o", str(target)]) == 0
    assert target.read_text(encoding="utf-8") == export_formulas("json")
    assert main(["export", "--format", "json", "-o", str(target), "--check"]) == 0
    target.write_text(target.read_text(encoding="utf-8").replace("1/N", "2/N", 1), encoding="utf-8")
    assert main(["export", "--format", "json", "-o", str(target), "--check"]) == 1
    capsys.readouterr()
    assert main(["export", "--format", "python"]) == 0
    assert capsys.readouterr().out == export_formulas("python")
    assert main(["export", "--format", "latex", "--fragment"]) == 0
    assert capsys.readouterr().out == export_formulas("latex", fragment=True)


def test_command_writes_the_c_source_with_its_header(tmp_path, capsys):
    source = tmp_path / "gyro.c"
    assert main(["export", "--format", "c", "-o", str(source)]) == 0
    assert source.read_text(encoding="utf-8") == export_formulas("c", header_name="gyro.h")
    assert (tmp_path / "gyro.h").read_text(encoding="utf-8") == export_formulas("c-header")
    assert '#include "gyro.h"' in source.read_text(encoding="utf-8")
    assert main(["export", "--format", "c", "-o", str(source), "--check"]) == 0
    (tmp_path / "gyro.h").write_text("stale", encoding="utf-8")
    assert main(["export", "--format", "c", "-o", str(source), "--check"]) == 1
    assert "gyro.h out of date" in capsys.readouterr().out


def test_command_refuses_check_without_a_file_and_a_directory_target(tmp_path, capsys):
    assert main(["export", "--format", "c", "--check"]) == 2
    assert "--check needs -o FILE" in capsys.readouterr().err
    assert main(["export", "--format", "c", "-o", str(tmp_path)]) == 2
    assert "is a folder; name a file inside it" in capsys.readouterr().err
    assert main(["export", "--format", "python", "--fragment"]) == 2
    assert "--fragment: only with --format latex" in capsys.readouterr().err
