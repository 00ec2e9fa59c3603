"""Decisions L368-L371 / W328 (session 33, trial T3 findings F1 / F2): two opposite turns on the spot done from
standing are two rows of turns.csv, on the foot (L371: a reversal ends a turn, L369: the first stride's own turn
counts) and on the lower back (W328: a run is cut between two opposite yaw-rate turns, a matched turn takes its
yaw-rate angle)."""

from __future__ import annotations

import inspect

import numpy as np
import pandas as pd
import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import clinical
from pdrlearn.track.clinical import opposite_yaw_cuts, turn_table

ROUTE = "stand:3, turn:360, stand:3, turn:-360, stand:3"  # the trial's turns-only route


def _foot_table() -> pd.DataFrame:
    """A foot table as plasys tracked the trial's route (user 7140): three strides of +120 deg, a 3.6 s stand, four
    strides of -60 / -120 / -120 / -60 deg (each row's own turn, ``turn_angle_rad``)."""
    start = np.array([8.82, 10.08, 11.27, 16.16, 17.39, 18.59, 19.81])
    end = np.array([10.08, 11.27, 12.54, 17.39, 18.59, 19.81, 21.06])
    turn = np.radians([120.0, 120.0, 120.0, -60.0, -120.0, -120.0, -60.0])
    return pd.DataFrame({"start_s": start, "end_s": end, "heading_rad": np.angle(np.exp(1j * np.cumsum(turn))),
                         "turn_angle_rad": turn, "length_m": 0.13, "gap_s": 0.0, "unit": "foot"})


def _true_turns(session) -> list[tuple[float, float, float]]:
    """The route's turns (the waist's true heading, 1 s mean, 5-95 % of each turn: L201 / L255's truth)."""
    from pdrlearn.sim.tug_truth import turn_span_indices

    t, hs, spans = turn_span_indices(session.trajectory, ROUTE)
    return [(float(t[a]), float(t[b]), float(hs[b] - hs[a]) / 0.9) for a, b in spans]


def test_reversal_ends_a_turn_and_first_stride_counts():
    st = _foot_table()
    params = inspect.signature(turn_table).parameters  # decisions L371 / L369 (L594: keywords, no switch)
    assert params["foot_split"].default is True and params["first_own"].default is True
    tt = turn_table(st)
    assert tt["angle_deg"].tolist() == pytest.approx([360.0, -360.0])
    assert tt["n_rows"].tolist() == [3, 4]
    assert tt.loc[0, "start_s"] >= 8.82 and tt.loc[0, "end_s"] <= 12.54  # inside its strides
    assert tt.loc[1, "start_s"] >= 16.16 and tt.loc[1, "end_s"] <= 21.06
    assert clinical.turns(st).tolist() == pytest.approx([360.0, -360.0])  # turn_count's turns
    assert clinical.turn_rows(st)[1].tolist() == [0, 3]  # the rows a bout counts them in (real rows, no rest row)
    # the trial's readings were one run summing both turns (-120 deg); decision L577 (session 41): the stand
    # between them now ends a foot turn by itself, so without L368's cut the turns stay apart (+240 deg without
    # the first stride)
    old = turn_table(st, foot_split=False, first_own=False)
    assert old["angle_deg"].tolist() == pytest.approx([240.0, -360.0])
    assert turn_table(st, first_own=False)["angle_deg"].tolist() == pytest.approx([240.0, -360.0])
    # a small opposite change (a slower stride's noise) stays in its turn; L368's cut needs 30 deg
    assert clinical.split_reversals(np.array([100.0, -10.0, 100.0]), 0, 3) == [(0, 3)]
    assert clinical.split_reversals(np.array([100.0, 100.0, -40.0, -90.0]), 0, 4) == [(0, 2), (2, 4)]


def test_foot_turns_in_place_read_two_full_turns():
    from pdrlearn.track.plasys import track_plasys

    s = simulate_path(parse_route(ROUTE), UserProfile.from_seed(7141), speed="normal", rate_hz=20.0, seed=7141)
    res = track_plasys(s)
    tt = turn_table(res.steps)
    assert tt["angle_deg"].tolist() == pytest.approx([360.0, -360.0], abs=10.0)
    for (a, b, _), row in zip(_true_turns(s), tt.itertuples(), strict=True):
        assert abs(row.start_s - a) < 0.8 and abs(row.end_s - b) < 0.8
    assert clinical.clinical_summary(res.steps)["turn_count"] == 2


