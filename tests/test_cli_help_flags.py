"""typer 0.29's help showed every boolean flag as ``--json <bool>``, which read as if it took a value: our flags
now show no type (their ``metavar`` is empty); typer's own ``--help`` line keeps its ``<bool>``."""

from __future__ import annotations

import typer.main

from pdrlearn.cli import app, main


def _help_lines(capsys, argv: list[str]) -> list[str]:
    assert main([*argv, "--help"]) == 0
    return capsys.readouterr().out.splitlines()


def test_no_flag_but_typers_help_shows_a_bool_type(capsys, monkeypatch):
    monkeypatch.setenv("COLUMNS", "160")
    names = sorted(typer.main.get_command(app).commands)
    assert {"track", "train", "evaluate", "train-all"} <= set(names)
    for argv in ([], *([n] for n in names)):
        bad = [ln for ln in _help_lines(capsys, argv) if "<bool>" in ln and "--help" not in ln]
        assert not bad, (argv, bad)


def test_flags_still_parse_as_flags(tmp_path, capsys):
    # an empty metavar changes the help only: a flag given a value is refused as before
    assert main(["track", str(tmp_path), "--out", str(tmp_path / "o"), "--json=3"]) == 2
    assert "does not take a value" in capsys.readouterr().err
