"""Decision B441 (session 43, trial T2 F8): an output the system refuses is named as the user gave it, never as the
atomic write's temporary folder: ``simulate --out rodir/s`` said ``rodir/.s.tmp-12963-h91819895-qx5i7afo:
Read-only file system``; it now checks the place before simulating (B317's check, as track, run and export) and
``atomic_directory`` names the target for an error in its temporary folder."""

from __future__ import annotations

import errno
import os
from pathlib import Path

import pytest

from pdrlearn.atomic import atomic_directory


def test_simulate_into_a_read_only_folder_names_it_before_simulating(tmp_path, monkeypatch, capsys):
    import pdrlearn.sim as sim
    from pdrlearn.cli import main

    real_access = os.access
    ro = tmp_path / "rodir"
    ro.mkdir()
    monkeypatch.setattr(os, "access", lambda p, mode, **k: False if (Path(p) == ro and mode & os.W_OK)
                        else real_access(p, mode, **k))
    simulated = []
    monkeypatch.setattr(sim, "simulate", lambda *a, **k: simulated.append(a))
    out = ro / "s"
    assert main(["simulate", "--scenario", "A", "--user-seed", "12082", "--out", str(out)]) == 2
    assert capsys.readouterr().err.strip() == (f"error: {out}: Permission denied; choose an output folder you can "
                                               "write to, or fix its permissions (decision B151)")
    assert simulated == [] and list(ro.iterdir()) == []


def test_atomic_directory_names_the_target_not_its_temporary_folder(tmp_path, monkeypatch):
    import pdrlearn.atomic as A

    target = tmp_path / "s"
    with pytest.raises(OSError) as exc:  # a file written in the temporary folder: named under the target
        with atomic_directory(target) as tmp:
            raise PermissionError(errno.EACCES, "Permission denied", str(tmp / "meta.json"))
    assert (exc.value.errno, exc.value.filename) == (errno.EACCES, str(target / "meta.json"))
    assert isinstance(exc.value, PermissionError) and exc.value.__cause__ is None
    with pytest.raises(OSError) as exc:  # another file: as it was
        with atomic_directory(target):
            raise OSError(errno.ENOENT, "No such file or directory", str(tmp_path / "input.csv"))
    assert exc.value.filename == str(tmp_path / "input.csv")

    def read_only(*_a, dir=None, prefix="", **_k):
        raise OSError(errno.EROFS, "Read-only file system", os.path.join(dir, prefix + "qx5i7afo"))

    monkeypatch.setattr(A.tempfile, "mkdtemp", read_only)
    with pytest.raises(OSError) as exc:  # T2 F8: the temporary folder's random name
        with atomic_directory(target):
            pass
    assert (exc.value.errno, exc.value.filename) == (errno.EROFS, str(target))
    assert list(tmp_path.iterdir()) == []
