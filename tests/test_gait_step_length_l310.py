"""Decisions L310-L313 (session 31, the stroke-rehab trial's follow-up): `pdrlearn gait`'s per-foot step length and
its asymmetry, and the 10 m walk test's middle-10-m time and speed in every foot track's summary."""

from __future__ import annotations

import json
import math

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.track.bilateral import STEP_AXIS_MAX_DEG, UNANCHORED_NOTE, bilateral_gait
from pdrlearn.track.walk_test import LOWER_BACK_NOTE, ten_metre_walk
from tests.cli_helpers import tracked_slow_walk


def _walk(s_left: float, s_right: float, n: int, *, turn_at: int | None = None, turn_deg: float = 0.0,
          close: bool = True) -> tuple[pd.DataFrame, pd.DataFrame]:
    """Two feet's tracked step tables of a walk whose steps onto the left foot are ``s_left`` long and onto the
    right ``s_right``: from standing side by side, the right foot first, ``n`` steps, then (``close``) the last
    foot brought beside the other. ``turn_at``: from that step on the walking direction is turned by
    ``turn_deg`` (the step lengths laid along it)."""
    pos = {"left": 0.0 + 0j, "right": 0.0 + 0j}
    rows = {"left": [], "right": []}
    t, heading, reach = 0.0, 0.0, 0.0
    for k in range(n + (1 if close else 0)):
        side = "right" if k % 2 == 0 else "left"
        other = "left" if side == "right" else "right"
        if turn_at is not None and k == turn_at:
            heading = math.radians(turn_deg)
        last = close and k == n
        reach = (reach if last else reach + (s_left if side == "left" else s_right))
        new = reach * complex(math.cos(heading), math.sin(heading)) if turn_at is None or k < turn_at else (
            pos[other] + (0 if last else (s_left if side == "left" else s_right)) * complex(math.cos(heading),
                                                                                          math.sin(heading)))
        if last:
            new = pos[other]
        d = new - pos[side]
        rows[side].append({"start_s": t - 0.6, "end_s": t + 0.1, "event_s": t, "tc_s": t - 0.4,
                           "length_m": abs(d), "heading_rad": math.atan2(d.imag, d.real) if abs(d) else heading})
        pos[side] = new
        t += 0.6
    return pd.DataFrame(rows["left"]), pd.DataFrame(rows["right"])


def _scaled(tab: pd.DataFrame, f: float = 1.0, rot_deg: float = 0.0) -> pd.DataFrame:
    return tab.assign(length_m=tab["length_m"] * f, heading_rad=tab["heading_rad"] + math.radians(rot_deg))


def test_step_length_per_foot_and_its_asymmetry_on_an_exact_walk():
    """L310: each step is the landing foot's position minus the other foot's, along the walk: 0.45 m onto the left,
    0.36 m onto the right; the first contact makes no step, the closing one is the anchor and no step length."""
    left, right = _walk(0.45, 0.36, 20)
    res = bilateral_gait(left, right)
    st, w = res["steps"], res["walk"]
    print(st[["side", "step_length_m"]].to_string())
    assert np.isnan(st["step_length_m"].iloc[-1]) and int(st["step_length_m"].notna().sum()) == len(st) - 1
    assert w["n_step_lengths"] == int((st["kind"] == "level").sum())  # L538: the headline's level steps
    ok = st.iloc[:-1]
    assert np.allclose(ok.loc[ok["side"] == "left", "step_length_m"], 0.45, atol=1e-9)
    assert np.allclose(ok.loc[ok["side"] == "right", "step_length_m"], 0.36, atol=1e-9)
    assert w["step_length_m_ratio"] == pytest.approx(0.45 / 0.36)
    assert w["step_length_m_si_pct"] == pytest.approx(100 * 0.09 / 0.405)
    assert w["step_length_scale_pct"] == pytest.approx(0.0, abs=1e-9)


