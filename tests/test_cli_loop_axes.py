"""``carousel-theory loop`` keeps only the gyro columns it analyses."""

from __future__ import annotations

import numpy as np
import pytest

from carousel_theory.cli.loop import analysed_only
from carousel_theory.data import Recording


def _recording() -> Recording:
    rng = np.random.default_rng(4)
    rates = {name: rng.standard_normal(50) for name in ("wx", "wy", "wz")}
    return Recording(time=np.arange(50) / 10.0, rates=rates, sample_rate=10.0, temperature=np.ones(50))


@pytest.mark.parametrize(
    ("axes", "kept"),
    [
        pytest.param(None, ("wx", "wy"), id="default"),
        pytest.param(("wz",), ("wz",), id="one-axis"),
        pytest.param(("wy", "wz"), ("wy", "wz"), id="two-axes"),
    ],
)
def test_only_the_analysed_axes_are_kept(axes, kept):
    recording = _recording()
    reduced = analysed_only(recording, axes)
    assert tuple(reduced.rates) == kept
    for axis in kept:
        assert reduced.rates[axis] is recording.rates[axis]  # no copy
    assert reduced.time is recording.time and reduced.temperature is recording.temperature
    assert len(recording.rates) == 3  # the user's recording is not changed


def test_a_missing_axis_leaves_the_recording_for_the_loop_to_refuse():
    recording = _recording()
    assert analysed_only(recording, ("wx", "wq")) is recording
