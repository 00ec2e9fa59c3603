"""Trial 12 (a waist-only user): `track --realtime` (W60), the leg length guessed from the height (W62), a
standing-only recording (W61), calibrate --start/--end (W61), dropped samples in the online detector (W59) and
one missing sample at 50 Hz (B46)."""

from __future__ import annotations

import json
import logging
import shutil
from pathlib import Path

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.track import get_pipeline

ROOT = Path(__file__).resolve().parents[1]
HA001_T5 = ROOT / "datasets" / "real" / "mobgap_HA001_Test5_Trial1"


def _copy_without_sensor_height(tmp_path: Path) -> Path:
    d = tmp_path / "nosh"
    shutil.copytree(HA001_T5, d)
    meta = json.loads((d / "meta.json").read_text())
    meta["subject"].pop("sensor_height_m")
    meta.pop("sensor_height_m", None)
    (d / "meta.json").write_text(json.dumps(meta))
    return d


def test_leg_from_height_warns_once_naming_the_option(tmp_path, caplog):
    d = _copy_without_sensor_height(tmp_path)
    with caplog.at_level(logging.WARNING):
        res = get_pipeline("waist-pendulum")(read_session(d))
    lines = [r.getMessage() for r in caplog.records if "sensor height" in r.getMessage()]
    assert len(lines) == 1 and "--sensor-height" in lines[0] and "sensor_height_m" in lines[0]
    assert "0.843 m" in lines[0]  # 0.53 x 1.59 m
    assert res.info["params"]["leg_m"] == pytest.approx(0.53 * 1.59)
    caplog.clear()
    with caplog.at_level(logging.WARNING):  # the PLL's frequency model has no leg length: no such line
        get_pipeline("waist-pll")(read_session(d))
    assert not [r for r in caplog.records if "sensor height" in r.getMessage()]
    caplog.clear()
    with caplog.at_level(logging.WARNING):  # given: no line
        get_pipeline("waist-pendulum")(read_session(HA001_T5))
    assert not [r for r in caplog.records if "sensor height" in r.getMessage()]


def test_track_realtime_flag_equals_the_params_option(tmp_path, capsys):
    p = tmp_path / "rt.json"
    p.write_text(json.dumps({"options": {"realtime": True}}))
    assert main(["track", "--no-plot", str(HA001_T5), "--realtime", "--out", str(tmp_path / "a"), "--json"]) == 0
    a = json.loads(capsys.readouterr().out)
    assert main(["track", "--no-plot", str(HA001_T5), "--params", str(p), "--out", str(tmp_path / "b"), "--json"]) == 0
    b = json.loads(capsys.readouterr().out)
    assert b["distance_m"] == a["distance_m"]
    assert a["info"]["options"]["realtime"] is True and a["info"]["method"].startswith("alvarez-realtime")
    assert (tmp_path / "a" / "steps.csv").read_text() == (tmp_path / "b" / "steps.csv").read_text()
    # the foot pipeline and the PLL have no causal variant: one line, exit 2
    assert main(["track", "--no-plot", str(HA001_T5), "--pipeline", "waist-pll", "--realtime", "--out",
                 str(tmp_path / "c")]) == 2
    err = capsys.readouterr().err
    assert "--realtime applies to the waist-pendulum pipeline only" in err and not (tmp_path / "c").exists()


def _standing(tmp_path: Path, end_ms: float = 4500) -> Path:
    """HA001 Test5 Trial1's first 4.5 s (standing before the walk at 5 s), no frames entry, no labels."""
    import pandas as pd

    d = tmp_path / "stand"
    d.mkdir()
    for f in ("wAccelerometer.csv", "wGyroscope.csv"):
        t = pd.read_csv(HA001_T5 / f)
        t[t["timestamp"] < end_ms].to_csv(d / f, index=False)
    meta = json.loads((HA001_T5 / "meta.json").read_text())
    meta["files"] = ["wAccelerometer.csv", "wGyroscope.csv"]
    meta.pop("frames", None)
    meta.pop("source_project")  # mobgap's known frame would be taken (frames_from_meta)
    (d / "meta.json").write_text(json.dumps(meta))
    return d


