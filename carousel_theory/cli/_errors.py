"""Turning what a sub-command raises into one line and an exit status.

Exit status 2: the input or an option is wrong (``ValueError``, ``TypeError``, a missing or unreadable
file, an output the policy refuses, a name too long). Exit status 1: a failure the user did not cause
but can act on (disk full, out of memory, a numerical failure the library could not avoid). An
unforeseen exception prints one line that says so and how to see the traceback (``--debug``).
"""

from __future__ import annotations

import errno
import os
import sys
import traceback

__all__ = ["BAD_INPUT", "FAILURE", "OPTIONAL_EXTRAS", "classify", "report_error", "silence_closed_pipe"]

BAD_INPUT = 2
FAILURE = 1

#: Optional module → the extra that installs it.
OPTIONAL_EXTRAS = {
    "matplotlib": ("plotting", "plots"),
    "dask": ("batch runs", "batch"),
    "distributed": ("batch runs", "batch"),
    "h5py": ("HDF5 files", "hdf5"),
}

_BAD_INPUT_OS_ERRORS = (
    FileNotFoundError,
    IsADirectoryError,
    NotADirectoryError,
    PermissionError,
    FileExistsError,
)
_BAD_INPUT_ERRNOS = {
    errno.ENOENT,
    errno.EISDIR,
    errno.ENOTDIR,
    errno.EACCES,
    errno.EPERM,
    errno.ENAMETOOLONG,
    errno.EEXIST,
    errno.EROFS,
}


#: ValueError texts raised inside NumPy, SciPy or ``math`` on a non-finite or degenerate intermediate:
#: a failure of the computation, not something the user typed.
_INTERNAL_VALUE_ERRORS = ("array must not contain infs or NaNs", "math domain error")

_NUMERICAL_FAILURE = (
    "numerical failure: the data make the model degenerate (a covariance that is not positive definite, "
    "or a number beyond float64's range); check that each column varies and is in a sensible unit "
    "(run with --debug for the details)"
)


def _os_message(error: OSError) -> str:
    where = error.filename if error.filename is not None else ""
    reason = error.strerror or str(error)
    return f"{where}: {reason}" if where else reason


def classify(error: BaseException) -> tuple[int, str]:
    """The exit status and the one-line message for ``error`` (no command name)."""
    if isinstance(error, ModuleNotFoundError) and (error.name or "").split(".")[0] in OPTIONAL_EXTRAS:
        what, extra = OPTIONAL_EXTRAS[(error.name or "").split(".")[0]]
        return BAD_INPUT, f"{what} needs {error.name}: python -m pip install 'carousel-theory[{extra}]'"
    if isinstance(error, OSError):
        caller_error = isinstance(error, _BAD_INPUT_OS_ERRORS) or error.errno in _BAD_INPUT_ERRNOS
        status = BAD_INPUT if caller_error else FAILURE
        return status, _os_message(error)
    if isinstance(error, MemoryError):
        return FAILURE, (
            "out of memory: the request needs more memory than this machine has;"
            " use a shorter recording, fewer axes or fewer τ"
        )
    numerical = (ArithmeticError, _linalg_error())
    internal = isinstance(error, ValueError) and str(error) in _INTERNAL_VALUE_ERRORS
    if isinstance(error, numerical) or internal:
        return FAILURE, _NUMERICAL_FAILURE
    if isinstance(error, ValueError | TypeError):
        return BAD_INPUT, str(error)
    return FAILURE, (
        f"unexpected {type(error).__name__}: {error} "
        "(run again with --debug for the traceback, and please report it)"
    )


def _linalg_error() -> type[BaseException]:
    import numpy as np

    return np.linalg.LinAlgError


def report_error(command: str, error: BaseException, *, debug: bool) -> int:
    """Print ``error`` as one line (or with its traceback when ``debug``); return the exit status."""
    status, message = classify(error)
    if debug:
        traceback.print_exception(error, file=sys.stderr)
    print(f"carousel-theory {command}: error: {message}", file=sys.stderr)
    return status


def silence_closed_pipe() -> int:
    """The reader of our output went away (``| head``): stop quietly, without a second error at exit."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError, AttributeError):
        pass
    return 0
