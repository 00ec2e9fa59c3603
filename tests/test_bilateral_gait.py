"""Decisions L259-L263: bilateral gait from two foot units of one walk (`pdrlearn gait`, session 29 PD trial
finding 9)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.bilateral import bilateral_gait, check_pair, cycle_table, foot_events, merged_contacts

ROOT = Path(__file__).resolve().parents[1]
LEFT, RIGHT = ROOT / "datasets/real/gaitmap_level_left", ROOT / "datasets/real/gaitmap_level_right"


def _foot(ic, swing=0.45, length=1.2) -> pd.DataFrame:
    """A foot track's steps.csv: one row per stride, its IC (event_s) and the toe-off before it (tc_s)."""
    ic = np.asarray(ic, float)
    return pd.DataFrame({"start_s": ic - 0.6, "end_s": ic + 0.2, "event_s": ic, "tc_s": ic - swing,
                         "length_m": length, "gap_s": 0.0, "unit": "foot"})


def test_hand_made_walk_step_times_asymmetry_and_support():
    """Left ICs 0, 1.2 ... and right ICs 0.7, 1.9 ...: the left step (right IC -> left IC) 0.5 s, the right 0.7 s:
    SI = 100 x 0.2 / 0.6 = 33.3 %, ratio 0.5 / 0.7. Swing 0.45 s each: the left cycle 0 -> 1.2 has the right TC
    at 0.25, right IC 0.7, left TC 0.75: double support (0.25 + 0.05) / 1.2 = 25 %, single support 0.45 / 1.2."""
    left = _foot(np.arange(5) * 1.2, length=1.3)
    right = _foot(0.7 + np.arange(5) * 1.2, length=1.1)
    r = bilateral_gait(left, right)
    w = r["walk"]
    assert w["n_steps_all_left"] == 4 and w["n_steps_all_right"] == 5  # L538: every step; the headline's level ones
    assert w["n_steps_left"] == 4 and w["n_steps_right"] == 3  # leave out the walk's first and last (start_stop)
    assert w["step_time_s_left"] == pytest.approx(0.5) and w["step_time_s_right"] == pytest.approx(0.7)
    assert w["step_time_s_si_pct"] == pytest.approx(100 * 0.2 / 0.6)
    assert w["step_time_s_ratio"] == pytest.approx(0.5 / 0.7)
    assert w["stride_length_m_si_pct"] == pytest.approx(100 * 0.2 / 1.2)
    assert w["double_support_pct"] == pytest.approx(25.0)
    assert w["single_support_pct_left"] == pytest.approx(37.5) and w["single_support_pct_right"] == pytest.approx(37.5)
    # L538: 8 cycles; the right one ending on the walk's last contact (start_stop) is not in the headline
    assert len(r["cycles"]) == 8 and w["n_support_cycles"] == 7 and r["toe_off"] and "L73" in r["reason"]
    assert len(r["bouts"]) == 1 and r["bouts"][0]["step_time_s_si_pct"] == pytest.approx(w["step_time_s_si_pct"])


def test_a_missed_stride_makes_no_step_and_no_cycle():
    """The right track misses its IC at 3.1 s: the left IC 3.6 s follows the left IC 2.4 s, so no step ends there,
    and the two cycles around the missing IC (left 2.4 -> 3.6, right 1.9 -> 4.3) are left out."""
    left = _foot(np.arange(5) * 1.2)
    right = _foot(np.delete(0.7 + np.arange(5) * 1.2, 2))
    r = bilateral_gait(left, right)
    assert r["walk"]["n_steps_all_left"] == 3 and r["walk"]["n_steps_all_right"] == 4  # L538: every step
    assert r["walk"]["step_time_s_left"] == pytest.approx(0.5)
    cyc = r["cycles"]
    assert not ((cyc["side"] == "left") & np.isclose(cyc["start_s"], 2.4)).any()
    assert not ((cyc["side"] == "right") & np.isclose(cyc["start_s"], 1.9)).any()


