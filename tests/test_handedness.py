"""Mirrored data (one axis negated in both the accelerometer and the gyroscope) declared with a right-handed
frame: D10 cannot see it (its inference builds left = up x forward); the gyroscope-vs-accelerometer test
does (decision D11). ``pdrlearn info`` runs the D10 and D11 checks and prints their results."""

from __future__ import annotations

import json
import logging
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.io.handedness import (
    AXES_MIN_LOG_RATIO,
    AXES_RATE_HZ,
    AXES_STRIDES,
    MIN_LOG_RATIO,
    axes_fix,
    axes_fix_acc,
    axes_label,
    foot_axes,
    foot_handedness,
    session_handedness,
    signed_permutations,
    turn_axis,
    waist_handedness,
)
from pdrlearn.io.session import Stream
from pdrlearn.signal.filters import interp_rows
from pdrlearn.sim import simulate

ROOT = Path(__file__).resolve().parents[1]
FOOT = ROOT / "datasets" / "real" / "gaitmap_level_left"
WAIST = ROOT / "datasets" / "real" / "mobgap_HA001_Test5_Trial1"


def _mirrored_copy(src: Path, dst: Path, prefix: str, axis: str) -> Path:
    """The recording with ``axis`` negated in its unit's accelerometer and gyroscope, meta.json unchanged."""
    shutil.copytree(src, dst)
    for name in ("Accelerometer", "Gyroscope"):
        f = dst / f"{prefix}{name}.csv"
        df = pd.read_csv(f)
        df[axis] = -df[axis]
        df.to_csv(f, index=False)
    return dst


def _warnings(caplog) -> list[str]:
    return [r.getMessage() for r in caplog.records if r.levelno == logging.WARNING]


def _one_foot_warning(d, caplog, needle: str):
    """Read ``d``, check its foot frame twice, and return the session and the one warning containing
    ``needle`` (asserting there is exactly one: the check warns once per session)."""
    s = read_session(d)
    with caplog.at_level(logging.WARNING):
        s.require_frame("foot")
        s.require_frame("foot")
    msgs = [m for m in _warnings(caplog) if needle in m]
    assert len(msgs) == 1, _warnings(caplog)
    return s, msgs[0]


@pytest.mark.parametrize("axis", ["x", "y", "z"])
def test_mirrored_foot_recording_warns_once_naming_the_files_and_the_fix(tmp_path, caplog, axis):
    d = _mirrored_copy(FOOT, tmp_path / "m", "f", axis)
    _, m = _one_foot_warning(d, caplog, "mirrored")
    assert str(d) in m and "fAccelerometer.csv" in m and "fGyroscope.csv" in m
    assert "left-handed" in m and "negate the y axis back" in m and "D11" in m  # L71: the lateral axis


def test_truthful_foot_and_waist_recordings_do_not_warn(caplog):
    for d, p in ((FOOT, "foot"), (WAIST, "waist")):
        s = read_session(d)
        with caplog.at_level(logging.WARNING):
            s.require_frame(p)
    assert not [m for m in _warnings(caplog) if "D11" in m]


def test_the_statistic_flips_sign_under_mirroring_and_is_clear_on_real_foot_data():
    s = read_session(FOOT)
    h = session_handedness(s, "foot")
    assert h.segments >= 20 and h.log_ratio > 1.5 and h.verdict == "right-handed"  # measured +3.15 over 33
    a, g = s["fAccelerometer"], s["fGyroscope"]
    acc, gyr = a.values.copy(), interp_rows(a.t, g.t, g.values)
    acc[:, 1] *= -1
    gyr[:, 1] *= -1
    m = foot_handedness(acc, gyr, a.rate_hz)
    assert m.log_ratio == pytest.approx(-h.log_ratio, abs=1e-6) and m.verdict == "mirrored"


