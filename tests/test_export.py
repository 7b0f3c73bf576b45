"""The exported formulas are the registry's: evaluated Python, compiled C and parsed JSON agree with it."""

from __future__ import annotations

import ctypes
import itertools
import json
import shutil
import subprocess

import pytest
import sympy as sp

from carousel_theory.cli import main
from carousel_theory.export import FORMATS, export_formulas, symbol_assumptions
from carousel_theory.formulas import FORMULAS

CLOSED = {name: entry for name, entry in FORMULAS.items() if entry.expression is not None}
OMITTED = sorted(name for name, entry in FORMULAS.items() if entry.expression is None)
RELATIVE = 1e-12

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


@pytest.mark.parametrize(
    "call, error",
    [
        pytest.param(lambda: export_formulas("xml"), ValueError, id="unknown-format"),
        pytest.param(lambda: export_formulas("JSON"), ValueError, id="format-is-case-sensitive"),
        pytest.param(lambda: export_formulas(None), TypeError, id="format-none"),
        pytest.param(lambda: export_formulas(1), TypeError, id="format-int"),
        pytest.param(lambda: symbol_assumptions("N"), AttributeError, id="assumptions-of-a-string"),
    ],
)
def test_invalid_calls(call, error):
    with pytest.raises(error):
        call()


def test_unknown_format_message_names_the_value_and_the_rule():
    with pytest.raises(ValueError, match=r"format='xml': must be one of \['c', 'json', 'latex', 'python'\]"):
        export_formulas("xml")


# --- Python --------------------------------------------------------------------------------------


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
        assert_close(function(**values), expected, (name, values))
        assert_close(float(entry.evaluate(digits=30, **values)), function(**values), (name, values))


def test_exported_python_documents_the_omissions(python_namespace):
    assert sorted(python_namespace["OMITTED"]) == OMITTED
    for name in OMITTED:
        assert name not in python_namespace
        assert "no closed form" in python_namespace["OMITTED"][name]


# --- C -------------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def c_library(tmp_path_factory):
    compiler = shutil.which("cc") or shutil.which("gcc")
    if compiler is None:
        pytest.skip("no C compiler (cc or gcc) on PATH")
    directory = tmp_path_factory.mktemp("exported_c")
    source, library = directory / "formulas.c", directory / "libformulas.so"
    source.write_text(export_formulas("c"), encoding="utf-8")
    subprocess.run(
        [compiler, "-shared", "-fPIC", "-O2", "-Wall", "-Werror", "-o", str(library), str(source), "-lm"],
        check=True,
        capture_output=True,
    )
    return ctypes.CDLL(str(library))


@pytest.mark.parametrize("name", sorted(CLOSED))
def test_exported_c_matches_the_registry(c_library, name):
    entry = FORMULAS[name]
    function = getattr(c_library, name)
    function.restype = ctypes.c_double
    function.argtypes = [ctypes.c_double] * len(entry.parameters)
    for values in points(name):
        got = function(*(float(values[p]) for p in entry.parameters))
        assert_close(got, entry.numeric(**values), (name, values))


def test_exported_c_omits_the_formulas_without_closed_form(c_library):
    text = export_formulas("c")
    for name in OMITTED:
        assert f"double {name}(" not in text
        assert f" * {name}: no closed form" in text
        assert not hasattr(c_library, name)


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
    text = export_formulas("latex")
    assert text.count(r"\begin{equation*}") == len(FORMULAS)
    for entry in CLOSED.values():
        assert sp.latex(entry.expression) in text
    for name in OMITTED:
        assert f"% omitted: no closed form: {FORMULAS[name].description}" in text


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


def test_command_refuses_check_without_a_file_and_a_directory_target(tmp_path, capsys):
    assert main(["export", "--format", "c", "--check"]) == 2
    assert "--check needs -o FILE" in capsys.readouterr().err
    assert main(["export", "--format", "c", "-o", str(tmp_path)]) == 2
    assert "is a directory" in capsys.readouterr().err
