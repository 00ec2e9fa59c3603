"""Decision L412 (session 34, trial T3 finding 7): each foot stride's travel direction (steps.csv ``travel``) and the
changes of it (``direction_changes``, direction_changes.csv), which a back-pedal or a side-shuffle reversal makes
without a turn (``turn_count`` 0)."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.columns import undocumented
from pdrlearn.track.travel import direction_change_table, travel_labels


def _table(raw, sideways=None, travel=None, turn=None, gap=None):
    n = len(raw)
    t = np.arange(n, dtype=float)
    out = pd.DataFrame({"start_s": t, "end_s": t + 1.0, "length_m": np.abs(raw), "raw_length_m": raw,
                        "turn_angle_rad": np.zeros(n) if turn is None else turn,
                        "sideways": np.zeros(n, bool) if sideways is None else sideways,
                        "gap_s": np.zeros(n) if gap is None else gap, "unit": "foot"})
    if travel is not None:
        out["travel"] = travel
    return out


def test_labels_and_changes_of_a_hand_made_table():
    """Forward, backward (raw length < 0), a side run to the left then one to the right, a turn stride (60 deg,
    skipped), a foot gap (empty) and a 5 cm shuffle (empty): 3 changes, none at the turn."""
    raw = [1.4, 1.4, -0.8, -0.8, -0.4, -0.4, -0.4, 0.4, 0.4, 0.4, 0.3, 1.4, 0.0, 0.05, -0.9]
    side = [False] * 4 + [True] * 6 + [False] * 5
    travel = [None] * 4 + ["left"] * 3 + ["right"] * 3 + [None] * 5
    turn = np.zeros(15)
    turn[10] = np.radians(60.0)
    gap = np.zeros(15)
    gap[12] = 2.0
    st = _table(np.array(raw), np.array(side), travel, turn, gap)
    labels = travel_labels(st)
    assert list(labels) == ["forward", "forward", "backward", "backward", "left", "left", "left", "right", "right",
                            "right", "turn", "forward", "", "", "backward"]
    changes = direction_change_table(st)
    assert list(zip(changes["from_travel"], changes["to_travel"], changes["row"], strict=True)) == [
        ("forward", "backward", 2), ("backward", "left", 4), ("left", "right", 7), ("right", "forward", 11),
        ("forward", "backward", 14)]
    # a lower-back table has no facing per step: no label, no table
    assert travel_labels(st.assign(unit="waist")) is None and direction_change_table(st.assign(unit="waist")) is None


@pytest.mark.parametrize(("route", "user", "expect"), [
    ("straight:5, backward:5", 7943, [("forward", "backward")]),
    ("side:4, side:-4", 7944, [("left", "right")]),
])
def test_reversals_without_a_turn_are_counted(tmp_path, route, user, expect):
    """A back-pedal after walking forward, and a side shuffle back the other way, turn the body by nothing
    (turn_count 0) but change the travel direction once (L412)."""
    ses = tmp_path / "ses"
    assert main(["simulate", "--route", route, "--user-seed", str(user), "--out", str(ses)]) == 0
    out = tmp_path / "track"
    assert main(["track", "--no-plot", str(ses), "--out", str(out)]) == 0
    summary = json.loads((out / "summary.json").read_text())
    changes = pd.read_csv(out / "direction_changes.csv")
    steps = pd.read_csv(out / "steps.csv")
    assert summary["turn_count"] == 0
    assert summary["direction_changes"] == len(changes) == len(expect)
    assert list(zip(changes["from_travel"], changes["to_travel"], strict=True)) == expect
    assert not undocumented("direction_changes.csv", changes.columns)
    assert not undocumented("steps.csv (foot)", steps.columns)
    first, second = expect[0]
    assert set(steps["travel"].dropna()) <= {first, second, "turn"}
