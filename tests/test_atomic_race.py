"""atomic_directory replaces only what the command checked (docs/decisions/bad-input.md B20): the old folder is
renamed aside first and compared with what `out_folder` saw; a folder changed meanwhile is put back, and a
target another process creates between the two renames keeps both outputs."""

from __future__ import annotations

from pathlib import Path

import pytest

from pdrlearn.atomic import OutputChangedError, atomic_directory, checked_outputs, expect_unchanged, fingerprint
from pdrlearn.cli import main
from pdrlearn.cli.common import out_folder


def _track_like(folder: Path, text: str = "old") -> Path:
    folder.mkdir()
    for name in ("steps.csv", "trajectory.csv"):
        (folder / name).write_text(text)
    (folder / "summary.json").write_text(_summary(text))  # a track's summary (B26: a run's says "runtime")
    return folder


def _summary(text: str) -> str:
    return f'{{"pipeline": "plasys", "note": "{text}"}}'


def _check(folder: Path) -> None:
    out_folder(folder, "track", force=True)


def test_fingerprint_survives_a_rename_but_not_an_edit(tmp_path):
    a = _track_like(tmp_path / "a")
    fp = fingerprint(a)
    b = a.rename(tmp_path / "b")
    assert fingerprint(b) == fp
    (b / "notes.txt").write_text("x")
    assert fingerprint(b) != fp
    assert fingerprint(tmp_path / "absent") == frozenset()


@pytest.mark.parametrize("change", ["added", "rewritten", "removed"])
def test_folder_changed_after_the_check_is_not_replaced(tmp_path, change):
    target = _track_like(tmp_path / "track")
    with checked_outputs():
        _check(target)
        with pytest.raises(OutputChangedError, match="changed after this command checked it"), \
                atomic_directory(target) as tmp:
            (tmp / "summary.json").write_text("new")
            if change == "added":  # e.g. the user saved notes into the folder while the command ran
                (target / "notes.txt").write_text("precious")
            elif change == "rewritten":  # e.g. another run of the same command finished first
                (target / "summary.json").write_text("the other run's")
            else:
                (target / "steps.csv").unlink()
    assert (target / "summary.json").exists() and [p.name for p in tmp_path.iterdir()] == ["track"]
    if change == "added":
        assert (target / "notes.txt").read_text() == "precious"


def test_unchanged_folder_is_replaced_and_nothing_left_behind(tmp_path):
    target = _track_like(tmp_path / "track")
    with checked_outputs():
        _check(target)
        with atomic_directory(target) as tmp:
            (tmp / "summary.json").write_text("new")
    assert [p.name for p in target.iterdir()] == ["summary.json"]
    assert [p.name for p in tmp_path.iterdir()] == ["track"]


def test_folder_created_after_an_absent_check_is_not_replaced(tmp_path):
    target = tmp_path / "track"
    with checked_outputs():
        _check(target)  # absent: nothing to replace was approved
        with pytest.raises(OutputChangedError), atomic_directory(target) as tmp:
            (tmp / "summary.json").write_text("new")
            _track_like(target, "someone else's")
    assert (target / "summary.json").read_text() == _summary("someone else's")


def test_folder_removed_after_the_check_is_simply_written(tmp_path):
    target = _track_like(tmp_path / "track")
    with checked_outputs():
        _check(target)
        with atomic_directory(target) as tmp:
            (tmp / "summary.json").write_text("new")
            for p in target.iterdir():
                p.unlink()
            target.rmdir()
    assert (target / "summary.json").read_text() == "new"


def test_target_created_between_the_renames_keeps_both(tmp_path, monkeypatch):
    """The window left: after the old folder is set aside another process writes the target. The new
    folder's rename fails, the old one cannot go back under its name, and the error says where it is."""
    target = _track_like(tmp_path / "track")
    real_rename = Path.rename

    def rename(self, dst):
        if self.name.startswith(".track.tmp-"):
            _track_like(target, "third")  # the other process wins the name
        return real_rename(self, dst)

    monkeypatch.setattr(Path, "rename", rename)
    with pytest.raises(OutputChangedError, match="previous output is kept in") as err, \
            atomic_directory(target) as tmp:
        (tmp / "summary.json").write_text("new")
    kept = Path(str(err.value).split("kept in ")[1])
    assert (kept / "summary.json").read_text() == _summary("old")
    assert (target / "summary.json").read_text() == _summary("third")


def test_old_set_aside_name_is_fresh(tmp_path):
    """A leftover `.track.old-*` of a crashed run (or a recycled pid) is never overwritten or reused."""
    target = _track_like(tmp_path / "track")
    stale = tmp_path / ".track.old-1"
    stale.mkdir()
    (stale / "x").write_text("leftover")
    with atomic_directory(target) as tmp:
        (tmp / "summary.json").write_text("new")
    assert (stale / "x").read_text() == "leftover"
    assert (target / "summary.json").read_text() == "new"


def test_library_call_without_a_check_replaces_as_before(tmp_path):
    target = _track_like(tmp_path / "track")
    expect_unchanged(target)  # outside checked_outputs(): not recorded
    with atomic_directory(target) as tmp:
        (tmp / "summary.json").write_text("new")
        (target / "notes.txt").write_text("x")
    assert [p.name for p in target.iterdir()] == ["summary.json"]


def test_cli_track_force_refuses_a_folder_changed_while_it_ran(tmp_path, monkeypatch, capsys):
    """End to end: `track --force` on a folder that gained a file after the check keeps it (exit 2, one line)."""
    session = tmp_path / "A"
    assert main(["simulate", "-s", "A", "-u", "1", "--out", str(session), "--json"]) == 0
    out = tmp_path / "t"
    assert main(["track", "--no-plot", str(session), "--method", "M2", "--out", str(out), "--json"]) == 0
    import pdrlearn.outfolder as outfolder  # decision E169: out_folder's checks are the library's

    real = outfolder.expect_unchanged

    def expect_then_edit(folder):
        real(folder)
        (Path(folder) / "notes.txt").write_text("written while track ran")

    monkeypatch.setattr(outfolder, "expect_unchanged", expect_then_edit)
    capsys.readouterr()
    assert main(["track", str(session), "--method", "M2", "--out", str(out), "--force", "--json"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"error: {out}: changed after this command checked it")
    assert (out / "notes.txt").read_text() == "written while track ran"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["A", "t"]
