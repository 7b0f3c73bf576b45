"""Rotation schemes: parsing, patterns and demodulation weights."""

from __future__ import annotations

import numpy as np
import pytest

from carousel_theory import rotation_schemes
from carousel_theory.rotation_schemes import (
    Carousel,
    Indexing,
    MeasuredProfile,
    Static,
    TwoAxisCarousel,
    demodulation_weights,
    parse_scheme,
    scheme_label,
)
from tests.conftest import public_functions

SCHEMES = [
    Static(),
    Carousel(8),
    Carousel(7.5),
    Indexing(2, 3, 1),
    Indexing(4, 2, 2, use_transitions=True),
    Indexing(3, 2, 0),
    MeasuredProfile.from_array([0.0, 1.0, 2.5, 4.0]),
    TwoAxisCarousel(6),
]


@pytest.mark.parametrize("scheme", SCHEMES, ids=lambda s: type(s).__name__)
def test_the_demodulated_mean_recovers_any_earth_rate_exactly(scheme):
    rng = np.random.default_rng(11)
    pattern = scheme.pattern(60)
    W = demodulation_weights(pattern)
    earth = rng.standard_normal(3)
    body = np.einsum("tji,j->ti", pattern.rotations, earth)  # ω_t = R_tᵀ Ω
    estimate = np.einsum("jgt,tg->j", W, body)
    np.testing.assert_allclose(estimate, earth[: pattern.components], rtol=0, atol=1e-14)


@pytest.mark.parametrize(
    ("scheme", "length"),
    [(Carousel(8), 48), (Indexing(2, 3, 1), 32), (Indexing(4, 2, 2), 48), (TwoAxisCarousel(6), 24)],
    ids=["carousel", "indexing2", "indexing4", "two-axis"],
)
def test_whole_cycles_cancel_every_bias(scheme, length):
    W = demodulation_weights(scheme.pattern(length))
    np.testing.assert_allclose(W.sum(axis=2), 0, atol=1e-15)


def test_a_non_integer_carousel_and_static_averaging_leave_the_bias():
    assert np.abs(demodulation_weights(Carousel(7.5).pattern(20)).sum(axis=2)).max() > 1e-3
    np.testing.assert_array_equal(demodulation_weights(Static().pattern(5)).sum(axis=2)[:2, :2], np.eye(2))


def test_indexing_pattern_holds_each_position_for_the_dwell_and_drops_transitions():
    pattern = Indexing(4, 2, 1).pattern(12)
    angles = np.arctan2(pattern.rotations[:, 1, 0], pattern.rotations[:, 0, 0])
    expected = np.array([0, 0, 0.5, 1, 1, 1.5, 2, 2, 2.5, 3, 3, 3.5]) * np.pi / 2
    np.testing.assert_allclose(np.mod(angles, 2 * np.pi), np.mod(expected, 2 * np.pi), atol=1e-15)
    assert pattern.used.tolist() == [True, True, False] * 4


