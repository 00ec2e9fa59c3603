"""Session 37, fixer FA (trial T2: a stroke unit's slow, hemiparetic walkers with two foot units). Decisions
steps 70, L459-L462. Fresh simulated users 9180-9189 only."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.displace.force_check import check_force_stance, swing_lulls_dropped

ROUTE = "stand:3, straight:16, stand:3"


def _sim(tmp_path, user, step_length, step_time, asym, foot, route=ROUTE):
    out = tmp_path / f"s{user}_{foot}"
    assert main(["simulate", "--route", route, "--bounce", "pendulum", "--rate", "100", "--user-seed", str(user),
                 "--step-length", str(step_length), "--step-time", str(step_time), "--step-time-asymmetry", str(asym),
                 "--foot", foot, "--out", str(out)]) == 0
    return out


def _masks():
    """100 Hz, a 1.7 s stride: loads 0-0.7, 1.5-2.4, 3.2-4.0 s (stance 0.9 s, swing 0.8 s), foot flats 0.1-0.4,
    1.7-2.1, 3.4-3.8 s, and a one-sample lull at 1.0 s inside the force's swing."""
    t = np.arange(0, 4.0, 0.01)
    rest = (((t >= 0.1) & (t < 0.4)) | ((t >= 1.7) & (t < 2.1)) | ((t >= 3.4) & (t < 3.8))
            | np.isclose(t, 1.0))
    loaded = (t < 0.7) | ((t >= 1.5) & (t < 2.4)) | (t >= 3.2)
    g = np.where(rest, 0.1, 3.0)
    return t, rest, loaded, g


def test_a_lull_inside_the_insoles_swing_is_no_rest_and_no_insole_fault_steps_70():
    """Steps 70: the one-sample IMU "rest" at 1.0 s lies in the force's unbroken swing 0.7-1.5 s: it is dropped, and
    L365 finds no failing stride (before it, the lull made two strides, both blamed on the insoles)."""
    t, rest, loaded, g = _masks()
    from pdrlearn.displace.foot import stance_runs

    rr = stance_runs(t, rest)
    assert len(rr) == 4 and len(swing_lulls_dropped(t, rr, loaded)) == 3
    chk = check_force_stance(t, loaded, rest, g)
    assert chk.n_bad == 0 and chk.n_strides == 2


def test_an_insole_that_drops_out_in_a_rest_is_still_blamed_steps_70():
    """The insole drops out 1.5-2.4 s, over the real rest 1.7-2.1 s: the force reads one unloaded span 0.7-3.2 s
    (swing, rest, swing) whose unloaded rest lasts 0.4 s, longer than any swing the force counts (0.15 s): no lull,
    L365 still blames the insole."""
    t, rest, loaded, g = _masks()
    rest = rest & ~np.isclose(t, 1.0)
    loaded = loaded & ~((t >= 1.5) & (t < 2.4))
    chk = check_force_stance(t, loaded, rest, g)
    assert chk.n_bad == 2 and chk.reasons == ["no load in the foot's rest"] * 2


def test_an_insole_dropout_over_a_short_real_foot_flat_is_still_blamed_steps_71():
    """Steps 71 (review R3 finding 1): gaitmap MS-like foot flats of 0.04 s (73 of 75 of its real rests are under
    0.15 s), one every 1.1 s stride inside a 0.7 s load; the insole drops out over the fourth stance. The unloaded
    rest is as short as a lull, but the loads around it start two strides apart: it stays a rest, all 7 strides are
    checked and the two around it blamed on the insole (steps 70 alone dropped it: 6 strides, no warning)."""
    t = np.arange(0, 8.8, 0.01)
    ph = t % 1.1
    rest = (ph >= 0.30) & (ph < 0.345)
    loaded = ph < 0.7
    g = np.where(rest, 0.1, 3.0)
    drop = loaded & ~((t >= 3.25) & (t < 4.1))
    from pdrlearn.displace.foot import stance_runs

    rr = stance_runs(t, rest)
    assert len(rr) == 8 and np.all(t[rr[:, 1] - 1] - t[rr[:, 0]] <= 0.045)
    assert len(swing_lulls_dropped(t, rr, drop)) == 8
    assert check_force_stance(t, loaded, rest, g).n_bad == 0
    chk = check_force_stance(t, drop, rest, g)
    assert chk.n_strides == 7 and chk.n_bad == 2 and chk.reasons == ["no load in the foot's rest"] * 2


