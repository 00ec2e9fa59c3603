"""Batch robustness (decisions B151, B152): a full disk or a refused output folder stops `track-all` at once with one
line naming OUT and the fix, exit 2, nothing left behind; figures are closed even when saving them fails."""

from __future__ import annotations

import errno
import shutil
from pathlib import Path

import pytest

from pdrlearn.cli import main


@pytest.fixture(scope="module")
def tree(tmp_path_factory) -> Path:
    """study/p01/walk, study/p02/walk, study/p03/walk: short simulated walks."""
    from pdrlearn import sim
    from pdrlearn.io import write_session

    root = tmp_path_factory.mktemp("robust") / "study"
    write_session(sim.simulate("walk", 11, length_m=10), root / "p01" / "walk")
    for p in ("p02", "p03"):
        shutil.copytree(root / "p01" / "walk", root / p / "walk")
    return root


def _disk_full(*_a, **_k):
    raise OSError(errno.ENOSPC, "No space left on device")


def test_a_full_disk_stops_the_batch_at_the_first_session(tree, tmp_path, monkeypatch, capsys):
    """B151/B152: was 3 sessions each 'failed: OSError ...', then exit 1."""
    import matplotlib.pyplot as plt

    from pdrlearn.cli import track as T

    calls = []
    real = T.write_track

    def full(tmp, tracked):
        calls.append(tmp)
        real(tmp, tracked)  # the figure is drawn ...
        _disk_full()  # ... and then the disk is full

    monkeypatch.setattr(T, "write_track", full)
    plt.close("all")
    out = tmp_path / "o"
    rc = main(["track-all", str(tree), "--out", str(out)])
    _, err = capsys.readouterr()
    assert rc == 2
    assert len(calls) == 1
    last = err.strip().splitlines()[-1]
    assert last == (f"error: {out}: No space left on device; free space on its disk or choose an output folder on "
                    "another disk (decision B151)")
    assert "Traceback" not in err and "[2/3]" not in err
    assert not out.exists() and sorted(p.name for p in tmp_path.iterdir()) == []  # the temporary folder is gone
    assert plt.get_fignums() == []


def test_a_full_disk_while_writing_sessions_csv_is_one_line(tree, tmp_path, monkeypatch, capsys):
    """B151: was a pandas traceback from _write_csv_atomic and exit 1."""
    from pdrlearn.cli import cohort as C

    monkeypatch.setattr(C, "_write_csv_atomic", _disk_full)
    out = tmp_path / "o"
    assert main(["track-all", str(tree), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert f"error: {out}: No space left on device; free space" in err and "Traceback" not in err
    assert not out.exists() and list(tmp_path.iterdir()) == []


def test_a_read_only_output_folder_exits_2(tree, tmp_path, monkeypatch, capsys):
    """B152: an output place the system refuses (here a read-only file system) is bad input, exit 2, not 1."""
    import pdrlearn.atomic as A

    def read_only(*_a, dir=None, **_k):
        raise OSError(errno.EROFS, "Read-only file system", str(dir))

    monkeypatch.setattr(A.tempfile, "mkdtemp", read_only)
    out = tmp_path / "o"
    assert main(["track-all", str(tree), "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err == (f"error: {out}: Read-only file system; choose an output folder you can write to, or fix its "
                   "permissions (decision B151)")


def test_a_figure_is_closed_when_saving_it_fails(tmp_path, monkeypatch):
    """B151: a failed save left the figure open (matplotlib's 'More than 20 figures' after 20 sessions)."""
    import matplotlib.pyplot as plt

    from pdrlearn.plots import save_atomic

    plt.close("all")
    fig = plt.figure()
    monkeypatch.setattr(fig, "savefig", _disk_full)
    with pytest.raises(OSError):
        save_atomic(fig, tmp_path / "f.png")
    assert plt.get_fignums() == []
