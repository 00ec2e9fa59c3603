"""pdrlearn.atomic.atomic_directory: when the new folder cannot be moved into place, the previous result is
put back under its own name (before, it was left renamed aside as `.NAME.old-PID`: `--force` lost it)."""

from __future__ import annotations

from pathlib import Path

import pytest

from pdrlearn.atomic import atomic_directory


def test_previous_folder_is_restored_when_the_final_rename_fails(tmp_path, monkeypatch):
    target = tmp_path / "track"
    target.mkdir()
    (target / "summary.json").write_text("old")
    real_rename = Path.rename

    def rename(self, dst):
        if self.name.startswith(".track.tmp-"):
            raise OSError(39, "Directory not empty")  # e.g. another process created the target meanwhile
        return real_rename(self, dst)

    monkeypatch.setattr(Path, "rename", rename)
    with pytest.raises(OSError), atomic_directory(target) as tmp:
        (tmp / "summary.json").write_text("new")
    assert (target / "summary.json").read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["track"]  # no temporary or set-aside folder left


def test_success_replaces_and_leaves_nothing_behind(tmp_path):
    target = tmp_path / "track"
    target.mkdir()
    (target / "summary.json").write_text("old")
    with atomic_directory(target) as tmp:
        (tmp / "summary.json").write_text("new")
    assert (target / "summary.json").read_text() == "new"
    assert [p.name for p in tmp_path.iterdir()] == ["track"]
