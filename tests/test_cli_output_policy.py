"""Every command that reads a recording checks its outputs before the work (issue 13, data loss and
tracebacks): never over the input, never through a link to it, a parent that is a file or a name that is
too long refused with exit status 2, and the input byte for byte unchanged."""

from __future__ import annotations

import hashlib
from pathlib import Path

import numpy as np
import pytest

from carousel_theory.cli import main
from carousel_theory.simulate import simulate_recording, write_recording


@pytest.fixture
def recording(tmp_path: Path) -> Path:
    simulated = simulate_recording(
        3000,
        100.0,
        rng=np.random.default_rng(13),
        white_variance=3.6e-5,
        rrw_variance=1e-11,
        axes=("wx", "wy"),
    )
    return write_recording(simulated, tmp_path / "a.csv")


def _digest(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def _refused(
    arguments: list[str], recording: Path, capsys: pytest.CaptureFixture[str], fragment: str
) -> None:
    before = _digest(recording)
    assert main(arguments) == 2
    err = capsys.readouterr().err
    assert fragment in err and "Traceback" not in err
    assert _digest(recording) == before


@pytest.mark.parametrize(
    "command",
    [
        ["fit", "{input}", "--markdown", "{input}"],
        ["fit", "{input}", "--plot", "{input}"],
        ["allan", "{input}", "--plot", "{input}"],
        ["predict", "{input}", "--calibration", "1000", "--horizon", "100", "--output", "{input}"],
        ["loop", "{input}", "--json", "{input}"],
    ],
    ids=["fit-markdown", "fit-plot", "allan-plot", "predict-output", "loop-json"],
)
def test_issue13_output_over_input_is_refused(command, recording, capsys):
    _refused([part.format(input=recording) for part in command], recording, capsys, "is the input")


def test_issue13_output_through_a_link_to_the_input_is_refused(recording, tmp_path, capsys):
    link = tmp_path / "link.json"
    link.symlink_to(recording)
    _refused(["loop", str(recording), "--json", str(link)], recording, capsys, "is the input")


def test_issue13_parent_that_is_a_file_is_refused_before_work(recording, capsys):
    _refused(
        ["fit", str(recording), "--markdown", str(recording / "x.md")], recording, capsys, "not a folder"
    )


def test_issue13_device_output_is_refused(recording, capsys):
    _refused(["allan", str(recording), "--plot", "/dev/full"], recording, capsys, "special file")


def test_issue13_overlong_output_name_is_refused(recording, tmp_path, capsys):
    _refused(
        ["loop", str(recording), "--json", str(tmp_path / ("x" * 300))], recording, capsys, "at most 255"
    )


def test_outputs_land_whole_and_nothing_else_is_written(recording, tmp_path, capsys):
    out = tmp_path / "out"
    assert main(["fit", str(recording), "--markdown", str(out / "r" / "fit.md")]) == 0
    assert "# Noise model of the recordings" in (out / "r" / "fit.md").read_text(encoding="utf-8")
    assert sorted(p.name for p in (out / "r").iterdir()) == ["fit.md"]


# --- point 2 for the commands that write without reading a recording ------------------------------

WRITERS = {
    "export": lambda out: ["export", "--format", "json", "-o", str(out / "formulas.json")],
    "export-c": lambda out: ["export", "--format", "c", "-o", str(out / "formulas.c")],
    "derive": lambda out: ["derive", "--out", str(out), "--only", "rotation_schemes"],
    "check": lambda out: ["check", "--out", str(out)],
    "figures": lambda out: ["figures", "--out", str(out), "--only", "tim2014_fig2"],
    "simulate": lambda out: ["simulate", str(out / "x.csv"), "--seed", "1", "--duration", "1"],
}


@pytest.mark.parametrize("command", sorted(WRITERS))
def test_issue13_point2_output_below_a_file_is_refused(command, recording, capsys):
    _refused(WRITERS[command](recording), recording, capsys, "not a folder")


@pytest.mark.parametrize("command", sorted(WRITERS))
def test_issue13_point2_overlong_output_name_is_refused(command, recording, tmp_path, capsys):
    _refused(WRITERS[command](tmp_path / ("y" * 300)), recording, capsys, "at most 255")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.csv"]


@pytest.mark.parametrize(
    ("command", "work"),
    [
        ("check", "carousel_theory.cli.check.run_checks"),
        ("figures", "carousel_theory.cli.figures.write_figures"),
        ("simulate", "carousel_theory.cli.simulate.simulate_recording"),
        ("derive", "carousel_theory.cli.derive.progress"),
    ],
)
def test_issue13_point2_a_refused_output_is_refused_before_the_work(
    command, work, recording, monkeypatch, capsys
):
    def forbidden(*args, **kwargs):
        raise AssertionError("the work started before the output was checked")

    monkeypatch.setattr(work, forbidden)
    _refused(WRITERS[command](recording), recording, capsys, "not a folder")


@pytest.mark.parametrize("command", ["export", "export-c", "derive", "simulate"])
def test_issue13_point2_missing_parent_folders_are_created(command, tmp_path, capsys):
    out = tmp_path / "new" / "deeper"
    assert main(WRITERS[command](out)) == 0
    assert "Traceback" not in capsys.readouterr().err
    written = sorted(p.name for p in out.iterdir())
    assert written and not [name for name in written if name.startswith(".")]


def test_issue13_point2_simulate_failing_midway_leaves_the_old_file(tmp_path, monkeypatch, capsys):
    target = tmp_path / "x.csv"
    target.write_text("t,wx\n0,1\n", encoding="utf-8")

    def half_written(recording, path):
        Path(path).write_text("t,wx\n0,", encoding="utf-8")
        raise OSError(28, "No space left on device", str(path))

    monkeypatch.setattr("carousel_theory.cli.simulate.write_recording", half_written)
    assert main(["simulate", str(target), "--seed", "1", "--duration", "1"]) == 1
    assert "No space left" in capsys.readouterr().err
    assert target.read_text(encoding="utf-8") == "t,wx\n0,1\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["x.csv"]


@pytest.mark.parametrize("out", ["x.txt", "/dev/full"])
def test_issue13_point6_simulate_refuses_an_unknown_format_before_the_work(out, tmp_path, capsys):
    target = out if out.startswith("/") else str(tmp_path / out)
    assert main(["simulate", target, "--seed", "1", "--duration", "1"]) == 2
    assert "must end in .csv or .npz" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


def test_issue13_point2_export_check_writes_nothing(tmp_path, capsys):
    target = tmp_path / "formulas.json"
    assert main(["export", "--format", "json", "-o", str(target), "--check"]) == 1
    assert "missing" in capsys.readouterr().out
    assert list(tmp_path.iterdir()) == []


def test_issue13_point1_design_plot_over_its_noise_file_is_refused(recording, tmp_path, capsys):
    noise = tmp_path / "fit.json"
    assert main(["fit", str(recording), "--json"]) == 0
    noise.write_text(capsys.readouterr().out, encoding="utf-8")
    arguments = ["design", "--noise", str(noise), "--latitude", "45", "--duration", "600"]
    _refused([*arguments, "--plot", str(noise)], noise, capsys, "is the input")
    _refused([*arguments, "--plot", str(recording / "p.png")], noise, capsys, "not a folder")
    assert main([*arguments, "--scheme", "static", "--plot", str(tmp_path / "new" / "p.png")]) == 0
    assert (tmp_path / "new" / "p.png").stat().st_size > 0
