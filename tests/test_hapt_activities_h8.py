"""Decision H8: `track` and `track-all` do not read HAPT's activities.csv (H4's labels): the whole recording is
tracked and pooled, and they say so -- `track-all` in one line for the batch, naming the sessions that have it, with
how to track walking only (--window, experiments/hapt.py)."""

from __future__ import annotations

from pathlib import Path

import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.io.external.hapt import ACTIVITIES_FILE, activities_line
from pdrlearn.sim import simulate

LABELS = "start_ms,end_ms,activity\n0,9980,standing\n10000,29980,walking\n"


@pytest.fixture(scope="module")
def batch(tmp_path_factory):
    root = tmp_path_factory.mktemp("h8")
    for name, user in (("h1", 4760), ("h2", 4761), ("plain", 4762)):
        write_session(simulate("A", user, seed=user), root / "all" / name)
    for name in ("h1", "h2"):
        (root / "all" / name / ACTIVITIES_FILE).write_text(LABELS)
    return root


def test_the_line_only_for_a_session_with_the_labels(batch):
    line = activities_line(batch / "all" / "h1")
    assert line is not None and "decision H8" in line and "--window START,END" in line
    assert "sitting, standing, lying" in line and "experiments/hapt.py" in line
    assert activities_line(batch / "all" / "plain") is None
    assert activities_line(Path(batch / "all" / "missing")) is None


def test_track_all_says_it_once_for_the_batch(batch, capsys):
    assert main(["track-all", "--no-plot", str(batch / "all"), "--out", str(batch / "out")]) == 0
    err = capsys.readouterr().err.splitlines()
    said = [ln for ln in err if "decision H8" in ln]
    assert len(said) == 1 and said[0].startswith("warning: h1, h2: activities.csv: its activity labels are not read")
    assert "[2 of 3 sessions]" in said[0]
    assert main(["track", "--no-plot", str(batch / "all" / "plain"), "--out", str(batch / "t")]) == 0
    assert "decision H8" not in capsys.readouterr().err
