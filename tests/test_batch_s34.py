"""Batch-workflow robustness (session 34, trial T4): dangling links (B315), a thread-safe pipeline registry (B316),
a read-only OUT checked before the work (B317), a session without strides (B318), SIGTERM and stale temporary
folders (B319), `simulate --force`'s line and the losing concurrent writer (B320). Simulated users 8000-8019."""

from __future__ import annotations

import json
import os
import shutil
from pathlib import Path

import pytest

from pdrlearn.cli import main


@pytest.fixture(scope="module")
def walk(tmp_path_factory) -> Path:
    """One short simulated walk (user 8000)."""
    from pdrlearn import sim
    from pdrlearn.io import write_session

    return write_session(sim.simulate("walk", 8000, length_m=10), tmp_path_factory.mktemp("s34") / "walk")


def _linked_copy(walk: Path, dest: Path, dangling: dict[str, str]) -> Path:
    """A copy of ``walk`` whose files named in ``dangling`` are symbolic links to the given missing targets."""
    shutil.copytree(walk, dest)
    for name, target in dangling.items():
        (dest / name).unlink()
        (dest / name).symlink_to(target)
    return dest


def test_a_dangling_sensor_link_is_one_line_naming_its_target(walk, tmp_path, capsys):
    """B315: was read as a missing gyroscope (warning 'waist unit incomplete', rc 0, a worse track)."""
    s = _linked_copy(walk, tmp_path / "s", {"wGyroscope.csv": "/nowhere/wGyroscope.csv"})
    out = tmp_path / "o"
    assert main(["track", str(s), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.strip().splitlines()[-1] == (
        f"error: {s / 'wGyroscope.csv'}: a symbolic link to /nowhere/wGyroscope.csv, which does not exist (a storage "
        "not mounted, or git-annex/DataLad content not fetched); fetch or mount it, or remove the link (decision B315)")
    assert not out.exists()


def test_a_folder_under_a_sensor_file_name_says_so(walk, tmp_path):
    """B315: was 'file not found', which is not what is wrong."""
    from pdrlearn.errors import DataError
    from pdrlearn.io import read_session

    s = tmp_path / "s"
    shutil.copytree(walk, s)
    (s / "wBarometer.csv").unlink()
    (s / "wBarometer.csv").mkdir()
    with pytest.raises(DataError, match=r"wBarometer.csv: is a folder, not a file; put the wBarometer.csv file there"):
        read_session(s)


def test_track_all_fails_sessions_of_dangling_links_instead_of_skipping_them(walk, tmp_path, capsys):
    """B315 (T4 finding 1): a session folder that is a dangling link, and a real folder holding only dangling links,
    were skipped (rc 0, n_sessions 1); now each is a failed session naming the link's target, exit 1."""
    root = tmp_path / "study"
    shutil.copytree(walk, root / "p01" / "walk")
    (root / "p02").mkdir()
    (root / "p02" / "walk").symlink_to("/mnt/storage_unmounted/p02/walk")
    (root / "p03" / "walk").mkdir(parents=True)
    for p in walk.iterdir():
        (root / "p03" / "walk" / p.name).symlink_to(f"/annex/objects/{p.name}")
    out = tmp_path / "o"
    rc = main(["track-all", "--no-plot", str(root), "--out", str(out), "--json"])
    captured = capsys.readouterr()
    assert rc == 1
    summary = json.loads(captured.out)
    assert (summary["n_sessions"], summary["n_tracked"], summary["n_failed"]) == (3, 1, 2)
    assert "a symbolic link to /mnt/storage_unmounted/p02/walk, which does not exist" in captured.err
    assert "a symbolic link to /annex/objects/" in captured.err


def test_a_cold_registry_read_from_threads_is_filled_once_for_all():
    """B316 (T4 finding 3): the first `get_pipeline` from 4 threads failed with "unknown pipeline 'plasys'; choose
    one of" (empty list): a thread arriving during the fill saw `_loading` and read the empty registry."""
    import threading
    import time
    from concurrent.futures import ThreadPoolExecutor

    from pdrlearn.plugins import Registry

    fills = []
    started = threading.Event()

    def fill():  # as importing the built-in pipelines' modules: takes a while, registers as it goes
        fills.append(1)
        started.set()
        time.sleep(0.3)
        reg.register("plasys", print)

    reg = Registry("pipeline", "pdrlearn.test_no_such_group", load_builtins=fill)

    def read(_):
        if _:
            started.wait(5)  # the others arrive while the first fills
        return reg["plasys"]

    with ThreadPoolExecutor(4) as ex:
        got = list(ex.map(read, range(4)))
    assert got == [print] * 4 and fills == [1]


def test_get_pipeline_from_threads_in_a_fresh_interpreter():
    """B316 with the real registry, cold in a new interpreter (trial T4's race.py: failed 6 runs of 6)."""
    import subprocess
    import sys

    code = ("from concurrent.futures import ThreadPoolExecutor\n"
            "from pdrlearn import get_pipeline\n"
            "with ThreadPoolExecutor(4) as ex:\n"
            "    got = list(ex.map(lambda _: get_pipeline('waist-pll'), range(8)))\n"
            "print(len(set(map(id, got))))\n")
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300,
                         env={**os.environ, "PYTHONPATH": str(Path(__file__).resolve().parents[1])})
    assert (run.returncode, run.stdout.strip()) == (0, "1"), run.stderr[-500:]


def test_a_read_only_output_place_is_refused_before_the_work(walk, tmp_path, monkeypatch, capsys):
    """B317 (T4 finding 4): a read-only OUT failed after the whole track, naming `.out.tmp-PID-XXXX`; now the nearest
    existing folder above OUT is checked first and the line names OUT (B151's line)."""
    import pdrlearn.io as io

    real_access = os.access
    ro = tmp_path / "ro"
    ro.mkdir()
    monkeypatch.setattr(os, "access", lambda p, mode, **k: False if (Path(p) == ro and mode & os.W_OK)
                        else real_access(p, mode, **k))
    read = []
    monkeypatch.setattr(io, "read_session", lambda *a, **k: read.append(a))
    out = ro / "sub" / "out"
    assert main(["track", str(walk), "--out", str(out), "--json"]) == 2
    captured = capsys.readouterr()
    assert captured.out == "" and read == []
    assert captured.err.strip().splitlines()[-1] == (
        f"error: {out}: Permission denied; choose an output folder you can write to, or fix its permissions "
        "(decision B151)")


@pytest.fixture(scope="module")
def still(tmp_path_factory) -> Path:
    """60 s standing still (user 8001): no stride."""
    from pdrlearn import sim
    from pdrlearn.io import write_session

    return write_session(sim.simulate("standstill", 8001), tmp_path_factory.mktemp("s34still") / "still")


def test_no_strides_names_the_folder_and_exits_4(still, tmp_path, capsys):
    """B318 (T4 finding 5): was `session 'sim_standstill_...': no strides detected`, exit 2 (bad input); a session
    without walking is a data outcome: the line names the folder, exit 4; stdout empty, nothing written."""
    out = tmp_path / "o"
    assert main(["track", "--no-plot", str(still), "--out", str(out), "--json"]) == 4
    captured = capsys.readouterr()
    assert captured.out == "" and not out.exists()
    assert captured.err.strip().splitlines()[-1].startswith(f"error: {still}: no strides detected; is the foot unit "
                                                            "moving?")


def test_sigterm_is_handled_as_ctrl_c(walk, tmp_path):
    """B319 (T4 finding 6): SIGTERM (SLURM, Snakemake) ended `track` silently (rc 143 from the kill, nothing on
    stderr) and left `.o.tmp-PID-XXXX`; now one line, the temporary folder removed, exit 143."""
    import subprocess
    import sys

    out = tmp_path / "res" / "o"
    code = ("import os, signal, sys\n"
            "import pdrlearn.cli.track as T\n"
            "from pdrlearn.cli import main\n"
            "real = T.write_track\n"
            "def write(tmp, tracked):\n"
            "    real(tmp, tracked)\n"
            "    os.kill(os.getpid(), signal.SIGTERM)  # while the output is being written\n"
            "T.write_track = write\n"
            f"sys.exit(main(['track', '--no-plot', {str(walk)!r}, '--out', {str(out)!r}]))\n")  # no figure read
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300,
                         env={**os.environ, "PYTHONPATH": str(Path(__file__).resolve().parents[1])})
    assert run.returncode == 143, run.stderr[-500:]
    assert run.stderr.strip().splitlines()[-1] == "error: terminated; nothing written"
    assert "Traceback" not in run.stderr and run.stdout == ""
    assert list((tmp_path / "res").iterdir()) == []  # neither OUT nor its temporary folder