@pytest.mark.parametrize("rate", [20.0, 100.0])
def test_simulated_foot_verdict_does_not_depend_on_the_rate(rate):
    s = simulate("A", 2, "normal", rate_hz=rate)
    h = session_handedness(s, "foot")
    assert h.verdict == "right-handed" and h.log_ratio > -MIN_LOG_RATIO
    for name in ("fAccelerometer", "fGyroscope"):
        st = s.streams[name]
        s.streams[name] = Stream(name, st.t, st.values * [1.0, 1.0, -1.0])
    assert session_handedness(s, "foot").verdict == "mirrored"


def test_a_standstill_gives_no_verdict():
    h = session_handedness(simulate("standstill", 0), "foot")
    assert h.segments == 0 and h.verdict == "unsure" and not h.mirrored


def test_the_waist_test_is_measured_but_never_warns(tmp_path, caplog):
    """Not adopted (docs/frames.md): truthful simulated waists score below zero."""
    d = _mirrored_copy(WAIST, tmp_path / "w", "w", "y")
    s = read_session(d)
    with caplog.at_level(logging.WARNING):
        s.require_frame("waist")
    assert not [m for m in _warnings(caplog) if "D11" in m]
    h = s.handedness("waist")
    assert h.verdict == "not tested" and not h.mirrored and h.log_ratio < 0
    acc, gyr = s["wAccelerometer"].values, s["wGyroscope"].values
    assert waist_handedness(acc, gyr, 100.0).log_ratio == pytest.approx(h.log_ratio)


def test_info_prints_the_frame_and_handedness_checks(capsys):
    assert main(["info", str(FOOT)]) == 0
    out, err = capsys.readouterr()
    line = [ln for ln in out.splitlines() if ln.startswith("foot axes:")]
    assert len(line) == 1, out
    assert "source_project frame" in line[0] and "not contradicted by the data (docs/decisions.md D10)" in line[0]
    assert "handedness (docs/decisions.md D11): right-handed" in line[0] and "strides" in line[0]
    assert "warning" not in err


def test_info_json_has_the_checks_and_prints_the_warning_once(tmp_path, capsys):
    d = _mirrored_copy(FOOT, tmp_path / "m", "f", "y")
    assert main(["info", str(d), "--json"]) == 0
    out, err = capsys.readouterr()
    chk = json.loads(out)["frame_checks"]["foot"]
    # D22: mirrored data give no forward push-off, so the inference gives up: not checked, never "ok"
    assert chk["source"] == "source_project" and chk["status"] == "unchecked"
    assert chk["check"].startswith("not checked (in swing the foot pitches toes-down")
    assert chk["frame"] == {"x": "forward", "y": "left", "z": "up"}
    assert chk["handedness"]["verdict"] == "mirrored" and chk["handedness"]["segments"] >= 20
    lines = [ln for ln in err.splitlines() if ln.startswith("warning:")]
    assert len(lines) == 1 and "mirrored" in lines[0] and str(d) in lines[0], err


def test_info_prints_a_d10_contradiction(tmp_path, capsys):
    d = tmp_path / "f"
    shutil.copytree(FOOT, d)
    meta = json.loads((d / "meta.json").read_text())
    meta["frames"] = {"foot": {"x": "backward", "y": "right", "z": "up"}}  # a wrong 180-degree yaw
    (d / "meta.json").write_text(json.dumps(meta))
    assert main(["info", str(d), "--json"]) == 0
    out, err = capsys.readouterr()
    chk = json.loads(out)["frame_checks"]["foot"]
    # a reversed forward: refused by the commands that need it (D23), said by info
    assert chk["source"] == "declared" and chk["status"] == "refused" and "contradicts its data" in chk["check"]
    assert main(["info", str(d)]) == 0
    out = " ".join(capsys.readouterr().out.split())
    assert "refused by the commands that need it" in out and "contradicts its data" in out
    meta["frames"] = {"foot": {"x": "forward", "y": "up", "z": "right"}}  # a wrong 90-degree turn: D10's warning
    (d / "meta.json").write_text(json.dumps(meta))
    assert main(["info", str(d), "--json"]) == 0
    out, err = capsys.readouterr()
    assert json.loads(out)["frame_checks"]["foot"]["status"] == "warned"
    assert sum("contradicts its data" in ln for ln in err.splitlines()) == 1


