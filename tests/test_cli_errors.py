"""The command line's error boundary: one line, the right exit status, no traceback."""

from __future__ import annotations

import errno
import io
import sys

import numpy as np
import pytest

from carousel_theory import __version__
from carousel_theory.cli import main
from carousel_theory.cli._errors import BAD_INPUT, FAILURE, classify


@pytest.mark.parametrize(
    ("error", "status", "fragment"),
    [
        (ValueError("N=0: must be >= 1"), BAD_INPUT, "N=0: must be >= 1"),
        (TypeError("N='a': must be an integer"), BAD_INPUT, "must be an integer"),
        (
            FileNotFoundError(errno.ENOENT, "No such file or directory", "x.csv"),
            BAD_INPUT,
            "x.csv: No such file",
        ),
        (NotADirectoryError(errno.ENOTDIR, "Not a directory", "a.csv/x.md"), BAD_INPUT, "a.csv/x.md"),
        (OSError(errno.ENAMETOOLONG, "File name too long", "xxx"), BAD_INPUT, "File name too long"),
        (OSError(errno.ENOSPC, "No space left on device", "/dev/full"), FAILURE, "No space left"),
        (IsADirectoryError("-o /tmp: is a directory"), BAD_INPUT, "-o /tmp: is a directory"),
        (MemoryError(), FAILURE, "out of memory"),
        (np.linalg.LinAlgError("Matrix is not positive definite"), FAILURE, "numerical failure"),
        (OverflowError("int too large"), FAILURE, "numerical failure"),
        (RuntimeError("boom"), FAILURE, "--debug"),
    ],
    ids=lambda value: type(value).__name__ if isinstance(value, BaseException) else str(value),
)
def test_classification(error: BaseException, status: int, fragment: str) -> None:
    got_status, message = classify(error)
    assert got_status == status
    assert fragment in message
    assert "\n" not in message


def test_missing_extra_names_the_extra() -> None:
    status, message = classify(ModuleNotFoundError("No module named 'dask'", name="dask"))
    assert status == BAD_INPUT
    assert "carousel-theory[batch]" in message


def test_unrelated_missing_module_is_unforeseen() -> None:
    status, message = classify(ModuleNotFoundError("No module named 'zzz'", name="zzz"))
    assert status == FAILURE
    assert "--debug" in message


