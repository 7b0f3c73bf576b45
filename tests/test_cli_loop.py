"""``carousel-theory simulate`` and ``carousel-theory loop`` end to end: files, JSON keys, exit codes."""

from __future__ import annotations

import json

import numpy as np
import pytest

from carousel_theory.cli import main


def test_simulate_then_loop_writes_json_and_report(tmp_path, capsys):
    data = tmp_path / "recording.csv"
    assert main(["simulate", str(data), "--seed", "2", "--duration", "300", "--effect", "spikes"]) == 0
    out, report = tmp_path / "result.json", tmp_path / "report"
    assert main(["loop", str(data), "--json", str(out), "--report", str(report)]) == 0
    result = json.loads(out.read_text(encoding="utf-8"))
    for key in ("effects", "metric", "error_before", "error_after", "model_before", "model_after", "steps"):
        assert key in result
    assert result["effects"] == ["spikes"]
    assert result["error_after"] < result["error_before"]
    assert {"wx", "wy"} == set(result["model_after"])
    assert all({"detections", "decision"} <= set(step) for step in result["steps"])
    assert {p.name for p in report.iterdir()} == {"summary.md", "allan_deviation.png", "bins.png"}
    assert "spikes" in (report / "summary.md").read_text(encoding="utf-8")
    assert "effects spikes" in capsys.readouterr().out


def test_clean_npz_gives_none_and_column_mapping(tmp_path):
    data = tmp_path / "recording.npz"
    assert main(["simulate", str(data), "--seed", "3", "--duration", "200"]) == 0
    out = tmp_path / "result.json"
    assert main(["loop", str(data), "-N", "100", "--json", str(out)]) == 0
    assert json.loads(out.read_text(encoding="utf-8"))["effects"] == ["none"]
    stored = dict(np.load(data))
    renamed = tmp_path / "renamed.npz"
    np.savez(renamed, time=stored["t"], gx=stored["wx"], gy=stored["wy"])
    assert (
        main(
            [
                "loop",
                str(renamed),
                "--column",
                "time=time",
                "--column",
                "wx=gx",
                "--column",
                "wy=gy",
                "--json",
                str(out),
            ]
        )
        == 0
    )
    assert json.loads(out.read_text(encoding="utf-8"))["effects"] == ["none"]


@pytest.mark.parametrize(
    ("arguments", "message"),
    [
        pytest.param(["loop", "missing.csv"], "no such file", id="missing-file"),
        pytest.param(["loop", "{short}", "-N", "200"], "too short", id="too-short-for-N"),
        pytest.param(["loop", "{short}", "--axes", "wz"], "not in the recording", id="unknown-axis"),
        pytest.param(["loop", "{nan}"], "non-finite", id="nan-in-data"),
        pytest.param(
            ["simulate", "{out}", "--seed", "1", "--effect", "wobble"], "unknown effect", id="unknown-effect"
        ),
        pytest.param(
            ["simulate", "{out}", "--seed", "1", "--duration", "0"], "must be > 0", id="zero-duration"
        ),
    ],
)
def test_bad_input_exits_2_with_a_message(tmp_path, capsys, arguments, message):
    short = tmp_path / "short.csv"
    short.write_text("t,wx,wy\n" + "".join(f"{i / 100},0.001,0.002\n" for i in range(500)), encoding="utf-8")
    nan = tmp_path / "nan.csv"
    nan.write_text("t,wx,wy\n0,1,2\n0.01,nan,2\n0.02,1,2\n", encoding="utf-8")
    values = {"short": str(short), "nan": str(nan), "out": str(tmp_path / "x.csv")}
    arguments = [a.format(**values) for a in arguments]
    assert main(arguments) == 2
    assert message in capsys.readouterr().err
