"""The ``allan`` and ``fit`` sub-commands: JSON contents, plots, reports, and clean refusals."""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

import numpy as np
import pytest
from conftest import Z_MONTE_CARLO

from carousel_theory.allan import allan_variance
from carousel_theory.cli import main


@pytest.fixture
def recording_csv(tmp_path) -> Path:
    rng = np.random.default_rng(31)
    n = 4000
    wx = 1e-3 * rng.standard_normal(n) + 1e-6 * np.cumsum(rng.standard_normal(n))
    wy = 2e-3 * rng.standard_normal(n)
    lines = ["t,wx,wy"] + [f"{i / 50!r},{float(wx[i])!r},{float(wy[i])!r}" for i in range(n)]
    path = tmp_path / "static.csv"
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def _digest(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


@pytest.mark.parametrize("estimator", ["overlapping", "non-overlapping"])
def test_allan_json_matches_the_api(recording_csv, capsys, estimator):
    before = _digest(recording_csv)
    assert main(["allan", str(recording_csv), "--estimator", estimator, "--json"]) == 0
    document = json.loads(capsys.readouterr().out)
    assert _digest(recording_csv) == before
    assert set(document["columns"]) == {"wx", "wy"} and document["sample_rate"] == 50.0
    data = np.loadtxt(recording_csv, delimiter=",", skiprows=1)
    for index, name in ((1, "wx"), (2, "wy")):
        expected = allan_variance(data[:, index], 50.0, estimator=estimator)
        column = document["columns"][name]
        for key in ("tau", "avar", "ci_low", "ci_high"):
            np.testing.assert_allclose(column[key], getattr(expected, key), rtol=1e-15)


def test_allan_text_and_plot(recording_csv, capsys, tmp_path):
    plot = tmp_path / "plots" / "allan.png"
    assert main(["allan", str(recording_csv), "--taus", "0.02,0.2,2", "--plot", str(plot)]) == 0
    out = capsys.readouterr().out
    assert "wx: τ (s)" in out and f"wrote {plot}" in out
    assert plot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_fit_json_markdown_and_plot(recording_csv, capsys, tmp_path):
    plot, report = tmp_path / "fit.png", tmp_path / "report.md"
    argv = [
        "fit",
        str(recording_csv),
        str(recording_csv),
        "--json",
        "--plot",
        str(plot),
        "--markdown",
        str(report),
    ]
    assert main(argv) == 0
    document = json.loads(capsys.readouterr().out)
    column = document["files"][0]["columns"]["wx"]
    assert {"model", "standard_errors", "field_units", "paper_units", "allan", "model_avar"} <= set(column)
    error = column["standard_errors"]["white_variance"]
    assert abs(column["model"]["white_variance"] - 1e-6) <= Z_MONTE_CARLO * error and error < 0.05e-6
    text = report.read_text(encoding="utf-8")
    assert "| σ_WN² (τ = 1 s) | (rad/s)² |" in text and "## Run-to-run consistency" in text
    assert plot.read_bytes()[:4] == b"\x89PNG"


def test_fit_text_with_tau_range(recording_csv, capsys):
    assert main(["fit", str(recording_csv), "--tau-min", "0.04", "--model", "white,rrw"]) == 0
    out = capsys.readouterr().out
    assert "angle random walk N" in out and "°/√h" in out and "rad/√s" in out and "(0.04 s" in out


BAD = [
    ("empty", "", ["allan"], "empty file"),
    ("nan", "t,wx\n0,1\n0.1,nan\n0.2,1\n0.3,2\n", ["allan"], "column 'wx' holds nan at row 1"),
    ("gap", "t,wx\n" + "".join(f"{t},1\n" for t in (0, 0.1, 0.2, 0.9, 1.0, 1.1)), ["allan"], "gap"),
    ("non-monotonic", "t,wx\n0,1\n0.1,2\n0.05,3\n", ["allan"], "not strictly increasing"),
    (
        "tau-over-third",
        "t,wx\n" + "".join(f"{i / 10},{i % 3}\n" for i in range(30)),
        ["allan", "--taus", "1.1"],
        "longer than a third of the recording",
    ),
    (
        "too-short-to-fit",
        "t,wx\n" + "".join(f"{i / 10},{i % 3}\n" for i in range(8)),
        ["fit"],
        "too few to fit",
    ),
    (
        "bad-confidence",
        "t,wx\n" + "".join(f"{i / 10},{i % 3}\n" for i in range(30)),
        ["allan", "--confidence", "2"],
        "--confidence=2.0",
    ),
]


@pytest.mark.parametrize(("text", "command", "message"), [b[1:] for b in BAD], ids=[b[0] for b in BAD])
def test_bad_input_exits_2_with_message(tmp_path, capsys, text, command, message):
    path = tmp_path / "bad.csv"
    path.write_text(text, encoding="utf-8")
    assert main([command[0], str(path), *command[1:]]) == 2
    assert message in capsys.readouterr().err


def test_binary_file_named_csv_and_unknown_component(tmp_path, capsys):
    path = tmp_path / "fake.csv"
    path.write_bytes(b"PK\x03\x04\x00\x01\x02")
    assert main(["allan", str(path)]) == 2
    assert "not a CSV text file" in capsys.readouterr().err
    with pytest.raises(SystemExit) as stop:
        main(["fit", str(path), "--model", "white,pink"])
    assert stop.value.code == 2
    assert "must be comma-separated names" in capsys.readouterr().err
