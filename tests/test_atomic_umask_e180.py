"""Decision E180: the atomic writers read the umask without changing it (trial T7 #8: os.umask twice per call)."""

from __future__ import annotations

import os
import stat

import pytest

from pdrlearn import atomic


@pytest.mark.skipif(not os.path.exists("/proc/self/status"), reason="Linux /proc only")
def test_atomic_writers_do_not_touch_the_process_umask_e180(tmp_path, monkeypatch):
    mask = os.umask(0o027)
    os.umask(mask)
    calls: list = []
    real = os.umask
    monkeypatch.setattr(os, "umask", lambda m: calls.append(m) or real(m))
    try:
        real(0o027)
        with atomic.atomic_directory(tmp_path / "out") as d:
            (d / "a.txt").write_text("x")
        with atomic.atomic_file(tmp_path / "f.txt") as f:
            f.write_text("y")
    finally:
        real(mask)
    assert calls == []  # E180: read from /proc/self/status, never set
    assert stat.S_IMODE((tmp_path / "out").stat().st_mode) == 0o750  # 0o777 & ~0o027, as mkdir gives
    assert stat.S_IMODE((tmp_path / "f.txt").stat().st_mode) == 0o640


def test_umask_falls_back_when_proc_says_nothing_e180(tmp_path, monkeypatch):
    status = tmp_path / "status"
    status.write_text("Name:\tpython\nUmask:\t0027\n")
    assert atomic._proc_umask(status) == 0o027
    status.write_text("Name:\tpython\n")  # a kernel before 4.7: no Umask field
    assert atomic._proc_umask(status) is None
    assert atomic._proc_umask(tmp_path / "absent") is None
    monkeypatch.setattr(atomic, "_proc_umask", lambda: None)
    mask = os.umask(0o022)
    os.umask(mask)
    assert atomic._umask() == mask  # the old way, and the umask restored
    assert os.umask(mask) == mask
