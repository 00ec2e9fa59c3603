"""Decision E264: `pdrlearn --version` prints the git commit (and whether the code differs from it) that git_state
knows: the checkout's, or an installed wheel's `_build.json` stamp (E187), so a paper can cite the code."""

from __future__ import annotations

import pdrlearn.buildinfo as buildinfo
from pdrlearn import __version__
from pdrlearn.cli import main as cli_main

COMMIT = "0123456789abcdef0123456789abcdef01234567"


def test_version_prints_the_checkouts_commit_and_dirty_flag(capsys, monkeypatch):
    monkeypatch.setattr(buildinfo, "git_state", lambda: (COMMIT, True))
    assert cli_main(["--version"]) == 0
    out = capsys.readouterr().out.strip()
    assert out == f"pdrlearn {__version__} (commit {COMMIT}, dirty: the code differs from this commit)"


def test_version_of_a_clean_build_names_only_the_commit(capsys, monkeypatch):
    monkeypatch.setattr(buildinfo, "git_state", lambda: (COMMIT, False))
    assert cli_main(["--version"]) == 0
    assert capsys.readouterr().out.strip() == f"pdrlearn {__version__} (commit {COMMIT})"


def test_version_without_a_known_commit_says_so(capsys, monkeypatch):
    monkeypatch.setattr(buildinfo, "git_state", lambda: (None, None))
    monkeypatch.setattr(buildinfo, "checkout_dir", lambda: None)  # decision E265: not a checkout
    assert cli_main(["--version"]) == 0
    out = capsys.readouterr().out.strip()
    assert out.startswith(f"pdrlearn {__version__} (commit unknown") and "build stamp" in out


def test_version_reads_the_wheels_build_stamp_outside_a_checkout(tmp_path, monkeypatch, capsys):
    """An installed copy (no .git beside the package) prints the commit `_build.json` holds (E187's reader)."""
    import json

    import pdrlearn

    pkg = tmp_path / "site" / "pdrlearn"
    pkg.mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "_build.json").write_text(json.dumps({"git_commit": COMMIT, "git_dirty": False}))
    monkeypatch.setattr(pdrlearn, "__file__", str(pkg / "__init__.py"))
    assert cli_main(["--version"]) == 0
    assert capsys.readouterr().out.strip() == f"pdrlearn {__version__} (commit {COMMIT})"
