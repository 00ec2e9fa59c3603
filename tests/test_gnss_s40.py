"""Session 40, fixer FH (trial T3 findings 2, 3, 4, 7, 9): GNSS offline smoothing (D36), GPX / ISO-time CSV fix
logs (D37), fix times against the session's absolute start and the path before the first fix (D38), the
GNSS-calibrated distance (D39), ``gnss_fixes`` on a session folder's trajectory.csv and the GNSS counts (D40)."""

from datetime import UTC, datetime, timedelta
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.aid import aid_track, read_fixes
from pdrlearn.aid.fixgen import gnss_fixes, write_nmea
from pdrlearn.aid.geo import enu_to_geodetic
from pdrlearn.aid.gnss import GnssPdrFusion
from pdrlearn.aid.synth import pdr_with_drift, position_errors, synthetic_walk
from pdrlearn.errors import DataError
from pdrlearn.io.session import Session
from pdrlearn.kernels.fixes import fit_length_scale, stretch_between_fixes
from pdrlearn.track.base import TrackResult
from pdrlearn.track.geoexport import write_geo_files

ORIGIN = (51.0, -1.8)
COUNTS = ("fixes_used", "fixes_superseded", "fixes_before_ttff", "fixes_inaccurate", "fixes_gated", "fixes_while_off",
          "fixes_outside_track")


def _legs(lengths_m=(600.0, 500.0, 600.0), step_m=0.75, step_s=0.55):
    """A walk of straight legs with 90 deg turns: true steps and trajectory."""
    rows, traj = [], [(0.0, 0.0, 0.0, 0.0)]
    t = x = y = 0.0
    h = 0.3
    for k, leg in enumerate(lengths_m):
        if k:
            h += np.pi / 2
        for _ in range(int(leg / step_m)):
            rows.append((t, t + step_s, t + step_s, step_m, h))
            t += step_s
            x, y = x + step_m * np.cos(h), y + step_m * np.sin(h)
            traj.append((t, x, y, 0.0))
    st = pd.DataFrame(rows, columns=["start_s", "end_s", "event_s", "length_m", "heading_rad"])
    return st, pd.DataFrame(traj, columns=["t", "x", "y", "z"])


def _pdr(steps: pd.DataFrame, *, scale=1.0, bias_deg=0.0, drift_deg_per_s=0.0, sway_deg=0.0) -> TrackResult:
    """A PDR track from true steps: length scale, heading bias + drift, and a left-right heading sway from step to
    step (a lower-back track's), which shortens the path's chord but not its length."""
    st = steps.copy()
    st["length_m"] = st["length_m"] * scale
    sway = sway_deg * (-1.0) ** np.arange(len(st))
    st["heading_rad"] = st["heading_rad"] + np.radians(bias_deg + drift_deg_per_s * st["end_s"] + sway)
    xs = np.r_[0.0, np.cumsum(st["length_m"] * np.cos(st["heading_rad"]))]
    ys = np.r_[0.0, np.cumsum(st["length_m"] * np.sin(st["heading_rad"]))]
    tr = pd.DataFrame({"t": np.r_[0.0, st["end_s"]], "x": xs, "y": ys, "z": 0.0})
    return TrackResult(st, tr, {"pipeline": "synthetic"})


# --- D36 -------------------------------------------------------------------------------------------------
def test_stretch_between_fixes_spreads_each_jump_and_projects_back():
    causal = np.array([[0, 0], [1, 0], [2, 0], [10, 0], [11, 0]], float)
    prior = causal.copy()
    prior[3] = [3.0, 0.0]  # the fix at row 3 moved the filter 7 m
    used = np.array([False, True, False, True, False])
    out = stretch_between_fixes(causal, prior, used, start_anchor=True)
    # rows 1..3: the 7 m jump at row 3 spread over the two steps since row 1 (seed 004 eq. 26)
    assert out[:, 0] == pytest.approx([0, 1, 2 + 3.5, 10, 11])
    prior[1] = [0.0, 0.0]  # the first fix moved the filter 1 m: without a known start, row 0 moves with it (D38)
    back = stretch_between_fixes(causal, prior, used, start_anchor=False)
    assert back[0, 0] == pytest.approx(1.0) and back[1, 0] == pytest.approx(1.0)


