"""``carousel-theory predict``: a user's recording, the simulated Table I batch, and bad input."""

from __future__ import annotations

import csv
import json
import math
import sys

import numpy as np
import pytest

from carousel_theory.cli import main
from carousel_theory.fast_prediction import fast_kalman_forecast
from carousel_theory.long_memory import fractional_integral


@pytest.fixture
def recording(tmp_path):
    rng = np.random.default_rng(17)
    rates = 1e-3 + 1e-4 * fractional_integral(rng.standard_normal(600), 0.5) + 3e-4 * rng.standard_normal(600)
    path = tmp_path / "gyro.npz"
    np.savez(path, t=np.arange(600) / 10.0, wx=rates, fs=10.0)
    return path, rates


def test_forecast_csv_holds_the_kalman_prediction_and_interval(recording, tmp_path, capsys):
    path, rates = recording
    output = tmp_path / "forecast.csv"
    arguments = ["predict", str(path), "--calibration", "200", "--horizon", "150", "--start", "100"]
    arguments += ["--driving-variance", "1e-8", "--white-variance", "9e-8", "--prior", "diffuse"]
    assert main([*arguments, "--output", str(output)]) == 0
    with output.open() as handle:
        table = list(csv.DictReader(handle))
    assert len(table) == 150
    assert table[0]["index"] == "300"
    expected = fast_kalman_forecast(rates[100:300], 150, d=0.5, driving_variance=1e-8, white_variance=9e-8)
    got = np.array([float(row["kf_prediction"]) for row in table])
    np.testing.assert_allclose(got, expected.mean, rtol=1e-12)
    sigma = np.array([float(row["kf_sigma"]) for row in table])
    np.testing.assert_allclose(sigma, np.sqrt(expected.observation_variance), rtol=1e-12)
    upper = np.array([float(row["kf_upper_2sigma"]) for row in table])
    np.testing.assert_allclose(upper, expected.mean + 2 * sigma, rtol=1e-12)
    assert float(table[0]["measured"]) == rates[300]
    assert float(table[0]["cm_prediction"]) == pytest.approx(rates[100:300].mean(), rel=1e-15)
    assert "IE" in capsys.readouterr().out


def test_a_long_forecast_csv_is_written_in_chunks_without_losing_a_row(recording, tmp_path):
    path, rates = recording
    output = tmp_path / "long.csv"
    arguments = ["predict", str(path), "--calibration", "200", "--horizon", "70000"]
    assert (
        main([*arguments, "--driving-variance", "1e-8", "--white-variance", "9e-8", "--output", str(output)])
        == 0
    )
    with output.open() as handle:
        table = list(csv.DictReader(handle))
    assert len(table) == 70000
    assert [row["index"] for row in table[65535:65538]] == ["65735", "65736", "65737"]
    expected = fast_kalman_forecast(
        rates[:200] - rates[:200].mean(),
        70000,
        driving_variance=1e-8,
        white_variance=9e-8,
        bias_mean=0.0,
        bias_variance=0.0,
    )
    got = np.array([float(row["kf_prediction"]) for row in table])
    np.testing.assert_allclose(got, expected.mean + rates[:200].mean(), rtol=1e-12)
    assert table[399]["measured"] != "" and table[400]["measured"] == ""


def test_forecast_json_and_estimated_variances(recording, tmp_path):
    path, _ = recording
    output = tmp_path / "forecast.json"
    assert (
        main(["predict", str(path), "--calibration", "300", "--horizon", "400", "--output", str(output)]) == 0
    )
    payload = json.loads(output.read_text())
    assert payload["model"]["driving_variance"] > 0
    columns = payload["columns"]
    assert len(columns["kf_prediction"]) == 400
    # beyond the end of the recording the measured column is empty
    assert columns["measured"][-1] is None and columns["measured"][0] is not None


