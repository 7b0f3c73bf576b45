"""The output policy: refuse before work, write completely or not at all, never over an input."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from carousel_theory.output_files import (
    OutputPathError,
    atomic_output,
    plan_outputs,
    write_bytes_atomic,
    write_text_atomic,
)


@pytest.fixture
def recording(tmp_path: Path) -> Path:
    path = tmp_path / "a.csv"
    path.write_text("t,wx\n0,1\n0.01,2\n", encoding="utf-8")
    return path


def test_output_equal_to_input_is_refused(recording: Path) -> None:
    with pytest.raises(OutputPathError, match="is the input"):
        plan_outputs([(recording, "file")], inputs=[recording])


def test_output_reaching_input_through_a_symlink_is_refused(recording: Path, tmp_path: Path) -> None:
    link = tmp_path / "link.csv"
    link.symlink_to(recording)
    with pytest.raises(OutputPathError, match="is the input"):
        plan_outputs([(link, "file")], inputs=[recording])


def test_output_reaching_input_through_a_hard_link_is_refused(recording: Path, tmp_path: Path) -> None:
    hard = tmp_path / "hard.csv"
    os.link(recording, hard)
    with pytest.raises(OutputPathError, match="is the input"):
        plan_outputs([(hard, "file")], inputs=[recording])


def test_output_through_a_relative_spelling_of_the_input_is_refused(
    recording: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(recording.parent)
    with pytest.raises(OutputPathError, match="is the input"):
        plan_outputs([(Path("./sub/../a.csv"), "file")], inputs=[recording])


def test_parent_that_is_a_file_is_refused(recording: Path) -> None:
    with pytest.raises(OutputPathError, match="is a file, not a folder"):
        plan_outputs([(recording / "x.md", "file")], inputs=[])


def test_device_is_refused() -> None:
    with pytest.raises(OutputPathError, match="special file"):
        plan_outputs([(Path("/dev/full"), "file")])


def test_name_over_255_bytes_is_refused(tmp_path: Path) -> None:
    with pytest.raises(OutputPathError, match="at most 255"):
        plan_outputs([(tmp_path / ("x" * 300 + ".md"), "file")])


def test_folder_named_as_file_output_is_refused(tmp_path: Path) -> None:
    with pytest.raises(OutputPathError, match="is a folder"):
        plan_outputs([(tmp_path, "file")])


def test_file_named_as_folder_output_is_refused(recording: Path) -> None:
    with pytest.raises(OutputPathError, match="not a folder"):
        plan_outputs([(recording, "directory")])


def test_same_output_twice_is_refused(tmp_path: Path) -> None:
    with pytest.raises(OutputPathError, match="named twice"):
        plan_outputs([(tmp_path / "r.md", "file"), (tmp_path / "." / "r.md", "file")])


def test_unwritable_folder_is_refused_before_work(tmp_path: Path) -> None:
    locked = tmp_path / "locked"
    locked.mkdir()
    locked.chmod(0o500)
    try:
        if os.access(locked, os.W_OK):
            pytest.skip("running as a user who may write anywhere (root): permissions cannot be tested")
        with pytest.raises(OutputPathError, match="not writable"):
            plan_outputs([(locked / "r.md", "file")])
    finally:
        locked.chmod(0o700)


def test_missing_options_are_skipped_and_valid_ones_planned(tmp_path: Path) -> None:
    planned = plan_outputs([(None, "file"), (tmp_path / "new" / "deeper" / "r.md", "file")])
    assert [p.path for p in planned] == [tmp_path / "new" / "deeper" / "r.md"]
    assert not (tmp_path / "new").exists(), "planning must not create anything"


def test_atomic_write_creates_parents_and_writes_everything(tmp_path: Path) -> None:
    target = tmp_path / "a" / "b" / "r.md"
    write_text_atomic(target, "é\n")
    assert target.read_text(encoding="utf-8") == "é\n"
    assert sorted(p.name for p in target.parent.iterdir()) == ["r.md"]


def test_failing_write_leaves_the_old_file_and_no_temporary(tmp_path: Path) -> None:
    target = tmp_path / "r.md"
    target.write_text("old", encoding="utf-8")
    with pytest.raises(RuntimeError), atomic_output(target) as temporary:
        temporary.write_text("half", encoding="utf-8")
        raise RuntimeError("interrupted")
    assert target.read_text(encoding="utf-8") == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["r.md"]


def test_atomic_write_keeps_the_permissions_of_the_file_it_replaces(tmp_path: Path) -> None:
    target = tmp_path / "r.bin"
    target.write_bytes(b"old")
    target.chmod(0o640)
    write_bytes_atomic(target, b"new")
    assert target.read_bytes() == b"new"
    assert (target.stat().st_mode & 0o777) == 0o640
