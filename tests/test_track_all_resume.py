"""Cohort C41: `track-all --resume` reuses the sessions an interrupted (killed) or earlier run tracked from the same
inputs and options, tracks the rest, and writes the tables an uninterrupted run writes, byte for byte."""

from __future__ import annotations

import contextlib
import io
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from pdrlearn.cli import main
from pdrlearn.cli.resume import RECORD

REPO = Path(__file__).resolve().parent.parent
TABLES = ("sessions.csv", "groups.csv", "subjects.csv", "changes.csv", "changes_summary.csv")


@pytest.fixture(scope="module")
def study(tmp_path_factory) -> Path:
    """Three subjects x two visits (foot + waist, and waist-only sessions) and one session without sensor files."""
    from pdrlearn import sim
    from pdrlearn.io import write_session

    root = tmp_path_factory.mktemp("resume") / "study"
    for i in range(6):
        d = root / ("a" if i % 2 == 0 else "b") / f"S{i // 2}" / ("v1", "v2")[i % 2]
        write_session(sim.simulate("walk", 990 + i, length_m=10 + i), d)
        meta = json.loads((d / "meta.json").read_text())
        (d / "meta.json").write_text(json.dumps({**meta, "subject": f"S{i // 2}", "visit": ("v1", "v2")[i % 2]}))
        if i % 3 == 2:
            for f in d.glob("f*.csv"):
                f.unlink()
    (root / "b" / "S9" / "v1").mkdir(parents=True)
    (root / "b" / "S9" / "v1" / "meta.json").write_text('{"subject": "S9", "visit": "v1"}')  # fails
    return root


def _run(*args: str) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        rc = main(["track-all", "--no-plot", *map(str, args)])
    return rc, out.getvalue(), err.getvalue()


@pytest.fixture(scope="module")
def tracked(study, tmp_path_factory) -> tuple[Path, Path]:
    """A copy of the study and its uninterrupted run, made once for the tests that each tracked such a copy first
    (decision D54): ``(root, out)``, read-only (:func:`first_run` hands each test its own state)."""
    base = tmp_path_factory.mktemp("tracked")
    root, out = base / "study", base / "o"
    shutil.copytree(study, root)
    assert _run(root, "--out", out)[0] == 1
    return root, out


@pytest.fixture
def restored(study, tracked) -> tuple[Path, Path]:
    """:func:`tracked`'s copy of the study restored (an earlier test edited it; it stays at its path, which the
    sessions' resume keys hold) and its uninterrupted run, read-only: ``(root, out)``."""
    root, out = tracked
    shutil.rmtree(root)
    shutil.copytree(study, root)
    return root, out


@pytest.fixture
def first_run(restored, tmp_path) -> tuple[Path, Path]:
    """:func:`restored`'s study and a copy of its run in ``tmp_path / "o"``: the state a test's own first run left."""
    root, out = restored
    shutil.copytree(out, tmp_path / "o")
    return root, tmp_path / "o"


def _files(folder: Path) -> dict[str, bytes]:
    """Every file of a batch output but run.json (its times differ run to run, decision C18)."""
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*"))
            if p.is_file() and p.name != "run.json"}


def test_a_killed_batch_resumes_and_writes_the_uninterrupted_tables(restored, tmp_path):
    """The uninterrupted run it is compared with is :func:`tracked`'s, of the same (restored) study folder (decision
    D58: it tracked the study a second time for itself)."""
    study, reference = restored
    out = tmp_path / "o"
    env = {**os.environ, "PYTHONPATH": str(REPO), "OMP_NUM_THREADS": "1"}
    proc = subprocess.Popen([sys.executable, "-m", "pdrlearn", "track-all", "--no-plot", str(study), "--out", str(out)],
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, env=env)
    seen = []
    for line in proc.stderr:  # killed (SIGKILL: no clean-up at all) once two sessions are done
        seen.append(line)
        if line.startswith("[2/7]"):
            proc.kill()
            break
    proc.wait()
    proc.stderr.close()
    assert any(s.startswith("[2/7]") for s in seen), seen
    assert not out.exists() and list(tmp_path.glob(".o.tmp-*"))  # what the kill left: the batch's temporary folder
    done = len(list(tmp_path.glob(f".o.tmp-*/*/*/*/{RECORD}")))  # the sessions complete when it was killed
    assert 2 <= done < 6
    rc, stdout, err = _run(study, "--out", out, "--resume")
    assert rc == 1
    n = int(stdout.split("sessions tracked (")[1].split(" reused")[0])
    assert n == done  # each session complete before the kill, and only those
    assert err.count(": reused, ") == n and "[7/7]" in err
    for name in TABLES:
        assert (out / name).read_bytes() == (reference / name).read_bytes(), name
    assert _files(out) == _files(reference)  # the session folders too
    run = json.loads((out / "run.json").read_text())
    assert run["n_reused"] == n and len(run["reused"]) == n and run["options"]["resume"] is True
    assert not list(tmp_path.glob(".o.*"))  # the interrupted run's folder went into OUT