def test_a_temporary_folder_of_another_pid_namespace_is_not_taken_for_stale(tmp_path, caplog):
    """B320 (T4 finding 6): B44's kill(pid, 0) called a live writer in another PID namespace (`unshare -p`, a
    container, another node) gone, and deleted its folder. A folder tagged with another machine/namespace is stale
    only when marked ended by its writer (Ctrl-C, SIGTERM) or unchanged for FOREIGN_QUIET_S."""
    import time

    from pdrlearn import atomic

    target = tmp_path / "o"
    other = "0" * 8 if atomic.machine_tag() != "0" * 8 else "1" * 8
    live = tmp_path / f".o.tmp-999999999-h{other}-live"  # a process id this namespace does not have
    quiet = tmp_path / f".o.tmp-999999998-h{other}-quiet"
    ended = tmp_path / f".o.tmp-999999997-h{other}-ended"
    mine = tmp_path / f".o.tmp-999999996-h{atomic.machine_tag()}-dead"  # this namespace: checked by kill(pid, 0)
    for p in (live, quiet, ended, mine):
        (p / "sub").mkdir(parents=True)
        (p / "sub" / "steps.csv").write_text("x\n")
    past = time.time() - atomic.FOREIGN_QUIET_S - 60
    for p in (quiet, quiet / "sub", quiet / "sub" / "steps.csv"):
        os.utime(p, (past, past))
    os.utime(ended, (atomic.ENDED_MTIME, atomic.ENDED_MTIME))
    gone = atomic.clean_leftovers(target)
    assert sorted(p.name for p in gone) == sorted(p.name for p in (quiet, ended, mine))
    assert live.exists()