def test_two_axis_flips_every_other_turn():
    pattern = TwoAxisCarousel(4).pattern(8)
    assert pattern.rotations[:4, 2, 2].tolist() == [1.0] * 4
    assert pattern.rotations[4:, 2, 2].tolist() == [-1.0] * 4


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("static", Static()),
        ("carousel:N=200", Carousel(200)),
        ("carousel:N=150.5", Carousel(150.5)),
        ("carousel:period=2", Carousel(200)),
        ("indexing:positions=4,dwell=10,transition=1", Indexing(4, 1000, 100)),
        ("indexing:positions=2,dwell=0.01", Indexing(2, 1, 0)),
        ("indexing:positions=2,dwell=1,transition=0.5,transitions=use", Indexing(2, 100, 50, True)),
        ("two-axis:N=200", TwoAxisCarousel(200)),
    ],
)
def test_parse_scheme(text, expected):
    scheme = parse_scheme(text, 100.0)
    assert scheme == expected
    assert parse_scheme(scheme_label(scheme, 100.0), 100.0) == scheme


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("spin:N=3", "must start with one of"),
        ("carousel", "exactly one of N= "),
        ("carousel:N=1", "must be >= 2"),
        ("carousel:N=abc", "N='abc' must be a number"),
        ("carousel:N=-5", "must be a finite number >= 0"),
        ("carousel:M=5", "unknown option"),
        ("carousel:N", "must have the form KEY=VALUE"),
        ("indexing:positions=4", "needs positions= and dwell="),
        ("indexing:positions=1,dwell=1", "must be an integer >= 2"),
        ("indexing:positions=2.5,dwell=1", "must be an integer >= 2"),
        ("indexing:positions=2,dwell=0.001", "shorter than one sample"),
        ("indexing:positions=2,dwell=0.015", "whole number of samples"),
        ("indexing:positions=2,dwell=1,transitions=maybe", "'discard' or 'use'"),
        ("static:N=3", "unknown option"),
        ("two-axis:N=10.5", "whole number of samples a turn"),
    ],
    ids=lambda value: value if isinstance(value, str) and ":" in value else None,
)
def test_bad_scheme_text_is_named_with_its_rule(text, message):
    with pytest.raises(ValueError, match="scheme=") as error:
        parse_scheme(text, 100.0)
    assert message in str(error.value)


@pytest.mark.parametrize(
    ("call", "error", "message"),
    [
        (lambda: Indexing(2, 0), ValueError, "dwell=0: must be at least one sample"),
        (lambda: Indexing(1, 5), ValueError, "positions=1: must be an integer >= 2"),
        (lambda: Indexing(2, 5, -1), ValueError, "transition=-1"),
        (lambda: Carousel(1.5), ValueError, "samples_per_revolution=1.5: must be >= 2"),
        (lambda: TwoAxisCarousel(1), ValueError, "samples_per_revolution=1"),
        (lambda: parse_scheme(3, 100.0), TypeError, "scheme=3"),
        (lambda: parse_scheme("static", -1.0), ValueError, "sample_rate=-1.0"),
        (lambda: MeasuredProfile.from_array([0.0, np.nan]), ValueError, "angles: must be finite"),
        (lambda: Static().pattern(0), ValueError, "length=0"),
    ],
    ids=[
        "dwell-0",
        "one-position",
        "negative-transition",
        "slow-carousel",
        "two-axis-1",
        "not-text",
        "rate",
        "nan-angle",
        "empty",
    ],
)
def test_invalid_calls(call, error, message):
    with pytest.raises(error, match=message.replace("(", r"\(").replace("[", r"\[")):
        call()


def test_all_is_honest():
    assert public_functions(rotation_schemes) <= set(rotation_schemes.__all__)


def test_profile_from_a_file_is_read_and_repeated(tmp_path):
    angles = np.array([0.0, 1.5, 3.0, 4.5])
    np.save(tmp_path / "angles.npy", angles)
    (tmp_path / "angles.txt").write_text("\n".join(str(a) for a in angles), encoding="utf-8")
    for name in ("angles.npy", "angles.txt"):
        scheme = parse_scheme(f"profile:file={tmp_path / name}", 100.0)
        assert scheme == MeasuredProfile.from_array(angles)
        pattern = scheme.pattern(6)
        np.testing.assert_allclose(
            np.arctan2(pattern.rotations[:, 1, 0], pattern.rotations[:, 0, 0])[4:], [0, 1.5]
        )


@pytest.mark.parametrize(
    ("make", "message"),
    [
        (lambda path: None, "does not exist"),
        (lambda path: path.write_text("a\nb\n", encoding="utf-8"), "holds no column of angles"),
    ],
    ids=["missing", "not-numbers"],
)
def test_bad_profile_file(tmp_path, make, message):
    path = tmp_path / "angles.txt"
    make(path)
    with pytest.raises(ValueError, match=message):
        parse_scheme(f"profile:file={path}", 100.0)
