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
