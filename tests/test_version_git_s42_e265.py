"""Decision E265 (session 42, fixer FT, review R2 finding 5): `pdrlearn --version` run from a git checkout where git
cannot run (not on PATH, or refusing a checkout owned by another user) said "neither a git checkout nor a wheel with a
build stamp", a false statement in the line a paper is asked to cite; it now says git could not be run there."""

from __future__ import annotations

import pdrlearn
from pdrlearn import __version__
from pdrlearn.buildinfo import version_line
from pdrlearn.cli import main as cli_main


def test_version_in_a_checkout_without_git_says_git_could_not_run(tmp_path, monkeypatch, capsys):
    (tmp_path / ".git").mkdir()  # a checkout beside the package: git_state asks git, which is not on PATH
    pkg = tmp_path / "pdrlearn"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    monkeypatch.setattr(pdrlearn, "__file__", str(pkg / "__init__.py"))
    monkeypatch.setenv("PATH", "")
    assert cli_main(["--version"]) == 0
    out = capsys.readouterr().out.strip()
    assert out.startswith(f"pdrlearn {__version__} (commit unknown: git could not be run in the checkout {tmp_path}")
    assert "neither a git checkout" not in out and f"safe.directory {tmp_path}" in out


def test_version_line_without_a_checkout_keeps_its_reason():
    assert version_line("0.1.0", None, None) == \
        "pdrlearn 0.1.0 (commit unknown: neither a git checkout nor a wheel with a build stamp)"
