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


@pytest.fixture(scope="module")
def filtered_npz(tmp_path_factory) -> Path:
    """1000 s at 100 Hz of white noise through a 4-sample moving average plus 1/f noise."""
    from test_fit_diagnostics import filtered_sensor

    from carousel_theory.data import recording_from_arrays
    from carousel_theory.simulate import write_recording

    path = tmp_path_factory.mktemp("filtered") / "filtered.npz"
    return write_recording(recording_from_arrays({"wx": filtered_sensor()}, sample_rate=100.0), path)


def _words(text: str) -> str:
    return " ".join(text.split())  # the notices are wrapped at 110 columns


def test_issue12_fit_says_on_stdout_when_its_model_is_rejected(filtered_npz, capsys):
    assert main(["fit", str(filtered_npz), "--model", "white,rrw", "--tau-min", "0.01"]) == 0
    out = _words(capsys.readouterr().out)
    assert "WARNING: the model is rejected by its own χ² test" in out
    assert "standard error above assumes a model that does not hold and is too small" in out
    assert "--tau-min 1" in out and "'flicker'" in out and "carousel-theory loop" in out
    assert "differs from the textbook read-off σ_A(τ)·√τ at τ = 1.28 s" in out


def test_issue12_default_model_climbs_the_ladder_until_not_rejected(filtered_npz, capsys):
    assert main(["fit", str(filtered_npz)]) == 0
    out = capsys.readouterr().out
    words = _words(out)
    assert "model white+rrw+flicker; " in out and "(1.28 s … " in out and "1/f order d profiled" in out
    assert (
        "wx: the default model is the first the recording does not reject; rejected: white+rrw over every τ"
        in words
    )
    assert "kept: white+rrw+flicker at τ ≥ 1 s" in words and "not rejected" in words
    assert "WARNING" not in out  # the default model is not rejected on this sensor-like recording


def test_issue12_default_model_says_when_the_recording_is_too_short_for_the_cut_off(tmp_path, capsys):
    from test_fit_diagnostics import filtered_sensor

    from carousel_theory.data import recording_from_arrays
    from carousel_theory.simulate import write_recording

    short = recording_from_arrays({"wx": filtered_sensor(10_000)}, sample_rate=100.0)
    path = write_recording(short, tmp_path / "short.npz")
    assert main(["fit", str(path)]) == 0
    out = _words(capsys.readouterr().out)
    assert "wx: the recording (100 s) leaves only 5 octave τ above 1 s (needs 6)" in out
    assert "(0.01 s … " in out and "WARNING: the model is rejected" in out


def test_white_noise_keeps_the_simplest_default_model_and_gives_no_notice(recording_csv, capsys):
    assert main(["fit", str(recording_csv)]) == 0
    out = capsys.readouterr().out
    assert out.count("model white+rrw; ") == 2 and "(0.02 s … " in out
    assert "WARNING" not in out and "read-off" not in out and "default model is the first" not in out


def test_issue13_fit_term_at_bound_is_reported_everywhere(filtered_npz, capsys, tmp_path):
    argv = ["fit", str(filtered_npz), "--model", "white,rrw,flicker", "--tau-min", "0.01"]
    report = tmp_path / "r.md"
    assert main([*argv, "--markdown", str(report)]) == 0
    out = capsys.readouterr().out
    (arw_line,) = [line for line in out.splitlines() if line.strip().startswith("angle random walk N")]
    assert "0 °/√h (held at zero: no standard error)" in arw_line
    (table_line,) = [line for line in out.splitlines() if line.strip().startswith("σ_WN² (τ = 1 s)")]
    assert "held at zero: no standard error" in table_line  # Table III's σ_WN² has no error either
    assert "white_variance is held at zero" in _words(out) and "nan" not in out.lower()
    text = report.read_text(encoding="utf-8")
    assert "white_variance is held at zero" in text
    assert "| angle random walk | °/√h | 0 (held at zero) |" in text
    assert main([*argv, "--json"]) == 0
    column = json.loads(capsys.readouterr().out)["files"][0]["columns"]["wx"]
    kinds = [notice["kind"] for notice in column["notices"]]
    assert "term_at_bound" in kinds and "model_rejected" in kinds
    assert column["at_bound"][0] == "white_variance"
    assert column["paper_units"]["white_variance_at_1s"]["standard_error"] is None


def test_fit_all_iterations_takes_every_one(recording_csv, capsys):
    # The method text says how many covariance evaluations each fit took; --all-iterations takes them all.
    argv = ["fit", str(recording_csv), "--model", "white,rrw,flicker", "--iterations", "5", "--json"]
    assert main([*argv, "--all-iterations"]) == 0
    every = json.loads(capsys.readouterr().out)
    assert main(argv) == 0
    settled = json.loads(capsys.readouterr().out)
    for axis in ("wx", "wy"):
        assert "5 iterations," in _method(every, axis)
        assert "(the last moved no parameter by more than 0.05" in _method(settled, axis)


def _method(document: dict, axis: str) -> str:
    (file,) = document["files"]
    return file["columns"][axis]["method"]


