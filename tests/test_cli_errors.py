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
