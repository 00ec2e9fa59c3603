"""Session 18 rehab trial: what n_steps counts (decision L103) and the walk's pauses, bouts, turns and
stride-time variability (decision L104), on simulated walks with known stops and turns."""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.base import get_pipeline
from pdrlearn.track.clinical import CLINICAL_KEYS, clinical_summary, pauses, turns
from pdrlearn.track.evaluate import track_summary
from tests.conftest import REAL

#: two 3 s stops, turns of 180, 90 and -45 deg, a gentle 90 deg curve (8 m radius, ~9 deg/s): 3 bouts, 2 turns
ROUTE = ("stand:2, straight:8, stand:3, straight:8, turn:180, straight:8, turn:90, straight:6, turn:-45, "
         "straight:6, stand:3, straight:6, curve:90:8, straight:3, stand:2")
#: a 0.4 m/s patient (0.3 m steps in 0.75 s at the simulator's slow speed: x 0.85 length, x 1.2 time)
PATIENT = {"step_length_m": 0.30 / 0.85, "step_time_s": 0.75 / 1.2}


@pytest.fixture(scope="module")
def walks():
    u1 = UserProfile.from_seed(1)
    return {"normal": simulate_path(parse_route(ROUTE), u1, speed="normal", rate_hz=20, seed=0),
            "patient": simulate_path(parse_route(ROUTE), dataclasses.replace(u1, **PATIENT), speed="slow",
                                     rate_hz=20, seed=0)}


@pytest.mark.parametrize("walk", ["normal", "patient"])
@pytest.mark.parametrize("pipeline", ["plasys", "waist-pendulum"])
def test_pauses_bouts_and_turns_of_a_known_walk(walks, walk, pipeline):
    s = walks[walk]
    # W385's default turn_bridge "side" recovers two turn steps of the patient walk (79.40, 80.10 s) but not the third,
    # which splits its turn bout (n_pauses 3, n_walking_bouts 4): a known cost recorded in W385; pinned here without
    # the bridge, as these counts were set
    kw = {"turn_bridge": False} if pipeline == "waist-pendulum" else {}
    summary = track_summary(get_pipeline(pipeline)(s, **kw), s, pipeline=pipeline)
    assert set(CLINICAL_KEYS) <= set(summary)
    assert summary["n_pauses"] == 2 and summary["n_walking_bouts"] == 3, summary
    assert 2.5 <= summary["longest_pause_s"] <= 4.5 and 5.0 <= summary["pause_time_s"] <= 8.5
    assert summary["turn_count_min_deg"] == 80.0
    if pipeline == "plasys":  # 180 and 90; not the 45 deg turn, not the curve
        assert summary["turn_count"] == 2
    else:  # the lower back's step headings turn in the pipeline's detected turns: a curve can count (L104)
        assert summary["turn_count"] in (2, 3)
    if pipeline == "plasys":  # the simulated users' stride-time scatter is ~2 % (truth 1.7-2.1 % on straight walks)
        assert 1.0 <= summary["stride_time_cv_pct"] <= 4.0 and summary["n_cv_strides"] >= 10
    else:  # L104: no variability from the lower back's scattered contacts
        assert summary["stride_time_cv_pct"] is None and summary["n_cv_strides"] == 0


def _foot_table(starts, turn_deg=None) -> pd.DataFrame:
    t = np.asarray(starts, dtype=float)
    n = len(t)
    turn = np.zeros(n) if turn_deg is None else np.radians(turn_deg)
    return pd.DataFrame({"start_s": t, "end_s": np.append(t[1:], t[-1] + 1.2), "heading_rad": np.cumsum(turn),
                         "turn_angle_rad": turn, "stride_time_s": np.full(n, 1.2), "gap_s": 0.0, "unit": "foot"})