def test_version(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as stop:
        main(["--version"])
    assert stop.value.code == 0
    assert capsys.readouterr().out.strip() == f"carousel-theory {__version__}"


def test_bad_value_is_one_line_with_status_2(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["formula", "rrw_average_var", "--set", "N=0", "--set", "k=1"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("carousel-theory formula: error:")
    assert "Traceback" not in err
    assert len(err.strip().splitlines()) == 1


class _ClosedPipe(io.StringIO):
    def write(self, text: str) -> int:
        raise BrokenPipeError(errno.EPIPE, "Broken pipe")


def test_closed_pipe_in_process(monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.setattr(sys, "stdout", _ClosedPipe())
    assert main(["formula", "--list"]) == 0
    assert capsys.readouterr().err == ""


# --- issue 13 point 14: messages that leaked internals ---------------------------------------------

_LEAKS = (
    "positive definite",
    "leading minor",
    "infs or NaNs",
    "math domain",
    "Traceback",
    "driving-variance",
)


def _write_columns(path, columns: dict[str, np.ndarray]) -> str:
    """A CSV of exactly these columns (``repr`` round-trips float64), with or without a time column."""
    rows = "".join(
        ",".join(repr(float(v)) for v in row) + "\n" for row in zip(*columns.values(), strict=True)
    )
    path.write_text(",".join(columns) + "\n" + "".join(rows), encoding="utf-8")
    return str(path)


def _signal(kind: str) -> np.ndarray:
    noise = np.random.default_rng(14).standard_normal(3000)
    return {
        "constant": np.full(3000, 0.5),
        "all-zero": np.zeros(3000),
        "huge": 1e300 * noise,
        "tiny": 1e-300 * noise,
    }[kind]


_RULES = {
    "constant": "constant (every sample is 0.5)",
    "all-zero": "constant (every sample is 0.0)",
    "huge": "rates must stay within ±1e+60",
    "tiny": "must be at least 1e-60",
}


@pytest.mark.parametrize("kind", sorted(_RULES))
@pytest.mark.parametrize("command", ["fit", "predict", "loop"])
def test_issue13_point14_degenerate_signals_name_the_file_column_and_rule(
    command: str, kind: str, tmp_path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = _write_columns(tmp_path / f"{kind}.csv", {"t": np.arange(3000) / 100.0, "wx": _signal(kind)})
    assert main([command, path]) == BAD_INPUT
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1
    assert f"{path}: column 'wx'" in err and _RULES[kind] in err
    assert not [leak for leak in _LEAKS if leak in err]


@pytest.mark.parametrize("command", ["allan", "fit"])
def test_issue13_point14_two_rows_name_the_file_and_column(command: str, tmp_path, capsys) -> None:
    path = _write_columns(tmp_path / "two.csv", {"t": np.array([0.0, 0.01]), "wx": np.array([1.0, 2.0])})
    assert main([command, path]) == BAD_INPUT
    err = capsys.readouterr().err
    assert f"{path}: 2 sample(s) in column(s) wx" in err and "at least 3" in err
    assert "y:" not in err


def test_issue13_point14_predict_without_time_column_takes_the_option_it_suggests(tmp_path, capsys) -> None:
    noise = 1e-3 * np.random.default_rng(141).standard_normal(1200)
    path = _write_columns(tmp_path / "no_time.csv", {"wx": noise})
    arguments = ["predict", path, "--calibration", "1000", "--horizon", "100"]
    assert main(arguments) == BAD_INPUT
    assert "no time column and no sample_rate" in capsys.readouterr().err
    assert main([*arguments, "--sample-rate", "100"]) == 0
    assert "KF" in capsys.readouterr().out


@pytest.mark.parametrize("scale", ["largest", "smallest"])
def test_issue13_point14_signals_just_inside_the_bounds_are_fitted(scale: str, tmp_path, capsys) -> None:
    noise = np.random.default_rng(142).standard_normal(3000)
    rates = (
        noise * (0.9e60 / np.max(np.abs(noise))) if scale == "largest" else noise * (2e-60 / np.std(noise))
    )
    path = _write_columns(tmp_path / f"{scale}.csv", {"t": np.arange(3000) / 100.0, "wx": rates})
    for command in (["fit", path], ["predict", path], ["loop", path, "--axes", "wx"]):
        assert main(command) == 0, capsys.readouterr().err
        assert capsys.readouterr().err == ""


@pytest.mark.parametrize(
    "error",
    [
        ValueError("array must not contain infs or NaNs"),
        ValueError("math domain error"),
        np.linalg.LinAlgError("1th leading minor not positive definite"),
    ],
    ids=["scipy-check-finite", "math-domain", "leading-minor"],
)
def test_issue13_point14_internal_numerical_texts_become_a_user_level_failure(error: BaseException) -> None:
    status, message = classify(error)
    assert status == FAILURE
    assert str(error) not in message and "--debug" in message


@pytest.mark.parametrize("value", ["-1", "x"])
def test_a_seed_that_is_not_a_non_negative_integer_is_refused_by_name(tmp_path, capsys, value):
    out = tmp_path / "o.csv"
    with pytest.raises(SystemExit) as raised:
        main(["simulate", str(out), "--seed", value])
    assert raised.value.code == BAD_INPUT
    assert f"argument --seed: '{value}': must be an integer >= 0" in capsys.readouterr().err
    assert not out.exists()


def test_a_division_by_zero_in_set_is_bad_input_named(capsys):
    assert main(["formula", "white_average_var", "--set", "N=1/0"]) == BAD_INPUT
    assert "--set N='1/0': division by zero" in capsys.readouterr().err