def test_gnss_outage_is_bridged_without_a_jump():
    steps, truth = _legs((700.0, 700.0, 700.0))
    pdr = _pdr(steps, scale=1.05, bias_deg=4.0, drift_deg_per_s=0.05)  # 20 deg of drift in the outage
    outage = (500.0, 900.0)
    fx = gnss_fixes(truth, accuracy_m=5.0, outages=[outage], seed=3)
    new = GnssPdrFusion().run(pdr.steps, fx)
    old = GnssPdrFusion(smooth=False, sigma_bias_deg=0.0, min_baseline_m=50.0).run(pdr.steps, fx)
    t = new.trajectory_["t"].to_numpy()
    gap = (t >= outage[0]) & (t <= outage[1])

    def moves(tr):
        return np.hypot(np.diff(tr["x"]), np.diff(tr["y"])).max()

    e_new, e_old = position_errors(new.trajectory_, truth), position_errors(old.trajectory_, truth)
    assert moves(old.trajectory_) > 15.0 and moves(new.trajectory_) < 3.0  # the old path jumped at the fix's return
    assert e_new[gap].max() < 0.5 * e_old[gap].max()
    causal = new.trajectory_.assign(x=new.trajectory_["x_rt"], y=new.trajectory_["y_rt"])
    assert moves(causal) > 15.0  # x_rt stays the causal filter, which jumps where x, y does not
    # sigma_bias_deg: the first fix after the outage corrects the causal filter in full (seed 001's per-step noise
    # alone keeps its variance small, so the fixes pulled it back over many strides: T3's 232 + 81 m)
    back = int(np.flatnonzero(t > outage[1])[0])
    e_rt, e_old_rt = position_errors(causal, truth), e_old
    assert e_rt[back] < 10.0 and e_old_rt[back] > 20.0


# --- D37 -------------------------------------------------------------------------------------------------
def _truth_geo(truth: pd.DataFrame) -> pd.DataFrame:
    lat, lon = enu_to_geodetic(truth["x"].to_numpy(), truth["y"].to_numpy(), *ORIGIN)
    return truth.assign(lat=lat, lon=lon)


def test_gpx_round_trip_through_track_gpx(tmp_path):
    steps, truth = _legs((300.0, 200.0))
    start = datetime(2026, 3, 15, 10, 0, tzinfo=UTC)
    fx = gnss_fixes(truth, accuracy_m=4.0, outages=[(0.0, 30.0)], origin=ORIGIN, seed=1)
    write_geo_files(tmp_path, fx, session="walk", pipeline=None, distance_m=None, start=start)
    log = read_fixes(tmp_path / "track.gpx")
    assert len(log) == len(fx) and log.stats["time_base"] == "utc"
    assert log.stats["first_epoch_s"] == pytest.approx((start + timedelta(seconds=fx["t"].iloc[0])).timestamp())
    assert log.fixes["lat"].to_numpy() == pytest.approx(fx["lat"].to_numpy(), abs=1e-7)
    assert log.fixes["accuracy_m"].iloc[0] == 10.0  # a GPX point reports no accuracy (D37)
    ses = Session(name="walk", meta={"recording_start": start.isoformat()})
    out = aid_track(_pdr(steps), ses, gnss_path=tmp_path / "track.gpx", start=ORIGIN)
    g = out.info["aid"]["gnss"]
    assert g["time_alignment"] == "recording_start" and g["first_fix_s"] == pytest.approx(fx["t"].iloc[0], abs=1e-3)
    assert np.median(position_errors(out.trajectory, truth)) < 4.0


def test_gpx_without_times_and_unknown_text_are_one_line_errors(tmp_path):
    p = tmp_path / "notime.gpx"
    p.write_text('<gpx version="1.1" xmlns="http://www.topografix.com/GPX/1/1"><trk><trkseg>'
                 '<trkpt lat="51.0" lon="-1.8"/></trkseg></trk></gpx>')
    with pytest.raises(DataError) as e:
        read_fixes(p)
    assert "<time>" in str(e.value) and "\n" not in str(e.value)
    junk = tmp_path / "fix.log"
    junk.write_text("hello\nworld\n")
    with pytest.raises(DataError) as e:
        read_fixes(junk)
    assert "GPX" in str(e.value) and "hdop" in str(e.value)


