"""Session 18's rehab trial on the waist pipelines: a track with no steps says why (W76), the slow-gait line of an
uncalibrated waist names the calibration (W77), and calibrate's implausible-factor line allows a slow walker (W78)."""

from __future__ import annotations

import dataclasses
import math
import re

import numpy as np
import pandas as pd

from pdrlearn.io.session import Stream
from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.track.gait import gait_range_warning
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.calibration import CalibrationWalk, check_gain
from pdrlearn.waist.params import WaistParams


def _damped_patient(gain: float = 0.4, lean_deg: float = 20.0):
    """The trial's rollator patient: 0.3 m steps in 0.75 s (0.4 m/s) over 14 m, the waist's dynamic part x gain
    about its 2 s mean and a forward lean (the trial's damp.py)."""
    u = dataclasses.replace(UserProfile.from_seed(1), step_length_m=0.30 / 0.85, step_time_s=0.75 / 1.2)
    s = simulate_path([Stand(3), Straight(14), Stand(3)], u, speed="slow", rate_hz=20, seed=0)
    a = math.radians(lean_deg)
    rot = np.array([[1, 0, 0], [0, math.cos(a), -math.sin(a)], [0, math.sin(a), math.cos(a)]])
    for name in ("wAccelerometer", "wGyroscope"):
        st = s.streams[name]
        lo = pd.DataFrame(st.values).rolling(40, center=True, min_periods=1).mean().to_numpy()
        s.streams[name] = Stream(name, st.t.copy(), (lo + gain * (st.values - lo)) @ rot.T)
    return s


def test_no_steps_warns_with_the_gate_the_level_and_a_fix_that_works():
    """W76: 0 steps on the damped walk is one warning naming the gate, the data's SD and the params fix; the
    threshold it suggests finds the walk's steps."""
    s = _damped_patient()
    r = track_waist(s, pipeline="waist-pendulum", relative_gate=False)  # W4's fixed gate
    assert not r.steps["has_next"].any()
    msg = [w for w in r.info["warnings"] if w.startswith("no steps found")]
    assert len(msg) == 1, r.info["warnings"]
    assert ">= 0.50 m/s^2" in msg[0] and "largest 2 s SD is" in msg[0] and "walk_threshold_mps2" in msg[0]
    x = float(re.search(r'"walk_threshold_mps2": ([0-9.]+)', msg[0]).group(1))
    assert 0.15 <= x < 0.5
    r2 = track_waist(s, pipeline="waist-pendulum", params={"walk_threshold_mps2": x}, relative_gate=False)
    n_true = len(s.extras["ics"])
    assert r2.steps["has_next"].sum() >= 0.9 * (n_true - 1), (len(r2.steps), n_true)
    assert not any(w.startswith("no steps found") for w in r2.info["warnings"])
    # W76's session-relative gate (the default) finds them with no params
    r3 = track_waist(s, pipeline="waist-pendulum")
    assert r3.steps["has_next"].sum() >= 0.9 * (n_true - 1) and r3.info["walk_threshold_mps2"] < 0.5
    assert not any(w.startswith("no steps found") for w in r3.info["warnings"])


def test_relative_gate_leaves_a_normal_walk_and_standing_alone():
    """W76: a normal walk keeps W4's 0.5 exactly (same steps, same distance); a standing-only recording gets the
    0.15 floor, no step, and the no-steps line (the gate never opened)."""
    u = UserProfile.from_seed(3)
    walk = simulate_path([Stand(2), Straight(12), Stand(2)], u, speed="normal", rate_hz=20, seed=1)
    a = track_waist(walk, pipeline="waist-pendulum")
    b = track_waist(walk, pipeline="waist-pendulum", relative_gate=False)
    assert a.info["walk_threshold_mps2"] == 0.5 and a.steps["length_m"].sum() == b.steps["length_m"].sum()
    still = simulate_path([Stand(20)], u, speed="normal", rate_hz=20, seed=1)
    r = track_waist(still, pipeline="waist-pendulum")
    assert len(r.steps) == 0 and r.info["walk_threshold_mps2"] == 0.15
    assert any(w.startswith("no steps found") and "never opened" in w for w in r.info["warnings"])