def test_slow_paretic_foot_keeps_its_stride_count_steps_70(tmp_path, capsys):
    """Fresh user 9185 (0.28 m in 0.90 s, step-time asymmetry 0.5, the left foot): before steps 70 the track had 30
    strides for the labels' 29 and an L365 insole line (experiments/results/paretic_lull_70.txt)."""
    d = _sim(tmp_path, 9185, 0.28, 0.90, 0.5, "left")
    capsys.readouterr()
    assert main(["track", "--no-plot", str(d), "--out", str(tmp_path / "t"), "--force"]) == 0
    err = capsys.readouterr().err
    n = json.loads((tmp_path / "t" / "summary.json").read_text())["n_strides_one_foot"]
    assert n == len(pd.read_csv(d / "steps.csv")) == 29
    assert "disagree with the foot IMU" not in err




@pytest.fixture(scope="module")
def short_visit(tmp_path_factory):
    """Fresh user 9355 (0.30 m in 0.80 s, asymmetry 0.4), both feet, 4 m: one bout of fewer than 10 steps a side."""
    root = tmp_path_factory.mktemp("l461")
    for foot in ("left", "right"):
        _sim(root / "study" / "v1", 9355, 0.30, 0.80, 0.4, foot, route="stand:3, straight:4, stand:3")
    return root


def test_gait_withholds_symmetry_indices_under_ten_steps_a_side_l461(short_visit, capsys):
    """Decision L461: `gait` (pair_sessions) on a 4 m walk gives the walk no SI or ratio and says why in
    ``si_withheld`` and the warnings; the kernel: 5 steps a side give no SI or ratio, 12 a side keep them."""
    from pdrlearn.track.bilateral import bilateral_gait, withhold_indices

    v = short_visit / "study" / "v1"
    out = short_visit / "g"
    assert main(["gait", str(v / "s9355_left"), str(v / "s9355_right"), "--out", str(out)]) == 0
    walk = json.loads((out / "gait_summary.json").read_text())["walk"]
    assert min(walk["n_steps_left"], walk["n_steps_right"]) < 10
    assert walk["step_time_s_si_pct"] is None and walk["stride_time_s_ratio"] is None
    assert "10 needed" in walk["si_withheld"]

    def foot(ic):
        ic = np.asarray(ic, float)
        return pd.DataFrame({"start_s": ic - 0.6, "end_s": ic + 0.2, "event_s": ic, "tc_s": ic - 0.45,
                             "length_m": 1.2, "gap_s": 0.0, "unit": "foot"})

    short = bilateral_gait(foot(np.arange(6) * 1.2), foot(0.7 + np.arange(6) * 1.2))["walk"]
    # decision L538: the headline's steps are the level ones, the walk's first (start_stop) step left out
    assert "4 steps on the right side, 10 needed" in withhold_indices(short)
    assert short["n_steps_left"] == 5 and short["step_time_s_si_pct"] is None and short["step_time_s_ratio"] is None
    long = bilateral_gait(foot(np.arange(13) * 1.2), foot(0.7 + np.arange(13) * 1.2))["walk"]
    assert withhold_indices(long) is None and long["step_time_s_si_pct"] == pytest.approx(100 * 0.2 / 0.6)


