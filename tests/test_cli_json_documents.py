"""``--json`` of allan, fit, loop and design: strict JSON (issue 13 point 10: no bare NaN when a term is
held at zero) and a header naming the document, its layout version and the package version (issue 12)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from carousel_theory import __version__
from carousel_theory.cli import main
from carousel_theory.json_output import SCHEMA_VERSION
from carousel_theory.simulate import simulate_recording, write_recording


def _strict(text: str) -> dict:
    def refuse(constant: str) -> object:
        raise AssertionError(f"invalid JSON constant {constant}")

    return json.loads(text, parse_constant=refuse)


@pytest.fixture(scope="module")
def white_only(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """White noise alone: a fitted rate random walk is held at zero and has no standard error."""
    simulated = simulate_recording(
        20_000,
        100.0,
        rng=np.random.default_rng(10),
        white_variance=3.6e-5,
        rrw_variance=0.0,
        axes=("wx", "wy"),
    )
    return write_recording(simulated, tmp_path_factory.mktemp("json") / "white.csv")


def _header(document: dict, name: str) -> None:
    assert document["schema"] == f"carousel-theory/{name}"
    assert document["schema_version"] == SCHEMA_VERSION
    assert document["carousel_theory_version"] == __version__


def test_issue13_fit_json_with_a_term_held_at_zero_is_strict(white_only, capsys):
    assert main(["fit", str(white_only), "--json"]) == 0
    document = _strict(capsys.readouterr().out)
    _header(document, "fit")
    column = document["files"][0]["columns"]["wx"]
    assert "rrw_variance" in column["at_bound"]
    rrw = column["field_units"]["rate_random_walk_deg_per_h_per_sqrt_h"]
    assert rrw["value"] == 0.0 and rrw["standard_error"] is None
    assert "held at zero" in rrw["standard_error_null_reason"]


def test_allan_json_is_strict_and_versioned(white_only, capsys):
    assert main(["allan", str(white_only), "--json"]) == 0
    _header(_strict(capsys.readouterr().out), "allan")


def test_loop_json_is_strict_and_versioned(white_only, tmp_path, capsys):
    out = tmp_path / "loop.json"
    assert main(["loop", str(white_only), "--json", str(out)]) == 0
    _header(_strict(out.read_text(encoding="utf-8")), "loop")


def test_design_reads_the_strict_fit_json(white_only, tmp_path, capsys):
    assert main(["fit", str(white_only), "--json"]) == 0
    noise = tmp_path / "fit.json"
    noise.write_text(capsys.readouterr().out, encoding="utf-8")
    assert main(["design", "--noise", str(noise), "--latitude", "60", "--duration", "60", "--json"]) == 0
    document = _strict(capsys.readouterr().out)
    _header(document, "design")
    assert document["recommended"]