def test_pause_and_turn_definitions():
    # strides every 1.2 s; one interval 1.3 s longer than the rhythm (a pause), one 0.7 s longer (none)
    t = np.cumsum([0] + [1.2] * 5 + [2.5] + [1.2] * 5 + [1.9] + [1.2] * 5)
    p = pauses(_foot_table(t))
    assert np.allclose(p, [1.3])
    table = _foot_table(t)
    table.loc[6, "stride_time_s"] = 2.5  # IC to IC across the short stop (L80): no rhythm, left out of the CV
    table.loc[12, "stride_time_s"] = 1.3
    c = clinical_summary(table)
    assert c["n_pauses"] == 1 and c["n_walking_bouts"] == 2 and c["longest_pause_s"] == pytest.approx(1.3)
    steady = np.r_[np.full(11, 1.2), 1.3]  # rows 1-3 and 8-16: not the first / last, nor next to the pause (5, 6)
    assert c["n_cv_strides"] == 12
    assert c["stride_time_cv_pct"] == pytest.approx(100 * steady.std(ddof=1) / steady.mean())
    # a slow turn on the spot is no pause: the same long interval with the heading turning 90 deg across it
    turn = np.zeros(len(t))
    turn[6] = 90.0
    assert len(pauses(_foot_table(t, turn))) == 0
    # turns: 3 x 60 deg in 3 strides (one turn of 180), then 4 x 10 deg per 1.2 s (a curve: 8 deg/s, no turn)
    t = np.arange(20) * 1.2
    turn = np.zeros(20)
    turn[5:8] = 60.0
    turn[12:16] = 10.0
    assert np.allclose(turns(_foot_table(t, turn)), [180.0])
    assert clinical_summary(_foot_table(t, turn))["turn_count"] == 1
    # a sensor gap is not a pause
    gap = _foot_table(np.cumsum([0] + [1.2] * 5 + [6.0] + [1.2] * 5))
    gap.loc[5, "gap_s"] = 4.0
    assert clinical_summary(gap)["n_pauses"] == 0
    empty = clinical_summary(_foot_table([0.0]).iloc[:0])
    assert empty["n_walking_bouts"] == 0 and empty["turn_count"] == 0 and empty["stride_time_cv_pct"] is None


def test_a_stand_then_a_turn_is_a_pause_and_a_turn():
    """L119 (session 20 rehab trial): a 40 s stand whose next stride turns 120 deg (then 60 deg) was no pause
    (heading change >= 30 deg across the interval: 'a turn on the spot') and, the 120 deg spread over 41 s, no
    turn either. Now the turn's time at 20 deg/s (6 s) is turning, the rest of the excess standing."""
    t = np.r_[np.arange(6) * 1.2, 6 * 1.2 + 40.0 + np.arange(6) * 1.2]
    turn = np.zeros(len(t))
    turn[6:8] = [120.0, 60.0]  # the stride after the stand turns: how the foot tracked the trial's walk
    for table in (_foot_table(t, turn), _foot_table(t, turn).drop(columns=["turn_angle_rad", "unit"])):
        c = clinical_summary(table)
        assert c["n_pauses"] == 1 and c["longest_pause_s"] == pytest.approx(40.0 - 120.0 / 20.0), c
        assert c["turn_count"] == 1 and np.allclose(turns(table), [180.0])


def test_real_walk_with_a_long_stand_before_a_turn(tmp_path):
    """L119 on a real recording: HA001 Test11 with 120 s of its own quiet standing spliced in at 20 s (the
    trial's tools/splice.py) - the walker stands, then turns (Test11 turns after its first stop). Before, the
    summary's pauses were the original's (longest 19.5 s): the 120 s stand ended in a >= 30 deg heading change."""
    import shutil

    src = REAL / "mobgap_HA001_Test11_Trial1"
    dst = tmp_path / "t11_stand"
    shutil.copytree(src, dst)
    at, dur = 20.0, 120.0
    for f in dst.glob("w*.csv"):
        d = pd.read_csv(f)
        t = d["timestamp"].to_numpy(float) / 1000.0
        dt = float(np.median(np.diff(t)))
        quiet = d[(t >= 15.0) & (t < 25.0)].drop(columns="timestamp").to_numpy()  # standing in the original
        n = int(round(dur / dt))
        ins = pd.DataFrame(quiet[np.arange(n) % len(quiet)], columns=d.columns[1:])
        k = int(np.searchsorted(t, at))
        ins.insert(0, "timestamp", (t[k - 1] + dt * (1 + np.arange(n))) * 1000.0)
        after = d.iloc[k:].copy()
        after["timestamp"] += n * dt * 1000.0
        pd.concat([d.iloc[:k], ins, after]).to_csv(f, index=False)
    for f in ("steps.csv", "ics.csv", "bouts.csv", "turns.csv"):
        if (dst / f).exists():
            d = pd.read_csv(dst / f)
            for c in [c for c in d.columns if c.endswith("_ms")]:
                d.loc[d[c] > at * 1000.0, c] += dur * 1000.0
            d.to_csv(dst / f, index=False)
    assert main(["track", "--no-plot", str(dst), "--out", str(tmp_path / "o")]) == 0
    summary = json.loads((tmp_path / "o" / "summary.json").read_text())
    assert summary["longest_pause_s"] >= 120.0 and summary["pause_time_s"] >= 120.0, summary


