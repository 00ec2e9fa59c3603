"""Decision E276 (session 43, trial T2 F1): the lean command's ``--out`` follows ``pdrlearn run``'s rules with the same
standard-library modules (``outfolder.out_folder``, ``atomic.atomic_directory``): a session folder or another
command's output is refused (the session's ground-truth steps.csv was overwritten), its own earlier replay is replaced
only with ``--force``, the output place is checked before the replay, and a full disk leaves nothing half-written."""

from __future__ import annotations

import errno
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from tests.lean_helpers import ROOT, lean_env

SHIPPED = ROOT / "models" / "plasys-sim-default"


@pytest.fixture(scope="module")
def made(tmp_path_factory):
    """Simulated scenario A of user 12080 and `pdrlearn run`'s output folder for it (shipped bundle)."""
    from pdrlearn import sim
    from pdrlearn.cli import main
    from pdrlearn.io import write_session

    root = tmp_path_factory.mktemp("e276")
    write_session(sim.simulate("A", 12080, seed=12080), root / "A")
    assert main(["run", "--no-plot", str(SHIPPED), str(root / "A"), "--out", str(root / "run")]) == 0
    return root


def _lean(*args) -> int:
    from pdrlearn.runtime.__main__ import main

    return main([str(SHIPPED), *map(str, args)])


def _snapshot(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def _error_line(capsys) -> str:
    err = [ln for ln in capsys.readouterr().err.splitlines() if not ln.startswith("warning: ")]
    assert len(err) == 1, err
    return err[0]


def test_the_session_folder_and_a_run_output_are_refused_and_left_as_they_were(made, capsys):
    for folder, what in ((made / "A", "a session (meta.json / sensor files)"),
                         (made / "run", "a run (steps.csv, trajectory.csv, path.png, summary.json), written by "
                                        "`pdrlearn run`")):
        before = _snapshot(folder)
        for force in ((), ("--force",)):
            assert _lean(made / "A", "--out", folder, *force) == 2
            line = _error_line(capsys)
            assert line.startswith(f"error: {folder}: holds {what}, not a lean replay"), line
            assert _snapshot(folder) == before  # T2: the session's ground-truth steps.csv was overwritten


def test_its_own_replay_is_replaced_only_with_force_and_run_refuses_it(made, tmp_path, capsys):
    from pdrlearn.cli import main

    out = tmp_path / "lean"
    assert _lean(made / "A", "--out", out) == 0
    assert sorted(p.name for p in out.iterdir()) == ["replay.json", "steps.csv", "trajectory.csv"]
    summary = json.loads((out / "replay.json").read_text())
    assert summary["n_steps"] >= 10 and summary["out"] == str(out)
    capsys.readouterr()
    assert _lean(made / "A", "--out", out) == 2
    assert _error_line(capsys) == (f"error: {out}: already holds a lean replay (steps.csv, trajectory.csv, "
                                   "replay.json); pass --force to replace it, or choose another output folder")
    (out / "notes.txt").write_text("keep")  # decision B422: --force deletes only what the command wrote
    assert _lean(made / "A", "--out", out, "--force") == 2
    assert "holds notes.txt, which 'python -m pdrlearn.runtime' did not write" in _error_line(capsys)
    (out / "notes.txt").unlink()
    old = (out / "steps.csv").stat().st_ino
    assert _lean(made / "A", "--out", out, "--force") == 0
    assert (out / "steps.csv").stat().st_ino != old and [p.name for p in tmp_path.iterdir()] == ["lean"]
    capsys.readouterr()
    assert main(["run", "--no-plot", str(SHIPPED), str(made / "A"), "--out", str(out), "--force"]) == 2
    assert "holds a lean replay (steps.csv, trajectory.csv, replay.json), written by `python -m pdrlearn.runtime`, " \
           "not a run" in capsys.readouterr().err


def test_a_read_only_place_is_refused_before_the_replay(made, tmp_path, monkeypatch, capsys):
    import pdrlearn.runtime.__main__ as lean

    real_access = os.access
    ro = tmp_path / "ro"
    ro.mkdir()
    monkeypatch.setattr(os, "access", lambda p, mode, **k: False if (Path(p) == ro and mode & os.W_OK)
                        else real_access(p, mode, **k))
    replayed = []
    monkeypatch.setattr(lean, "replay", lambda *a, **k: replayed.append(a))
    out = ro / "x"
    assert _lean(made / "A", "--out", out) == 2
    assert _error_line(capsys) == (f"error: {out}: Permission denied; choose an output folder you can write to, or "
                                   "fix its permissions (decision B151)")
    assert replayed == [] and list(ro.iterdir()) == []  # T2: 34 s of replay, then a traceback at mkdir


def test_a_full_disk_is_one_line_and_leaves_the_previous_replay_whole(made, tmp_path, monkeypatch, capsys):
    import pdrlearn.runtime.__main__ as lean

    out = tmp_path / "lean"
    assert _lean(made / "A", "--out", out) == 0
    before = _snapshot(out)
    real_write = lean._write

    def full_disk(folder, steps, start_s):
        real_write(folder, steps, start_s)
        with (folder / "steps.csv").open("a") as f:  # a partial row, then the disk is full (T2: cut mid-number)
            f.write("12.3")
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(lean, "_write", full_disk)
    capsys.readouterr()
    assert _lean(made / "A", "--out", out, "--force") == 2
    assert _error_line(capsys) == (f"error: {out}: No space left on device; free space on its disk or choose an "
                                   "output folder on another disk (decision B151)")
    assert _snapshot(out) == before and [p.name for p in tmp_path.iterdir()] == ["lean"]  # no temporary folder left
    assert _lean(made / "A", "--out", tmp_path / "new") == 2
    capsys.readouterr()
    assert not (tmp_path / "new").exists()


def test_the_refusal_needs_no_package_of_the_full_install(made, tmp_path):
    before = _snapshot(made / "A")
    r = subprocess.run([sys.executable, "-m", "pdrlearn.runtime", str(SHIPPED), str(made / "A"), "--out",
                        str(made / "A")], capture_output=True, text=True, timeout=300, env=lean_env(tmp_path),
                       cwd=tmp_path)
    assert r.returncode == 2 and r.stderr.count("\n") == 1, r.stderr[-2000:]
    assert r.stderr.startswith(f"error: {made / 'A'}: holds a session")
    assert _snapshot(made / "A") == before


def test_the_sensor_names_the_session_check_uses_are_the_readers():
    from pdrlearn.io.sensors import SENSORS
    from pdrlearn.runtime.replay import SENSOR_KINDS
    from pdrlearn.sensor_names import SENSOR_NAMES

    assert SENSOR_NAMES == tuple(SENSORS) == tuple(SENSOR_KINDS)
