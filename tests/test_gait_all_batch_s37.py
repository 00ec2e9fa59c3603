"""Cohort C115 / C116 (session 37): `gait-all --jobs N` pairs the visit folders on N worker processes and writes the
serial run's bytes; `gait-all --resume` goes on from an interrupted or earlier run without pairing the finished pairs
again. Simulated users 9100-9109 only (here 9100-9103)."""

from __future__ import annotations

import contextlib
import io
import json
import os
import shutil
import subprocess
from pathlib import Path

import pytest

from pdrlearn.cli import main

ROUTE = "stand:2, straight:10, stand:2"


def _foot(folder: Path, foot: str, user: int, visit: str, seed: int) -> None:
    assert main(["simulate", "--route", ROUTE, "--user-seed", str(user), "--seed", str(seed), "--rate", "50",
                 "--foot", foot, "--out", str(folder), "--subject", f"P{user}", "--visit", visit]) == 0


def _meta(folder: Path, **fields) -> None:
    meta = json.loads((folder / "meta.json").read_text())
    (folder / "meta.json").write_text(json.dumps({**meta, **fields}))


@pytest.fixture(scope="module")
def study(tmp_path_factory) -> Path:
    """Four visit folders with both feet (P9102/visit1's two feet on different clocks: gait refuses it) and one with
    the left foot only."""
    root = tmp_path_factory.mktemp("gaitall") / "study"
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        for user, visit, seed in ((9100, "visit1", 1), (9100, "visit2", 2), (9101, "visit1", 3), (9102, "visit1", 4)):
            for foot in ("left", "right"):
                _foot(root / f"P{user}" / visit / foot[0].upper(), foot, user, visit, seed)
        _foot(root / "P9103" / "visit1" / "L", "left", 9103, "visit1", 5)
    _meta(root / "P9102" / "visit1" / "L", clock_id="watch-a")  # decision L283: refused, a failed row
    _meta(root / "P9102" / "visit1" / "R", clock_id="watch-b")
    return root


