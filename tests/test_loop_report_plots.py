"""The loop's report plots (issue 12 point 6): the bins plot titled and laid out like TIM 2014 Fig. 7
((a) averaged x, (b) averaged y, (c) carouselled, dashed ±2σ), legends outside the data, a short title,
rates in the requested output unit; checked on the matplotlib objects."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

pytest.importorskip("matplotlib")

from carousel_theory.closed_loop import run_loop
from carousel_theory.closed_loop.report import allan_report_figure, bins_report_figure, write_report
from carousel_theory.plots import pyplot
from carousel_theory.simulate import simulate_recording

DEGREE_PER_HOUR = math.pi / 180.0 / 3600.0  # one °/h in rad/s, written out here


@pytest.fixture(scope="module")
def result():
    recording = simulate_recording(
        30_000,
        100.0,
        rng=np.random.default_rng(2),
        bias=0.01,
        white_variance=3.6e-5,
        rrw_variance=1e-11,
        effects=["spikes"],
    )
    return run_loop(replace(recording, source="/some/long/folder/bench_run7.csv"))


def _legends_overlap(figure) -> list[bool]:
    figure.canvas.draw()
    renderer = figure.canvas.get_renderer()
    return [
        any(
            legend.get_window_extent(renderer).overlaps(plot.get_window_extent(renderer))
            for plot in figure.axes
        )
        for legend in figure.legends
    ]


def test_bins_plot_is_laid_out_like_fig7(result):
    figure = bins_report_figure(result)
    assert [plot.get_title(loc="left") for plot in figure.axes] == [
        "(a) averaged wx-gyro",
        "(b) averaged wy-gyro",
        "(c) carouselled estimate",
    ]
    title = figure.get_suptitle()
    assert title.startswith("bench_run7: ") and "N = 200" in title and "TIM 2014 Fig. 7" in title
    assert "/" not in title.split(":")[0]
    for plot in figure.axes:
        styles = [line.get_linestyle() for line in plot.get_lines()]
        assert styles.count("--") == 2  # the ±2σ band of the model after, dashed as in the figure
    assert _legends_overlap(figure) == [False]
    pyplot().close(figure)


def test_bins_plot_in_output_units(result):
    in_rad = bins_report_figure(result)
    in_deg_h = bins_report_figure(result, output_units="deg/h")
    for first, second in zip(in_rad.axes, in_deg_h.axes, strict=True):
        assert second.get_ylabel() == "rate (°/h)"
        for a, b in zip(first.get_lines(), second.get_lines(), strict=True):
            np.testing.assert_allclose(b.get_ydata(), np.asarray(a.get_ydata()) / DEGREE_PER_HOUR, rtol=1e-12)
    pyplot().close(in_rad)
    pyplot().close(in_deg_h)


def test_allan_report_plot_has_a_short_title_and_its_legend_below(result):
    figure = allan_report_figure(result, output_units="deg/s")
    assert figure.get_suptitle() == "bench_run7: Allan deviation before and after the loop"
    assert [plot.get_title() for plot in figure.axes] == ["wx", "wy"]
    assert all(plot.get_ylabel() == "Allan deviation (°/s)" for plot in figure.axes)
    assert _legends_overlap(figure) == [False]
    pyplot().close(figure)


def test_write_report_refuses_an_unknown_unit_before_writing(result, tmp_path):
    with pytest.raises(ValueError, match="output_units='rad/h'"):
        write_report(result, tmp_path / "report", output_units="rad/h")
    assert not (tmp_path / "report").exists()
