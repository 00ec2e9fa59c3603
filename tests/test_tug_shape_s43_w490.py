"""Session 43, fixer FC: W490 / L614 - a TUG trial turns about once at its far end and walks at most 9 m each way
(trial T1 F3: a daily walk read "1 TUG trial(s): 48.39 s"; trial T3 F8: a foot track's sit, 20 m, sit read
"1 TUG trial(s): 25.75 s" with no turn)."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd

from pdrlearn.cli import main
from pdrlearn.waist.transfers import (
    SIT_TO_STAND,
    STAND_TO_SIT,
    TUG_LEG_MAX_M,
    contact_path,
    transfer_summary,
    tug_turn_legs,
)


def _turns(*rows):
    return pd.DataFrame([{"start_s": a, "end_s": b, "angle_deg": g} for a, b, g in rows],
                        columns=["start_s", "end_s", "angle_deg"])


def test_tug_turn_legs_kernel_w490():
    t = np.arange(8.0, 24.0, 0.5)  # steps from 8 to 23.5 s, 0.4 m each
    ln = np.full(t.size, 0.4)
    about = _turns((14.0, 16.0, 178.0), (22.5, 24.5, -175.0))  # the TUG turn, then the turn to sit
    assert tug_turn_legs(7.0, 25.0, about, t, ln)  # 2.4 m out, 2.6 m back
    assert tug_turn_legs(7.0, 25.0, _turns((14.0, 16.0, -140.0)), t, ln)  # inside 180 +- 45 deg
    assert not tug_turn_legs(7.0, 25.0, _turns((14.0, 16.0, 90.0), (18.0, 20.0, 180.0)), t, ln)  # a corner first
    assert not tug_turn_legs(7.0, 25.0, _turns(), t, ln)  # no turn: a walk from one chair to another
    assert not tug_turn_legs(7.0, 25.0, _turns((30.0, 32.0, 180.0)), t, ln)  # the turn is not inside the walk
    assert not tug_turn_legs(7.0, 25.0, about, t, np.full(t.size, 1.5))  # 18 m out: a corridor, no TUG
    nine = np.where(t < 11.0, 0.0, np.where(t < 14.0, 1.5, 0.4))  # 6 x 1.5 m out: exactly TUG_LEG_MAX_M
    assert nine[(t > 7.0) & (t < 14.0)].sum() == TUG_LEG_MAX_M and tug_turn_legs(7.0, 25.0, about, t, nine)
    assert not tug_turn_legs(7.0, 25.0, about, t, np.where(t < 11.0, 0.1, nine))  # 9.6 m out
    assert tug_turn_legs(7.0, 25.0, about, t)  # no lengths: the turn alone
    # not judged without a turns table, or one of times only (a kernel's caller without angles)
    assert tug_turn_legs(7.0, 25.0, None, t, ln)
    assert tug_turn_legs(7.0, 25.0, pd.DataFrame({"start_s": [], "end_s": []}), t, ln)


def test_a_daily_walk_and_a_straight_walk_are_chair_walks_w490():
    tr = pd.DataFrame([{"transfer": 1, "kind": SIT_TO_STAND, "start_s": 5.0, "end_s": 7.0},
                       {"transfer": 2, "kind": STAND_TO_SIT, "start_s": 25.0, "end_s": 27.0}])
    t = np.arange(8.0, 24.0, 0.5)
    out = np.where(t < 15.0, 0.0, np.pi)  # out and back: nets about 0 (W445's (c) holds)
    steps = pd.DataFrame({"start_s": t, "length_m": 0.4, "heading_rad": out})
    tug = transfer_summary(tr, steps, turns=_turns((15.0, 15.5, 180.0)))
    assert tug["n_tug_trials"] == 1 and tug["tug_time_s"] == 22.0 and tug["n_chair_walks"] == 0
    # T1's daily walk: a 90 deg corner first
    daily = transfer_summary(tr, steps, turns=_turns((10.0, 11.0, 90.0), (15.0, 15.5, 180.0)))
    assert daily["n_tug_trials"] == 0 and daily["tug_time_s"] is None and daily["n_chair_walks"] == 1
    assert "no about-turn first" in daily["tug_time_note"] and "W490" in daily["tug_time_note"]
    # legs of 6 m each way at 0.4 m steps x 2.5 (a corridor): over 9 m
    far = transfer_summary(tr, steps.assign(length_m=1.0), turns=_turns((15.0, 15.5, 180.0)))
    assert far["n_tug_trials"] == 0 and far["n_chair_walks"] == 1
    # L614: a two-unit foot track's trunk contacts carry no length; its strides do (a straight 20 m walk, no turn)
    trunk = steps[["start_s"]]
    strides = pd.DataFrame({"start_s": t[::2] - 0.3, "event_s": t[::2], "length_m": 1.25, "heading_rad": 0.0})
    assert set(contact_path(trunk, strides)) == {"path_s", "length_m", "heading_rad"}
    assert transfer_summary(tr, trunk)["n_tug_trials"] == 1  # W445 alone (duration): a TUG
    foot = transfer_summary(tr, trunk, turns=_turns(), walk=strides)
    assert foot["n_tug_trials"] == 0 and foot["n_chair_walks"] == 1


def test_a_foot_track_of_sit_walk_sit_reports_no_tug_l614(tmp_path, capsys):
    """Trial T3 F8's case, short: a two-unit session that rises, walks 8 m straight and sits; the default (foot)
    track read it as a TUG trial before W490 / L614."""
    d = tmp_path / "s"
    assert main(["simulate", "--route", "straight:8", "--sit-start", "5", "--sit-end", "5", "--user-seed", "12046",
                 "--out", str(d)]) == 0
    assert main(["track", "--no-plot", str(d), "--out", str(tmp_path / "t")]) == 0
    out = capsys.readouterr().out
    s = json.loads((tmp_path / "t" / "summary.json").read_text())
    assert s["n_sit_to_stand"] == 1 and s["n_stand_to_sit"] == 1  # the waist found the rise and the sit (W418)
    assert s["n_tug_trials"] == 0 and s["tug_time_s"] is None and s["n_chair_walks"] == 1
    assert "TUG trial(s)" not in out and not (tmp_path / "t" / "tug_trials.csv").exists()
