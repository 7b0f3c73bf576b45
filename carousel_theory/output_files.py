"""One output policy for everything that writes: never over an input, never half-written.

Every command that writes files goes through :func:`plan_outputs` before its work starts and through
:func:`atomic_output` (or :func:`write_text_atomic`) when it writes:

* an output that is, or reaches through a link, one of the inputs is refused (a recording is never
  overwritten by its own report);
* an output that is a directory, a device or a FIFO, whose parent is a file, whose name is longer than
  the file system allows, or whose nearest existing folder is not writable is refused before any work;
* missing parent folders are created;
* the bytes go to a temporary file in the target folder and are renamed over the target only once they
  are complete, so an interrupted or failing run leaves the old file, or nothing.

Refusals are :class:`OutputPathError` (a ``ValueError``: bad input, exit status 2 in the CLI); failures
while writing stay ``OSError`` with the path named.
"""

from __future__ import annotations

import contextlib
import errno
import os
import stat
import tempfile
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Literal

__all__ = [
    "OutputPathError",
    "PlannedOutput",
    "atomic_output",
    "plan_outputs",
    "write_bytes_atomic",
    "write_text_atomic",
]

PathLike = str | os.PathLike[str]


class OutputPathError(ValueError):
    """An output path breaks the output policy; raised before any work is done."""


@dataclass(frozen=True)
class PlannedOutput:
    """An output that passed the policy: where it goes and whether it is a file or a folder."""

    path: Path
    kind: Literal["file", "directory"]


def _same_file(a: Path, b: Path) -> bool:
    if os.path.realpath(a) == os.path.realpath(b):
        return True
    try:
        return os.path.samefile(a, b)
    except OSError:
        return False


def _name_too_long(path: Path) -> str | None:
    for part in path.parts:
        if len(os.fsencode(part)) > 255:
            return part
    return None


def _nearest_existing(path: Path) -> Path:
    current = path.parent
    while not current.exists() and current != current.parent:
        current = current.parent
    return current


def _check_kind(path: Path, kind: str) -> None:
    if not path.exists():
        return
    mode = path.stat().st_mode
    if kind == "directory":
        if not stat.S_ISDIR(mode):
            raise OutputPathError(f"output folder {str(path)!r}: exists and is not a folder")
        return
    if stat.S_ISDIR(mode):
        raise OutputPathError(f"output {str(path)!r}: is a folder; name a file inside it")
    if not stat.S_ISREG(mode):
        raise OutputPathError(f"output {str(path)!r}: is a device or special file, not a regular file")
    if not os.access(path, os.W_OK):
        raise OutputPathError(f"output {str(path)!r}: exists and is not writable")


def _check_parent(path: Path) -> None:
    ancestor = _nearest_existing(path)
    if not ancestor.is_dir():
        raise OutputPathError(f"output {str(path)!r}: its parent {str(ancestor)!r} is a file, not a folder")
    if not os.access(ancestor, os.W_OK | os.X_OK):
        raise OutputPathError(f"output {str(path)!r}: the folder {str(ancestor)!r} is not writable")


def _check_one(path: Path, kind: str, inputs: list[Path]) -> None:
    long_part = _name_too_long(path)
    if long_part is not None:
        raise OutputPathError(
            f"output {str(path)[:80]!r}…: a name of {len(os.fsencode(long_part))} bytes; "
            "file names may have at most 255"
        )
    for source in inputs:
        if _same_file(path, source):
            raise OutputPathError(
                f"output {str(path)!r}: is the input {str(source)!r}; "
                "carousel-theory never writes over a recording — choose another output"
            )
    _check_kind(path, kind)
    _check_parent(path)


def plan_outputs(
    outputs: Iterable[tuple[PathLike | None, Literal["file", "directory"]]],
    inputs: Iterable[PathLike] = (),
) -> list[PlannedOutput]:
    """Check every output against the policy, before any work starts.

    Parameters
    ----------
    outputs : iterable of (path or None, "file" | "directory")
        The outputs a command was asked for; ``None`` entries (an option not given) are skipped.
    inputs : iterable of path
        Files the command reads; no output may be, or link to, one of them.

    Raises
    ------
    OutputPathError
        Naming the output and the rule it breaks.
    """
    sources = [Path(p) for p in inputs]
    planned: list[PlannedOutput] = []
    for raw, kind in outputs:
        if raw is None:
            continue
        path = Path(raw)
        _check_one(path, kind, sources)
        for earlier in planned:
            if _same_file(earlier.path, path):
                raise OutputPathError(f"output {str(path)!r}: named twice; give each output its own path")
        planned.append(PlannedOutput(path, kind))
    return planned


@contextlib.contextmanager
def atomic_output(path: PathLike, suffix: str | None = None) -> Iterator[Path]:
    """Yield a temporary path in the target's folder; on success rename it over ``path``.

    The caller writes the whole output to the yielded path (``savefig``, ``np.savez``, ``open``). If
    the block raises, the temporary file is removed and ``path`` is untouched.
    """
    target = Path(path)
    _check_kind(target, "file")
    target.parent.mkdir(parents=True, exist_ok=True)
    ending = target.suffix if suffix is None else suffix
    handle, temporary_name = tempfile.mkstemp(
        prefix=f".{target.name[:200]}.", suffix=ending, dir=target.parent
    )
    os.close(handle)
    temporary = Path(temporary_name)
    try:
        yield temporary
        if target.exists():
            os.chmod(temporary, stat.S_IMODE(target.stat().st_mode))
        else:
            os.chmod(temporary, 0o666 & ~_umask())
        os.replace(temporary, target)
    except BaseException:
        with contextlib.suppress(OSError):
            temporary.unlink()
        raise


def _umask() -> int:
    current = os.umask(0)
    os.umask(current)
    return current


def write_bytes_atomic(path: PathLike, data: bytes) -> None:
    """Write ``data`` to ``path`` completely or not at all (see :func:`atomic_output`)."""
    with atomic_output(path) as temporary, open(temporary, "wb") as stream:
        stream.write(data)
        stream.flush()
        try:
            os.fsync(stream.fileno())
        except OSError as error:  # some file systems do not sync; the rename is still atomic
            if error.errno not in (errno.EINVAL, errno.ENOTSUP):
                raise


def write_text_atomic(path: PathLike, text: str) -> None:
    """Write ``text`` (UTF-8) to ``path`` completely or not at all."""
    write_bytes_atomic(path, text.encode("utf-8"))