def test_walking_speed_leaves_out_the_pauses():
    """L110: ``walking_speed_mps`` = distance / the walking time outside the pauses; ``gait_speed_mps`` (L79)
    keeps a short stop's time. Strides of 1 m every 1.2 s, one of them 2.5 s (a 1.3 s pause inside the walking
    time: L79 cuts stops over 3 s only), then a 4.2 s stop (a 3 s pause, outside the walking time already)."""
    from pdrlearn.track.gait import gait_summary

    t = np.cumsum([0] + [1.2] * 5 + [2.5] + [1.2] * 5)
    table = _foot_table(t).assign(length_m=1.0, speed_mps=1.0 / 1.2, cadence_spm=100.0)
    g = gait_summary(table)
    assert g["walking_time_s"] == pytest.approx(15.7) and g["gait_speed_mps"] == pytest.approx(12 / 15.7)
    assert g["walking_time_no_pauses_s"] == pytest.approx(15.7 - 1.3)
    assert g["walking_speed_mps"] == pytest.approx(12 / 14.4)
    from pdrlearn.cli.common import gait_line

    line = gait_line({**g, "distance_m": 12.0})
    assert "12.00 m in 15.70 s walking; 0.83 m/s in the 14.40 s outside pauses)" in line, line
    # a stop over 3 s: L79 leaves its time out of the walking time already, so nothing more is taken away
    stop = table.copy()
    stop.loc[5, "end_s"] = stop.loc[5, "start_s"] + 1.2  # stride 5 ends; the walker stands until row 6 starts
    stop.loc[6:, ["start_s", "end_s"]] += 3.0  # 4.3 s from the end of stride 5 to the start of stride 6
    g = gait_summary(stop)
    assert clinical_summary(stop)["longest_pause_s"] == pytest.approx(4.3)
    assert g["walking_time_s"] == pytest.approx(15.7 - 1.3) and g["walking_time_no_pauses_s"] == pytest.approx(14.4)
    # no pause: the two speeds agree
    g = gait_summary(_foot_table(np.arange(10) * 1.2).assign(length_m=1.0, speed_mps=1.0 / 1.2, cadence_spm=100.0))
    assert g["walking_speed_mps"] == pytest.approx(g["gait_speed_mps"]) == pytest.approx(10 / 12.0)
    assert "outside pauses" not in gait_line({**g, "distance_m": 10.0})


def test_step_time_asymmetry_by_hand():
    """L111 (Python API): the symmetry index 100 |a - b| / (0.5 (a + b)) of the two feet's mean step times, the
    feet alternating inside a walking sequence; a new sequence may start on either foot; a short one is left out."""
    from pdrlearn.track.clinical import step_time_asymmetry, symmetry_index_pct

    assert symmetry_index_pct(0.5, 0.6) == pytest.approx(100 * 0.1 / 0.55) == symmetry_index_pct(0.6, 0.5)
    one = np.tile([0.5, 0.6], 5)  # 10 steps: 5 of each foot
    seq = np.r_[one, np.nan]  # the sequence's last contact has no step time
    hn = np.r_[np.ones(10, bool), False]
    assert step_time_asymmetry(seq, hn) == (pytest.approx(18.181818), 10)
    # a second sequence starting on the other foot (0.6 first) reads the same; a 3-and-3 one is too short
    two = np.r_[seq, np.r_[np.tile([0.6, 0.5], 5), np.nan], np.r_[np.tile([0.5, 0.9], 3), np.nan]]
    hn2 = np.r_[hn, hn, np.ones(6, bool), False]
    assert step_time_asymmetry(two, hn2) == (pytest.approx(18.181818), 20)
    # unequal sequences weigh by their step times: 10 at 18.18 %, 8 symmetric at 0 %
    sym = np.r_[np.full(8, 0.55), np.nan]
    got, n = step_time_asymmetry(np.r_[seq, sym], np.r_[hn, np.ones(8, bool), False])
    assert n == 18 and got == pytest.approx(18.181818 * 10 / 18)
    # a spurious contact (a W27 fragment) ends the sequence: the feet after it are not mixed with those before
    frag = np.r_[np.tile([0.5, 0.6], 4), 0.1, np.tile([0.6, 0.5], 4), np.nan]
    broken = np.zeros(len(frag), bool)
    broken[8] = True
    assert step_time_asymmetry(frag, np.r_[np.ones(len(frag) - 1, bool), False], broken)[0] == pytest.approx(18.181818)
    assert step_time_asymmetry(np.full(5, np.nan), np.ones(5, bool)) == (None, 0)