def test_a_pause_splits_the_walk_into_bouts_with_their_own_asymmetry():
    """Bout 1 symmetric (0.6 / 0.6 s), a 5 s stand, bout 2 asymmetric (0.5 / 0.7 s): two bouts, their own SI."""
    l1, r1 = np.arange(6) * 1.2, 0.6 + np.arange(6) * 1.2
    l2, r2 = 12.0 + np.arange(6) * 1.2, 12.7 + np.arange(6) * 1.2
    r = bilateral_gait(_foot(np.r_[l1, l2]), _foot(np.r_[r1, r2]))
    assert [b["bout"] for b in r["bouts"]] == [1, 2]
    assert r["bouts"][0]["step_time_s_si_pct"] == pytest.approx(0.0, abs=1e-9)
    assert r["bouts"][1]["step_time_s_si_pct"] == pytest.approx(100 * 0.2 / 0.6)
    assert r["steps"]["step_time_s"].max() < 1.0  # no step across the stand


def test_without_toe_off_the_step_times_are_given_and_support_is_none():
    left, right = _foot(np.arange(5) * 1.2).drop(columns="tc_s"), _foot(0.7 + np.arange(5) * 1.2).drop(columns="tc_s")
    r = bilateral_gait(left, right)
    assert r["walk"]["step_time_s_si_pct"] == pytest.approx(100 * 0.2 / 0.6)
    assert r["walk"]["double_support_pct"] is None and not r["toe_off"] and "--toe-off" in r["reason"]


def test_out_of_order_events_give_no_support():
    """A toe-off after the foot's own next IC (a wrong event) gives the cycle no support times."""
    left = _foot(np.arange(4) * 1.2)
    left.loc[2, "tc_s"] = 2.5  # after the IC 2.4 of that row
    both = merged_contacts(foot_events(left), foot_events(_foot(0.7 + np.arange(4) * 1.2)))
    cyc = cycle_table(both)
    bad = (cyc["side"] == "left") & np.isclose(cyc["start_s"], 1.2)
    assert cyc.loc[bad, "double_support_pct"].isna().all() and bad.any()


def test_refuses_clocks_that_do_not_overlap():
    with pytest.raises(DataError, match="clocks do not overlap"):
        bilateral_gait(_foot(np.arange(5) * 1.2), _foot(100 + np.arange(5) * 1.2))
    with pytest.raises(DataError, match="1 initial contact"):
        bilateral_gait(_foot([0.0]), _foot(np.arange(5) * 1.2))


def test_refuses_the_same_foot_the_wrong_order_and_one_recording_twice():
    with pytest.raises(DataError, match="both the left foot"):
        check_pair(Path("a"), Path("b"), {"foot": "left"}, {"foot": "left"})
    with pytest.raises(DataError, match="says the right foot, given as the left"):
        check_pair(Path("a"), Path("b"), {"foot": "right"}, {"foot": "left"})
    with pytest.raises(DataError, match="same recording"):
        check_pair(Path("a"), Path("b"), {}, {}, "x", "x")
    check_pair(Path("a"), Path("b"), {}, {"instrumented_foot": "right"}, "x", "y")  # no foot given: taken as given


def test_simulator_contacts_read_the_simulated_ratio():
    """Decision L263: the simulator's both-feet contacts (ics.csv) of a walk with --step-time-asymmetry 0.3 read
    the symmetry ratio L / R the simulator made (1.3, S35; the walker's variability adds ~0.01)."""
    s = simulate_path(parse_route("stand:2, straight:20, stand:2"), UserProfile.from_seed(5101), rate_hz=20.0,
                      seed=3, scenario="route", step_time_asymmetry=0.3)
    ics = s.extras["ics"]
    feet = [pd.DataFrame({"ic_s": ics.loc[ics["foot"] == f, "ic_s"].to_numpy(float)}) for f in ("left", "right")]
    w = bilateral_gait(*feet)["walk"]
    assert abs(w["step_time_s_ratio"] - 1.3) < 0.03, w["step_time_s_ratio"]
    assert w["double_support_pct"] is None  # ics.csv has no toe-off


def _cli(argv, capsys):
    rc = main(argv)
    return rc, capsys.readouterr()