def test_csv_with_iso_times_latitude_longitude_and_hdop(tmp_path):
    steps, truth = _legs((300.0,))
    fx = gnss_fixes(truth, accuracy_m=4.0, origin=ORIGIN, seed=2)
    t0 = datetime(2026, 3, 15, 10, 0, tzinfo=UTC)
    p = tmp_path / "garmin.csv"
    pd.DataFrame({"time": [(t0 + timedelta(seconds=float(s))).isoformat() for s in fx["t"]],
                  "latitude": fx["lat"], "longitude": fx["lon"], "hdop": fx["accuracy_m"] / 4.0}).to_csv(p, index=False)
    log = read_fixes(p)
    assert log.stats["time_base"] == "utc" and log.fixes["t"].iloc[0] == 0.0
    assert log.fixes["accuracy_m"].to_numpy() == pytest.approx(fx["accuracy_m"].to_numpy())  # HDOP x 4 m
    no_acc = tmp_path / "noacc.csv"
    pd.DataFrame({"t": [1.0], "latitude": [51.0], "longitude": [-1.8]}).to_csv(no_acc, index=False)
    with pytest.raises(DataError) as e:
        read_fixes(no_acc)
    assert "accuracy_m" in str(e.value) and "hdop" in str(e.value) and "ISO 8601" in str(e.value)
    bad_t = tmp_path / "badt.csv"
    pd.DataFrame({"t": ["soon"], "lat": [51.0], "lon": [-1.8], "accuracy_m": [5.0]}).to_csv(bad_t, index=False)
    with pytest.raises(DataError, match="neither a number"):
        read_fixes(bad_t)
    ms = tmp_path / "ms.csv"  # a session folder's timestamp (ms) is not taken for seconds
    pd.DataFrame({"timestamp": [1000.0], "lat": [51.0], "lon": [-1.8], "accuracy_m": [5.0]}).to_csv(ms, index=False)
    with pytest.raises(DataError, match="name it t when it is session seconds"):
        read_fixes(ms)


# --- D38 -------------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def late_log(tmp_path_factory):
    """A 1 km walk whose GNSS log starts 240 s in (NMEA: first fix at 10:00:00 UTC)."""
    d = tmp_path_factory.mktemp("late")
    steps, truth = _legs((400.0, 300.0, 300.0))
    fx = gnss_fixes(truth, accuracy_m=4.0, outages=[(0.0, 240.0)], origin=ORIGIN, seed=5)
    write_nmea(fx, d / "late.nmea")  # utc_start_s 36000: the first fix is 10:00:00
    return d / "late.nmea", steps, truth, float(fx["t"].iloc[0])


def test_late_first_fix_warns_then_aligns_by_offset_or_recording_start(late_log):
    path, steps, truth, t_first = late_log
    pdr = _pdr(steps, bias_deg=2.0)
    plain = aid_track(pdr, Session(name="w"), gnss_path=path)
    assert plain.info["aid"]["gnss"]["time_alignment"] == "assumed"
    assert any("--gnss-time-offset" in w for w in plain.info["warnings"])
    by_offset = aid_track(pdr, Session(name="w"), gnss_path=path, gnss_time_offset_s=t_first)
    start = datetime(2026, 3, 15, 10, 0, tzinfo=UTC) - timedelta(seconds=t_first)
    by_start = aid_track(pdr, Session(name="w", meta={"recording_start": start.isoformat()}), gnss_path=path)
    for r, how in ((by_offset, "offset"), (by_start, "recording_start")):
        g = r.info["aid"]["gnss"]
        assert g["time_alignment"] == how and g["first_fix_s"] == pytest.approx(t_first, abs=1e-3)
        assert not any("--gnss-time-offset" in w for w in r.info.get("warnings", []))
    # origin = the first fix: compare in the fixes' frame (truth shifted to put its first-fix point at 0)
    t = by_offset.trajectory["t"].to_numpy()
    x0, y0 = np.interp(t_first, truth["t"], truth["x"]), np.interp(t_first, truth["t"], truth["y"])
    ref = truth.assign(x=truth["x"] - x0, y=truth["y"] - y0)
    err_plain = position_errors(plain.trajectory, ref)
    err = position_errors(by_offset.trajectory, ref)
    assert np.median(err) < 6.0 and np.median(err_plain) > 50.0  # T3: 437 m median with the silent shift
    before = t < t_first  # D38: the path before the first fix is the PDR's shape ending at that fix
    assert err[before].max() < 15.0


def test_time_offset_with_a_session_seconds_csv_is_refused(tmp_path):
    steps, truth = _legs((200.0,))
    fx = gnss_fixes(truth, accuracy_m=4.0, seed=1)
    p = tmp_path / "fix.csv"
    fx[["t", "x", "y", "accuracy_m"]].to_csv(p, index=False)
    with pytest.raises(DataError, match="already in session seconds"):
        aid_track(_pdr(steps), Session(name="w"), gnss_path=p, gnss_time_offset_s=10.0)


