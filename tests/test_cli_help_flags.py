"""typer 0.29's help showed every boolean flag as ``--json <bool>``, which read as if it took a value: our flags
and typer's own ``--help`` now show no type (their ``metavar`` is empty). Docstring paragraphs are reflowed to
the terminal's width (typer kept each source line break)."""

from __future__ import annotations

import typer.main

from pdrlearn.cli import app, main


def _help_lines(capsys, argv: list[str]) -> list[str]:
    assert main([*argv, "--help"]) == 0
    return capsys.readouterr().out.splitlines()


def test_no_flag_shows_a_bool_type(capsys, monkeypatch):
    monkeypatch.setenv("COLUMNS", "160")
    names = sorted(typer.main.get_command(app).commands)
    assert {"track", "train", "evaluate", "train-all"} <= set(names)
    for argv in ([], *([n] for n in names)):
        bad = [ln for ln in _help_lines(capsys, argv) if "<bool>" in ln]
        assert not bad, (argv, bad)


def test_flags_still_parse_as_flags(tmp_path, capsys):
    # an empty metavar changes the help only: a flag given a value is refused as before
    assert main(["track", str(tmp_path), "--out", str(tmp_path / "o"), "--json=3"]) == 2
    assert "does not take a value" in capsys.readouterr().err


def test_docstring_paragraphs_wrap_at_the_terminal_width(capsys, monkeypatch):
    monkeypatch.setenv("COLUMNS", "160")
    lines = [" ".join(ln.split()) for ln in _help_lines(capsys, ["steps"])]
    # one source paragraph of two lines (broken after "against"): at 160 columns its first line goes on
    (line,) = [ln for ln in lines if ln.startswith("Foot detectors find")]
    assert "are scored against steps.csv (ic_ms); waist detectors" in line


def test_reflow_keeps_indented_examples():
    from pdrlearn.cli import reflow_paragraphs

    doc = """Title line.

    Prose that goes
    on here.

    Examples:

        pdrlearn x --a \\
            --b
    """
    assert reflow_paragraphs(doc) == ("Title line.\n\nProse that goes on here.\n\nExamples:\n\n"
                                      "    pdrlearn x --a \\\n        --b")