def test_cli_on_the_gaitmap_pair(tmp_path, capsys):
    """The real level walk: both feet tracked with --toe-off; the mocap events give the reference line."""
    rc, out = _cli(["gait", str(LEFT), str(RIGHT), "--out", str(tmp_path / "g")], capsys)
    assert rc == 0, out.err
    # decision L538: the headline is the level straight steps' (the 4 x 10 m walk's turns and starts left out)
    # decision L603: 26/26 (24/24 before, when two drifting right strides were stair steps)
    assert "steps left/right 26/26 (level straight steps, of 32/31" in out.out
    assert "reference (the sessions' labelled contacts):" in out.out
    assert "double support" in out.out and "L262" in out.out
    summary = json.loads((tmp_path / "g" / "gait_summary.json").read_text())
    # no false warning; L311's line says why it has no step length (a return walk: no anchor)
    assert [w for w in summary["warnings"] if "L311" not in w] == [] and "L284" not in out.err and "L285" not in out.err
    assert len(summary["warnings"]) == 1 and "no step length: the walk is not anchored" in summary["warnings"][0]
    w, ref = summary["walk"], summary["reference"]["walk"]
    assert abs(w["step_time_s_si_pct"] - ref["step_time_s_si_pct"]) < 3.0
    assert 20 < w["double_support_pct"] < ref["double_support_pct"] < 40  # L262: reads low
    steps = pd.read_csv(tmp_path / "g" / "gait_steps.csv")
    assert set(steps["side"]) == {"left", "right"} and (steps["step_time_s"] > 0.4).all()
    rc, out = _cli(["gait", str(LEFT), str(RIGHT), "--out", str(tmp_path / "g")], capsys)
    assert rc != 0 and "--force" in out.err  # an existing output is replaced only with --force


@pytest.mark.parametrize("args, msg", [
    ([LEFT, LEFT], "hold the same recording"),
    ([RIGHT, LEFT], "says the right foot, given as the left"),
    ([LEFT, ROOT / "datasets/real/gaitmap_stairs_up_left"], "are both the left foot"),
    ([LEFT, ROOT / "datasets/real/mobgap_HA001_Test5_Trial1"], "has no foot unit"),
    (["{tmp}/missing", RIGHT], "session folder not found"),
    (["{tmp}/empty", RIGHT], "no samples (empty file)"),
])
def test_cli_refusals_are_one_line(args, msg, tmp_path, capsys):
    empty = tmp_path / "empty"  # a foot session whose sensor files hold a header only
    empty.mkdir()
    (empty / "meta.json").write_text((LEFT / "meta.json").read_text())
    for name in ("fAccelerometer", "fGyroscope"):
        (empty / f"{name}.csv").write_text("timestamp,x,y,z\n")
    args = [str(a).format(tmp=tmp_path) for a in args]
    rc, out = _cli(["gait", *args, "--out", str(tmp_path / "g")], capsys)
    err = [x for x in out.err.splitlines() if x.startswith("error:")]
    assert rc != 0 and len(err) == 1 and msg in err[0], out.err
    assert "Traceback" not in out.err and not (tmp_path / "g").exists()


def test_gait_says_no_model_once_as_info_and_track_still_warns(caplog):
    """Decision E153 (trial T1 finding F10): `gait` takes no model, so each foot track's "no model" warning (whose
    advice, pass a model, it cannot follow) becomes one INFO line for the pair; `track` without a model still warns."""
    import logging

    from pdrlearn.io import read_session
    from pdrlearn.track.bilateral import GAIT_NO_MODEL_INFO, pair_sessions
    from pdrlearn.track.plasys import NO_MODEL_WARNING, track_plasys

    with caplog.at_level(logging.INFO, logger="pdrlearn"):
        pair_sessions(LEFT, RIGHT)
    no_model = [r for r in caplog.records if r.levelno >= logging.WARNING and NO_MODEL_WARNING in r.getMessage()]
    info = [r for r in caplog.records if r.levelno == logging.INFO and r.getMessage() == GAIT_NO_MODEL_INFO]
    assert no_model == [] and len(info) == 1
    caplog.clear()
    with caplog.at_level(logging.INFO, logger="pdrlearn"):
        track_plasys(read_session(LEFT))
    assert any(r.levelno == logging.WARNING and NO_MODEL_WARNING in r.getMessage() for r in caplog.records)