def test_cli_time_offset_without_gnss_is_refused(tmp_path, capsys):
    from pdrlearn.cli import main

    real = Path(__file__).resolve().parents[1] / "datasets" / "real"
    rc = main(["track", str(real / "gaitmap_level_left"), "--gnss-time-offset", "300", "--out", str(tmp_path / "o")])
    err = [ln for ln in capsys.readouterr().err.splitlines() if ln.strip()]
    assert rc == 2 and len(err) == 1 and "--gnss-time-offset" in err[0] and "--gnss FILE" in err[0], err


# --- D39 -------------------------------------------------------------------------------------------------
def test_fit_length_scale_uses_straight_windows_only():
    steps, truth = _legs((900.0, 900.0))
    pdr = _pdr(steps, scale=0.8, sway_deg=15.0)  # the sway shortens the chord by cos 15 deg = 0.966, not the distance
    fx = gnss_fixes(truth, accuracy_m=5.0, seed=4)
    f = GnssPdrFusion().run(pdr.steps, fx)
    assert f.distance_scale_ == pytest.approx(1.25, rel=0.015)  # fixes' chord / PDR chord would give 1.29
    assert f.distance_scale_windows_ >= 5 and f.distance_scale_covered_m_ >= 1000.0
    # a loop: the chord is short against the path, no window counts
    th = np.linspace(0, 2 * np.pi, 401)
    xy = np.c_[np.cos(th), np.sin(th)] * 100.0
    path = np.r_[0.0, np.cumsum(np.hypot(*np.diff(xy, axis=0).T))]
    scale, cover, n = fit_length_scale(xy, np.arange(401.0), xy, path)
    assert np.isnan(scale) and n == 0 and cover == 0.0


def test_aided_distance_is_gnss_calibrated_and_path_length_reported(tmp_path):
    steps, truth = _legs((900.0, 900.0))
    true_m = float(steps["length_m"].sum())
    pdr = _pdr(steps, scale=0.8)  # T3's waist-only track: -19 %
    fx = gnss_fixes(truth, accuracy_m=5.0, origin=ORIGIN, seed=4)
    out = aid_track(pdr, Session(name="w"), gnss_path=_write_csv(fx, tmp_path / "gnss1.csv"), start=ORIGIN)
    g = out.info["aid"]["gnss"]
    assert g["distance_scaled"] and g["distance_pdr_m"] == pytest.approx(0.8 * true_m, rel=1e-6)
    assert out.steps["length_m"].sum() == pytest.approx(true_m, rel=0.015)
    assert out.info["aid"]["path_length_m"] > 0.9 * true_m
    short = _pdr(_legs((400.0,))[0], scale=0.8)  # 400 m of windows < 1000 m: the PDR's lengths kept
    fx2 = gnss_fixes(_legs((400.0,))[1], accuracy_m=5.0, origin=ORIGIN, seed=4)
    out2 = aid_track(short, Session(name="w"), gnss_path=_write_csv(fx2, tmp_path / "gnss2.csv"), start=ORIGIN)
    assert not out2.info["aid"]["gnss"]["distance_scaled"]
    assert out2.steps["length_m"].sum() == pytest.approx(short.steps["length_m"].sum())


def _write_csv(fx: pd.DataFrame, p: Path) -> Path:
    """The fixes as a session-seconds CSV at ``p`` (in the test's tmp_path: nothing left behind)."""
    fx[["t", "lat", "lon", "accuracy_m"]].to_csv(p, index=False)
    return p


# --- D40 -------------------------------------------------------------------------------------------------
def test_gnss_fixes_reads_a_session_folder_trajectory_and_counts_add_up():
    steps_true, truth = synthetic_walk(2, length_m=400)
    folder_table = pd.DataFrame({"timestamp": truth["t"] * 1000.0, "x": truth["x"], "y": truth["y"]})
    fx = gnss_fixes(folder_table, rate_hz=2.0, accuracy_m=5.0, seed=2)
    assert fx["t"].iloc[0] == pytest.approx(truth["t"].iloc[0], abs=0.5) and len(fx) > 100
    pdr = pdr_with_drift(steps_true, 2)
    f = GnssPdrFusion().run(pdr.steps, fx)
    assert f.stats_["fixes_superseded"] > 0  # 2 Hz fixes, ~2 steps a second: some steps hold two
    assert sum(f.stats_[k] for k in COUNTS) == f.stats_["fixes_total"] == len(fx)