def test_standing_only_without_frames_tracks_zero_steps(tmp_path, capsys):
    d = _standing(tmp_path)
    assert main(["track", "--no-plot", str(d), "--out", str(tmp_path / "t"), "--json"]) == 0
    cap = capsys.readouterr()
    out = json.loads(cap.out)
    assert out["n_steps"] == 0 and out["distance_m"] == 0.0
    assert "no walking to track" in cap.err and cap.err.count("no walking to track") == 1
    assert "frames_inferred" not in out
    # calibrate says what is wrong: no steps, not "steps carry no length"
    assert main(["calibrate", str(d), "-d", "10", "--out", str(tmp_path / "p.json")]) == 2
    err = capsys.readouterr().err
    assert f"0 steps detected in {d}" in err and "calibrate needs a walk" in err


@pytest.mark.parametrize("detector", ["waist-ic"])  # pll needs no frame: 0 steps without a warning
def test_steps_on_a_standing_only_recording_without_frames_counts_zero(tmp_path, capsys, detector):
    """W61 for `pdrlearn steps` as for `track` (it had stopped with exit 2 asking for the frame): 0 steps, one
    warning, and an empty steps table with the columns of a waist detection."""
    d = _standing(tmp_path)
    out_csv = tmp_path / "s.csv"
    assert main(["steps", str(d), "--detector", detector, "--out", str(out_csv), "--json"]) == 0
    cap = capsys.readouterr()
    assert json.loads(cap.out)["count"] == 0
    assert cap.err.count("no walking to track") == 1 and "0 steps;" in cap.err
    assert out_csv.read_text().strip() == "start_s,end_s,event_s,unit,confidence"


def test_a_window_of_walking_is_not_tracked_as_standing(tmp_path, capsys):
    """The first 7.5 s (2.5 s of walking from 5 s): one 4 s window of walking is 400 samples, 3.99999999999996 s
    at the file's 100.000000000001 Hz, and was taken for "less than 4 s of walking": W61 then tracked a walking
    recording as 0 steps, 0 m ("4 s of walking (under 4 s ...)"). It is judged by the rhythm test instead, which
    refuses it asking for the frame."""
    d = _standing(tmp_path, end_ms=7500)
    assert main(["track", str(d), "--out", str(tmp_path / "t")]) == 2
    err = capsys.readouterr().err
    assert "no walking to track" not in err and "declares no axis frame" in err and "no walking rhythm" in err


