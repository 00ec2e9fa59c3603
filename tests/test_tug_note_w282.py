"""Decisions W281, W282 (trial s32 findings 4 and 6): ``tug_time_note`` says why there is no TUG time and points at
``--window``; `pdrlearn steps` says why `track` can count fewer lower-back steps."""

from __future__ import annotations

import json

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.cli.common import transfer_line
from pdrlearn.waist.transfers import SIT_TO_STAND, STAND_TO_SIT, transfer_summary


def _tr(*rows):
    return pd.DataFrame([{"transfer": i + 1, "kind": k, "start_s": t0, "end_s": t0 + 1.5, "duration_s": 1.5,
                          "peak_s": t0 + 0.7, "peak_tilt_deg": 40.0, "height_change_m": 0.4}
                         for i, (k, t0) in enumerate(rows)])


def test_tug_time_note_says_why_and_points_at_window():
    one = _tr((SIT_TO_STAND, 5.0), (STAND_TO_SIT, 25.0))
    s = transfer_summary(one, pd.DataFrame({"start_s": [8.0, 20.0]}))
    assert s["tug_time_s"] == pytest.approx(21.5) and s["tug_time_note"] is None  # a TUG: no note
    # two TUG trials in one recording (the trial's user 150): the count, each rise and sit, and --window
    two = _tr((SIT_TO_STAND, 5.0), (STAND_TO_SIT, 25.0), (SIT_TO_STAND, 37.0), (STAND_TO_SIT, 57.5))
    s = transfer_summary(two, pd.DataFrame({"start_s": [8.0, 20.0, 40.0, 50.0]}))
    # W325: these two are TUG trials, each timed in tug_trials.csv, so the note says that instead of --window
    assert s["tug_time_s"] is None and s["n_tug_trials"] == 2 and "tug_trials.csv" in s["tug_time_note"]
    # a step while seated between them (at 30 s): no trial, W282's note
    s = transfer_summary(two, pd.DataFrame({"start_s": [8.0, 20.0, 30.0, 40.0, 50.0]}))
    assert s["tug_time_s"] is None and s["n_tug_trials"] == 0
    note = s["tug_time_note"]
    assert note.startswith("no TUG time: 4 transfers (2 sit-to-stand, 2 stand-to-sit)") and "--window" in note
    assert "rises start at 5.0, 37.0 s" in note and "sits end at 26.5, 59.0 s" in note
    assert note in transfer_line(s)  # the console's transfer line carries it
    # a step before the rise
    s = transfer_summary(one, pd.DataFrame({"start_s": [2.0, 8.0, 20.0]}))
    assert s["tug_time_s"] is None and "1 step(s) before the rise at 5.0 s and 0 after" in s["tug_time_note"]
    # starting standing: a sit, a rise, a sit
    s = transfer_summary(_tr((STAND_TO_SIT, 2.0), (SIT_TO_STAND, 5.0), (STAND_TO_SIT, 25.0)))
    assert "does not start and end seated (first transfer stand-to-sit at 2.0 s" in s["tug_time_note"]
    # no rise followed by a sit: nothing a TUG could be timed on, no note (W258's lines unchanged)
    assert transfer_summary(_tr((STAND_TO_SIT, 2.0), (SIT_TO_STAND, 30.0)))["tug_time_note"] is None
    assert transfer_summary(None)["tug_time_note"] is None  # a foot track


def test_steps_says_why_track_counts_fewer_lower_back_steps(tmp_path, capsys):
    d = tmp_path / "tug"
    assert main(["simulate", "--route", "straight:3, turn:180, straight:3", "--sit-start", "5", "--sit-end", "5",
                 "--user-seed", "110", "--out", str(d)]) == 0
    capsys.readouterr()
    assert main(["steps", str(d), "--detector", "waist-ic"]) == 0
    out = capsys.readouterr().out
    count = int(out.split(": ", 1)[1].split(" steps")[0])
    assert "note: these are the detector's contacts; " in out and "(W281" in out  # W297 names them when it can
    # turn_bridge false (W385's "side" default recovers a turn step here, 12 = 12): the sit veto alone
    (tmp_path / "params.json").write_text(json.dumps({"options": {"turn_bridge": False}}))
    assert main(["track", "--no-plot", str(d), "--units", "waist", "--out", str(tmp_path / "t"), "--json",
                 "--params", str(tmp_path / "params.json")]) == 0
    tracked = json.loads(capsys.readouterr().out)["n_steps"]
    assert tracked < count  # the seated contact the sit veto drops (W185)
    assert main(["steps", str(d), "--json", "--detector", "waist-ic"]) == 0
    assert "note:" not in capsys.readouterr().out  # the JSON stays one object
