"""Progress reporting for long work: shown on a terminal, silent when piped."""

from __future__ import annotations

import sys
import time
from collections.abc import Iterable, Iterator
from typing import TextIO, TypeVar

T = TypeVar("T")

__all__ = ["progress"]


def progress(
    items: Iterable[T],
    total: int | None = None,
    label: str = "",
    stream: TextIO | None = None,
    enabled: bool | None = None,
) -> Iterator[T]:
    """Yield ``items`` unchanged, drawing a one-line progress counter on ``stream`` (stderr).

    The counter is drawn only when ``stream`` is a terminal (or ``enabled=True``), so output
    that is piped or captured stays clean. It redraws at most ten times a second.
    """
    stream = sys.stderr if stream is None else stream
    if enabled is None:
        enabled = bool(getattr(stream, "isatty", lambda: False)())
    if not enabled:
        yield from items
        return
    if total is None and hasattr(items, "__len__"):
        total = len(items)  # type: ignore[arg-type]
    start = last = time.monotonic()
    try:
        for count, item in enumerate(items, start=1):
            yield item
            now = time.monotonic()
            if now - last >= 0.1 or count == total:
                last = now
                of = f"/{total}" if total else ""
                stream.write(f"\r{label} {count}{of}  {now - start:6.1f} s")
                stream.flush()
    finally:  # also when the consumer stops early (an open-ended counter closed by its user)
        stream.write("\n")
        stream.flush()