def test_the_closing_step_takes_out_a_relative_scale_and_a_rotated_frame_changes_nothing():
    """L310: the left track reading 2 % long drifts the steps apart (0.17 m by the end) unless the closing step's
    offset takes the relative scale out; the left unit's heading 30 deg off (no compass) is turned back. Without a
    closing stride or without the opening half stride the walk is not anchored: no step length, L311's line."""
    left, right = _walk(0.45, 0.36, 40)
    res = bilateral_gait(_scaled(left, 1.02, 30.0), right)
    st = res["steps"].iloc[:-1]
    err = np.where(st["side"] == "left", st["step_length_m"] - 0.45, st["step_length_m"] - 0.36)
    print("errors with the closure", np.round(err, 4), res["walk"]["step_length_scale_pct"])
    assert np.abs(err).max() < 0.005 and res["walk"]["step_length_scale_pct"] == pytest.approx(2.0, abs=0.1)
    for open_walk in (bilateral_gait(_scaled(left.iloc[:-1], 1.02, 30.0), right),  # no closing stride
                      bilateral_gait(_scaled(left, 1.02, 30.0), right.iloc[1:])):  # no opening half stride
        assert open_walk["walk"]["step_length_scale_pct"] is None and open_walk["walk"]["step_length_m_left"] is None
        assert open_walk["steps"]["step_length_m"].isna().all() and UNANCHORED_NOTE in open_walk["warnings"]


def test_turns_missing_contacts_and_label_tables():
    """L310: a walk closing off its first axis (a 90 deg turn) is not anchored; after a 180 deg turn the walk is
    back on its axis and its steps have lengths (those in the turn none); a return walk closing near its start is
    not anchored: no step length and L311's line; a contact one track missed makes no step; labels give none."""
    left, right = _walk(0.45, 0.36, 30, turn_at=15, turn_deg=90.0)  # closes off the first axis: no anchor
    ell = bilateral_gait(left, right)
    assert ell["steps"]["step_length_m"].isna().all() and UNANCHORED_NOTE in ell["warnings"]
    assert STEP_AXIS_MAX_DEG < 90
    left, right = _walk(0.45, 0.36, 55, turn_at=15, turn_deg=180.0)  # out 6 m, back 16 m: ends 10 m away
    st = bilateral_gait(left, right)["steps"]
    back = st.iloc[16:-1]
    assert back["step_length_m"].notna().all()
    assert np.allclose(back.loc[back["side"] == "left", "step_length_m"], 0.45, atol=1e-9)
    ret = bilateral_gait(*_walk(0.45, 0.36, 30, turn_at=15, turn_deg=180.0))  # a return walk, closed near its start
    assert ret["steps"]["step_length_m"].isna().all() and ret["walk"]["step_length_scale_pct"] is None
    assert UNANCHORED_NOTE in ret["warnings"]
    left, right = _walk(0.45, 0.36, 20)
    miss = right.drop(index=4).reset_index(drop=True)
    miss.loc[4, "length_m"] = 2 * (0.45 + 0.36)  # the track's next stride covers the missed one
    st = bilateral_gait(left, miss)["steps"]
    assert len(st) == len(bilateral_gait(left, right)["steps"]) - 2
    assert np.allclose(st.loc[st["side"] == "left", "step_length_m"].iloc[:-1], 0.45, atol=1e-9)
    labels = [pd.DataFrame({"ic_s": t["event_s"], "tc_s": t["tc_s"]}) for t in (left, right)]
    w = bilateral_gait(*labels)["walk"]
    assert w["step_length_m_left"] is None and w["n_step_lengths"] == 0


@pytest.mark.parametrize("paretic", ["left", "right"])
def test_gait_on_simulated_asymmetric_feet_against_the_true_step_lengths(tmp_path, capsys, paretic):
    """L311: two simulated feet of one walk with step-length asymmetry 0.2 (S42): every tracked step matched to the
    simulator's step (ics.csv) within 0.03 m, median within 0.01 m; the ratio within 0.05 of the true one, the
    longer step on the paretic side; gait_steps.csv and the printed line carry it."""
    args = ["--route", "stand:3, straight:14, stand:3", "--user-seed", "6002", "--rate", "100", "--step-length",
            "0.4", "--step-time", "0.7", "--step-length-asymmetry", "0.2", "--paretic-side", paretic]
    for foot in ("left", "right"):
        assert main(["simulate", *args, "--foot", foot, "--out", str(tmp_path / foot)]) == 0
    capsys.readouterr()
    assert main(["gait", str(tmp_path / "left"), str(tmp_path / "right"), "--out", str(tmp_path / "g")]) == 0
    out = capsys.readouterr().out
    assert "step length left/right" in out and "the closing step took out" in out
    st = pd.read_csv(tmp_path / "g" / "gait_steps.csv")
    walk = json.loads((tmp_path / "g" / "gait_summary.json").read_text())["walk"]
    ics = pd.read_csv(tmp_path / "right" / "ics.csv")
    ics = ics[ics["kind"] == "walk"]
    err, true = [], {"left": [], "right": []}
    for _, s in st.dropna(subset=["step_length_m"]).iterrows():
        c = ics[ics["foot"] == s["side"]]
        j = (c["ic_ms"] / 1000 - s["ic_s"]).abs().idxmin()
        assert abs(c.loc[j, "ic_ms"] / 1000 - s["ic_s"]) < 0.15
        err.append(s["step_length_m"] - c.loc[j, "step_length_m"])
        true[s["side"]].append(c.loc[j, "step_length_m"])
    err = np.array(err)
    ratio = np.mean(true["left"]) / np.mean(true["right"])
    print(f"paretic {paretic}: {len(err)} steps, error median {np.median(err):+.4f} m, max |.| "
          f"{np.abs(err).max():.4f} m; ratio {walk['step_length_m_ratio']:.3f} vs true {ratio:.3f}")
    assert len(err) >= 30 and abs(np.median(err)) < 0.01 and np.abs(err).max() < 0.03
    assert abs(walk["step_length_m_ratio"] - ratio) < 0.05
    assert (walk["step_length_m_ratio"] > 1) == (paretic == "left")


