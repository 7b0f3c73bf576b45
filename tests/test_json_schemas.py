"""Every JSON document of the command line validates against its schema under docs/schemas/ (jsonschema),
on real command output; the schemas are not vacuous (a document without its units map is refused)."""

from __future__ import annotations

import copy
import json
from pathlib import Path

import numpy as np
import pytest

from carousel_theory.cli import main
from carousel_theory.simulate import simulate_recording, write_recording
from carousel_theory.units import UNIT_NAMES

jsonschema = pytest.importorskip("jsonschema")

SCHEMAS = Path(__file__).resolve().parent.parent / "docs" / "schemas"


def _strict(text: str) -> dict:
    def refuse(constant: str) -> object:
        raise AssertionError(f"invalid JSON constant {constant}")

    return json.loads(text, parse_constant=refuse)


def _check_units_maps(value: object) -> int:
    """Every ``units`` map, at any depth, names sibling members and known units; returns how many."""
    if isinstance(value, list):
        return sum(_check_units_maps(item) for item in value)
    if not isinstance(value, dict):
        return 0
    found = 0
    if isinstance(value.get("units"), dict):
        for key, unit in value["units"].items():
            assert key in value, f"units names {key!r}, which is not a sibling member"
            assert unit in UNIT_NAMES, f"{key}: unknown unit {unit!r}"
        found = 1
    return found + sum(_check_units_maps(item) for key, item in value.items() if key != "units")


def _validate(document: dict) -> None:
    name = document["schema"].removeprefix("carousel-theory/")
    schema = json.loads((SCHEMAS / f"{name}.schema.json").read_text(encoding="utf-8"))
    jsonschema.Draft202012Validator.check_schema(schema)
    jsonschema.Draft202012Validator(schema).validate(document)
    _check_units_maps(document)


@pytest.fixture(scope="module")
def recording(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """White noise alone: the rate random walk of a fit is held at zero, so the fit's JSON has nulls."""
    simulated = simulate_recording(
        20_000, 100.0, rng=np.random.default_rng(12), white_variance=3.6e-5, axes=("wx", "wy")
    )
    return write_recording(simulated, tmp_path_factory.mktemp("schemas") / "white.csv")


def _stdout(capsys, argv: list[str]) -> dict:
    assert main(argv) == 0
    return _strict(capsys.readouterr().out)


@pytest.mark.parametrize("units", ["rad/s", "deg/h"])
def test_allan_document(recording, capsys, units):
    _validate(_stdout(capsys, ["allan", str(recording), "--json", "--output-units", units]))


@pytest.mark.parametrize("model", ["white,rrw", "white,rrw,flicker,quantization"])
def test_fit_document(recording, capsys, model):
    document = _stdout(capsys, ["fit", str(recording), "--json", "--model", model, "--output-units", "deg/s"])
    _validate(document)


def test_design_document(recording, capsys, tmp_path):
    noise = tmp_path / "fit.json"
    noise.write_text(json.dumps(_stdout(capsys, ["fit", str(recording), "--json"])), encoding="utf-8")
    argv = ["design", "--noise", str(noise), "--latitude", "60", "--duration", "60", "--json"]
    _validate(_stdout(capsys, argv))


def test_loop_document(recording, capsys, tmp_path):
    out = tmp_path / "loop.json"
    assert main(["loop", str(recording), "--json", str(out)]) == 0
    _validate(_strict(out.read_text(encoding="utf-8")))


def test_loop_document_with_fitted_effects_names_their_units(tmp_path, capsys):
    simulated = simulate_recording(
        60_000, 100.0, rng=np.random.default_rng(2), white_variance=3.6e-5, effects=["sinusoid"]
    )
    data = write_recording(simulated, tmp_path / "sinusoid.csv")
    out = tmp_path / "loop.json"
    assert main(["loop", str(data), "--json", str(out)]) == 0
    document = _strict(out.read_text(encoding="utf-8"))
    _validate(document)
    (fitted,) = [entry for entry in document["fitted_effects"] if entry["effect"] == "sinusoid"]
    assert fitted["parameters"]["wx"]["units"] == {
        "frequency_hz": "Hz",
        "amplitude": "rad/s",
        "phase_rad": "rad",
    }


def test_predict_document(recording, capsys, tmp_path):
    out = tmp_path / "forecast.json"
    argv = ["predict", str(recording), "--calibration", "500", "--horizon", "600", "--output", str(out)]
    assert main([*argv, "--output-units", "deg/h"]) == 0
    _validate(_strict(out.read_text(encoding="utf-8")))


def test_predict_table1_documents(capsys, tmp_path):
    _validate(_stdout(capsys, ["predict", "--table1", "--runs", "5", "--calibration", "20", "--json"]))
    directory = tmp_path / "recordings"
    directory.mkdir()
    rates = np.random.default_rng(5).standard_normal(800) * 1e-3
    np.savez(directory / "run.npz", t=np.arange(800) / 50.0, wx=rates, wy=-rates, fs=50.0)
    argv = ["predict", "--table1", "--data", str(directory), "--calibration", "100", "--json"]
    document = _stdout(capsys, argv)
    _validate(document)
    assert document["axes"]["wx"]["KF"]["units"]["mean_rsse"] == "rad/s"


def test_formula_and_graycode_documents(capsys):
    _validate(_stdout(capsys, ["formula", "rrw_carousel_var", "--set", "N=6", "--json"]))
    _validate(_stdout(capsys, ["formula", "--list", "--json"]))
    _validate(_stdout(capsys, ["graycode", "--check-up-to", "4", "--json"]))


def test_every_schema_names_the_unit_vocabulary_of_the_package():
    files = sorted(SCHEMAS.glob("*.schema.json"))
    assert {path.name.removesuffix(".schema.json") for path in files} == {
        "allan",
        "design",
        "fit",
        "formula",
        "formula-list",
        "graycode",
        "loop",
        "predict",
        "predict-table1",
    }
    for path in files:
        schema = json.loads(path.read_text(encoding="utf-8"))
        assert schema["$defs"]["unit"]["enum"] == sorted(UNIT_NAMES), path.name


def test_schema_refuses_a_document_without_its_units(recording, capsys):
    document = _stdout(capsys, ["fit", str(recording), "--json"])
    _validate(document)
    for path in (("units",), ("model", "units"), ("allan", "units")):
        broken = copy.deepcopy(document)
        target = broken["files"][0]["columns"]["wx"]
        for key in path[:-1]:
            target = target[key]
        del target[path[-1]]
        with pytest.raises(jsonschema.ValidationError):
            _validate(broken)
    wrong = copy.deepcopy(document)
    wrong["files"][0]["columns"]["wx"]["model"]["units"]["bias"] = "furlong/fortnight"
    with pytest.raises(jsonschema.ValidationError):
        _validate(wrong)