def test_what_n_steps_counts_in_summary_cli_and_report(walks, tmp_path, capsys):
    """L103: n_steps keeps its meaning (steps.csv rows); n_steps_counts says what they are, n_steps_both_feet
    and n_strides_one_foot give both counts; track's line and report's columns say what they count."""
    s = walks["patient"]
    write_session(s, tmp_path / "sess")
    true_steps = len(s.extras["ics"])
    runs = {}
    for pipeline in ("plasys", "waist-pendulum"):
        out = tmp_path / "results" / pipeline
        assert main(["track", "--no-plot", str(tmp_path / "sess"), "--pipeline", pipeline, "--out", str(out)]) == 0
        runs[pipeline] = json.loads((out / "summary.json").read_text())
        line = capsys.readouterr().out.splitlines()[0]
        d = runs[pipeline]
        if pipeline == "plasys":
            assert d["n_steps_counts"] == "strides of the tracked foot"
            assert d["n_strides_one_foot"] == d["n_steps"] and d["n_steps_both_feet"] == 2 * d["n_steps"]
            assert f"{d['n_steps']} strides of the tracked foot (~{2 * d['n_steps']} steps)" in line
        else:
            assert d["n_steps_counts"] == "steps of both feet"
            assert d["n_strides_one_foot"] is None and d["n_steps_both_feet"] == d["n_steps"]
            # decision W604: with turning steps W331 counted, the console adds them in brackets after n_steps
            turns = d.get("n_steps_with_turns")
            tail = ", " if turns in (None, d["n_steps"]) else f" (~{turns} with the turning steps on the spot"
            assert f"{d['n_steps']} steps{tail}" in line
        # foot: 2 per stride, the other foot unseen (+-1 per bout); the lower back misses a few slow steps
        tol = 3 if pipeline == "plasys" else 0.1 * true_steps
        assert abs(d["n_steps_both_feet"] - true_steps) <= tol, (d["n_steps_both_feet"], true_steps)
    assert main(["report", str(tmp_path / "results"), "--out", str(tmp_path / "rep")]) == 0
    md = (tmp_path / "rep" / "report.md").read_text()
    header = next(ln for ln in md.splitlines() if ln.startswith("| run"))
    assert "steps (both feet)" in header and "strides (tracked foot)" in header and "| n_steps " not in header


#: decision L106: 180 and 90 deg turns; the streamed stride's own turn (E51) left out the turn between strides
STREAM_ROUTE = "straight:8, turn:180, straight:8, turn:90, straight:6"


def test_streamed_turn_count_matches_offline_and_run(tmp_path, capsys):
    """L106: track --streaming and pdrlearn run count the turns offline track counts (the streamed rows' own turn
    plus ``pivot_rad``, the turn between strides); run and track --streaming give the same clinical summary."""
    from pathlib import Path

    bundle = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"
    s = simulate_path(parse_route(STREAM_ROUTE), UserProfile.from_seed(3), speed="normal", rate_hz=20, seed=0)
    write_session(s, tmp_path / "sess")
    runs = {}
    cmds = {"offline": ["track", "--no-plot"], "streaming": ["track", "--no-plot", "--streaming"],
            "run": ["run", "--no-plot", str(bundle)]}
    for name, argv in cmds.items():
        assert main([*argv, str(tmp_path / "sess"), "--out", str(tmp_path / name)]) == 0, capsys.readouterr().err
        runs[name] = json.loads((tmp_path / name / "summary.json").read_text())
    assert runs["offline"]["turn_count"] == 2
    assert runs["streaming"]["turn_count"] == runs["offline"]["turn_count"]
    assert all(runs["run"][k] == runs["streaming"][k] for k in CLINICAL_KEYS), (runs["run"], runs["streaming"])
    st = pd.read_csv(tmp_path / "streaming" / "steps.csv")
    total = np.degrees((st["turn_angle_rad"] + st["pivot_rad"]).sum())
    assert abs(total - 270.0) <= 20.0, total  # the whole turn, not the ~80 % the rows' own turns hold


