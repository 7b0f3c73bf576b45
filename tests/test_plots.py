"""Plots a reader can use (issue 12 point 6), checked on the matplotlib objects, not on pixels: axes told
apart by marker and τ offset, short titles, legends outside the data, the fit's τ range, each term's
curve with its slope and the total, and every rate axis in the requested output unit."""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("matplotlib")

from matplotlib.container import ErrorbarContainer
from matplotlib.patches import Rectangle

from carousel_theory.allan import allan_variance
from carousel_theory.fitting import fit_noise_model
from carousel_theory.noise_model import NoiseModel
from carousel_theory.plots import (
    MARKERS,
    TAU_OFFSET_STEP,
    allan_figure,
    component_curves,
    fit_figure,
    plot_allan,
    plot_fit,
    pyplot,
    short_title,
    unit_label,
)
from carousel_theory.simulate import sample_noise

RATE = 100.0
#: Size of one unit in rad/s, written out independently of carousel_theory.units.
UNIT_SIZE = {"rad/s": 1.0, "deg/s": math.pi / 180.0, "deg/h": math.pi / 180.0 / 3600.0}


def legend_overlaps_data(figure) -> list[bool]:
    """For each axes with a legend, or the figure legends against every axes: do the boxes overlap?"""
    figure.canvas.draw()
    renderer = figure.canvas.get_renderer()
    panels = [plot.get_window_extent(renderer) for plot in figure.axes]
    legends = [plot.get_legend() for plot in figure.axes if plot.get_legend() is not None] + list(
        figure.legends
    )
    return [any(legend.get_window_extent(renderer).overlaps(panel) for panel in panels) for legend in legends]


@pytest.fixture(scope="module")
def three_axes() -> dict:
    rng = np.random.default_rng(12)
    return {
        name: allan_variance(scale * rng.standard_normal(20_000), RATE, "octave")
        for name, scale in (("wx", 1e-3), ("wy", 1.2e-3), ("wz", 0.9e-3))
    }


@pytest.fixture(scope="module")
def white_rrw_fit():
    model = NoiseModel(sample_rate=RATE, white_variance=1e-6, rrw_variance=1e-12)
    y = sample_noise(model, 100_000, rng=np.random.default_rng(4))
    return fit_noise_model(y, RATE, ("white", "rrw"), tau_range=(0.05, 1000.0))


def test_short_title_names_the_stem_not_the_path():
    assert short_title("/very/long/folder/adis16405_run1.npz", "Allan deviation") == (
        "adis16405_run1: Allan deviation"
    )


@pytest.mark.parametrize("units", ["rad/s", "deg/s", "deg/h", "mrad/s", "°/h"])
def test_unit_label(units):
    if units not in UNIT_SIZE:
        with pytest.raises(ValueError, match=r"output_units='.*': must be one of"):
            unit_label(units)
    else:
        assert unit_label(units) == {"rad/s": "rad/s", "deg/s": "°/s", "deg/h": "°/h"}[units]


def test_allan_axes_are_told_apart_by_marker_and_tau_offset(three_axes):
    figure = allan_figure(three_axes, "adis16405_run1: Allan deviation")
    plot = figure.axes[0]
    bars = [c for c in plot.containers if isinstance(c, ErrorbarContainer)]
    assert len(bars) == 3
    markers = [bar.lines[0].get_marker() for bar in bars]
    assert markers == list(MARKERS[:3])
    taus = [bar.lines[0].get_xdata() for bar in bars]
    np.testing.assert_allclose(taus[1] / taus[0], TAU_OFFSET_STEP, rtol=1e-12)
    np.testing.assert_allclose(taus[1], three_axes["wy"].tau, rtol=1e-12)  # the middle one is not moved
    assert plot.get_title() == "adis16405_run1: Allan deviation"
    assert legend_overlaps_data(figure) == [False]
    pyplot().close(figure)


@pytest.mark.parametrize("units", ["rad/s", "deg/s", "deg/h"])
def test_allan_plot_in_output_units(three_axes, units):
    figure = allan_figure(three_axes, "t", output_units=units)
    plot = figure.axes[0]
    assert plot.get_ylabel().endswith(f"({unit_label(units)})")
    first = next(c for c in plot.containers if isinstance(c, ErrorbarContainer))
    expected = np.sqrt(three_axes["wx"].avar) / UNIT_SIZE[units]
    np.testing.assert_allclose(first.lines[0].get_ydata(), expected, rtol=1e-12)
    pyplot().close(figure)


def test_allan_plot_refuses_an_unknown_unit(three_axes, tmp_path):
    with pytest.raises(ValueError, match="output_units='furlong/s'"):
        plot_allan(tmp_path / "a.png", three_axes, "t", output_units="furlong/s")
    assert not (tmp_path / "a.png").exists()


