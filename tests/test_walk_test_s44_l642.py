"""Decision L642 (session 44, FF, trial T1 finding F1): a timed corridor walk test starts at "go" - the first step
after the last standstill before the first full lap (a walk to the start line and a wait) - or at
``--walk-test-start`` / meta.json ``walk_test_start_s``."""

from __future__ import annotations

import json

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.track.corridor import corridor_laps
from tests.walk_test_s44_helpers import laps_after, strides, turns_at


def _walk_to_start_and_wait():
    """4 strides to the start cone, a turn at 4.5 s, standing until "go" at 30 s, then 9 laps of 30 m (trial T1's
    P06, shortened to 1 s strides of 1 m)."""
    t, cones = laps_after(30.0, 9)
    return strides(np.concatenate([np.arange(4.0), t])), turns_at([4.5, *cones])


def test_the_test_starts_after_the_wait_for_go_l642():
    steps, turns = _walk_to_start_and_wait()
    laps, s, warnings = corridor_laps(steps, turns, 30.0, duration_s=270.0)
    assert s["walk_test_start_s"] == pytest.approx(30.0)
    # L740: the 9th lap ends at the timer (no cone turn inside the test): 8 laps + a 30 m partial lap
    assert s["n_laps"] == 8 and s["walk_test_distance_m"] == pytest.approx(270.0)
    assert s["walk_test_distance_per_minute_m"] == pytest.approx([60.0] * 4)
    line = [w for w in warnings if "L642" in w]
    assert len(line) == 1 and "started at 30.0 s" in line[0] and "26.0 s standstill" in line[0]
    assert "4.0 m walked before it are not scored" in line[0]
    # L516's first step, asked for: the old start (the walk to the cone and the wait inside the test)
    _, old, w_old = corridor_laps(steps, turns, 30.0, duration_s=270.0, start="first-step")
    assert old["walk_test_start_s"] == 0.0 and old["walk_test_distance_m"] < 250.0 and not [w for w in w_old
                                                                                          if "L642" in w]
    # a time given is taken as given
    _, given, _ = corridor_laps(steps, turns, 30.0, duration_s=270.0, start=29.5)
    assert given["walk_test_start_s"] == 29.5 and given["n_laps"] == 8  # L740: 8 laps + 29.5 m


def test_a_rest_inside_the_first_lap_is_no_go_l642():
    """10 m of lap 1, 20 s standing, the 20 m left of it: the walk after the rest is no full lap, so no "go"."""
    t, cones = laps_after(50.0, 5)
    steps = strides(np.concatenate([np.arange(10.0), np.arange(30.0, 50.0), t]))
    _, s, warnings = corridor_laps(steps, turns_at([50.0, *cones]), 30.0, duration_s=200.0)
    assert s["walk_test_start_s"] == 0.0 and not [w for w in warnings if "L642" in w]


def test_a_track_that_lost_steps_has_no_go_l642():
    """The same walk to the start tracked at 0.15 m a stride (a pipeline losing steps, L646): its gaps are not
    known standstills, the test starts at the first step."""
    steps, turns = _walk_to_start_and_wait()
    _, s, warnings = corridor_laps(steps.assign(length_m=0.15), turns, 30.0, duration_s=270.0)
    assert s["walk_test_start_s"] == 0.0 and not [w for w in warnings if "L642" in w]


ROUTE = ("stand:3, straight:4, turn:180, stand:12, straight:15, turn:180, straight:15, turn:180, straight:15, "
         "stand:3")


@pytest.fixture(scope="module")
def walk_to_start(tmp_path_factory):
    """User 12400: 4 m to the start cone, a turn, 12 s standing, then 3 x 15 m."""
    ses = tmp_path_factory.mktemp("l642") / "study" / "P1" / "v1"
    assert main(["simulate", "--route", ROUTE, "--step-length", "0.5", "--step-time", "0.6", "--bounce",
                 "pendulum", "--user-seed", "12400", "--rate", "100", "--out", str(ses)]) == 0
    return ses