def test_stride_time_cv_withheld_when_contact_timing_scatters():
    """L113 (an option, not adopted): contacts that jump between two times of the stride (0 or +0.1 s after the
    swing onset's rhythm) withhold the CV with a warning; the same strides with contacts as steady as their
    onsets keep it; by default (the rule failed) the CV is printed."""
    from pdrlearn.track.clinical import CONTACT_SCATTER_OPTION_S, stride_cv_warning

    starts = np.arange(20) * 1.1 + np.random.default_rng(0).normal(0.0, 0.01, 20)
    table = _foot_table(starts)
    ic = starts + 0.8 + np.where(np.arange(20) % 3 == 0, 0.1, 0.0)  # bimodal contact: 0 or +0.1 s late
    table["stride_time_s"] = np.diff(ic, prepend=np.nan)
    default = clinical_summary(table)
    assert default["stride_time_cv_pct"] > 5 and default["stride_time_cv_withheld"] is None
    c = clinical_summary(table, contact_scatter_max_s=CONTACT_SCATTER_OPTION_S)
    assert c["stride_time_cv_pct"] is None and c["n_cv_strides"] == 17
    w = c["stride_time_cv_withheld"]
    assert w["contact_scatter_s"] >= CONTACT_SCATTER_OPTION_S and w["contact_cv_pct"] > 3 * w["swing_onset_cv_pct"]
    assert w["contact_cv_pct"] == pytest.approx(default["stride_time_cv_pct"])
    assert "stride-time CV withheld" in stride_cv_warning(c)
    table["stride_time_s"] = np.diff(starts + 0.8, prepend=np.nan)  # contacts as steady as the onsets
    c = clinical_summary(table, contact_scatter_max_s=CONTACT_SCATTER_OPTION_S)
    assert c["stride_time_cv_withheld"] is None and 0.5 < c["stride_time_cv_pct"] < 2.0
    assert stride_cv_warning(c) is None


def test_track_without_force_sensors_withholds_a_scattered_cv(tmp_path, capsys, monkeypatch):
    """L113 with the check switched on (its option), the session 19 trial's case: simulated user 5 (scenario A's
    20 m) without force sensors. Its accelerometer contacts jump between the heel strike and a peak ~0.1 s later
    (true CV 1.37 %, the contacts' 12.98 %): track prints a warning and no CV; with the force sensors the CV
    stays (2.2 %)."""
    from pdrlearn.track import clinical

    monkeypatch.setattr(clinical, "CONTACT_SCATTER_MAX_S", clinical.CONTACT_SCATTER_OPTION_S)
    sess = tmp_path / "A5"
    assert main(["simulate", "--scenario", "A", "--user-seed", "5", "--out", str(sess)]) == 0
    assert main(["track", "--no-plot", str(sess), "--model", "oracle", "--out", str(tmp_path / "f")]) == 0
    with_force = json.loads((tmp_path / "f" / "summary.json").read_text())
    assert 1.0 < with_force["stride_time_cv_pct"] < 4.0 and with_force["stride_time_cv_withheld"] is None
    for name in ("fForceA.csv", "fForceB.csv"):
        (sess / name).unlink()
    capsys.readouterr()
    assert main(["track", "--no-plot", str(sess), "--model", "oracle", "--out", str(tmp_path / "nf")]) == 0
    out = capsys.readouterr()
    summary = json.loads((tmp_path / "nf" / "summary.json").read_text())
    assert summary["stride_time_cv_pct"] is None and summary["stride_time_cv_withheld"]["contact_cv_pct"] > 10
    assert "stride-time CV withheld" in out.err and "stride-time CV withheld" in out.out
    assert any("stride-time CV withheld" in w for w in summary["info"]["warnings"])