def test_opposite_yaw_cuts_and_yaw_angle():
    yaw = [{"start_s": 8.2, "end_s": 13.0, "angle_deg": 359.0}, {"start_s": 16.2, "end_s": 21.0, "angle_deg": -361.0},
           {"start_s": 25.0, "end_s": 27.0, "angle_deg": -90.0}]
    assert opposite_yaw_cuts(yaw).tolist() == pytest.approx([14.6])  # same-way neighbours are not cut
    assert opposite_yaw_cuts([]).size == 0
    # a lower-back table whose step headings ran +265 deg, stood, then -350 deg: one turning run (L119's pause
    # interval holds a turn) summing -85 deg, which L231's branch read as -445 deg (trial T3 F2)
    t = np.r_[np.arange(9.15, 12.6, 0.55), np.arange(17.1, 20.6, 0.55)]
    h = np.r_[np.linspace(57.0, 322.0, 7), np.linspace(241.0, -28.0, 7)]
    st = pd.DataFrame({"start_s": t, "end_s": np.r_[t[1:], t[-1] + 0.55], "heading_rad": np.radians(h),
                       "length_m": 0.3, "unit": "waist"})
    recs = [dict(r, peak_s=0.5 * (r["start_s"] + r["end_s"]), peak_dps=100.0) for r in yaw[:2]]
    tt = turn_table(st, yaw_turns=recs)
    assert tt["angle_deg"].tolist() == pytest.approx([359.0, -361.0])  # W328: the yaw-rate turns' angles
    assert tt[["start_s", "end_s"]].to_numpy().ravel().tolist() == pytest.approx([8.2, 13.0, 16.2, 21.0])
    old = turn_table(st, yaw_turns=recs, yaw_split=False, yaw_angle=False)
    assert len(old) == 1 and abs(old.loc[0, "angle_deg"]) > 400.0
    assert turn_table(st, yaw_turns=recs, yaw_angle=False)["angle_deg"].tolist() == pytest.approx([265.0, -350.0],
                                                                                                   abs=25.0)


def test_waist_opposite_turns_from_standing_are_two_rows():
    from pdrlearn.track.waist import track_waist

    s = simulate_path(parse_route(ROUTE), UserProfile.from_seed(7140), speed="normal", rate_hz=100.0, seed=7140)
    res = track_waist(s, pipeline="waist-pendulum")
    tt = turn_table(res.steps, yaw_turns=res.info["yaw_turns"])
    assert tt["angle_deg"].tolist() == pytest.approx([360.0, -360.0], abs=10.0)
    for (a, b, _), row in zip(_true_turns(s), tt.itertuples(), strict=True):
        assert row.start_s < a + 0.5 and row.end_s > b - 0.5  # El-Gohary's boundaries hold the turn
    old = turn_table(res.steps, yaw_turns=res.info["yaw_turns"], yaw_split=False, yaw_angle=False)
    assert len(old) == 1  # the trial's reading: one row of about -445 deg


def test_window_keeps_only_its_turns_and_result_turns_sees_the_yaw_rate():
    """Decisions W329 (trial T3 F4: ``--window`` kept the lower back's turns outside it) and W330 (F7:
    ``turn_table(result.steps)`` missed a lower-back track's turns)."""
    from pdrlearn.track.evaluate import track_summary
    from pdrlearn.track.waist import track_waist
    from pdrlearn.track.window import window_track

    s = simulate_path(parse_route(ROUTE), UserProfile.from_seed(7142), speed="normal", rate_hz=100.0, seed=7142)
    res = track_waist(s, pipeline="waist-pendulum")
    whole = res.turns()
    assert len(whole) == 2
    pd.testing.assert_frame_equal(turn_table(res), turn_table(res.steps, yaw_turns=res.info["yaw_turns"]))
    cut = 0.5 * (whole.loc[0, "end_s"] + whole.loc[1, "start_s"])  # the stand between the two turns
    first, cut_session = window_track(res, s, 0.0, cut)
    tt = first.turns()
    assert len(tt) == 1 and tt.loc[0, "angle_deg"] == pytest.approx(whole.loc[0, "angle_deg"])
    summary = track_summary(first, cut_session)
    assert summary["turn_count"] == 1
    assert summary["median_turn_duration_s"] == pytest.approx(tt.loc[0, "duration_s"])
    second = window_track(res, s, cut, float(s.trajectory["t"].iloc[-1]))[0].turns()
    assert second["angle_deg"].tolist() == pytest.approx([whole.loc[1, "angle_deg"]])