def test_resume_tracks_again_what_changed_or_is_incomplete(first_run):
    root, out = first_run
    before = (out / "sessions.csv").read_bytes()
    rc, _, err = _run(root, "--out", out)  # without --resume an existing output is refused, as before
    assert rc == 2 and "--force" in err
    meta = root / "a" / "S0" / "v1" / "meta.json"
    meta.write_text(meta.read_text().replace("}", ', "note": "x"}', 1))  # an input file changed
    (out / "b" / "S1" / "v2" / "steps.csv").unlink()  # an output incomplete
    rc, stdout, err = _run(root, "--out", out, "--resume")
    assert rc == 1 and "(4 reused from an earlier run, --resume)" in stdout  # 6 tracked - 1 changed - 1 incomplete
    for rel in ("a/S0/v1", "b/S1/v2", "b/S9/v1"):  # tracked again (a failed session is never reused)
        assert f"] {rel}: reused" not in err
    assert (out / "b" / "S1" / "v2" / "steps.csv").is_file() and (out / "sessions.csv").read_bytes() == before
    rc, stdout, _ = _run(root, "--out", out, "--resume", "--storey-height", "2.9")  # an option changed
    assert "(0 reused" in stdout
    rc, stdout, _ = _run(root, "--out", out, "--resume", "--storey-height", "2.9", "--jobs", "1")
    assert "(6 reused" in stdout  # --jobs is not part of a session's output


def test_resume_says_why_a_session_was_tracked_again_as_gait_all_c135(first_run):
    """Cohort C135: track-all's line of a session whose record was found but not reused names what changed, in
    gait-all's words (C116: ``recomputed, input files changed: left meta.json since the earlier run``), through the
    one check both commands share."""
    root, out = first_run
    meta = root / "a" / "S0" / "v1" / "meta.json"
    meta.write_text(meta.read_text() + "\n")  # the same meaning, other bytes
    (out / "b" / "S1" / "v2" / "steps.csv").unlink()
    rc, _, err = _run(root, "--out", out, "--resume")
    lines = {ln.split("] ")[1].split(":")[0]: ln for ln in err.splitlines() if ln.startswith("[")}
    assert lines["a/S0/v1"].endswith(" s; recomputed, input files changed: meta.json since the earlier run)"), err
    assert "; recomputed, its folder in OUT is incomplete or edited since the earlier run)" in lines["b/S1/v2"], err
    assert "recomputed" not in lines["b/S9/v1"] and ": reused, " in lines["a/S1/v1"], err  # failed: no record
    rc, _, err = _run(root, "--out", out, "--resume", "--storey-height", "2.9")
    assert err.count("; recomputed, the options, model, calibration file, session folder or pdrlearn's code "
                     "changed since the earlier run)") == 6, err


def test_one_reuse_check_gives_both_commands_the_same_reason_c135(tmp_path):
    """Cohort C135: a pair record (gait-all) and a session folder's record (track-all) with the same input file
    changed give the same words; intact and unchanged, both are reused."""
    from pdrlearn.cli.resume import reusable, write_record

    folder = tmp_path / "session"
    folder.mkdir()
    (folder / "steps.csv").write_text("t\n1\n")
    old, new = {"meta.json": "a", "f.csv": "b"}, {"meta.json": "c", "f.csv": "b"}
    write_record(folder / RECORD, "k", old, {"x": 1}, outputs=folder)
    write_record(tmp_path / "pair.json", "k", {"left": old, "right": old}, {"x": 1})
    _, _, track = reusable([folder / RECORD], "k", new, key_changed="-", outputs=True)
    _, _, gait = reusable([tmp_path / "pair.json"], "k", {"left": new, "right": old}, key_changed="-")
    assert track == "input files changed: meta.json" and gait == "input files changed: left meta.json"
    assert reusable([folder / RECORD], "k", old, key_changed="-", outputs=True) == (folder / RECORD, {"x": 1}, None)
    assert reusable([tmp_path / "pair.json"], "k", {"left": old, "right": old}, key_changed="-")[1:] == ({"x": 1}, None)