def _foot_walk(length_m: float, stride_m: float = 1.2, stride_s: float = 1.5, turn_after_m: float | None = None
               ) -> pd.DataFrame:
    n = int(round(length_m / stride_m))
    t = 2.0 + stride_s * np.arange(1, n + 1)
    head = np.zeros(n)
    if turn_after_m is not None:
        head[int(turn_after_m / stride_m):] = math.pi / 2
    return pd.DataFrame({"start_s": t - stride_s, "end_s": t + 0.2, "event_s": t, "length_m": stride_m,
                         "heading_rad": head, "unit": "foot"})


def test_ten_metre_walk_kernel():
    """L312 / L313: the middle 10 m of a steady 0.8 m/s walk take 12.5 s; a 12 m walk, a walk turning inside its
    first 14 m, a stride without a length there and a lower-back table are not timed, each with its note."""
    r = ten_metre_walk(_foot_walk(20.4))
    assert r["ten_m_walk_time_s"] == pytest.approx(12.5) and r["ten_m_walk_speed_mps"] == pytest.approx(0.8)
    assert r["ten_m_walk_note"] is None
    short = ten_metre_walk(_foot_walk(12.0))
    assert short["ten_m_walk_time_s"] is None and "no walking bout of 14 m" in short["ten_m_walk_note"]
    assert "the longest 12.00 m" in short["ten_m_walk_note"]  # L349: 2 decimals
    turned = ten_metre_walk(_foot_walk(20.4, turn_after_m=7.2))
    assert turned["ten_m_walk_time_s"] is None and "turn" in turned["ten_m_walk_note"]
    late_turn = ten_metre_walk(_foot_walk(20.4, turn_after_m=15.6))  # after the 14 m: timed
    assert late_turn["ten_m_walk_time_s"] == pytest.approx(12.5)
    bad = _foot_walk(20.4).assign(impossible=False)
    bad.loc[3, "impossible"] = True
    assert "no length" in ten_metre_walk(bad)["ten_m_walk_note"]
    assert ten_metre_walk(_foot_walk(20.4).assign(unit="waist"))["ten_m_walk_note"] == LOWER_BACK_NOTE
    assert ten_metre_walk(pd.DataFrame())["ten_m_walk_time_s"] is None


def test_ten_metre_walk_on_a_simulated_walk_of_known_speed(tmp_path, capsys):
    """L313: a simulated 0.5 m/s walker's 16 m walk: the foot track's middle-10-m speed within 2 % of the body's
    true crossing of 2 m and 12 m; `track` prints it and summary.json carries the keys."""
    out, summary, t, x, _ = tracked_slow_walk(tmp_path, capsys, "stand:3, straight:16, stand:3", 6029, 0.35, 0.7)
    true_s = t[np.argmax(x >= 12.0)] - t[np.argmax(x >= 2.0)]
    err = 100 * (summary["ten_m_walk_speed_mps"] / (10 / true_s) - 1)
    print(f"10 m walk: tracked {summary['ten_m_walk_time_s']:.2f} s, true {true_s:.2f} s, speed error {err:+.2f} %")
    assert abs(err) < 2.0 and "10 m walk test" in out
