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


def test_ctrl_c_says_in_one_line_what_was_written(tmp_path, monkeypatch, capsys):
    """Decision B96 (session 19 teaching trial): Ctrl-C ended a command with exit code 130 and no line."""
    import pdrlearn.io
    import pdrlearn.sim
    from pdrlearn.cli import main

    def interrupt(*args, **kwargs):
        raise KeyboardInterrupt

    out = tmp_path / "sim"
    with monkeypatch.context() as m:
        m.setattr(pdrlearn.sim, "simulate", interrupt)
        assert main(["simulate", "--scenario", "A", "-u", "1", "--out", str(out)]) == 130
    assert capsys.readouterr().err.strip() == "error: interrupted (Ctrl-C); nothing written"
    assert not out.exists()
    real = pdrlearn.io.write_session

    def write_then_interrupt(session, folder, **kw):
        real(session, folder, **kw)
        raise KeyboardInterrupt

    monkeypatch.setattr(pdrlearn.io, "write_session", write_then_interrupt)
    assert main(["simulate", "--scenario", "standstill", "-u", "1", "--out", str(out)]) == 130
    assert capsys.readouterr().err.strip().endswith(f"error: interrupted (Ctrl-C); written before it: {out}; "
                                                    "nothing else")
    assert (out / "meta.json").is_file()
