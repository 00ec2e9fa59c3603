"""Decisions E158 / E159 (docs/decisions/export.md): the model manifest (``train``) and the bundle manifest
(``export``) record the git commit of the code that wrote them (no key outside a git checkout), and their creation
time honours SOURCE_DATE_EPOCH, so a re-export of one model is byte-identical."""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

import pdrlearn
from pdrlearn.buildinfo import git_stamp
from pdrlearn.cli import main
from pdrlearn.export.bundle import base_manifest
from tests.cli_helpers import simulated_session_and_model

REPO = Path(pdrlearn.__file__).resolve().parent.parent


def test_train_and_export_stamp_the_commit_and_honour_source_date_epoch(tmp_path, monkeypatch, capsys):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1700000000")
    _, model = simulated_session_and_model(tmp_path)
    head = subprocess.run(["git", "-C", str(REPO), "rev-parse", "HEAD"], capture_output=True, text=True,
                          check=True).stdout.strip()
    trained = json.loads((model / "manifest.json").read_text())
    assert trained["git_commit"] == head and isinstance(trained["git_dirty"], bool)
    assert trained["created"] == "2023-11-14T22:13:20+00:00"
    for out in ("b1", "b2"):
        assert main(["export", str(model), "--out", str(tmp_path / out)]) == 0
    b1, b2 = (json.loads((tmp_path / b / "manifest.json").read_text()) for b in ("b1", "b2"))
    assert b1["git_commit"] == head and b1["created_utc"] == "2023-11-14T22:13:20+00:00"
    assert (tmp_path / "b1" / "manifest.sha256").read_bytes() == (tmp_path / "b2" / "manifest.sha256").read_bytes()
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "yesterday")
    capsys.readouterr()
    assert main(["export", str(model), "--out", str(tmp_path / "b3")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "SOURCE_DATE_EPOCH 'yesterday' is not a whole number of seconds" in err
    assert not (tmp_path / "b3").exists()  # nothing half-written


def test_no_commit_key_outside_a_git_checkout(tmp_path, monkeypatch):
    monkeypatch.setattr(pdrlearn, "__file__", str(tmp_path / "site-packages" / "pdrlearn" / "__init__.py"))
    assert git_stamp() == {}
    m = base_manifest(user="u")
    assert "git_commit" not in m and "git_dirty" not in m and m["created_utc"]
