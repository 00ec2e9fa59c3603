"""Decision L647 (session 44, trial T1 finding F4): a turn is not a rest. A gap between walking bouts is turning for
the time a turns.csv turn covers (widened by one step interval on each side: the stepless turn's entry and exit
steps) and a rest only for what is left, when that is at least 1 s: laps.csv's ``rest_s`` and the report's rests
between walking bouts. A slow walker's stepless cone turns split the walk into bouts but are no rests; a real stand
in mid-corridor still is one."""
from __future__ import annotations

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.report.time_course import rest_table
from pdrlearn.track.rests import rest_seconds, step_interval_s

#: trial T1's P05 walker (0.3 m steps of 1.0 s, step-time asymmetry 0.25) on a 12 m corridor, an 8 s stand mid-lap 2
ROUTE = "straight:12, turn:180, straight:6, stand:8, straight:6, turn:180, straight:12"


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    d = tmp_path_factory.mktemp("l647")
    assert main(["simulate", "--route", ROUTE, "--step-length", "0.3", "--step-time", "1.0",
                 "--step-time-asymmetry", "0.25", "--bounce", "pendulum", "--rate", "100", "--user-seed", "12442",
                 "--stand", "3", "--out", str(d / "s")]) == 0
    assert main(["track", "--no-plot", str(d / "s"), "--units", "waist", "--corridor", "12", "--out",
                 str(d / "t")]) == 0
    return d / "t"


def test_stepless_cone_turns_are_no_rests_and_the_stand_is_one(walk):
    bouts, turns = pd.read_csv(walk / "bouts.csv"), pd.read_csv(walk / "turns.csv")
    laps = pd.read_csv(walk / "laps.csv")
    # the lower back sees no step in a cone turn; since C180 (session 45) the turns fill their gaps: the stand alone
    # splits the walk (L647's 4 bouts, one per cone turn and the stand, are now 2)
    assert len(bouts) == 2 and len(turns) == 2
    assert list(laps["rest_s"].iloc[[0, 2]]) == [0.0, 0.0]  # the turns' gaps (6.8 s and 7.1 s) are no rest
    assert 8.0 <= laps["rest_s"].iloc[1] <= 10.5  # the 8 s stand (its gap from the last step's end)
    rests = rest_table(bouts, turns)
    assert len(rests) == 1 and rests["start_s"].iloc[0] > turns["end_s"].iloc[0]
    assert 8.0 <= rests["duration_s"].iloc[0] <= 10.5


def test_a_gap_leftover_under_a_second_is_no_rest_and_a_long_one_is_the_rest_outside_the_turn():
    bouts = pd.DataFrame({"start_s": [0.0, 20.0, 60.0], "end_s": [10.0, 40.0, 80.0], "cadence_spm": [60.0] * 3})
    turns = pd.DataFrame({"start_s": [11.0, 45.0], "end_s": [18.5, 49.0]})
    assert step_interval_s(bouts) == 1.0
    # gap 10-20: the turn widened by 1 s covers 10-19.5, leaving 0.5 s - under 1 s, no rest
    # gap 40-60: the turn widened covers 44-50, leaving 4 + 10 s of rest
    assert rest_seconds(0.0, 80.0, bouts, turns) == pytest.approx(14.0)
    rests = rest_table(bouts, turns)
    assert list(rests["duration_s"]) == pytest.approx([14.0]) and list(rests["start_s"]) == [40.0]
    assert rest_table(bouts, None)["duration_s"].tolist() == pytest.approx([10.0, 20.0])  # no turns: the gaps
