"""Decision E268: ``main`` builds typer's click group once per process, not on every call (``app(...)`` and the
``-v`` hoisting each rebuilt it from every command's signature: about 0.05 s of CPU per call)."""

from __future__ import annotations

import typer.main

from pdrlearn import cli
from pdrlearn.cli import main


def test_the_click_group_is_built_once_for_many_calls_e268(monkeypatch, capsys, tmp_path):
    built = []
    real = typer.main.get_command

    def counting(app):
        built.append(app)
        return real(app)

    monkeypatch.setattr(typer.main, "get_command", counting)
    cli.click_app.cache_clear()
    try:
        for argv in (["info", str(tmp_path / "none")], ["info", str(tmp_path / "none"), "-v"],
                     ["columns", "--help"], ["steps", "--bogus"]):
            assert main(argv) == 2 or argv[-1] == "--help"
        out = capsys.readouterr()
        assert out.err.count("error: ") == 3 and "No such option: --bogus" in out.err  # each call parsed its own line
        assert "Usage:" in out.out and " columns [O" in out.out
        assert len(built) == 1, f"the click group was built {len(built)} times for 4 calls"
    finally:
        cli.click_app.cache_clear()  # later tests build it from the real get_command
