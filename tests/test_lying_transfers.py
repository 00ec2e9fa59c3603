"""Decision W245: transfers.csv's lying kinds (sit-to-lie, lie-to-sit, stand-to-lie, lie-to-stand) from the edges of
W222's lying, on hand-made tilt signals and on a hand-made lower-back session through `track`."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import Stream, write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.waist.lying import (
    LIE_TO_SIT,
    LIE_TO_STAND,
    LYING_KINDS,
    MIN_LYING_S,
    SIT_TO_LIE,
    STAND_TO_LIE,
    lying_transfer_rows,
)
from pdrlearn.waist.posture_time import LYING_TILT_DEG, label_postures
from pdrlearn.waist.transfers import SIT_TO_STAND, STAND_TO_SIT, TRANSFER_COLUMNS, transfer_summary

FS = 50.0


def _ramp(t, knots):
    """A tilt (deg) through the (time, tilt) knots, linear between them."""
    k = np.array(knots, dtype=float)
    return np.interp(t, k[:, 0], k[:, 1])


def _rows(tilt, t, transfers=None, walking=None):
    tr = pd.DataFrame(columns=list(TRANSFER_COLUMNS)) if transfers is None else transfers
    code = label_postures(t, tilt, np.zeros(t.size, bool) if walking is None else walking, tr)
    chair = tr[["start_s", "end_s"]].to_numpy(float) if len(tr) else None  # as postures_and_transfers passes them
    return pd.DataFrame(lying_transfer_rows(t, tilt, code, FS, np.zeros(t.size), chair),
                        columns=list(TRANSFER_COLUMNS[1:]))


def test_the_four_kinds_their_times_and_no_row_at_the_recording_edges():
    t = np.arange(0.0, 110.0, 1 / FS)
    # lying at the start (no transfer: not recorded), up to a 20 deg seat at 16-18 s (lie-to-sit), standing 3 deg,
    # down to lying at 40-42 s (stand-to-lie: 43 deg/s), up to standing at 60-62 s (lie-to-stand), a 25 deg seat,
    # down to lying at 95-97 s (sit-to-lie), lying at the end (no transfer)
    tilt = _ramp(t, [(0, 90), (16, 90), (18, 20), (25, 20), (26, 3), (40, 3), (42, 90), (60, 90), (62, 3), (75, 3),
                     (76, 25), (95, 25), (97, 90), (110, 90)])
    rows = _rows(tilt, t)
    assert rows["kind"].tolist() == [LIE_TO_SIT, STAND_TO_LIE, LIE_TO_STAND, SIT_TO_LIE]
    # the movement is where the tilt moves 10 deg/s or more (W182's mechanism); peak_s where it passes 60 deg
    want = np.array([[16.0, 18.0], [40.0, 42.0], [60.0, 62.0], [95.0, 97.0]])
    assert np.abs(rows[["start_s", "end_s"]].to_numpy() - want).max() < 0.2
    passes = [16 + 2 * 30 / 70, 40 + 2 * 57 / 87, 60 + 2 * 30 / 87, 95 + 2 * 35 / 65]
    assert rows["peak_s"].to_numpy() == pytest.approx(passes, abs=0.03)
    assert (rows["peak_tilt_deg"] >= LYING_TILT_DEG).all()
    assert rows["duration_s"].to_numpy() == pytest.approx((rows["end_s"] - rows["start_s"]).to_numpy())


@pytest.mark.parametrize("lying_s", [6.0, 14.0])
def test_a_lying_run_under_min_lying_s_gives_no_transfer_w247(lying_s):
    t = np.arange(0.0, 60.0, 1 / FS)
    # a phone put down for a few seconds reads lying; W247: a run under 10 s gives no row, a longer one its two
    tilt = _ramp(t, [(0, 3), (20, 3), (21, 90), (21 + lying_s, 90), (22 + lying_s, 3), (60, 3)])
    kinds = _rows(tilt, t)["kind"].tolist()
    assert MIN_LYING_S == 10.0
    assert kinds == ([] if lying_s < MIN_LYING_S else [STAND_TO_LIE, LIE_TO_STAND])


def test_the_side_is_w222s_label_a_chair_transfer_first_and_an_unknown_side_gives_no_row():
    t = np.arange(0.0, 60.0, 1 / FS)
    # an upright seat (3 deg: the tilt alone says standing) entered by a stand-to-sit at 10 s, then lying at 30-32 s
    tilt = _ramp(t, [(0, 3), (30, 3), (32, 90), (45, 90), (47, 3), (60, 3)])
    chair = pd.DataFrame([{"transfer": 1, "kind": STAND_TO_SIT, "start_s": 9.0, "end_s": 11.0, "duration_s": 2.0,
                           "peak_s": 10.0, "peak_tilt_deg": 35.0, "height_change_m": -0.4}])
    assert _rows(tilt, t)["kind"].tolist() == [STAND_TO_LIE, LIE_TO_STAND]
    assert _rows(tilt, t, chair)["kind"].tolist() == [SIT_TO_LIE, LIE_TO_STAND]  # the seat's transfer decides
    gone = tilt.copy()
    gone[t < 29.5] = np.nan  # no up direction before lying down (W234: unknown): that side names no posture
    assert _rows(gone, t)["kind"].tolist() == [LIE_TO_STAND]
    assert _rows(np.full(t.size, 90.0), t).empty and _rows(np.full(t.size, 3.0), t).empty


def test_lying_rows_do_not_vote_on_w222s_postures_and_leave_the_chair_summary():
    t = np.arange(0.0, 60.0, 1 / FS)
    tilt = _ramp(t, [(0, 3), (30, 3), (32, 90), (60, 90)])
    walking = np.zeros(t.size, bool)
    lie = pd.DataFrame([{"transfer": 1, "kind": STAND_TO_LIE, "start_s": 30.0, "end_s": 32.0, "duration_s": 2.0,
                         "peak_s": 20.0, "peak_tilt_deg": 90.0, "height_change_m": -0.5}])
    assert (label_postures(t, tilt, walking, lie) == label_postures(t, tilt, walking, lie.iloc[:0])).all()
    s = transfer_summary(lie)
    assert s["n_sit_to_stand"] == 0 and s["n_stand_to_sit"] == 0 and s["tug_time_s"] is None


def _rotated(v: np.ndarray, axis: np.ndarray, angle: np.ndarray) -> np.ndarray:
    """``v`` (3,) seen from a body turned by ``angle`` (n,) about ``axis`` (its own frame): rotated by -angle."""
    a = -np.asarray(angle)[:, None]
    k = axis / np.linalg.norm(axis)
    return v * np.cos(a) + np.cross(k, v) * np.sin(a) + k * (k @ v) * (1 - np.cos(a))


def _lie_down_and_up(session):
    """The simulated session (ending standing still) continued: 3 s still, lying down backward in 2 s (a 90 deg turn
    about the waist unit's left axis), 20 s lying, up again in 2 s, 10 s standing - every stream extended, the waist
    unit's accelerometer, gyroscope and magnetometer turned with the body, the others held."""
    dt = 1 / FS
    t_end = max(s.t[-1] for s in session.streams.values())
    pieces = [(3.0, 0.0, 0.0), (2.0, 0.0, 90.0), (20.0, 90.0, 90.0), (2.0, 90.0, 0.0), (10.0, 0.0, 0.0)]
    n = int(round(sum(p[0] for p in pieces) * FS))
    t = t_end + dt * np.arange(1, n + 1)
    ang = np.concatenate([np.linspace(a, b, int(round(d * FS)), endpoint=False) for d, a, b in pieces])
    ang = np.radians(ang)
    rate = np.gradient(ang, dt)
    left = np.array([1.0, 0.0, 0.0])  # the waist frame is x left, y up, z forward (the simulator's)
    rng = np.random.default_rng(5980)
    streams = {}
    for name, s in session.streams.items():
        rest = s.values[-int(FS // 2):].mean(axis=0)
        if name in ("wAccelerometer", "wMagneticField"):
            add = _rotated(rest, left, ang) + rng.normal(0, 0.02, (n, 3))
        elif name == "wGyroscope":
            add = rest + rate[:, None] * left + rng.normal(0, 0.002, (n, 3))
        else:
            add = np.tile(s.values[-1], (n, 1))
        streams[name] = Stream(name, np.r_[s.t, t], np.vstack([s.values, add]))
    session.streams = streams
    return float(t[0]) + 3.0, float(t[0]) + 25.0  # the lying down's and the getting up's start


def test_a_lower_back_track_writes_a_stand_to_lie_and_a_lie_to_stand(tmp_path):
    s = simulate_path(parse_route("straight:10, stand:5"), UserProfile.from_seed(5980), rate_hz=FS, seed=5980)
    down, up = _lie_down_and_up(s)
    write_session(s, tmp_path / "lie")
    out = tmp_path / "out"
    assert main(["track", "--no-plot", str(tmp_path / "lie"), "--pipeline", "waist-pendulum", "--out", str(out)]) == 0
    tr = pd.read_csv(out / "transfers.csv")
    assert list(tr.columns) == list(TRANSFER_COLUMNS)
    lying = tr[tr["kind"].isin(LYING_KINDS)]
    assert lying["kind"].tolist() == [STAND_TO_LIE, LIE_TO_STAND]
    assert tr["transfer"].tolist() == list(range(1, len(tr) + 1))
    assert np.abs(lying[["start_s", "end_s"]].to_numpy() - [[down, down + 2], [up, up + 2]]).max() < 0.5
    assert not tr["kind"].isin([SIT_TO_STAND, STAND_TO_SIT]).any()
    summary = json.loads((out / "summary.json").read_text())
    assert summary["n_lie_down"] == 1 and summary["n_get_up"] == 1  # decision W258


def test_the_side_is_the_posture_held_over_w249s_window_not_a_brief_sit_on_the_bed(monkeypatch):
    from pdrlearn.waist import lying

    t = np.arange(0.0, 80.0, 1 / FS)
    # standing 3 deg for 28 s, sat on the bed's edge (20 deg) for 2.5 s, then lying down; up to a 20 deg seat
    # held 3 s before standing up (W222: tilt >= 15 deg reads sitting)
    tilt = _ramp(t, [(0, 3), (28, 3), (28.5, 20), (31, 20), (33, 90), (50, 90), (52, 20), (55, 20), (55.5, 3),
                     (80, 3)])
    assert lying.SIDE_WINDOW_S == 10.0
    assert _rows(tilt, t)["kind"].tolist() == [STAND_TO_LIE, LIE_TO_STAND]  # the posture held over 10 s
    monkeypatch.setattr(lying, "SIDE_WINDOW_S", None)  # W245's one sample, 1 s out: inside the brief sit
    assert _rows(tilt, t)["kind"].tolist() == [SIT_TO_LIE, LIE_TO_SIT]


def test_the_lying_kinds_are_counted_by_direction_in_the_summary_and_the_line_w258():
    from pdrlearn.cli.common import transfer_line

    rows = [(STAND_TO_SIT, 10.0), (STAND_TO_LIE, 13.0), (LIE_TO_SIT, 40.0), (SIT_TO_LIE, 50.0), (LIE_TO_STAND, 90.0),
            (SIT_TO_STAND, 95.0)]
    tr = pd.DataFrame([{"transfer": i + 1, "kind": k, "start_s": t0, "end_s": t0 + 2.0, "duration_s": 2.0,
                        "peak_s": t0 + 1.0, "peak_tilt_deg": 80.0, "height_change_m": 0.0}
                       for i, (k, t0) in enumerate(rows)])
    s = transfer_summary(tr)
    assert (s["n_lie_down"], s["n_get_up"], s["n_sit_to_stand"], s["n_stand_to_sit"]) == (2, 2, 1, 1)
    assert transfer_line(s) == "1 sit-to-stand, 1 stand-to-sit, 2 lying down, 2 getting up (transfers.csv)"
    chair = transfer_summary(tr[tr["kind"].isin([SIT_TO_STAND, STAND_TO_SIT])])
    assert (chair["n_lie_down"], chair["n_get_up"]) == (0, 0)
    assert transfer_line(chair) == "1 sit-to-stand, 1 stand-to-sit (transfers.csv)"  # unchanged without lying
    only = transfer_summary(tr[tr["kind"].isin([STAND_TO_LIE])])
    assert transfer_line(only) == "0 sit-to-stand, 0 stand-to-sit, 1 lying down, 0 getting up (transfers.csv)"
    assert transfer_summary(None)["n_lie_down"] is None  # a foot track


def test_a_seen_sit_on_the_bed_makes_the_side_sitting_w259():
    """W259 (adopted by its rule): W249's 10 s window does not reach back (on) across a W182 chair row: S60's bed
    (stand-to-sit onto its edge, 2.5 s seated, lying; getting up to a 3 s sit, then sit-to-stand) reads sit-to-lie
    and lie-to-sit, not W249's stand-side kinds beside the chair rows that say the trunk sat."""
    from experiments.hapt_transfers import before_w259
    from pdrlearn.waist import lying

    t = np.arange(0.0, 80.0, 1 / FS)
    tilt = _ramp(t, [(0, 3), (28, 3), (28.5, 20), (31, 20), (33, 90), (50, 90), (52, 20), (55, 20), (55.5, 3),
                     (80, 3)])
    chair = pd.DataFrame([{"transfer": i + 1, "kind": k, "start_s": a, "end_s": b, "duration_s": b - a,
                           "peak_s": (a + b) / 2, "peak_tilt_deg": 30.0, "height_change_m": dz}
                          for i, (k, a, b, dz) in enumerate([(STAND_TO_SIT, 27.5, 29.0, -0.4),
                                                             (SIT_TO_STAND, 54.8, 56.3, 0.4)])])
    assert not hasattr(lying, "SIDE_AFTER_CHAIR")  # W259 is the code (decision W467)
    assert _rows(tilt, t, chair)["kind"].tolist() == [SIT_TO_LIE, LIE_TO_SIT]
    with before_w259():  # W249's window crosses the chair rows into standing
        assert _rows(tilt, t, chair)["kind"].tolist() == [STAND_TO_LIE, LIE_TO_STAND]
    assert _rows(tilt, t)["kind"].tolist() == [STAND_TO_LIE, LIE_TO_STAND]  # no chair row: W249 either way