def test_fit_prints_the_gauss_markov_term_with_its_errors(tmp_path, capsys):
    from carousel_theory.data import recording_from_arrays
    from carousel_theory.noise_model import NoiseModel
    from carousel_theory.simulate import sample_noise, write_recording

    model = NoiseModel(sample_rate=100.0, white_variance=3.6e-5, ar_variance=4e-6, ar_coefficients=(0.8,))
    y = sample_noise(model, 200_000, rng=np.random.default_rng(8))
    path = write_recording(recording_from_arrays({"wx": y}, sample_rate=100.0), tmp_path / "gm.npz")
    assert main(["fit", str(path), "--model", "white,ar", "--json"]) == 0
    column = json.loads(capsys.readouterr().out)["files"][0]["columns"]["wx"]
    (phi,), (error,) = column["model"]["ar_coefficients"], column["ar_coefficient_errors"]
    assert abs(phi - 0.8) <= 4 * error and 0 < error < 0.01  # measured over seeds: about 0.0045
    assert main(["fit", str(path), "--model", "white,ar"]) == 0
    out = capsys.readouterr().out
    tau = -1.0 / (100.0 * np.log(phi))  # the correlation time of the printed φ: 0.045 s at φ = 0.8
    assert f"AR(1) coefficients φ                         {phi:.4g} ± {error:.2g}" in out
    assert f"Gauss–Markov correlation time τ_c            {tau:.4g} ± " in out
    report = tmp_path / "gm.md"
    assert main(["fit", str(path), "--model", "white,ar", "--markdown", str(report)]) == 0
    assert f"| AR coefficients φ | — | {phi:.3g} ± {error:.2g} |" in report.read_text(encoding="utf-8")


def test_fit_takes_given_ar_coefficients_and_refuses_them_where_they_mean_nothing(tmp_path, capsys):
    from carousel_theory.data import recording_from_arrays
    from carousel_theory.noise_model import NoiseModel
    from carousel_theory.simulate import sample_noise, write_recording

    model = NoiseModel(sample_rate=100.0, white_variance=3.6e-5, ar_variance=4e-6, ar_coefficients=(0.8,))
    y = sample_noise(model, 50_000, rng=np.random.default_rng(9))
    path = write_recording(recording_from_arrays({"wx": y}, sample_rate=100.0), tmp_path / "gm.npz")
    command = ["fit", str(path), "--model", "white,ar", "--ar-coefficients", "0.8"]
    assert main([*command, "--json"]) == 0
    column = json.loads(capsys.readouterr().out)["files"][0]["columns"]["wx"]
    assert column["model"]["ar_coefficients"] == [0.8]
    assert column["ar_coefficient_errors"] == []
    assert "AR(1) coefficients given" in column["method"]
    report = tmp_path / "gm.md"
    assert main([*command, "--markdown", str(report)]) == 0
    assert "--ar-coefficients 0.8 " in report.read_text(encoding="utf-8")
    refused = [
        (["--ar-coefficients", "0.8"], "--ar-coefficients=(0.8,): only with 'ar' in --model"),
        (["--model", "white,ar", "--ar-coefficients", "1.2"], "ar_coefficients=(1.2,): must describe a"),
        (["--model", "white,ar", "--ar-order", "0"], "--ar-order=0: must be an integer >= 1"),
        (["--model", "white,ar", "--ar-order", "2", "--ar-coefficients", "0.8"], "--ar-order=2: the coeff"),
    ]
    for options, message in refused:
        capsys.readouterr()
        assert main(["fit", str(path), *options]) == 2
        assert message in capsys.readouterr().err
    with pytest.raises(SystemExit):
        main(["fit", str(path), "--model", "white,ar", "--ar-coefficients", "0.5,x"])
    assert "comma-separated numbers" in capsys.readouterr().err


def test_fit_gives_the_fitted_order_with_its_interval_everywhere(filtered_npz, capsys, tmp_path):
    # The 1/f order d is printed with its standard error and its χ²-difference interval; the Markdown row
    # and the JSON member hold the same interval, which is FitResult.interval's.
    from carousel_theory.data import load_recording
    from carousel_theory.fitting import ORDER_RANGE, fit_recording

    argv = ["fit", str(filtered_npz), "--model", "white,rrw,flicker", "--tau-min", "1"]
    report = tmp_path / "r.md"
    assert main([*argv, "--markdown", str(report)]) == 0
    out = capsys.readouterr().out
    recording = load_recording(filtered_npz)
    fit = fit_recording(recording, ("white", "rrw", "flicker"), tau_min=1.0)["wx"]
    low, high = fit.interval("flicker_d")
    assert low < fit.model.flicker_d < high
    # an end at the edge of the range searched is marked (on this recording d is not determined)
    cell = " … ".join(f"{end:.3g}" + (" (edge)" if end in ORDER_RANGE else "") for end in (low, high))
    lines = [text for text in out.splitlines() if text.strip().startswith("1/f order d ")]
    assert lines and f"95 % interval {cell} (χ² difference)" in lines[0]
    text = report.read_text(encoding="utf-8")
    assert f"| 1/f order d, 95 % interval (χ² difference) | — | {cell} |" in text
    assert main([*argv, "--json"]) == 0
    column = json.loads(capsys.readouterr().out)["files"][0]["columns"]["wx"]
    assert column["flicker_d_interval"] == pytest.approx([low, high], rel=1e-12)