def test_calibrate_start_end_counts_the_measured_stretch_only(tmp_path, capsys):
    """HA001 Test5 Trial1: the whole recording's steps (10, from 5.0 s) vs the 5.01 m bout (5.04-9.87 s, 8
    steps): --start/--end gives the bout's K (trial 12: 0.974 vs 1.219)."""
    from pdrlearn.waist.calibration import calibrate

    s = read_session(HA001_T5)
    k_all = calibrate([s], "waist-pendulum", distances=[5.01]).k
    k_bouts = calibrate([s], "waist-pendulum").k
    cut = calibrate([s], "waist-pendulum", distances=[5.01], spans=[(5.0, 11.0)])
    assert abs(cut.k - k_bouts) < 0.01 < abs(k_all - k_bouts)
    assert any("counted over 8 steps" in n for n in cut.notes)
    assert main(["calibrate", str(HA001_T5), "-d", "5.01", "--start", "5", "--end", "11", "--out",
                 str(tmp_path / "p.json"), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["k"] == pytest.approx(cut.k)
    assert main(["calibrate", str(HA001_T5), "--start", "5", "--out", str(tmp_path / "q.json")]) == 2
    assert "pass --distance METERS too" in capsys.readouterr().err
    assert main(["calibrate", str(HA001_T5), "-d", "5", "--start", "20", "--out", str(tmp_path / "q.json")]) == 2
    assert "no detected step" in capsys.readouterr().err


@pytest.mark.parametrize("span", [["--start", "nan"], ["--end", "inf"]])
def test_calibrate_start_end_must_be_finite(tmp_path, capsys, span):
    src = str(HA001_T5)
    assert main(["calibrate", src, "-d", "5.01", *span, "--out", str(tmp_path / "p.json")]) == 2
    err = capsys.readouterr().err
    assert f"{span[0]} {span[1]}: give seconds from the start" in err and not (tmp_path / "p.json").exists()


def test_calibrate_start_end_on_a_clock_that_does_not_start_at_0(tmp_path):
    """--start/--end are seconds from the recording's start; the contacts span calibrate prints must be on the
    same clock, or a user narrowing the stretch from it gets the wrong steps (review: it printed 105.7-110.6 s
    for a recording whose clock starts at 100 s, where --start 5 --end 11 had counted them)."""
    import pandas as pd

    from pdrlearn.waist.calibration import calibrate

    d = tmp_path / "late"
    shutil.copytree(HA001_T5, d)
    for f in d.glob("*.csv"):
        t = pd.read_csv(f)
        for c in t.columns:
            if c == "timestamp" or c.endswith("_ms"):
                t[c] = t[c] + 100000
        t.to_csv(f, index=False)
    ref = calibrate([read_session(HA001_T5)], "waist-pendulum", distances=[5.01], spans=[(5.0, 11.0)])
    late = calibrate([read_session(d)], "waist-pendulum", distances=[5.01], spans=[(5.0, 11.0)])
    assert late.k == pytest.approx(ref.k)
    span = [n for n in late.notes if "counted over" in n]
    assert span == [n for n in ref.notes if "counted over" in n]
    assert "contacts 5.7-10.6 s from the recording's start" in span[0]


def test_one_missing_sample_is_bridged_not_a_gap(caplog):
    """Decision B46: one dropped sample (an interval of 2 periods) is bridged by the step windows' time
    interpolation, as W34 bridges it in the waist pipelines; two in a row are a gap (B11). Trial 12: 3 of 51
    waist steps of a 50 Hz recording with 6 single dropped samples lost their channels."""
    from pdrlearn.features import step_windows
    from pdrlearn.io.session import Stream
    from pdrlearn.sim import simulate

    s = simulate("walk", user_seed=2, length_m=20.0, rate_hz=50.0)
    acc = s.streams["wAccelerometer"]
    single = np.zeros(len(acc), dtype=bool)
    single[[300, 420, 555]] = True
    for name in ("wAccelerometer", "wGyroscope"):
        st = s.streams[name]
        s.streams[name] = Stream(name, st.t[~single], st.values[~single])
    with caplog.at_level(logging.WARNING):
        w = step_windows(s)
    assert "waist" not in w.gap_steps and "overlap a gap" not in caplog.text
    assert np.isfinite(w.X).all()
    double = single.copy()
    double[[301]] = True  # 300 and 301: two samples in a row
    s2 = simulate("walk", user_seed=2, length_m=20.0, rate_hz=50.0)
    for name in ("wAccelerometer", "wGyroscope"):
        st = s2.streams[name]
        s2.streams[name] = Stream(name, st.t[~double], st.values[~double])
    w2 = step_windows(s2)
    t_gap = acc.t[300]
    hit = (s2.steps["start_s"] < t_gap + 0.06).to_numpy() & (s2.steps["end_s"] > t_gap - 0.02).to_numpy()
    assert hit.any() and np.array_equal(w2.gap_steps["waist"], hit)


@pytest.mark.parametrize("delay_s", [None, 1.75])
def test_online_with_dropped_samples_equals_detect(delay_s):
    """Decision W59: a stream with 6 single dropped samples and a 1.5 s gap gives, pushed in chunks, the
    contacts of ``detect`` on the same session (which bridges them, W34; before: 106 vs 105 offline contacts,
    99 vs 100 realtime)."""
    import pandas as pd

    from pdrlearn.io.session import Stream
    from pdrlearn.steps import WaistICStepDetector

    s = read_session(ROOT / "datasets" / "real" / "mobgap_HA001_Test11_Trial1")
    n = len(s["wAccelerometer"])
    drop = np.zeros(n, dtype=bool)
    drop[np.random.default_rng(0).choice(np.arange(50, n - 50), 6, replace=False)] = True
    drop[3000:3150] = True  # 1.5 s: filled as a rest and ends the walking sequence (B11)
    for name in ("wAccelerometer", "wGyroscope"):
        st = s[name]
        s.streams[name] = Stream(name, st.t[~drop], st.values[~drop])
    a, g = s["wAccelerometer"], s["wGyroscope"]
    t, v = a.t, np.column_stack([a.values, g.values])
    det = WaistICStepDetector(delay_s=delay_s)
    off = det.detect(s)
    on = det.online(a.rate_hz, rotation=s.require_frame("waist").matrix())
    out = pd.concat([on.push(t[i:i + 37], v[i:i + 37]) for i in range(0, len(t), 37)] + [on.flush()],
                    ignore_index=True)
    assert len(out) == len(off) > 90
    np.testing.assert_allclose(out["start_s"], off["start_s"], atol=1e-9)
    np.testing.assert_allclose(out["end_s"], off["end_s"], atol=1e-9)