def _go(out) -> float:
    return json.loads((out / "summary.json").read_text())["walk_test_start_s"]


def test_track_and_track_all_start_at_go_or_the_given_start_l642(walk_to_start, tmp_path, capsys):
    ses = walk_to_start
    first = min(float(x) for x in np.loadtxt(ses / "ics.csv", delimiter=",", skiprows=1, usecols=0, ndmin=1)) / 1000
    base = ["--units", "waist", "--corridor", "15", "--walk-test-duration", "40", "--no-plot"]
    assert main(["track", str(ses), *base, "--out", str(tmp_path / "auto")]) == 0
    err = capsys.readouterr().err
    go = _go(tmp_path / "auto")
    assert go > first + 15.0 and "L642" in err  # after the 12 s standstill, not the first step
    assert main(["track", str(ses), *base, "--walk-test-start", "first-step", "--out", str(tmp_path / "fs")]) == 0
    assert _go(tmp_path / "fs") < first + 1.0
    # a session's own "go" in meta.json, read by track-all (its --window is one span for every session)
    meta = json.loads((ses / "meta.json").read_text())
    (ses / "meta.json").write_text(json.dumps({**meta, "walk_test_start_s": 12.5}))
    try:
        assert main(["track-all", str(ses.parent.parent), *base, "--out", str(tmp_path / "all")]) == 0
        summary = next((tmp_path / "all").rglob("summary.json"))
        assert json.loads(summary.read_text())["walk_test_start_s"] == 12.5
        # --walk-test-start SECONDS wins over meta.json
        assert main(["track", str(ses), *base, "--walk-test-start", "20", "--out", str(tmp_path / "s20")]) == 0
        assert _go(tmp_path / "s20") == 20.0
    finally:
        (ses / "meta.json").write_text(json.dumps(meta))


def test_a_start_after_the_walk_is_one_line_l642(walk_to_start, tmp_path, capsys):
    capsys.readouterr()
    assert main(["track", str(walk_to_start), "--units", "waist", "--corridor", "15", "--walk-test-duration", "40",
                 "--walk-test-start", "900", "--no-plot", "--out", str(tmp_path / "o")]) != 0
    text = capsys.readouterr().err
    err = [x for x in text.splitlines() if x.startswith("error")]
    assert len(err) == 1 and "walk test's start 900 s" in err[0] and "Traceback" not in text
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("args, words", [(["--walk-test-duration", "360", "--walk-test-start", "soon"], "auto"),
                                         (["--walk-test-duration", "360", "--walk-test-start=-3"], "seconds"),
                                         (["--walk-test-start", "37"], "add --walk-test-duration")])
def test_a_bad_walk_test_start_is_one_line_l642(walk_to_start, tmp_path, capsys, args, words):
    capsys.readouterr()
    assert main(["track", str(walk_to_start), "--units", "waist", "--corridor", "15", *args, "--no-plot",
                 "--out", str(tmp_path / "o")]) != 0
    err = [x for x in capsys.readouterr().err.splitlines() if x.strip()]
    assert len(err) == 1 and "--walk-test-start" in err[0] and words in err[0] and "Traceback" not in err[0]
    assert not (tmp_path / "o").exists()


def test_the_test_minutes_start_at_go_c178_l642(walk_to_start, tmp_path):
    """The lead's merge of C178 (``--per`` follows the walk test by default) with L642 (the test starts at go): the
    periods start at the test's go, not at the walk to the start cone."""
    base = ["--units", "waist", "--corridor", "15", "--walk-test-duration", "40", "--no-plot", "--per", "10s"]
    assert main(["track", str(walk_to_start), *base, "--out", str(tmp_path / "per")]) == 0
    s = json.loads((tmp_path / "per" / "summary.json").read_text())
    assert s["per_start_s"] == pytest.approx(s["walk_test_start_s"])