def test_a_track_all_stopped_by_sigterm_marks_its_kept_folder_ended(tmp_path, monkeypatch):
    """B319: the temporary folder track-all keeps on an interrupt (for --resume, C41) is marked ended, which a run on
    another node (another tag) reads without a process check; the adopter's own copy is no longer marked (a resumed
    run had deleted the folder it was reading, at its next write)."""
    from pdrlearn import atomic

    target = tmp_path / "o"
    with pytest.raises(KeyboardInterrupt), atomic.atomic_directory(target, keep_on_interrupt=True) as tmp:
        (tmp / "a").mkdir()
        raise KeyboardInterrupt
    assert tmp.is_dir() and tmp.stat().st_mtime == atomic.ENDED_MTIME
    assert atomic.clean_leftovers(target) == []  # this machine: its writer (this process) runs
    other = "0" * 8 if atomic.machine_tag() != "0" * 8 else "1" * 8
    monkeypatch.setattr(atomic, "machine_tag", lambda: other)  # as seen from another node
    adopted = atomic.adopt_leftovers(target)
    assert len(adopted) == 1 and adopted[0].stat().st_mtime > atomic.ENDED_MTIME
    assert atomic.clean_leftovers(target) == [] and (adopted[0] / "a").is_dir()


def test_simulate_force_says_replaced(tmp_path, capsys):
    """B320 (T4 finding 9): `simulate --force` replaced the session without the `replaced PATH` line the other
    commands print."""
    out = tmp_path / "B"
    args = ["simulate", "--scenario", "walk", "--length-m", "5", "--user-seed", "8002", "--out", str(out), "--json"]
    assert main(args) == 0
    assert "replaced" not in capsys.readouterr().err
    assert main([*args[:-1], "--force", "--json"]) == 0
    assert f"replaced {out}" in capsys.readouterr().err.splitlines()


def test_the_losing_concurrent_writer_says_another_process_wrote_it(tmp_path):
    """B320 (T4 finding 10): two runs to the same new --out; the loser said "changed after this command checked it
    ... run the command again" (which then said "pass --force"): it now says another process wrote it."""
    from pdrlearn.atomic import OutputChangedError, atomic_directory, checked_outputs, expect_unchanged

    target = tmp_path / "o"
    with checked_outputs():
        expect_unchanged(target)  # absent when checked
        with pytest.raises(OutputChangedError, match=r"another process wrote its output there while this command "
                           r"ran \(it was absent or empty when checked\); this command's output was not written -- "
                           r"keep that one, or pass --force to replace it"), atomic_directory(target) as tmp:
            (tmp / "summary.json").write_text("mine")
            target.mkdir()
            (target / "summary.json").write_text("the winner's")
    assert (target / "summary.json").read_text() == "the winner's"
    assert [p.name for p in tmp_path.iterdir()] == ["o"]


def test_shell_log_files_in_the_output_folder_are_named_with_the_fix(walk, tmp_path, capsys):
    """E160 (T4 finding 7): `--out D > D/track.json 2> D/track.log` said "exists and does not hold a track"; the
    folder is replaced as a whole (which would delete the logs the shell is writing), so it is still refused, now
    naming the logs and where to put them; the files are untouched."""
    d = tmp_path / "D"
    d.mkdir()
    (d / "track.json").write_text("")
    (d / "track.log").write_text("started\n")
    assert main(["track", str(walk), "--out", str(d), "--json"]) == 2
    line = capsys.readouterr().err.strip().splitlines()[-1]
    assert line.startswith(f"error: {d}: holds track.json, track.log (a shell redirect's log files?), not a track ")
    assert line.endswith(f"the output folder is replaced as a whole, which would delete them -- write the logs beside "
                         f"it (`> {d}.json 2> {d}.log`) or into another folder (decision E160)")
    assert sorted(p.name for p in d.iterdir()) == ["track.json", "track.log"]
    assert (d / "track.log").read_text() == "started\n"
