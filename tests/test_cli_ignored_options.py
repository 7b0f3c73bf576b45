"""Options that used to be silently ignored or accepted are refused with the value and the rule
(issue 13 point 15)."""

from __future__ import annotations

import numpy as np
import pytest

from carousel_theory.cli import main
from carousel_theory.effects import check_effect_parameters
from carousel_theory.simulate import simulate_recording, write_recording


@pytest.fixture(scope="module")
def recording(tmp_path_factory):
    simulated = simulate_recording(
        3000,
        100.0,
        rng=np.random.default_rng(15),
        white_variance=3.6e-5,
        rrw_variance=1e-11,
        axes=("wx", "wy"),
    )
    return str(write_recording(simulated, tmp_path_factory.mktemp("options") / "a.csv"))


CASES = [
    ("fit-tau-min-zero", ["fit", "{r}", "--tau-min", "0"], "--tau-min=0.0: must be a positive"),
    ("fit-tau-range-reversed", ["fit", "{r}", "--tau-min", "2", "--tau-max", "1"], "must be below --tau-max"),
    ("fit-flicker-d-without-flicker", ["fit", "{r}", "--flicker-d", "0.5"], "only with 'flicker' in --model"),
    ("loop-axis-twice", ["loop", "{r}", "--axes", "wx,wx"], "names an axis twice"),
    ("check-only-empty", ["check", "--only", ""], "must be a non-empty claim-id prefix"),
]


@pytest.mark.parametrize(("arguments", "message"), [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_issue13_ignored_option_is_refused(arguments, message, recording, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main([part.format(r=recording) for part in arguments]) == 2
    assert message in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == [], "a refused command writes nothing"


def test_issue13_partial_check_says_it_writes_nothing(tmp_path, capsys):
    assert main(["check", "--only", "TIM2014-eq18", "--out", str(tmp_path)]) == 0
    assert "writes no file" in capsys.readouterr().out
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(
    ("effect", "parameters", "message"),
    [
        ("spikes", {"rate": -1}, "spikes:rate=-1.0"),
        ("warmup", {"time_constant": -1}, "warmup:time_constant=-1.0"),
        ("colored_noise", {"coefficient": 1.0}, "colored_noise:coefficient=1.0"),
        ("steps", {"time": 1.5}, "steps:time=1.5"),
        ("flicker", {"d": 1.0}, "flicker:d=1.0"),
    ],
)
def test_issue13_effect_parameters_out_of_range_are_refused(effect, parameters, message):
    with pytest.raises(ValueError, match=message):
        check_effect_parameters(effect, parameters)
