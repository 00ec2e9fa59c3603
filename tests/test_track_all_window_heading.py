"""Decision L108: `pdrlearn track-all` takes `track`'s --window START,END (L105) and --initial-heading DEG (L98),
parsed by the same code before the first session; what depends on a session (a window inside its recording, a
relative heading) is checked per session: that session fails with `track`'s error line, the others are tracked."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pandas as pd
import pytest

from pdrlearn.cli import main


@pytest.fixture(scope="module")
def tree(tmp_path_factory) -> Path:
    """study/a/p01 (12 m, 20.3 s, no waist magnetometer), study/a/p02 (the same walk with its magnetometer: an
    absolute heading offline), study/b/p03 (3 m, 13.6 s, no magnetometer)."""
    from pdrlearn import sim
    from pdrlearn.io import write_session

    root = tmp_path_factory.mktemp("tw") / "study"
    for where, length in (("a/p01", 12), ("a/p02", 12), ("b/p03", 3)):
        write_session(sim.simulate("walk", 1, length_m=length), root / where)
    for where in ("a/p01", "b/p03"):
        (root / where / "wMagneticField.csv").unlink()
    return root


def test_track_all_window_and_initial_heading_are_per_session(tree, tmp_path, capsys):
    args = ["--window", "2,16", "--initial-heading", "90"]
    assert main(["track-all", str(tree), "--out", str(tmp_path / "b"), *args]) == 1  # some sessions failed
    capsys.readouterr()
    s = pd.read_csv(tmp_path / "b" / "sessions.csv").set_index("path")
    assert list(s["status"]) == ["ok", "failed", "ok"]
    # the window counts from each session's start: the 13.6 s recording's window is clipped to 2-13.6 s, said in
    # its warnings (decision B242; refused before)
    assert s.loc["b/p03", "window_end_s"] == pytest.approx(13.6)
    assert "--window 2,16 ends after the recording, which lasts 13.60 s" in s.loc["b/p03", "warnings"]
    # the magnetometer's heading is absolute: --initial-heading refused for that session only (L98's check)
    assert "absolute" in s.loc["a/p02", "error"] and "drop --initial-heading" in s.loc["a/p02", "error"]
    ok = s.loc["a/p01"]
    assert ok["window_start_s"] == 2.0 and ok["window_end_s"] == 16.0
    # the batch's session is what `track` gives with the same options
    assert main(["track", "--no-plot", str(tree / "a/p01"), "--out", str(tmp_path / "one"), *args]) == 0
    one = json.loads((tmp_path / "one" / "summary.json").read_text())
    got = json.loads((tmp_path / "b" / "a/p01" / "summary.json").read_text())
    assert got["info"]["initial_heading_rad"] == pytest.approx(math.pi / 2)
    assert got["info"]["window"] == {"start_s": 2.0, "end_s": 16.0}
    for k in ("n_steps", "distance_m", "final_position", "window_start_s", "window_end_s"):
        assert got[k] == one[k], k
    assert ok["n_steps"] == one["n_steps"] and ok["distance_m"] == pytest.approx(one["distance_m"])
    # and the window's track set off north: its end lies north of its start (ENU, 90 deg)
    tr = pd.read_csv(tmp_path / "b" / "a/p01" / "trajectory.csv")
    dx, dy = tr["x"].iloc[-1] - tr["x"].iloc[0], tr["y"].iloc[-1] - tr["y"].iloc[0]
    assert dy > 5.0 and abs(dx) < 0.3 * dy


@pytest.mark.parametrize(("args", "says"), [
    (["--window", "5,2"], "--window '5,2': END 2 s must be later than START 5 s"),
    (["--window", "0"], "--window '0': expected two numbers START,END"),
    (["--initial-heading", "nan"], "--initial-heading nan: give the start direction as a finite number"),
])
def test_track_all_bad_window_or_heading_is_one_line_before_any_session(tree, tmp_path, capsys, monkeypatch,
                                                                          args, says):
    import pdrlearn.cli.cohort as cohort

    monkeypatch.setattr(cohort, "find_sessions", lambda *a, **k: pytest.fail("looked for sessions first"))
    capsys.readouterr()
    assert main(["track-all", str(tree), "--out", str(tmp_path / "o"), *args]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: ") and says in err[0], err
    assert not (tmp_path / "o").exists()
