"""``--output-units`` on allan, fit, loop and predict: every printed figure names its unit, and the
converted numbers are the rad/s numbers times a factor worked out here by hand."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

from carousel_theory.cli import main
from carousel_theory.simulate import simulate_recording, write_recording

#: rad/s → °/h, written out: (180/π)·3600.
DEG_PER_HOUR = 180.0 / math.pi * 3600.0


@pytest.fixture(scope="module")
def recording(tmp_path_factory: pytest.TempPathFactory) -> Path:
    simulated = simulate_recording(
        8_000, 50.0, rng=np.random.default_rng(33), white_variance=1e-6, rrw_variance=1e-12, bias=1e-3
    )
    return write_recording(simulated, tmp_path_factory.mktemp("units") / "run.csv")


def _json(capsys, argv: list[str]) -> dict:
    assert main(argv) == 0
    return json.loads(capsys.readouterr().out)


def test_allan_json_arrays_follow_the_output_unit(recording, capsys):
    si = _json(capsys, ["allan", str(recording), "--json"])["columns"]["wx"]
    per_hour = _json(capsys, ["allan", str(recording), "--json", "--output-units", "deg/h"])["columns"]["wx"]
    np.testing.assert_allclose(per_hour["avar"], np.array(si["avar"]) * DEG_PER_HOUR**2, rtol=1e-14)
    np.testing.assert_allclose(per_hour["ci_high"], np.array(si["ci_high"]) * DEG_PER_HOUR**2, rtol=1e-14)
    assert per_hour["tau"] == si["tau"]
    assert (si["units"]["avar"], per_hour["units"]["avar"]) == ("(rad/s)^2", "(deg/h)^2")


def test_allan_table_names_its_units(recording, capsys):
    assert main(["allan", str(recording), "--output-units", "deg/s"]) == 0
    out = capsys.readouterr().out
    assert "Allan deviation (°/s), 95 % interval (°/s)" in out


def test_fit_keeps_the_model_in_si_and_converts_the_allan_variance(recording, capsys):
    si = _json(capsys, ["fit", str(recording), "--json"])["files"][0]["columns"]["wx"]
    argv = ["fit", str(recording), "--json", "--output-units", "deg/h"]
    per_hour = _json(capsys, argv)["files"][0]["columns"]["wx"]
    assert per_hour["model"] == si["model"]
    np.testing.assert_allclose(
        per_hour["model_avar"], np.array(si["model_avar"]) * DEG_PER_HOUR**2, rtol=1e-14
    )
    arw = si["ieee952"]
    # 1 rad/√s = (180/π)·60 °/√h.
    assert arw["conventional"]["angle_random_walk"]["value"] == pytest.approx(
        arw["si"]["angle_random_walk"]["value"] * 180 / math.pi * 60, rel=1e-14
    )


def test_fit_prints_every_figure_with_its_unit(recording, capsys):
    bias_si = _json(capsys, ["fit", str(recording), "--json"])["files"][0]["columns"]["wx"]["model"]["bias"]
    assert main(["fit", str(recording), "--output-units", "deg/h"]) == 0
    out = capsys.readouterr().out
    for text in ("°/√h", "rad/√s", "°/h/√h", "rad/s/√s", "(rad/s)²/s"):
        assert text in out
    bias = re.search(r"bias \(record mean\)\s+(\S+) ± \S+ °/h", out)
    assert bias is not None
    assert float(bias.group(1)) == pytest.approx(bias_si * DEG_PER_HOUR, rel=5e-4)  # printed to 4 digits


def test_predict_prints_ie_and_rsse_with_units(recording, capsys):
    argv = ["predict", str(recording), "--calibration", "1000", "--horizon", "500"]
    assert main(argv) == 0
    si = capsys.readouterr().out
    assert main([*argv, "--output-units", "deg/h"]) == 0
    per_hour = capsys.readouterr().out
    pattern = r"KF: IE (\S+) (\S+)·sample \((\S+) (\S+) of angle\), RSSE (\S+) (\S+)"
    ie, rate, angle, angle_unit, rsse, rsse_unit = re.search(pattern, si).groups()
    assert (rate, angle_unit, rsse_unit) == ("rad/s", "rad", "rad/s")
    assert float(angle) == pytest.approx(float(ie) / 50.0, rel=1e-5)  # IE · Δt, Δt = 1/50 s
    converted = re.search(pattern, per_hour).groups()
    assert (converted[1], converted[3], converted[5]) == ("°/h", "°", "°/h")
    assert float(converted[0]) == pytest.approx(float(ie) * DEG_PER_HOUR, rel=1e-5)
    assert float(converted[2]) == pytest.approx(float(angle) * 180 / math.pi, rel=1e-5)
    assert float(converted[4]) == pytest.approx(float(rsse) * DEG_PER_HOUR, rel=1e-5)


def test_predict_forecast_file_follows_the_output_unit(recording, tmp_path, capsys):
    files = {unit: tmp_path / f"{unit.replace('/', '_')}.json" for unit in ("rad/s", "deg/h")}
    for unit, path in files.items():
        argv = ["predict", str(recording), "--calibration", "1000", "--horizon", "300", "--output", str(path)]
        assert main([*argv, "--output-units", unit]) == 0
    si, per_hour = (json.loads(path.read_text())["columns"] for path in files.values())
    np.testing.assert_allclose(
        per_hour["kf_prediction"], np.array(si["kf_prediction"]) * DEG_PER_HOUR, rtol=1e-14
    )
    assert per_hour["time_s"] == si["time_s"] and per_hour["units"]["measured"] == "deg/h"


def test_loop_prints_the_model_with_units(recording, capsys):
    assert main(["loop", str(recording), "--output-units", "deg/h"]) == 0
    out = capsys.readouterr().out
    assert re.search(r"wx: bias \S+ °/h; ARW \S+ °/√h \(\S+ rad/√s\); RRW \S+ °/h/√h \(\S+ rad/s/√s\)", out)


def test_unknown_output_unit_is_refused(capsys):
    with pytest.raises(SystemExit):
        main(["allan", "x.csv", "--output-units", "rpm"])
    assert "invalid choice: 'rpm'" in capsys.readouterr().err


def test_table1_refuses_output_units(capsys):
    assert main(["predict", "--table1", "--runs", "3", "--output-units", "deg/h"]) == 2
    assert "--output-units='deg/h': applies to a DATA forecast" in capsys.readouterr().err