# --- D11 amendment: axis agreement (gyroscope axes permuted against the accelerometer's) ---------------------

WAIST_TURNS = ROOT / "datasets" / "real" / "mobgap_HA001_Test11_Trial1"


def _gyro_permuted_copy(src: Path, dst: Path, prefix: str, cols: tuple[str, str, str]) -> Path:
    """The recording with its gyroscope's columns rewritten: new (x, y, z) = ``cols`` of the old, e.g.
    ("z", "y", "-x") (the new-user trial's chip turned 90 deg about y), meta.json unchanged."""
    shutil.copytree(src, dst)
    f = dst / f"{prefix}Gyroscope.csv"
    df = pd.read_csv(f)
    old = df[["x", "y", "z"]].copy()
    for new, c in zip("xyz", cols, strict=True):
        df[new] = -old[c[1]] if c.startswith("-") else old[c]
    df.to_csv(f, index=False)
    return dst


def test_the_48_signed_permutations_and_their_labels():
    P = signed_permutations()
    assert P.shape == (48, 3, 3) and len({p.tobytes() for p in P}) == 48
    assert np.array_equal(P[0], np.eye(3)) and np.array_equal(P[7], -np.eye(3))
    assert sorted(np.round(np.linalg.det(P)).astype(int).tolist()).count(1) == 24
    # recorded gyroscope = (w_z, w_y, -w_x): the rate in the accelerometer's axes is (-g_z, g_y, g_x)
    Pt = np.array([[0, 0, -1], [0, 1, 0], [1, 0, 0]], float)
    assert axes_label(Pt) == "(z, y, -x)" and axes_fix(Pt) == "x = -z, y = y, z = x"
    w = np.array([0.1, 0.2, 0.3])
    assert np.allclose(Pt @ np.array([w[2], w[1], -w[0]]), w)


@pytest.mark.parametrize("cols", [("z", "y", "-x"), ("y", "-x", "z"), ("x", "-z", "y"), ("y", "z", "x"),
                                  ("-y", "x", "z")])
def test_foot_with_permuted_gyroscope_axes_warns_once_naming_the_permutation(tmp_path, caplog, cols):
    d = _gyro_permuted_copy(FOOT, tmp_path / "p", "f", cols)
    s, m = _one_foot_warning(d, caplog, "D11")
    label = "(" + ", ".join(cols) + ")"
    assert str(d) in m and "fGyroscope.csv" in m and label in m and "D11 amendment" in m, m
    assert s.handedness("foot").verdict == "axes differ"


def test_foot_axes_finds_the_applied_permutation_on_simulated_data():
    s = simulate("A", 2, "normal")
    a, g = s["fAccelerometer"], s["fGyroscope"]
    acc, gyr = a.values, interp_rows(a.t, g.t, g.values)
    h = foot_handedness(acc, gyr, a.rate_hz)
    assert h.verdict == "right-handed" and h.axes_log_ratio < AXES_MIN_LOG_RATIO
    for Q in signed_permutations()[[3, 10, 17, 29, 40]]:  # rotations and reflections
        hq = foot_handedness(acc, gyr @ Q.T, a.rate_hz)
        assert np.array_equal(hq.axes, Q.T) and hq.axes_log_ratio > AXES_MIN_LOG_RATIO
        assert hq.verdict in ("axes differ", "mirrored")


