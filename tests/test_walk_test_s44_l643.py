"""Decision L643 (session 44, FF, trial T1 finding F2): `--corridor` on a recording whose laps are not a corridor's
(a 3 m TUG) scores no walk test and says why."""

from __future__ import annotations

import json

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.report.clinical import walk_test_line
from pdrlearn.track.corridor import corridor_laps, corridor_line
from tests.walk_test_s44_helpers import strides, turns_at


def _tug():
    """A TUG's walk: 3 strides of 1 m out, a turn, 3 back, a turn (laps of 3 m in ~4 s)."""
    return strides([0.0, 1.0, 2.0, 4.0, 5.0, 6.0], unit="waist"), turns_at([3.5, 7.5])


def test_a_tug_scores_no_corridor_walk_test_l643():
    steps, turns = _tug()
    laps, s, warnings = corridor_laps(steps, turns, 30.0, duration_s=360.0)
    assert s["walk_test_distance_m"] is None and s["n_laps"] is None and s["fatigue_index"] is None
    assert s["walk_test_distance_per_minute_m"] is None and laps.empty
    assert "not a corridor test" in s["walk_test_note"] and "L643" in s["walk_test_note"]
    assert [w for w in warnings if "L643" in w] and not [w for w in warnings if "L644" in w]
    assert "not a corridor test" in corridor_line(s)
    line = walk_test_line(s, "lower-back unit")
    assert line.startswith("- Corridor walk test (6MWT): not scored: not a corridor test")
    # the same laps at a walking lap time (a slow walker whose track lost steps, L646) are still scored
    slow = steps.assign(start_s=steps["start_s"] * 10.0, end_s=steps["end_s"] * 10.0 + 9.0)
    _, s_slow, _ = corridor_laps(slow, turns_at([35.0, 75.0]), 30.0)
    assert s_slow["n_laps"] == 2 and s_slow["walk_test_note"] is not None and "L646" in s_slow["walk_test_note"]


def test_a_simulated_tug_with_corridor_is_not_a_6mwt_l643(tmp_path, capsys):
    """User 12401: a 3 m TUG (main: `1 lap(s), 60.0 m` at 3.9 m/s laps)."""
    ses = tmp_path / "tug"
    assert main(["simulate", "--route", "straight:3, turn:180, straight:3, turn:180", "--sit-start", "5",
                 "--sit-end", "5", "--stand", "0.5", "--step-length", "0.4", "--step-time", "0.7", "--bounce",
                 "pendulum", "--user-seed", "12401", "--rate", "100", "--out", str(ses)]) == 0
    out = tmp_path / "o"
    assert main(["track", str(ses), "--units", "waist", "--corridor", "30", "--walk-test-duration", "360",
                 "--no-plot", "--out", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    assert s["walk_test_distance_m"] is None and s["n_laps"] is None
    assert "not a corridor test" in s["walk_test_note"]
    assert "not a corridor test" in capsys.readouterr().out
    assert pd.read_csv(out / "laps.csv").empty
    assert s["corridor_m"] == pytest.approx(30.0)