def test_fit_d_estimates_the_order_with_the_variances(recording, tmp_path, capsys):
    path, _ = recording
    output = tmp_path / "forecast.json"
    assert main(["predict", str(path), "--calibration", "300", "--fit-d", "--output", str(output)]) == 0
    assert "d, σ_w², σ_v² by REML" in capsys.readouterr().out
    assert json.loads(output.read_text())["model"]["d"] != 0.5


def test_fit_d_on_a_short_calibration_is_refused_or_flagged(recording, tmp_path, capsys):
    # 3 samples leave 2 contrasts after the bias for 3 parameters: refused with the rule. 6 samples end
    # REML at the bounds of both d and σ_v²/σ_w² (d = 0.05, ratio 10⁴ here): the estimate is printed with
    # a notice naming them, not as if the segment had identified them.
    path, _ = recording
    output = tmp_path / "forecast.json"
    arguments = ["predict", str(path), "--fit-d", "--output", str(output), "--calibration"]
    assert main([*arguments, "3"]) == 2
    assert "leave 2 contrasts after each section's bias; REML of 3 parameters" in capsys.readouterr().err
    assert main([*arguments, "6"]) == 0
    out = capsys.readouterr().out
    notice = "notice: REML ended at the search bound of σ_v²/σ_w², d: the calibration segment (6 samples)"
    assert notice in out
    model = json.loads(output.read_text())["model"]
    assert model["d"] == pytest.approx(0.05, abs=1e-4)
    assert model["at_bound"] == ["white_to_driving_variance_ratio", "d"]


