"""Decisions B330 / B331 (session 34, new-user re-read NU #4, #5): a ``track-all`` whose every session failed for
having no stride exits 4 like ``track`` (B318's data outcome), not 2 (bad input); an interrupted ``track-all``
says it keeps sessions only when it has some. Simulated users 8281-8283."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from pdrlearn.cli import main


@pytest.fixture(scope="module")
def still(tmp_path_factory) -> Path:
    """A standstill session (user 8281): no strides."""
    from pdrlearn import sim
    from pdrlearn.io import write_session

    return write_session(sim.simulate("standstill", 8281), tmp_path_factory.mktemp("b330") / "study" / "still")


def test_track_all_of_only_no_stride_sessions_exits_4_b330(still, tmp_path, capsys):
    out = tmp_path / "o"
    assert main(["track", "--no-plot", str(still), "--out", str(tmp_path / "one")]) == 4  # B318: track alone
    capsys.readouterr()
    assert main(["track-all", "--no-plot", str(still.parent), "--out", str(out)]) == 4  # was 2
    err = capsys.readouterr().err
    assert err.strip().splitlines()[-1].startswith("error: every session failed; first error: still:")
    assert "no strides detected" in err and not out.exists()


def test_track_all_with_another_failure_still_exits_2_b330(still, tmp_path, capsys):
    study = tmp_path / "study"
    shutil.copytree(still, study / "still")
    bad = shutil.copytree(still, study / "bad")
    (bad / "fAccelerometer.csv").write_text("not,a,sensor,file\n1,2\n")  # bad input, not a data outcome
    assert main(["track-all", str(study), "--out", str(tmp_path / "o")]) == 2
    assert "every session failed" in capsys.readouterr().err


@pytest.mark.parametrize("n", [0, 2])
def test_interrupted_line_says_kept_only_when_kept_b331(n):
    from pdrlearn.cli.cohort import _interrupted_line

    line = _interrupted_line(n)
    assert ("kept" in line and "--resume" in line and f"after {n} session(s)" in line) if n else \
        ("no session is kept" in line and "they are kept" not in line and "--resume" not in line)
