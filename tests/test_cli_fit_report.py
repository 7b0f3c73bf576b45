"""``fit --markdown`` over runs that hold different axes (issue 13 point 3: a KeyError in one order,
an axis silently left out in the other)."""

from __future__ import annotations

import numpy as np
import pytest

from carousel_theory.cli import main
from carousel_theory.simulate import simulate_recording, write_recording


def _write(path, axes, seed):
    simulated = simulate_recording(
        6000, 100.0, rng=np.random.default_rng(seed), white_variance=3.6e-5, rrw_variance=1e-11, axes=axes
    )
    return write_recording(simulated, path)


@pytest.mark.parametrize("order", ["three-then-two", "two-then-three"])
def test_issue13_fit_report_over_runs_with_different_axes(order, tmp_path, capsys):
    three = _write(tmp_path / "a3.csv", ("wx", "wy", "wz"), 1)
    two = _write(tmp_path / "b2.csv", ("wx", "wy"), 2)
    files = [three, two] if order == "three-then-two" else [two, three]
    report = tmp_path / "r.md"
    assert main(["fit", *map(str, files), "--markdown", str(report)]) == 0
    text = report.read_text(encoding="utf-8")
    assert text.count("| parameter | unit | wx | wy | wz |") == 2  # a3's table and the consistency table
    assert "| parameter | unit | wx | wy |\n" in text  # b2's own table
    assert "wz: not in b2.csv" in text
