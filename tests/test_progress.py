"""The progress counter: drawn when enabled, silent otherwise, and its line ended even when the
consumer stops early (an open-ended counter closed by its user)."""

from __future__ import annotations

import io
import itertools

from carousel_theory.progress import progress


def test_a_counter_closed_early_still_ends_its_line():
    stream = io.StringIO()
    ticks = progress(itertools.count(), label="evaluations", stream=stream, enabled=True)
    for _ in range(3):
        next(ticks)
    ticks.close()
    text = stream.getvalue()
    assert text.endswith("\n") and text.count("\n") == 1  # redraws are rate-limited; the end is not


def test_the_last_item_of_a_known_total_is_drawn():
    stream = io.StringIO()
    assert list(progress(range(3), label="runs", stream=stream, enabled=True)) == [0, 1, 2]
    assert stream.getvalue().split("\r")[-1].startswith("runs 3/3")


def test_nothing_is_written_when_not_enabled():
    stream = io.StringIO()
    assert list(progress(range(5), label="x", stream=stream, enabled=False)) == [0, 1, 2, 3, 4]
    assert stream.getvalue() == ""


def test_a_stream_that_is_not_a_terminal_stays_clean():
    stream = io.StringIO()
    ticks = progress(itertools.count(), stream=stream)
    next(ticks)
    ticks.close()
    assert stream.getvalue() == ""
