"""`carousel-theory design` and the design module: noise from `fit --json`, JSON output, bad input."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from carousel_theory import design
from carousel_theory.cli import main
from carousel_theory.design import (
    DesignSettings,
    default_schemes,
    evaluate_scheme,
    noise_models_from_fit_json,
    record_length,
)
from carousel_theory.fitting import NoiseModel
from carousel_theory.formulas import formula
from carousel_theory.heading import EARTH_RATE
from carousel_theory.rotation_schemes import Carousel, Indexing, Static
from tests.conftest import public_functions


def _run(capsys, *argv):
    code = main(["design", *argv])
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def test_json_reports_each_scheme_and_the_recommendation(capsys):
    code, out, _ = _run(
        capsys,
        "--white", "1e-4", "--rrw", "1e-10", "--latitude", "61.5", "--duration", "600",
        "--scheme", "static", "--scheme", "carousel:N=200",
        "--scheme", "indexing:positions=4,dwell=10,transition=1", "--json",
    )  # fmt: skip
    assert code == 0
    result = json.loads(out)
    assert [record["scheme"] for record in result["schemes"]] == [
        "static",
        "carousel:N=200",
        "indexing:positions=4,dwell=10,transition=1",
    ]
    for record in result["schemes"]:
        assert {"scheme", "rate_variance", "heading_sigma_deg", "heading_rms_deg", "duration"} <= set(record)
    assert result["recommended"] == "carousel:N=200"


def test_indexing_rate_variance_is_the_registry_closed_form(capsys):
    """4-position indexing, 10-s dwell, 1-s transition at 100 Hz, 600 s = 13 whole cycles (520 s)."""
    white, rrw = 1e-4, 1e-10
    code, out, _ = _run(
        capsys,
        "--white", str(white), "--rrw", str(rrw), "--latitude", "45", "--duration", "600",
        "--scheme", "indexing:positions=4,dwell=10,transition=1", "--json",
    )  # fmt: skip
    assert code == 0
    record = json.loads(out)["schemes"][0]
    cycles = 600 // 44
    expected = white * formula("indexing4_white_var").numeric(N=1000, k=cycles) + rrw * formula(
        "indexing4_rrw_var"
    ).numeric(N=1000, k=cycles, g=100)
    assert record["samples"] == cycles * 4400
    assert math.isclose(record["rate_variance"], expected, rel_tol=1e-10)
    magnitude = EARTH_RATE * math.cos(math.radians(45))
    assert math.isclose(
        record["heading_sigma_deg"], math.degrees(math.sqrt(expected) / magnitude), rel_tol=1e-12
    )


def test_noise_from_fit_json_of_a_simulated_recording(tmp_path, capsys):
    data = tmp_path / "gyro.npz"
    assert main(["simulate", str(data), "--seed", "4", "--duration", "300", "--white-variance", "1e-4"]) == 0
    capsys.readouterr()
    assert main(["fit", str(data), "--json"]) == 0
    fit = tmp_path / "fit.json"
    fit.write_text(capsys.readouterr().out, encoding="utf-8")
    models, rate = noise_models_from_fit_json(fit)
    assert rate == 100.0 and len(models) == 2
    assert all(abs(model.white_variance / 1e-4 - 1) < 0.05 for model in models)
    code, out, _ = _run(capsys, "--noise", str(fit), "--latitude", "30", "--duration", "100", "--json")
    assert code == 0
    assert len(json.loads(out)["schemes"]) > 5  # the built-in sweep


def test_adapter_accepts_the_bare_layouts():
    bare = {
        "wx": {"white": 2.0, "sample_rate": 50.0},
        "wy": {"white_variance": 4.0, "rrw": 1e-3, "sample_rate": 50.0},
    }
    models, rate = noise_models_from_fit_json(bare)
    assert (
        rate == 50.0 and [m.white_variance for m in models] == [2.0, 4.0] and models[1].rrw_variance == 1e-3
    )
    files = {
        "files": [
            {"columns": {"wx": {"model": {"white_variance": v, "sample_rate": 10.0}}}} for v in (1.0, 3.0)
        ]
    }
    assert noise_models_from_fit_json(files)[0][0].white_variance == 2.0  # averaged over files


def test_monte_carlo_option_reports_the_atan2_rms_beside_the_exact_one(capsys):
    code, out, _ = _run(
        capsys,
        "--white", "1e-4", "--latitude", "61.5", "--duration", "600", "--scheme", "carousel:N=200",
        "--monte-carlo", "200000", "--seed", "3", "--json",
    )  # fmt: skip
    assert code == 0
    record = json.loads(out)["schemes"][0]
    assert (
        abs(record["monte_carlo_rms_deg"] - record["heading_rms_deg"])
        <= 4.5 * record["monte_carlo_rms_standard_error_deg"]
    )


def test_imperfections_enter_as_options(capsys):
    code, out, _ = _run(
        capsys,
        "--white", "1e-6", "--latitude", "61.5", "--duration", "600", "--scheme", "carousel:N=200",
        "--angle-bias", "0.01", "--json",
    )  # fmt: skip
    assert code == 0
    record = json.loads(out)["schemes"][0]
    assert math.isclose(record["heading_bias_deg"], -math.degrees(0.01), rel_tol=1e-3)


def test_plot_is_written(tmp_path, capsys):
    plot = tmp_path / "heading.png"
    code, _, _ = _run(
        capsys, "--white", "1e-4", "--latitude", "10", "--duration", "60", "--duration", "600",
        "--scheme", "static", "--scheme", "carousel:period=5", "--plot", str(plot),
    )  # fmt: skip
    assert code == 0 and plot.stat().st_size > 1000


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--white", "1", "--latitude", "10", "--duration", "-5"], "--duration=-5.0: must be > 0 seconds"),
        (["--white=-1", "--latitude", "10", "--duration", "5"], "--white=-1.0: must be >= 0"),
        (["--white", "nan", "--latitude", "10", "--duration", "5"], "--white=nan: must be a number, not NaN"),
        (["--white", "1", "--rrw", "inf", "--latitude", "10", "--duration", "5"], "--rrw=inf: must be"),
        (["--white", "1", "--latitude", "91", "--duration", "5"], "latitude=91.0: must lie in [-90, 90]"),
        (["--white", "1", "--latitude", "90", "--duration", "5"], "heading is undefined"),
        (
            ["--white", "1", "--latitude", "-90", "--duration", "5"],
            "latitude=-90.0: must be strictly between",
        ),
        (
            [
                "--white",
                "1",
                "--latitude",
                "10",
                "--duration",
                "5",
                "--scheme",
                "indexing:positions=2,dwell=0.001",
            ],
            "shorter than one sample",
        ),
        (
            ["--white", "1", "--latitude", "10", "--duration", "5", "--scheme", "carousel;N=5"],
            "must start with one of",
        ),
        (["--latitude", "10", "--duration", "5"], "noise model: give --noise FILE.json or at least one of"),
        (
            ["--white", "1", "--latitude", "10", "--duration", "1", "--scheme", "carousel:period=10"],
            "duration=1.0: shorter than one cycle",
        ),
        (["--white", "1", "--latitude", "10", "--duration", "5", "--angle-noise", "-1"], "angle_noise=-1.0"),
    ],
    ids=[
        "negative-duration",
        "negative-white",
        "nan-white",
        "infinite-rrw",
        "beyond-90",
        "pole",
        "south-pole",
        "short-dwell",
        "unparsable",
        "no-noise",
        "short-record",
        "negative-imperfection",
    ],
)
def test_bad_input_is_named_with_its_rule(capsys, argv, message):
    code, _, err = _run(capsys, *argv)
    assert code == 2
    assert message in err


def test_record_length_and_validation():
    assert record_length(Carousel(200), 10.5, 100.0) == 1000
    assert record_length(Carousel(150.5), 10.5, 100.0) == 1050
    assert record_length(Static(), 0.015, 100.0) == 1
    with pytest.raises(ValueError, match="duration=0: must be > 0 seconds"):
        record_length(Static(), 0, 100.0)
    with pytest.raises(ValueError, match="latitude=90"):
        DesignSettings([NoiseModel(100.0)], 100.0, 90)


def test_default_sweep_and_evaluation_without_quadrature():
    schemes = default_schemes(100.0)
    assert len(schemes) == 17 and isinstance(schemes[-1], Indexing)
    settings = DesignSettings([NoiseModel(100.0, white_variance=1e-4)], 100.0, 45.0, exact=False)
    results = evaluate_scheme(schemes[1], [100.0, 200.0], settings)
    assert results[0].heading_rms_deg is None
    assert np.isclose(results[0].rate_variance, 2 * results[1].rate_variance)


def test_all_is_honest():
    assert public_functions(design) <= set(design.__all__)