def test_the_axis_search_is_one_batch_on_few_strides_at_a_low_rate():
    """8 strides at ~30 Hz in one batch (AXES_STRIDES, AXES_RATE_HZ): not 48 full-rate integrations."""
    s = read_session(FOOT)
    a, g = s["fAccelerometer"], s["fGyroscope"]
    acc, gyr = a.values, interp_rows(a.t, g.t, g.values)
    from pdrlearn.displace.foot import inertial_stance
    from pdrlearn.track.frame_inference import rest_to_rest

    i0, i1 = rest_to_rest(inertial_stance(acc, gyr, a.rate_hz), a.rate_hz)
    import pdrlearn.displace._kernels as K

    calls = []
    orig = K.strapdown

    def spy(acc_, gyr_, dt, idx, mask, *args, **kw):
        calls.append((dt, int(mask.sum())))
        return orig(acc_, gyr_, dt, idx, mask, *args, **kw)

    K.strapdown = spy
    try:
        foot_axes(acc, gyr, a.rate_hz, i0, i1)
    finally:
        K.strapdown = orig
    (dt, samples), = calls
    k = int(a.rate_hz // AXES_RATE_HZ)
    assert k >= 2 and dt == pytest.approx(k / a.rate_hz)  # 204.8 Hz averaged in blocks
    full = int((i1 - i0 + 1).sum())
    assert samples <= 48 * AXES_STRIDES * ((i1 - i0).max() // k + 1)
    assert samples < 0.1 * 48 * full  # not 48 full-rate integrations of every stride


def test_waist_gyroscope_turning_about_a_horizontal_axis_warns_once(tmp_path, caplog):
    d = _gyro_permuted_copy(WAIST_TURNS, tmp_path / "w", "w", ("y", "-x", "z"))
    s = read_session(d)
    with caplog.at_level(logging.WARNING):
        s.require_frame("waist")
        s.require_frame("waist")
        s.frame_checks()
    msgs = [m for m in _warnings(caplog) if "D11" in m]
    assert len(msgs) == 1, _warnings(caplog)
    assert str(d) in msgs[0] and "wGyroscope.csv" in msgs[0] and "from gravity" in msgs[0]
    h = s.handedness("waist")
    assert h.verdict == "axes differ" and h.turn_deg > 60 and h.turn_windows >= 50


def test_truthful_waist_with_turns_does_not_warn_and_commands_skip_the_ratio(caplog):
    s = read_session(WAIST_TURNS)
    with caplog.at_level(logging.WARNING):
        s.require_frame("waist")
    assert not [m for m in _warnings(caplog) if "D11" in m]
    h = s.handedness("waist", ratio=False)
    assert h.segments == 0 and h.turn_deg < 15 and h.turn_windows >= 50  # measured 5.9 deg over 95
    assert s.handedness("waist").segments > 0  # info asks for the ratio: computed then


def test_turn_axis_hand_computed():
    fs = 20.0
    n = 400
    gyr = np.zeros((n, 3))
    gyr[100:140, 1] = np.radians(90.0)  # two 90-degree turns about y (2 s at 90 deg/s)
    gyr[250:290, 1] = -np.radians(90.0)
    acc = np.tile([0.0, 9.81, 0.0], (n, 1))
    ang, nt, gi, ai = turn_axis(acc, gyr, fs)
    assert ang == pytest.approx(0.0, abs=1e-6) and gi == ai == 1 and nt >= 4
    ang, nt, gi, ai = turn_axis(acc, gyr[:, [1, 0, 2]], fs)
    assert ang == pytest.approx(90.0) and gi == 0 and ai == 1
    assert turn_axis(acc, np.zeros((n, 3)), fs)[1] == 0
    # gravity-removed acceleration (mean about 0) has no gravity to compare with: no verdict
    assert turn_axis(acc - acc.mean(axis=0), gyr[:, [1, 0, 2]], fs)[1] == 0


def test_info_without_turn_windows_prints_no_none_angle(tmp_path, capsys):
    """Review s11: a waist walk without turns printed 'turning axis None deg from gravity over 0 turn windows'."""
    from pdrlearn.io import write_session

    s = simulate("A", 1, "normal")  # straight: no turn window
    write_session(s, tmp_path / "a")
    assert main(["info", str(tmp_path / "a")]) == 0
    line = [ln for ln in capsys.readouterr().out.splitlines() if ln.startswith("waist axes:")]
    assert len(line) == 1 and "None" not in line[0] and "over 0 turn windows" not in line[0], line


def test_info_on_a_too_short_unit_does_not_say_it_has_no_data(tmp_path, capsys):
    """Review s11: a unit with an accelerometer and a gyroscope too short for the test was described as having
    'no accelerometer + gyroscope data'."""
    from pdrlearn.io import write_session

    s = simulate("A", 1, "normal")
    for n, st in list(s.streams.items()):
        s.streams[n] = Stream(n, st.t[:5], st.values[:5])
    write_session(s, tmp_path / "a")
    for f in (tmp_path / "a").glob("*.csv"):  # labels past the 5 samples' end
        if f.stem not in s.streams:
            f.unlink()
    assert main(["info", str(tmp_path / "a")]) == 0
    line = [ln for ln in capsys.readouterr().out.splitlines() if ln.startswith("foot axes:")]
    assert len(line) == 1 and "no accelerometer + gyroscope data" not in line[0] and "not run" in line[0], line


def _acc_swapped_copy(dst: Path) -> Path:
    """FOOT imported with its accelerometer columns in the wrong order (x and y swapped, trial 2 finding 8:
    ``--acc acc_y_g,acc_x_g,acc_z_g``), the gyroscope right, and no frame declared."""
    shutil.copytree(FOOT, dst)
    f = dst / "fAccelerometer.csv"
    df = pd.read_csv(f)
    df[["x", "y"]] = df[["y", "x"]].to_numpy()
    df.to_csv(f, index=False)
    meta = json.loads((dst / "meta.json").read_text())
    for key in ("frames", "source_project"):
        meta.pop(key, None)
    (dst / "meta.json").write_text(json.dumps(meta))
    return dst


def test_the_accelerometer_fix_is_the_inverse_with_the_fewest_negations():
    swap = np.array([[0, 1, 0], [1, 0, 0], [0, 0, 1]], float)
    assert axes_fix_acc(-swap) == ("x = y, y = x, z = z", False)  # the gyroscope's fix negates all three
    Pt = np.array([[0, 0, -1], [0, 1, 0], [1, 0, 0]], float)  # a rotation: its inverse P^T (one negation)
    assert axes_fix_acc(Pt) == ("x = z, y = y, z = -x", False)
    for P in signed_permutations()[1:]:
        fix, negate = axes_fix_acc(P)
        assert fix.count("-") <= 1 and negate == (np.linalg.det(P) < 0)


def test_wrong_accelerometer_column_order_names_both_rewrites_and_track_names_them_not_frames(tmp_path, capsys):
    """Trial 2, finding 8: the warning told to rewrite the (right) gyroscope only, and track asked for a
    "frames" entry that the warning itself said cannot fix the data."""
    d = _acc_swapped_copy(tmp_path / "swapped")
    rc = main(["track", "--no-plot", str(d), "--method", "M2", "--out", str(tmp_path / "t")])
    lines = capsys.readouterr().err.splitlines()
    warn = [ln for ln in lines if ln.startswith("warning: ") and "D11 amendment" in ln]
    err = [ln for ln in lines if ln.startswith("error: ")]
    assert rc == 2 and len(warn) == 1 and len(err) == 1, lines
    for text in (warn[0], err[0]):
        assert "cannot tell which file is wrong" in text, text
        assert "fGyroscope.csv is, rewrite its columns as x = -y, y = -x, z = -z" in text, text
        assert "fAccelerometer.csv is (e.g. its columns were given in the wrong order), rewrite its columns as " \
               "x = y, y = x, z = z" in text, text
        assert "a \"frames\" entry cannot fix this" in text
    assert "add a \"frames\" entry" not in err[0] and "axes differ" in err[0]
    # the accelerometer rewrite named is a fix: the unswapped files pass the test
    s = read_session(d)
    a, g = s["fAccelerometer"], s["fGyroscope"]
    acc = a.values[:, [1, 0, 2]]
    assert foot_handedness(acc, interp_rows(a.t, g.t, g.values), a.rate_hz).verdict == "right-handed"


# -- B106: a unit turned in its holster mid-walk is not "axes differ" ---------------------------------------------
def _holster_turn(fs=50.0, gyr_perm=(0, 1, 2)):
    """60 s of a waist unit: gravity along y, turned 90 deg about z (forward) over 25-26 s (gravity then along x),
    and two walker turns of 90 deg about gravity after it; ``gyr_perm`` reorders the gyroscope columns."""
    t = np.arange(0.0, 60.0, 1.0 / fs)
    ang = np.radians(90.0) * np.clip(t - 25.0, 0.0, 1.0)
    g = 9.81 * np.column_stack([np.sin(ang), np.cos(ang), np.zeros_like(t)])
    acc = g + 1.5 * np.sin(2 * np.pi * 1.8 * t)[:, None] * g / 9.81  # walking bounce along gravity
    gyr = np.zeros_like(acc)
    gyr[:, 2] = np.where((t >= 25.0) & (t <= 26.0), np.radians(90.0), 0.0)  # the holster turn
    for t0 in (40.0, 50.0):
        on = (t >= t0) & (t < t0 + 2.0)
        gyr[on] += np.radians(45.0) * g[on] / 9.81  # a walker's turn: about gravity
    gyr += 0.05 * np.sin(2 * np.pi * 0.9 * t)[:, None]  # the pelvis's oscillation
    return acc, gyr[:, list(gyr_perm)], fs


def test_a_unit_turned_in_its_holster_is_not_read_as_disagreeing_axes():
    from pdrlearn.io.handedness import TURN_MAX_DEG, turn_axis, waist_handedness

    acc, gyr, fs = _holster_turn()
    ang, n, _, _ = turn_axis(acc, gyr, fs)
    assert n >= 3 and ang < TURN_MAX_DEG  # before B106: the holster turn and the mixed gravity gave > 30 deg
    assert not waist_handedness(acc, gyr, fs, ratio=False).axes_differ
    acc, gyr, fs = _holster_turn(gyr_perm=(2, 0, 1))  # gyroscope columns really permuted: still caught
    ang, n, _, _ = turn_axis(acc, gyr, fs)
    assert n >= 3 and ang > TURN_MAX_DEG and waist_handedness(acc, gyr, fs, ratio=False).axes_differ


# -- B263: lying down and turning over in bed are not "axes differ" -----------------------------------------------
@pytest.mark.parametrize("user", [6290, 6293])
def test_a_lying_session_is_not_read_as_disagreeing_axes_b263(user):
    """Simulated `stand, straight, lie:300:30, straight, stand` (S58-S59; before B263 both read "axes differ"): the
    sit on the bed, the lying down and the rolls turn the unit about
    horizontal axes; no turn window is left, no verdict. The same session's gyroscope permuted on an upright walk
    with turns is still caught (B106's and the D11 amendment's tests above)."""
    from pdrlearn.io.handedness import turn_axis, unit_imu_arrays, waist_handedness
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    s = simulate_path(parse_route("stand:5, straight:10, lie:300:30, straight:10, stand:5"),
                      UserProfile.from_seed(user), rate_hz=20.0, seed=user)
    assert len(s.extras["rolls"]) >= 1
    acc, gyr, fs = unit_imu_arrays(s, "waist")
    assert not waist_handedness(acc, gyr, fs, ratio=False).axes_differ
    assert turn_axis(acc, gyr, fs)[1] < 3