def test_quantisation_of_whole_sample_contacts_by_hand():
    """L116: rounding both contacts of a 1.1 s stride to 20 Hz samples adds 100 x 0.05 / sqrt(6) / 1.1 = 1.856 % in
    quadrature (a true 2.01 % reads 2.74 %, the session 20 trial's 2.81 %), and the median cadence moves by 120 / 1.10
    - 120 / 1.15 = 4.74 steps/min (the trial's 109.09 -> 104.35); at 100 Hz 0.371 %. The warning: a reported 2.81 %
    at 20 Hz (the rounding raises it by 33 %, from 2.11 %) warns, at 100 Hz (0.9 %) not, nor contacts between
    samples."""
    from pdrlearn.track.clinical import (
        BETWEEN_SAMPLES,
        WHOLE_SAMPLES,
        cadence_step_spm,
        quantisation_cv_pct,
        resolution_warning,
    )

    assert quantisation_cv_pct(0.05, 1.1) == pytest.approx(1.8557, abs=1e-4)
    assert quantisation_cv_pct(0.01, 1.1) == pytest.approx(0.371135, abs=1e-6)
    assert cadence_step_spm(0.05, 1.1) == pytest.approx(109.0909 - 104.3478, abs=1e-3)
    s = {"stride_time_cv_pct": 2.81, "timing_resolution_s": 0.05, "median_stride_time_s": 1.1,
         "contact_timing": WHOLE_SAMPLES}
    w = resolution_warning(s)
    assert w is not None and "2.81 %" in w and "~1.86 %" in w and "~2.11 %" in w and "4.7 steps/min" in w
    assert "20 Hz" in w and "L116" in w
    assert resolution_warning({**s, "timing_resolution_s": 0.01}) is None
    assert resolution_warning({**s, "contact_timing": BETWEEN_SAMPLES}) is None
    assert resolution_warning({**s, "stride_time_cv_pct": None}) is None
    assert resolution_warning({**s, "stride_time_cv_pct": 1.5}) is not None  # under the rounding's own 1.86 %


@pytest.mark.parametrize("pipeline", ["plasys", "waist-pendulum"])
def test_summary_says_the_contacts_timing_resolution(walks, pipeline, monkeypatch):
    """L116: every track summary says one sample period of the contacts' stream (0.05 s at 20 Hz) and whether the
    contacts lie on whole samples (the lower back's always; the foot's unless steps decision 32 is on)."""
    from pdrlearn.kernels import contact
    from pdrlearn.track.clinical import BETWEEN_SAMPLES, WHOLE_SAMPLES

    s = walks["normal"]
    for sub in (False, True):
        monkeypatch.setattr(contact, "SUBSAMPLE", sub)
        summary = track_summary(get_pipeline(pipeline)(s), s, pipeline=pipeline)
        assert summary["timing_resolution_s"] == pytest.approx(0.05)
        foot_between = sub and pipeline == "plasys"
        assert summary["contact_timing"] == (BETWEEN_SAMPLES if foot_between else WHOLE_SAMPLES)