def test_table1_json_has_every_method_with_population_values(capsys):
    assert main(["predict", "--table1", "--runs", "40", "--seed", "3", "--calibration", "50", "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    for method in ("KF", "MA", "CM"):
        entry = result[method]
        for key in ("mean_ie", "std_ie", "mean_rsse", "std_rsse"):
            assert math.isfinite(entry[key])
            assert math.isfinite(entry["population"][key])
        assert entry["population"]["mean_ie"] == 0.0
    assert result["settings"]["runs"] == 40 and result["settings"]["horizon"] == 50


def test_table1_is_reproducible_for_a_seed(capsys):
    arguments = ["predict", "--table1", "--runs", "20", "--seed", "9", "--calibration", "30", "--json"]
    main(arguments)
    first = capsys.readouterr().out
    main(arguments)
    assert capsys.readouterr().out == first


@pytest.mark.data
def test_prediction_on_the_measured_recording(shared_data, tmp_path):
    path = shared_data / "adis16405_static" / "adis16405_run1.npz"
    output = tmp_path / "adis.csv"
    arguments = ["predict", str(path), "--axis", "wy", "--calibration", "500", "--output", str(output)]
    assert main([*arguments, "--driving-variance", "2.7e-6", "--white-variance", "3.7e-5"]) == 0
    assert output.read_text().count("\n") == 501


INVALID = [
    ("calibration_one_sample", ["--calibration", "1"], "--calibration"),
    ("horizon_zero", ["--horizon", "0"], "--horizon"),
    ("d_one", ["--d", "1.0"], "--d"),
    ("d_negative", ["--d", "-0.1"], "--d"),
    (
        "driving_variance_negative",
        ["--driving-variance", "-1", "--white-variance", "0"],
        "--driving-variance",
    ),
    ("start_negative", ["--start", "-5"], "--start"),
    ("calibration_too_long", ["--calibration", "5000"], "--calibration"),
    ("unknown_axis", ["--axis", "wq"], "--axis"),
    ("output_suffix", ["--output", "forecast.txt"], "--output"),
]


@pytest.mark.parametrize(("extra", "named"), [(e, n) for _, e, n in INVALID], ids=[i for i, _, _ in INVALID])
def test_invalid_options_exit_2_with_a_message(recording, tmp_path, capsys, monkeypatch, extra, named):
    monkeypatch.chdir(tmp_path)
    path, _ = recording
    assert main(["predict", str(path), "--calibration", "100", *extra]) == 2
    assert named in capsys.readouterr().err


def test_nan_in_the_recording_is_refused(tmp_path, capsys):
    path = tmp_path / "bad.csv"
    path.write_text("t,wx\n0,0.1\n0.1,nan\n0.2,0.3\n")
    assert main(["predict", str(path), "--calibration", "2"]) == 2
    assert "nan" in capsys.readouterr().err.lower()


def test_inf_in_the_recording_is_refused(tmp_path, capsys):
    path = tmp_path / "bad.npz"
    np.savez(path, t=np.arange(4.0), wx=np.array([0.0, np.inf, 1.0, 2.0]))
    assert main(["predict", str(path), "--calibration", "2"]) == 2
    assert "inf" in capsys.readouterr().err.lower()


@pytest.mark.parametrize(
    "arguments",
    [
        ["predict"],
        ["predict", "--table1", "--runs", "1"],
        ["predict", "--table1", "x.npz"],
        ["predict", "--table1", "--fit-d"],
    ],
    ids=["no_data", "table1_one_run", "table1_with_data_file", "table1_fit_d"],
)
def test_invalid_invocations_exit_2(arguments, capsys):
    assert main(arguments) == 2
    assert "error" in capsys.readouterr().err


def test_table1_on_a_directory_of_recordings_writes_and_checks_markdown(tmp_path, capsys):
    rng = np.random.default_rng(23)
    directory = tmp_path / "recordings"
    directory.mkdir()
    for index in range(2):
        rates = 1e-3 * fractional_integral(rng.standard_normal(1600), 0.5) + 2e-3 * rng.standard_normal(1600)
        np.savez(directory / f"run{index}.npz", t=np.arange(1600) / 50.0, wx=rates, wy=-rates, fs=50.0)
    report = tmp_path / "table.md"
    arguments = ["predict", "--table1", "--data", str(directory), "--calibration", "100", "--average", "2"]
    assert main([*arguments, "--json", "--markdown", str(report)]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["settings"]["sample_rate_hz"] == 25.0
    assert result["axes"]["wx"]["sections"] == 8  # 2 files × 800 averaged samples / 200
    for method in ("KF", "MA", "CM"):
        assert math.isfinite(result["axes"]["wy"][method]["std_ie"])
    text = report.read_text()
    assert "| mean RSSE |" in text and "--average 2" in text
    assert main([*arguments, "--markdown", str(report), "--check"]) == 0


def _csv_values(path):
    with path.open(newline="") as handle:
        rows = list(csv.reader(handle))
    return rows[0], rows[1:]


def test_the_csv_writers_with_and_without_pyarrow_give_the_same_numbers_exactly(
    recording, tmp_path, monkeypatch
):
    pytest.importorskip("pyarrow")
    path, _ = recording
    arguments = ["predict", str(path), "--calibration", "300", "--horizon", "500"]
    arguments += ["--driving-variance", "1e-8", "--white-variance", "9e-8"]
    with_arrow = tmp_path / "arrow.csv"
    assert main([*arguments, "--output", str(with_arrow)]) == 0
    monkeypatch.setitem(sys.modules, "pyarrow", None)  # import pyarrow now raises ImportError
    as_text = tmp_path / "text.csv"
    assert main([*arguments, "--output", str(as_text)]) == 0
    # Two writers ran (pyarrow spells some numbers differently, e.g. 30 for 30.0), not the text one twice.
    assert with_arrow.read_bytes() != as_text.read_bytes()
    header, arrow_rows = _csv_values(with_arrow)
    assert (header, len(arrow_rows)) == (_csv_values(as_text)[0], 500)
    text_rows = _csv_values(as_text)[1]
    assert [row[0] for row in arrow_rows] == [str(index) for index in range(300, 800)]
    for arrow_row, text_row in zip(arrow_rows, text_rows, strict=True):
        # Both are exact round trips of the same doubles; empty where not measured.
        assert [cell == "" for cell in arrow_row] == [cell == "" for cell in text_row]
        assert [float(cell) for cell in arrow_row if cell] == [float(cell) for cell in text_row if cell]
    assert text_rows[299][-1] != "" and text_rows[300][-1] == ""  # the recording ends at sample 599