def _run(*args, stdout: list | None = None) -> tuple[int, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        rc = main(["gait-all", *map(str, args)])
    if stdout is not None:
        stdout.append(out.getvalue())
    return rc, err.getvalue()


def _files(folder: Path, said: bool = True) -> dict[str, bytes]:
    """Every file of a gait-all output, the hidden pair records included (``said=False``: without the warnings a
    record keeps as said, C129, which name the ROOT of the run that said them)."""
    out = {}
    for p in sorted(folder.rglob("*")):
        if p.is_file():
            data = p.read_bytes()
            if not said and p.parent.name == ".gait-all-pairs":
                record = json.loads(data)
                record["value"].pop("warnings", None)
                record.pop("value_sha256", None)  # the record's hash of its value, warnings included
                data = json.dumps(record, sort_keys=True).encode()
            out[p.relative_to(folder).as_posix()] = data
    return out


@pytest.fixture(scope="module")
def serial(study, tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("serial") / "o"
    rc, err = _run(study, "--out", out)
    assert rc == 1, err  # the refused pair
    return out


@pytest.mark.extended  # D57: test_gait_all_warnings_c129's --jobs 2 run still equals the serial one by default
def test_gait_all_jobs_writes_the_serial_runs_bytes_c115(study, serial, tmp_path):
    out = tmp_path / "par"
    rc, err = _run(study, "--out", out, "--jobs", "2")
    assert rc == 1, err
    lines = [ln for ln in err.splitlines() if ln.startswith("[")]
    assert len(lines) == 5 and {ln.split("]")[0] for ln in lines} == {f"[{k}/5" for k in range(1, 6)}, err
    assert sum("P9102/visit1: failed: " in ln and "clock" in ln for ln in lines) == 1, err
    assert sum("P9103/visit1: no pair: 1 left and 0 right" in ln for ln in lines) == 1, err
    got, ref = _files(out), _files(serial)
    assert sorted(got) == sorted(ref) and len([n for n in ref if n.startswith(".gait-all-pairs/")]) == 3
    assert got == ref  # byte for byte, the records included


@pytest.mark.parametrize("jobs", ["0", "-1", "two"])
def test_gait_all_jobs_must_be_a_positive_integer_c115(study, tmp_path, jobs):
    rc, err = _run(study, "--out", tmp_path / "o", "--jobs", jobs)
    assert rc == 2 and len(err.strip().splitlines()) == 1 and "Traceback" not in err, err
    assert "'--jobs'" in err and "Input should be" in err, err
    assert not (tmp_path / "o").exists()


def test_gait_all_resume_after_an_interrupt_pairs_only_the_rest_c116(study, serial, tmp_path, monkeypatch):
    import pdrlearn.track.bilateral as bilateral

    real, calls = bilateral.pair_sessions, []

    def interrupted(left, right):
        calls.append(Path(left).parent)
        if len(calls) == 3:  # Ctrl-C while the third pair is tracked
            raise KeyboardInterrupt
        return real(left, right)

    monkeypatch.setattr(bilateral, "pair_sessions", interrupted)
    out = tmp_path / "o"
    rc, err = _run(study, "--out", out)
    assert rc != 0 and not out.exists(), err
    assert "gait-all: interrupted after 2 pair(s); they are kept in a temporary folder beside OUT" in err, err
    # the command's process has ended (as a Ctrl-C'd `pdrlearn gait-all` has): its folder named with an ended pid
    (left,) = [p for p in tmp_path.iterdir() if p.name.startswith(f".o.tmp-{os.getpid()}-")]
    ended = subprocess.Popen(["true"])
    ended.wait()
    left.rename(left.with_name(left.name.replace(f"-{os.getpid()}-", f"-{ended.pid}-")))
    calls.clear()
    monkeypatch.setattr(bilateral, "pair_sessions", lambda left, right: calls.append(Path(left).parent)
                        or real(left, right))
    said = []
    rc, err = _run(study, "--out", out, "--resume", stdout=said)
    assert rc == 1, err
    assert [c.relative_to(study).as_posix() for c in calls] == ["P9101/visit1", "P9102/visit1"], err
    assert "P9100/visit1: reused, " in err and "P9100/visit2: reused, " in err, err
    assert "3 of 5 visit folder(s) paired (2 reused from an earlier run, --resume)" in said[0], said
    assert _files(out) == _files(serial)  # the uninterrupted run's bytes
    assert sorted(p.name for p in tmp_path.iterdir()) == ["o"]  # the adopted temporary folder removed


def test_gait_all_resume_pairs_again_a_failed_or_changed_pair_c116(study, serial, tmp_path):
    root = tmp_path / "study"
    shutil.copytree(study, root)
    out = tmp_path / "o"
    shutil.copytree(serial, out)  # the study moved: its records still hold (paths below ROOT)
    _meta(root / "P9102" / "visit1" / "R", clock_id="watch-a")  # the failed pair fixed
    left = root / "P9100" / "visit2" / "L" / "meta.json"
    left.write_text(left.read_text() + "\n")  # the same meaning, other bytes
    rc, err = _run(root, "--out", out, "--resume")
    assert rc == 0, err
    lines = {ln.split("] ")[1].split(":")[0]: ln for ln in err.splitlines() if ln.startswith("[")}
    assert "reused" not in lines["P9102/visit1"] and ": ok, " in lines["P9102/visit1"], err
    assert "recomputed, input files changed: left meta.json since the earlier run" in lines["P9100/visit2"], err
    assert ": reused, " in lines["P9100/visit1"] and ": reused, " in lines["P9101/visit1"], err
    fresh = tmp_path / "fresh"
    assert _run(root, "--out", fresh)[0] == 0
    # C129: a record keeps the warnings as they were said, naming the study's folder of that run (it moved here)
    assert _files(out, said=False) == _files(fresh, said=False)
    # without --resume an existing OUT is still refused (as before)
    assert _run(root, "--out", out)[0] == 2


def test_a_record_cut_short_leaves_no_temporary_file_c116(tmp_path, monkeypatch):
    """Closing re-read (session 37): the record writer (then write_file_record) wrote its own ``.part`` file, left
    behind when the write failed; it now goes through the project's atomic writer (whole or absent, nothing else)."""
    from pathlib import Path as P

    from pdrlearn.cli.resume import write_record

    real = P.write_text

    def broken(self, text, *a, **k):
        real(self, text[:10], *a, **k)
        raise OSError("disk full")

    monkeypatch.setattr(P, "write_text", broken)
    with pytest.raises(OSError, match="disk full"):
        write_record(tmp_path / "recs" / "a.json", "k", {}, {"row": 1})
    monkeypatch.setattr(P, "write_text", real)
    assert sorted(p.name for p in (tmp_path / "recs").iterdir()) == []
    assert write_record(tmp_path / "recs" / "a.json", "k", {}, {"row": 1}) == {"row": 1}
    assert sorted(p.name for p in (tmp_path / "recs").iterdir()) == ["a.json"]
