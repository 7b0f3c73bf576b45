"""``allan_variance`` on 2-D arrays, DataFrames and recordings (one result per axis), and open τ ranges.

The reference for every axis is the 1-D call on that column, itself checked against allantools in
test_allan.py: the per-axis results must equal it exactly.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from carousel_theory.allan import AllanResult, AllanResultsByAxis, allan_variance, check_tau_range
from carousel_theory.data import recording_from_arrays
from carousel_theory.fitting import fit_noise_model

RATE = 20.0


@pytest.fixture
def table() -> np.ndarray:
    return np.random.default_rng(21).standard_normal((600, 3))


def _same(got: AllanResult, expected: AllanResult) -> None:
    for name in ("tau", "avar", "ci_low", "ci_high", "edf", "terms"):
        np.testing.assert_array_equal(getattr(got, name), getattr(expected, name))


def test_two_dimensional_array_gives_one_result_per_column(table):
    results = allan_variance(table, RATE)
    assert isinstance(results, AllanResultsByAxis)
    assert list(results) == ["wx", "wy", "wz"] and len(results) == 3 and results.sample_rate == RATE
    for index, axis in enumerate(results):
        _same(results[axis], allan_variance(table[:, index], RATE))


def test_wide_array_names_its_axes_by_index():
    wide = np.random.default_rng(22).standard_normal((100, 4))
    assert list(allan_variance(wide, 1.0)) == ["w0", "w1", "w2", "w3"]


def test_data_frame_with_a_time_column_and_extra_columns(table):
    frame = pd.DataFrame(
        {
            "time": np.arange(600) / RATE,
            "gx": table[:, 0],
            "gy": table[:, 1],
            "temp": np.full(600, 25.0),  # not an axis
        }
    )
    results = allan_variance(frame, estimator="non-overlapping", tau_range=(0.2, None))
    assert list(results) == ["gx", "gy"] and results.sample_rate == RATE
    _same(
        results["gy"], allan_variance(table[:, 1], RATE, estimator="non-overlapping", tau_range=(0.2, None))
    )


def test_data_frame_with_datetime_index_column_and_without_time(table):
    stamps = pd.Timestamp("2024-03-01T12:00:00") + pd.to_timedelta(np.arange(600) * 50, unit="ms")
    frame = pd.DataFrame({"timestamp": stamps, "wx": table[:, 0]})
    _same(allan_variance(frame)["wx"], allan_variance(table[:, 0], RATE))
    bare = pd.DataFrame({"wx": table[:, 0], "wy": table[:, 1]})
    _same(allan_variance(bare, RATE)["wy"], allan_variance(table[:, 1], RATE))


def test_recording_gives_its_axes(table):
    recording = recording_from_arrays({"wx": table[:, 0], "wz": table[:, 2]}, sample_rate=RATE)
    results = allan_variance(recording, noise="rrw")
    _same(results["wz"], allan_variance(table[:, 2], RATE, noise="rrw"))


def test_non_uniform_data_frame_is_refused_with_where(table):
    time = np.arange(600) / RATE
    time[300:] += 0.5
    frame = pd.DataFrame({"t": time, "wx": table[:, 0]})
    with pytest.raises(ValueError, match=r"DataFrame: gap: 1 steps .* t\[299\]"):
        allan_variance(frame)


@pytest.mark.parametrize(
    ("tau_range", "kept"),
    [
        ((0.1, None), slice(1, None)),  # octave τ: 0.05, 0.1, 0.2, …, 6.4 s
        ((None, 0.4), slice(0, 4)),
        ((0.2, 0.8), slice(2, 5)),
        ((None, None), slice(0, None)),
    ],
    ids=["low-only", "high-only", "both", "neither"],
)
def test_open_tau_ranges_keep_the_octave_tau_inside(table, tau_range, kept):
    full = allan_variance(table[:, 0], RATE)
    part = allan_variance(table[:, 0], RATE, tau_range=tau_range)
    np.testing.assert_array_equal(part.tau, full.tau[kept])
    np.testing.assert_array_equal(part.avar, full.avar[kept])
    np.testing.assert_array_equal(part.edf, full.edf[kept])


def test_fit_takes_an_open_tau_range():
    y = np.random.default_rng(23).standard_normal(20_000)
    open_high = fit_noise_model(y, 100.0, ("white",), tau_range=(0.1, None), iterations=1)
    closed = fit_noise_model(y, 100.0, ("white",), tau_range=(0.1, 1e9), iterations=1)
    assert open_high.model.white_variance == closed.model.white_variance
    assert open_high.allan.tau[open_high.used].min() == pytest.approx(0.16)  # the first octave τ ≥ 0.1 s


def test_check_tau_range_fills_open_ends():
    assert check_tau_range(None) == (0.0, math.inf)
    assert check_tau_range((None, 3)) == (0.0, 3.0)
    assert check_tau_range((0.5, None)) == (0.5, math.inf)


INVALID = [
    ("range-reversed", {"tau_range": (1.0, 0.5)}, ValueError, "low must not exceed high"),
    ("range-zero", {"tau_range": (0.0, None)}, ValueError, "tau_range=0.0"),
    ("range-negative", {"tau_range": (None, -1.0)}, ValueError, "tau_range=-1.0"),
    ("range-inf", {"tau_range": (math.inf, None)}, ValueError, "tau_range=inf"),
    ("range-shape", {"tau_range": (1.0,)}, ValueError, r"must be \(low, high\)"),
    ("range-string", {"tau_range": "0.1:1"}, ValueError, r"must be \(low, high\)"),
    ("range-empty", {"tau_range": (100.0, 200.0)}, ValueError, "holds none of the τ"),
    ("no-rate", {"sample_rate": None}, ValueError, "sample_rate=None: required"),
]


@pytest.mark.parametrize(
    ("options", "error", "message"), [case[1:] for case in INVALID], ids=[case[0] for case in INVALID]
)
def test_invalid_calls(table, options, error, message):
    arguments = {"sample_rate": RATE, **options}
    with pytest.raises(error, match=message):
        allan_variance(table[:, 0], **arguments)


def test_recording_with_a_sample_rate_is_refused(table):
    recording = recording_from_arrays({"wx": table[:, 0]}, sample_rate=RATE)
    with pytest.raises(ValueError, match="a Recording carries its own"):
        allan_variance(recording, RATE)


@pytest.mark.parametrize(
    "call",
    [
        lambda y: allan_variance(y, RATE),
        lambda y: allan_variance(list(y), RATE),
        lambda y: fit_noise_model(y, RATE),
    ],
)
def test_complex_samples_are_refused_not_cast(call):
    # Casting to float64 would keep the real parts with only a ComplexWarning: refused by name, even when
    # every imaginary part is 0 (the array's type says it holds something other than rates).
    y = np.random.default_rng(3).standard_normal(2000) * (1.0 + 0.0j)
    with pytest.raises(TypeError, match="y: must be an array of real numbers, got complex values"):
        call(y)
