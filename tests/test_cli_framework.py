"""The command framework: every sub-command registers, bad arguments exit 2 with a message."""

from __future__ import annotations

import pytest

from carousel_theory.cli import build_parser, main


def test_every_subcommand_has_a_handler():
    parser = build_parser()
    subparsers = next(a for a in parser._actions if a.dest == "command")
    assert {"check", "derive"} <= set(subparsers.choices)
    for name, sub in subparsers.choices.items():
        assert callable(sub.get_default("handler")), name


def test_unknown_command_exits_with_usage_error(capsys):
    with pytest.raises(SystemExit) as excinfo:
        main(["no-such-command"])
    assert excinfo.value.code == 2
    assert "invalid choice" in capsys.readouterr().err


def test_missing_matplotlib_is_a_clean_error(monkeypatch, capsys):
    import carousel_theory.cli as cli

    def handler(args):
        raise ModuleNotFoundError("No module named 'matplotlib'", name="matplotlib")

    parser = build_parser()
    monkeypatch.setattr(cli, "build_parser", lambda command=None: parser)
    check_parser = next(a for a in parser._actions if a.dest == "command").choices["check"]
    check_parser.set_defaults(handler=handler)
    assert main(["check"]) == 2
    assert "carousel-theory[plots]" in capsys.readouterr().err


def test_a_command_builds_only_its_own_parser():
    # A run of one command registers that command alone; no command (or an unknown one) registers all.
    only = build_parser("predict")
    choices = next(a for a in only._actions if a.dest == "command").choices
    assert list(choices) == ["predict"]
    every = next(a for a in build_parser()._actions if a.dest == "command").choices
    assert {"allan", "check", "fit", "loop", "predict"} <= set(every)
    unknown = next(a for a in build_parser("nosuch")._actions if a.dest == "command").choices
    assert set(unknown) == set(every)