def test_gait_all_bout_rows_withhold_their_indices_under_ten_steps_a_side_l461(short_visit, capsys):
    """Decision L461 amended (review R3 finding 2): gait-all writes no walk row, so its bouts carry the rule: a bout
    with fewer than 10 steps a side has empty ``*_si_pct`` / ``*_ratio`` and says why in ``si_withheld`` (before,
    gait_bouts.csv kept the SI the warning said was withheld)."""
    assert main(["gait-all", str(short_visit / "study"), "--out", str(short_visit / "ga")]) == 0
    bouts = pd.read_csv(short_visit / "ga" / "gait_bouts.csv")
    pairs = pd.read_csv(short_visit / "ga" / "gait_pairs.csv")
    assert "symmetry indices and ratios withheld" in pairs.loc[0, "warnings"]
    few = bouts[bouts[["n_steps_left", "n_steps_right"]].min(axis=1) < 10]
    assert len(few) >= 1
    si = [c for c in bouts if c.endswith(("_si_pct", "_ratio"))]
    assert len(si) >= 10 and few[si].isna().all().all()
    assert few["si_withheld"].str.contains("10 needed on each side").all()


def test_gait_and_gait_all_carry_each_foots_trust_lines_l461(tmp_path, capsys):
    """Decision L461: fresh user 9182 at 0.31 m/s, both feet: gait_summary.json's warnings and each side's
    ``sessions`` hold the track's slower-than-validated line (L95), and gait-all's gait_pairs.csv has them in
    ``warnings``; before, both were empty of it."""
    visit = tmp_path / "study" / "v1"
    for foot in ("left", "right"):
        d = _sim(visit, 9182, 0.25, 0.80, 0.5, foot, route="stand:3, straight:8, stand:3")
    left, right = visit / "s9182_left", visit / "s9182_right"
    assert main(["gait", str(left), str(right), "--out", str(tmp_path / "g")]) == 0
    res = json.loads((tmp_path / "g" / "gait_summary.json").read_text())
    assert any(w.startswith("left foot:") and "slower than the walking" in w for w in res["warnings"])
    assert any("slower than the walking" in w for w in res["sessions"]["right"]["warnings"])
    assert main(["gait-all", str(tmp_path / "study"), "--out", str(tmp_path / "ga")]) == 0
    pairs = pd.read_csv(tmp_path / "ga" / "gait_pairs.csv")
    assert "right foot:" in pairs.loc[0, "warnings"] and "slower than the walking" in pairs.loc[0, "warnings"]
    assert d.exists()


def test_corridor_test_says_its_duration_and_notes_a_whole_recording_l462():
    """Decision L462: 480 one-second strides up and down a corridor without --window: walk_test_duration_s 480 s and
    one note that this is no 6-minute test; with the 6-minute span no note."""
    from pdrlearn.track.corridor import corridor_laps

    t = np.arange(480, dtype=float)
    steps = pd.DataFrame({"start_s": t, "end_s": t + 1.0, "event_s": t + 1.0, "length_m": 1.0,
                          "heading_rad": np.where((np.arange(480) // 30) % 2 == 0, 0.0, np.pi), "unit": "foot"})
    mids = np.arange(30, 480, 30, dtype=float)
    turns = pd.DataFrame({"start_s": mids - 0.5, "end_s": mids + 0.5, "angle_deg": 180.0})
    _, keys, lines = corridor_laps(steps, turns, 30.0)
    assert keys["walk_test_duration_s"] == pytest.approx(480.0)
    assert sum("not a 6-minute test" in x and "L462" in x for x in lines) == 1
    _, keys, lines = corridor_laps(steps, turns, 30.0, span=(0.0, 360.0))
    assert keys["walk_test_duration_s"] == pytest.approx(360.0) and not any("L462" in x for x in lines)


def test_corridor_duration_is_a_corridor_key_in_the_no_steps_path_and_the_report_table_l462():
    """L462 amended (review R3 finding 5): ``walk_test_duration_s`` was written only past the no-steps return and
    was not in ``corridor.KEYS``, so a corridor run without steps omitted it and `pdrlearn report`'s walk-test table
    (E152) showed the distance without its span."""
    from pdrlearn.report.tests_table import WALK_TEST_COLUMNS
    from pdrlearn.track.corridor import corridor_laps

    _, keys, _ = corridor_laps(pd.DataFrame(), None, 30.0)
    assert "walk_test_duration_s" in keys and keys["walk_test_duration_s"] is None
    assert "walk_test_duration_s" in WALK_TEST_COLUMNS