def test_slow_line_of_an_uncalibrated_waist_names_the_calibration():
    """W77: the L95 slow line fires on the measured cadence even when the (uncalibrated) speed looks normal, and on
    an uncalibrated waist track it says the distance depends on a calibration; calibrated or foot: no such clause."""
    base = {"median_cadence_spm": 62.0, "median_speed_mps": 0.9}
    waist = {**base, "info": {"pipeline": "waist-pendulum", "params_source": "defaults"}}
    line = gait_range_warning(waist)
    assert line is not None and "62 steps/min" in line and "slower than" in line
    assert "uncalibrated" in line and "pdrlearn calibrate" in line
    for other in ({**base, "info": {"pipeline": "waist-pendulum", "params_source": "calibrated"}},
                  {**base, "info": {"pipeline": "plasys", "params_source": "defaults"}}, base):
        line = gait_range_warning(other)
        assert line is not None and "uncalibrated" not in line
    assert gait_range_warning({**waist, "median_cadence_spm": 100.0}) is None


def test_implausible_calibration_factor_allows_a_slow_walker():
    """W78: a known distance well under the default model's names both a wrong --distance and a shuffling walker,
    and says the calibration is kept; above, a damped trunk."""
    base = WaistParams(leg_m=0.9, k=1.0, f_m=0.0)
    g = np.full(9, 0.6)  # 5.4 m under the default model
    low = check_gain([CalibrationWalk(2.9, np.full(9, 1.3), g, name="tenmwt")], "waist-pendulum", base)
    assert len(low) == 1 and "0.54 x" in low[0]
    assert "--distance is wrong" in low[0] and "shorter steps" in low[0] and "kept" in low[0]
    assert "check --distance" not in low[0]
    high = check_gain([CalibrationWalk(11.0, np.full(9, 1.3), g, name="aid")], "waist-pendulum", base)
    assert len(high) == 1 and "walking aid" in high[0] and "--distance is wrong" in high[0]


def test_steps_waist_ic_uses_tracks_gate_on_a_damped_real_walk(tmp_path, capsys):
    """Decision steps 35 (session 20 rehab trial): real HA001 Test5 with the lower back's dynamic acceleration x
    0.25 about its 2 s mean (a rollator walker, the trial's damp.py): `steps --detector waist-ic` kept W4's fixed
    0.5 m/s^2 gate and found 0 steps, silently, while `track` (W76's relative gate) found 11. Both now share the
    gate: the same contacts."""
    import json
    import shutil

    from pdrlearn.cli import main
    from tests.conftest import REAL

    dst = tmp_path / "t5_damped"
    shutil.copytree(REAL / "mobgap_HA001_Test5_Trial1", dst)
    a = pd.read_csv(dst / "wAccelerometer.csv")
    n = int(round(2.0 / np.median(np.diff(a["timestamp"].to_numpy(float) / 1000.0))))
    for c in "xyz":
        m = a[c].rolling(n, center=True, min_periods=1).mean()
        a[c] = m + 0.25 * (a[c] - m)
    a.to_csv(dst / "wAccelerometer.csv", index=False)
    assert main(["steps", str(dst), "--detector", "waist-ic", "--json", "--out", str(tmp_path / "ic.csv")]) == 0
    found = json.loads(capsys.readouterr().out)
    assert main(["track", "--no-plot", str(dst), "--out", str(tmp_path / "o")]) == 0
    tracked = pd.read_csv(tmp_path / "o" / "steps.csv")
    assert found["count"] == len(tracked) >= 9, (found["count"], len(tracked))
    assert np.allclose(pd.read_csv(tmp_path / "ic.csv")["event_s"], tracked["event_s"])


def test_steps_on_a_waist_only_session_scores_one_foots_contacts(tmp_path, capsys):
    """Decision W96 (session 20 rehab trial): a lower-back detector on a session without ics.csv was scored against
    steps.csv's strides of one foot - every other-foot step a false positive (precision 0.40 on a 0.4 m/s walk).
    Now only that foot's recall is scored, and the output says so."""
    import json

    from pdrlearn.cli import main

    s = tmp_path / "w"
    assert main(["simulate", "--route", "stand:2, straight:6, stand:2", "--user-seed", "404", "--out", str(s)]) == 0
    for f in [*s.glob("f*.csv"), s / "ics.csv"]:
        f.unlink()
    capsys.readouterr()
    assert main(["steps", str(s), "--detector", "waist-ic", "--json"]) == 0
    r = json.loads(capsys.readouterr().out)
    assert r["one_foot"] == "right" and r["recall"] >= 0.8, r
    assert r["precision"] is None and r["f1"] is None and r["count"] > 1.5 * r["reference_count"]
    assert main(["steps", str(s), "--detector", "waist-ic"]) == 0
    assert "precision, F1 and count error not scored" in capsys.readouterr().out
