"""Decisions W277-W279: the still standing upright of a lower-back session without walking, transfers.csv's
sequence flags, and the five-times sit-to-stand time."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.waist.ahrs import imu_from_body
from pdrlearn.waist.transfers import (
    NOT_ALTERNATING,
    SIT_TO_LIE,
    SIT_TO_STAND,
    STAND_TO_SIT,
    TRANSFER_COLUMNS,
    WALKING_BOTH_SIDES,
    chair_transfers_upright,
    sequence_flags,
    sts5_time_s,
    transfer_summary,
    upright_message,
)
from pdrlearn.waist.upright import standing_mask, still_mask, walking_is_reliable


def test_walking_needs_a_sequence_of_four_contacts():
    assert walking_is_reliable([True, True, True, False])  # 4 contacts in one sequence
    assert not walking_is_reliable([True, True, False, True, True, False])  # two sequences of 3
    assert not walking_is_reliable([False, False])  # a rise's lone contacts
    assert not walking_is_reliable([])


def test_still_mask_needs_a_second_of_calm():
    fs = 20.0
    gyr = np.zeros((200, 3))
    gyr[40:60, 1] = 1.0  # a 1 s movement
    gyr[100:112, 0] = 0.5  # 0.6 s of movement: the calm between 60 and 100 is 2 s, kept
    gyr[130:145, 0] = 0.5
    m = still_mask(gyr, fs)
    assert m[:30].all() and not m[45:55].any() and m[70:95].all()
    assert not m[120:125].any()  # 112-130 minus the window's smear: under 1 s of calm


def test_standing_mask_is_the_transfers_vote():
    t = np.arange(0.0, 30.0, 1.0)
    still = np.ones(t.size, dtype=bool)
    tr = pd.DataFrame([{"kind": SIT_TO_STAND, "start_s": 5.0, "end_s": 7.0},
                       {"kind": STAND_TO_SIT, "start_s": 15.0, "end_s": 17.0},
                       {"kind": SIT_TO_STAND, "start_s": 22.0, "end_s": 24.0},
                       {"kind": SIT_TO_STAND, "start_s": 26.0, "end_s": 27.0}])
    m = standing_mask(t, still, tr, SIT_TO_STAND, STAND_TO_SIT)
    assert not m[:5].any()  # before the first rise: seated
    assert m[8:15].all()  # after a rise, before a sit
    assert not m[18:22].any()  # after a sit
    assert not m[25]  # after a rise but before a rise: the vote disagrees
    assert m[28:].all()  # after the last rise
    assert not standing_mask(t, still, tr.iloc[:0], SIT_TO_STAND, STAND_TO_SIT).any()


def test_sequence_flags_hand_made():
    kinds = [SIT_TO_STAND, SIT_TO_STAND, STAND_TO_SIT, SIT_TO_LIE]
    flags = sequence_flags(kinds, [3.0, 35.0, 60.0, 80.0], [4.0, 36.0, 61.0, 82.0],
                           walk_s=[20.0, 33.5, 37.0, 58.5, 62.5])
    assert flags[0] == NOT_ALTERNATING  # two rises in a row: both flagged
    assert flags[1] == f"{NOT_ALTERNATING}; {WALKING_BOTH_SIDES}"  # and walking 1.5 s before, 1 s after
    assert flags[2] == WALKING_BOTH_SIDES  # sits down from standing: the sequence is fine
    assert flags[3] == ""  # sit-to-lie after a stand-to-sit
    assert sequence_flags([SIT_TO_STAND, STAND_TO_SIT], [0.0, 10.0], [1.0, 11.0], [2.5, 8.5]) == ["", ""]
    # walking 1.5 s after the rise and before the sit, but on one side only of each: a TUG
    assert sequence_flags([SIT_TO_STAND, STAND_TO_SIT], [0.0, 10.0], [1.0, 11.0], [-2.5, 13.5]) == ["", ""]


def _sts_rows(n_rises=5, flag=""):
    rows = []
    for i in range(n_rises):
        rows.append({"transfer": 2 * i + 1, "kind": SIT_TO_STAND, "start_s": 10.0 * i + 3.0, "end_s": 10.0 * i + 4.5,
                     "duration_s": 1.5, "peak_s": 10.0 * i + 3.7, "peak_tilt_deg": 40.0, "height_change_m": 0.4,
                     "flag": flag})
        rows.append({"transfer": 2 * i + 2, "kind": STAND_TO_SIT, "start_s": 10.0 * i + 8.0,
                     "end_s": 10.0 * i + 9.5, "duration_s": 1.5, "peak_s": 10.0 * i + 8.7, "peak_tilt_deg": 40.0,
                     "height_change_m": -0.4, "flag": ""})
    return pd.DataFrame(rows, columns=list(TRANSFER_COLUMNS))


def test_sts5_time_only_for_five_alternating_rises():
    tr = _sts_rows()
    assert sts5_time_s(tr) == pytest.approx(49.5 - 3.0)
    assert transfer_summary(tr)["sts5_time_s"] == pytest.approx(46.5)
    assert transfer_summary(tr)["n_transfers_flagged"] == 0
    assert sts5_time_s(_sts_rows(4)) is None  # four rises
    assert sts5_time_s(tr.iloc[:-1]) is None  # no last sit
    assert sts5_time_s(_sts_rows(flag=NOT_ALTERNATING)) is None
    assert transfer_summary(_sts_rows(flag=NOT_ALTERNATING))["n_transfers_flagged"] == 5
    inside = pd.DataFrame({"event_s": [3.5], "has_next": [False]})  # a rise's bounce
    assert sts5_time_s(tr, inside) == pytest.approx(46.5)
    shift = pd.DataFrame({"event_s": [5.0, 5.5], "has_next": [True, False]})
    assert sts5_time_s(tr, shift) == pytest.approx(46.5)  # a weight shift read as a step: no walking sequence
    walked = pd.DataFrame({"event_s": [5.0, 5.5, 6.0, 6.5], "has_next": [True, True, True, False]})
    assert sts5_time_s(tr, walked) is None  # walking between two rises: not one chair test
    old = tr.drop(columns="flag").to_dict("records")  # rows written before W278 (no flag column)
    assert transfer_summary(old)["n_transfers_flagged"] == 0


def test_no_walking_and_no_standing_leaves_the_upright_unknown():
    fs = 50.0
    t = np.arange(0, 20, 1 / fs)
    acc = np.tile([0.0, 0.0, 9.80665], (t.size, 1))  # sitting (or standing) still throughout: no transfer
    imu = imu_from_body(t, acc, np.zeros((t.size, 3)), fs=fs)
    rows, up, source = chair_transfers_upright(imu, pd.DataFrame(columns=["event_s", "has_next"]))
    assert source == "none" and up is None and rows.empty
    assert "left empty" in upright_message(source, 0) and "W277" in upright_message(source, 0)


@pytest.fixture(scope="module")
def sts(tmp_path_factory):
    """User 6410 (W277's range): seated 3 s, five rises and sits with no walking, seated 5 s at the end."""
    d = tmp_path_factory.mktemp("sts") / "sts"
    s = simulate_path(parse_route("sit:1, sit:1, sit:1, sit:1"), UserProfile.from_seed(6410), seed=6410,
                      sit_start_s=3.0, sit_end_s=5.0)
    write_session(s, d)
    return d


def test_five_times_sit_to_stand_without_walking_finds_every_transfer(sts, tmp_path, capsys):
    truth = pd.read_csv(sts / "transfers.csv") / 1000.0
    out = tmp_path / "w"
    assert main(["track", "--no-plot", str(sts), "--units", "waist", "--out", str(out)]) == 0
    printed = capsys.readouterr()
    tr = pd.read_csv(out / "transfers.csv")
    assert tr["kind"].tolist() == [SIT_TO_STAND, STAND_TO_SIT] * 5  # before W277: 0 rises and 1 sit
    rises = truth["rise_ms"].to_numpy()[:5]
    sits = truth["start_ms"].to_numpy()[1:]
    assert np.abs(tr["start_s"].to_numpy()[0::2] - rises).max() < 0.6
    assert np.abs(tr["start_s"].to_numpy()[1::2] - sits).max() < 0.6
    assert tr["flag"].isna().all()
    summary = json.loads((out / "summary.json").read_text())
    assert summary["sts5_time_s"] == pytest.approx(truth["seated_ms"].iloc[-1] - rises[0], abs=0.5)
    assert summary["tug_time_note"] is None  # decision W279: W282's note is for a TUG
    assert summary["n_bouts"] == 0  # the rises' false contacts are vetoed against the still upright
    assert "5 sit-to-stand, 5 stand-to-sit (transfers.csv), five-times sit-to-stand" in printed.out
    assert "decision W277" in printed.err
    assert "axes disagree" not in printed.err  # decision W280: the rises' pitching is no turn


def test_a_pitching_trunk_is_not_read_as_disagreeing_axes_w280(sts):
    from pdrlearn.io import read_session
    from pdrlearn.io.handedness import turn_axis

    fs, n = 20.0, 400
    t = np.arange(n) / fs
    pitch = np.radians(40.0) * np.clip(np.minimum((t - 5.0), (9.0 - t)), 0.0, 1.0)  # 40 deg forward and back
    pitch += np.radians(40.0) * np.clip(np.minimum((t - 12.0), (16.0 - t)), 0.0, 1.0)
    gyr = np.zeros((n, 3))
    gyr[:, 1] = np.gradient(pitch, t)
    tilted = 9.81 * np.stack([-np.sin(pitch), np.zeros(n), np.cos(pitch)], axis=1)  # gravity turns with the pitch
    assert turn_axis(tilted, gyr, fs)[1] == 0  # every turn window tilts: none is left (before W280: 90 deg)
    still = np.tile([0.0, 0.0, 9.81], (n, 1))  # the same rotation with gravity still: a gyroscope's wrong axes
    ang, windows, _, _ = turn_axis(still, gyr, fs)
    assert windows >= 2 and ang > 80.0
    assert read_session(sts).handedness("waist", ratio=False).verdict != "axes differ"