def test_step_time_asymmetry_report_says_what_it_can():
    """L121 (session 20 rehab trial): one foot's table cannot give a step-time asymmetry (None, why); on the lower
    back an index under 20 % is the contacts' timing (symmetric walkers read up to 18.8 %): None with the raw
    index; 20 % or more is reported with the caveat that the size is over-read."""
    from pdrlearn.track.clinical import ASYMMETRY_FLOOR_PCT, step_time_asymmetry_report

    foot = step_time_asymmetry_report(_foot_table(np.arange(12) * 1.2))
    assert foot["step_time_asymmetry_pct"] is None and "one foot" in foot["reason"]

    def waist(a, b, n=12):
        t = np.cumsum(np.r_[0.0, np.tile([a, b], n // 2)])
        return pd.DataFrame({"start_s": t[:-1], "end_s": t[1:], "has_next": True, "unit": "waist"})

    small = step_time_asymmetry_report(waist(0.50, 0.55))  # SI 9.5 %
    assert small["step_time_asymmetry_pct"] is None and small["raw_pct"] == pytest.approx(100 * 0.05 / 0.525)
    assert f"{ASYMMETRY_FLOOR_PCT:.0f} %" in small["reason"]
    big = step_time_asymmetry_report(waist(0.45, 0.75))  # SI 50 %
    assert big["step_time_asymmetry_pct"] == pytest.approx(50.0) and big["n_step_times"] == 12
    assert "misreads the size, mostly over" in big["reason"]  # L216: it under-reads too


def test_stride_time_cv_keeps_level_forward_strides_only():
    """Decision L188: stair strides (|dz_m| >= 0.10 m, L179) and backward strides are no steady walker's rhythm."""
    n = 30
    table = _foot_table(np.arange(n) * 1.2)
    table["stride_time_s"] = 1.2 + 0.02 * np.sin(np.arange(n))
    table["dz_m"] = np.r_[np.zeros(12), np.full(10, 0.17), np.zeros(8)]
    table["direction"] = np.r_[np.full(26, "forward"), np.full(4, "backward")]
    table.loc[12:21, "stride_time_s"] = 0.85  # stairs
    table.loc[26, "stride_time_s"] = 2.0  # the stride into backward steps
    c = clinical_summary(table)
    # steady: rows 1-10 (row 11's next is a stair) and 23-24 (22 follows a stair, 25 precedes a backward stride)
    steady = table["stride_time_s"].to_numpy()[np.r_[1:11, 23:25]]
    assert c["n_cv_strides"] == 12
    assert c["stride_time_cv_pct"] == pytest.approx(100 * steady.std(ddof=1) / steady.mean())
    assert c["stride_time_cv_pct"] < 2.0
    # without the columns (a table of a track without a model, or an older one) every stride stays level forward
    assert clinical_summary(table.drop(columns=["dz_m", "direction"]))["n_cv_strides"] == n - 2


def test_readme_route_gives_no_pooled_stride_time_cv(tmp_path, capsys):
    """Decision L188, the session-26 trial's S2: the README route (5 level strides, two flights, a turn, backward
    steps) read a CV of 25.9 % pooling stairs, level and the backward stride; too few steady level strides now."""
    route = "straight:5, up:17, turn:180, down:17, backward:3"
    assert main(["simulate", "--route", route, "--user-seed", "1", "--out", str(tmp_path / "floors")]) == 0
    assert main(["track", "--no-plot", str(tmp_path / "floors"), "--out", str(tmp_path / "out")]) == 0
    out = capsys.readouterr().out
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["stride_time_cv_pct"] is None and summary["n_cv_strides"] < 10, summary
    assert "no stride-time CV (" in out and "steady level forward strides, 10 needed)" in out


def test_summary_takes_the_steady_strides_once(monkeypatch):
    """Session 37 re-read: the stride-time CV, its direction (L444), the length CVs (L212, L380) and the pooled-CV
    check (L196) all read one :func:`steady_rows` per summary, not one each; the summary is the same."""
    import pdrlearn.track.clinical as C

    # two walking bouts of different rhythm (1.0 s then 1.4 s strides) around a 3 s stop: the pooled-CV path runs
    t = np.concatenate([np.arange(12) * 1.0, 11.0 + 4.0 + np.arange(12) * 1.4])
    table = _foot_table(t)
    table["stride_time_s"] = np.r_[np.full(12, 1.0), np.full(12, 1.4)] * (1 + 0.01 * np.sin(np.arange(24)))
    table["length_m"] = 1.2
    before = clinical_summary(table)
    calls = []
    real = C.steady_rows
    monkeypatch.setattr(C, "steady_rows", lambda steps: calls.append(1) or real(steps))
    c = clinical_summary(table)
    assert len(calls) == 1
    assert c["stride_time_cv_bouts"] and c["stride_time_cv_direction"] == "forward", c
    assert json.dumps(c, sort_keys=True) == json.dumps(before, sort_keys=True)
    # review R1: the passed rows give what each check computes on its own rows (not the new code against itself)
    monkeypatch.setattr(C, "steady_rows", real)
    assert c["stride_time_cv_direction"] == C.cv_direction(table)
    alone = C.pooled_cv(table, c["stride_time_cv_pct"])
    assert alone and c["stride_time_cv_bouts"] == alone["bouts"]
    assert c["stride_time_cv_within_bouts_pct"] == alone["within_bouts_cv_pct"]