def test_components_sum_to_the_model_and_carry_their_slopes(white_rrw_fit):
    curves = component_curves(white_rrw_fit)
    assert [curve.term for curve in curves] == ["white", "rrw"]
    assert [curve.slope for curve in curves] == [-0.5, 0.5]
    assert "slope −1/2" in curves[0].label and "slope +1/2" in curves[1].label
    np.testing.assert_allclose(sum(curve.avar for curve in curves), white_rrw_fit.model_avar, rtol=1e-12)
    # each term's own log-log slope, measured on its curve at long τ (white) and long τ (RRW)
    for curve in curves:
        measured = np.diff(np.log(np.sqrt(curve.avar[-3:]))) / np.diff(np.log(curve.tau[-3:]))
        np.testing.assert_allclose(measured, curve.slope, atol=1e-3)


def test_flicker_slope_is_d_minus_one_half():
    model = NoiseModel(sample_rate=RATE, white_variance=1e-6, flicker_variance=1e-9, flicker_d=0.7)
    y = sample_noise(model, 50_000, rng=np.random.default_rng(8))
    fit = fit_noise_model(y, RATE, ("white", "flicker"), flicker_d=0.7)
    flicker = next(curve for curve in component_curves(fit) if curve.term == "flicker")
    assert flicker.slope == pytest.approx(0.2, abs=1e-12)
    assert "d = 0.70" in flicker.label and "slope +0.20" in flicker.label


def test_fit_plot_draws_range_components_total(white_rrw_fit):
    figure = fit_figure({"wx": white_rrw_fit, "wy": white_rrw_fit}, "run: fit", output_units="deg/h")
    assert figure.get_suptitle() == "run: fit" and len(figure.axes) == 2
    for plot in figure.axes:
        assert [p.get_label() for p in plot.patches if isinstance(p, Rectangle)] == ["τ range of the fit"]
        labels = [line.get_label() for line in plot.get_lines() if not line.get_label().startswith("_")]
        assert labels == [
            "white noise (angle random walk), slope −1/2",
            "rate random walk, slope +1/2",
            "total model",
        ]
        total = plot.get_lines()[-1]
        np.testing.assert_allclose(
            total.get_ydata(), np.sqrt(white_rrw_fit.model_avar) / UNIT_SIZE["deg/h"], rtol=1e-12
        )
        assert plot.get_ylabel().endswith("(°/h)")
        assert "χ²" in plot.get_title()
    assert legend_overlaps_data(figure) == [False, False]
    pyplot().close(figure)


def test_fit_plot_shades_exactly_the_fitted_tau(white_rrw_fit):
    figure = fit_figure({"wx": white_rrw_fit}, "t")
    plot = figure.axes[0]
    span = next(p for p in plot.patches if p.get_label() == "τ range of the fit")
    tau_used = white_rrw_fit.allan.tau[white_rrw_fit.used]
    assert (span.get_x(), span.get_x() + span.get_width()) == pytest.approx((tau_used[0], tau_used[-1]))
    assert not white_rrw_fit.used.all()  # the test would not see a wrong range otherwise
    pyplot().close(figure)


def test_plot_files_are_written(three_axes, white_rrw_fit, tmp_path):
    plot_allan(tmp_path / "a.png", three_axes, "t")
    plot_fit(tmp_path / "f.png", {"wx": white_rrw_fit}, "t")
    assert (tmp_path / "a.png").read_bytes()[:4] == b"\x89PNG" == (tmp_path / "f.png").read_bytes()[:4]


def test_the_overlap_check_sees_a_legend_inside_the_data(three_axes):
    figure = allan_figure(three_axes, "t")
    plot = figure.axes[0]
    plot.legend(loc="upper right")  # the placement the plots no longer use
    assert legend_overlaps_data(figure) == [True]
    pyplot().close(figure)


def test_fleet_distributions_flag_outliers_in_a_legend_outside_and_convert_bias_instability():
    from carousel_theory.batch.report import distributions_figure
    from carousel_theory.batch.rows import BatchRow

    arw = [1.0, 1.1, 0.9, 1.05, 0.95, 1.02, 30.0]  # the last unit is far outside the others
    rows = [
        BatchRow(
            path=f"unit{k}.csv",
            task="fit",
            axis="wx",
            angle_random_walk_deg_per_sqrt_h=value,
            bias_instability_deg_per_h=36.0 + k,
            rate_random_walk_deg_per_h_per_sqrt_h=100.0 + k,
        )
        for k, value in enumerate(arw)
    ]
    figure = distributions_figure(rows, output_units="deg/s")
    arw_panel, bias_panel, _ = figure.axes
    flagged = [line.get_xdata()[0] for line in arw_panel.get_lines()]
    assert flagged == [30.0]
    assert bias_panel.get_xlabel() == "bias instability (°/s)"
    assert bias_panel.get_xlim()[1] < 1.0  # 36–42 °/h is about 0.01 °/s
    assert figure.get_suptitle() == "Fleet distributions: 7 recordings, 7 axes"
    assert [text.get_text() for text in figure.legends[0].get_texts()] == ["units", "flagged (|z| > 3.5)"]
    assert legend_overlaps_data(figure) == [False]
    pyplot().close(figure)
