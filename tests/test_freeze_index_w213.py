"""The freeze index (Moore et al. 2008, Baechlin et al. 2010), freezes.csv and the lower back's freeze veto
(decisions W213, W214)."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.kernels.freeze import FI_POWER_MIN, freeze_episodes, freeze_index, inside_episodes
from pdrlearn.sim import Freeze, Stand, Straight, UserProfile, simulate_path
from pdrlearn.track.freezes import FREEZE_COLUMNS, freeze_summary, freezes_of

FS = 100.0


def _t(seconds: float) -> np.ndarray:
    return np.arange(int(seconds * FS)) / FS


def test_freeze_index_of_sines():
    t = _t(12.0)
    _, fi5, p5 = freeze_index(np.sin(2 * np.pi * 5.0 * t), FS)
    _, fi15, p15 = freeze_index(np.sin(2 * np.pi * 1.5 * t), FS)
    assert np.all(fi5 > 100) and np.all(fi15 < 0.1)
    assert p5 == pytest.approx(np.full(p5.size, 0.5), rel=0.05)  # mean square of a unit sine
    c, fi, _ = freeze_index(np.zeros(100), FS)
    assert c.size == 0 and fi.size == 0  # shorter than one 4 s window


def test_standing_noise_is_under_the_power_threshold():
    x = 9.81 + 0.02 * np.random.default_rng(0).standard_normal(int(20 * FS))
    _, _, p = freeze_index(x, FS)
    assert np.all(p < FI_POWER_MIN)
    assert freeze_episodes(_t(20.0), x, FS) == []


def test_episode_bounds_follow_a_burst():
    t = _t(30.0)
    walk = 1.5 * np.sin(2 * np.pi * 1.8 * t)
    burst = (t >= 10.0) & (t < 18.0)
    x = np.where(burst, 1.0 * np.sin(2 * np.pi * 6.0 * t), walk)
    eps = freeze_episodes(t, x, FS, threshold=3.0)
    assert len(eps) == 1
    a, b, peak = eps[0]
    assert abs(a - 10.0) < 2.5 and abs(b - 18.0) < 2.5 and peak > 3.0
    assert list(inside_episodes(np.array([5.0, 14.0, 25.0]), eps)) == [False, True, False]


@pytest.fixture(scope="module")
def frozen():
    route = [Stand(2.0), Straight(4.0), Freeze(10.0, 5.0, 10.0), Straight(4.0), Stand(2.0)]
    user = UserProfile.from_seed(4812)
    import dataclasses

    user = dataclasses.replace(user, step_length_m=0.2, step_time_s=0.55)  # the trial's shuffling gait
    return simulate_path(route, user, rate_hz=100, seed=4812, bounce="pendulum")


@pytest.mark.parametrize("unit", ["wAccelerometer", "fAccelerometer"])
def test_simulated_freeze_found_on_both_units(frozen, unit):
    fz = frozen.extras["freezes"]
    a, b = float(fz["start_s"].iloc[0]), float(fz["end_s"].iloc[0])
    rows = freezes_of(frozen.streams[unit].t, frozen.streams[unit].values)
    assert len(rows) == 1 and list(rows[0]) == list(FREEZE_COLUMNS)
    assert rows[0]["start_s"] < a + 2.0 and rows[0]["end_s"] > b - 2.0
    assert freeze_summary(rows)["n_freezes"] == 1


def test_no_freeze_on_a_plain_walk():
    s = simulate_path([Stand(3.0), Straight(14.0), Stand(3.0)], UserProfile.from_seed(11), rate_hz=100, seed=11)
    for unit in ("wAccelerometer", "fAccelerometer"):
        assert freezes_of(s.streams[unit].t, s.streams[unit].values) == []
    assert freeze_summary(None) == {"n_freezes": None, "freeze_time_s": None}


def test_freeze_veto_drops_the_trembling_contacts(frozen):
    from pdrlearn.track.waist import track_waist

    fz = frozen.extras["freezes"]
    a, b = float(fz["start_s"].iloc[0]), float(fz["end_s"].iloc[0])
    # W214 was measured without a stand veto (W217: the default again); "adjacent" (W198) drops this session's
    # trembling (a weak run, no walking bounce)
    # W337's foot_rest_veto (default on) drops the trembling too (the frozen foot does not swing, W342): off here, to
    # see W214's freeze veto alone
    off = track_waist(frozen, pipeline="waist-pendulum", stand_veto=False, foot_rest_veto=False)
    on = track_waist(frozen, pipeline="waist-pendulum", stand_veto=False, freeze_veto=True,  # W216: implies the index
                     foot_rest_veto=False)
    ev0, ev1 = off.steps["event_s"].to_numpy(float), on.steps["event_s"].to_numpy(float)
    assert ((ev0 > a) & (ev0 < b)).sum() >= 5  # the finding: trembling read as steps without the stand veto
    adj = track_waist(frozen, pipeline="waist-pendulum", stand_veto="adjacent",
                      foot_rest_veto=False).steps["event_s"].to_numpy(float)
    assert ((adj > a) & (adj < b)).sum() == 0  # W198's value drops them here (and, W217, may drop the walks too)
    assert ((ev1 > a) & (ev1 < b)).sum() == 0
    assert on.info["n_frozen_contacts"] == ev0.size - ev1.size and off.info["n_frozen_contacts"] == 0
    assert off.info["freezes"] is None and len(on.info["freezes"]) == 1  # W216: off, the index is not computed
    assert on.info["freezes"] == track_waist(frozen, pipeline="waist-pendulum", freeze_index=True).info["freezes"]


def test_freeze_veto_is_named_ignored_by_a_realtime_track(frozen):
    from pdrlearn.track.waist import track_waist

    res = track_waist(frozen, pipeline="waist-pendulum", realtime=True, freeze_veto=True)
    assert any("freeze_veto" in w and "W214" in w for w in res.info["warnings"])
    assert res.info["n_frozen_contacts"] == 0


def test_track_writes_freezes_csv_and_summary(frozen, tmp_path):
    from pdrlearn.cli import main
    from pdrlearn.io import write_session

    d = tmp_path / "s"
    write_session(frozen, d)
    for pipeline in ("waist-pendulum", "plasys"):  # W216: the lower back's index with --freeze-index
        out = tmp_path / pipeline
        flag = ["--freeze-index"] if pipeline == "waist-pendulum" else []
        assert main(["track", "--no-plot", str(d), "--pipeline", pipeline, "--out", str(out), *flag]) == 0
        table = pd.read_csv(out / "freezes.csv")
        assert list(table.columns) == list(FREEZE_COLUMNS) and len(table) == 1
        summary = json.loads((out / "summary.json").read_text())
        assert summary["n_freezes"] == 1 and summary["freeze_time_s"] == pytest.approx(table["duration_s"].sum())
        assert "freezes" not in summary["info"]


HA001_TEST11 = "datasets/real/mobgap_HA001_Test11_Trial1"


@pytest.mark.skipif(not __import__("os").path.isdir(HA001_TEST11), reason="real mobgap recording absent")
def test_lower_back_freeze_index_is_opt_in_w216(tmp_path, capsys):
    """W216: the real healthy walker's daily activities (W215: 4 false episodes, 14.5 s) read no freeze by default:
    no freezes.csv, null keys (not measured), no line; --freeze-index (or the PARAMS option) gives the episodes."""
    from pdrlearn.cli import main

    out = tmp_path / "default"
    assert main(["track", "--no-plot", HA001_TEST11, "--out", str(out)]) == 0
    printed = capsys.readouterr()
    summary = json.loads((out / "summary.json").read_text())
    assert not (out / "freezes.csv").exists()
    assert "n_freezes" in summary and summary["n_freezes"] is None and summary["freeze_time_s"] is None
    assert "freezes.csv" not in printed.out + printed.err and "freeze episode" not in printed.out + printed.err
    assert not any("freeze" in w for w in summary["info"]["warnings"])
    on = tmp_path / "on"
    assert main(["track", "--no-plot", HA001_TEST11, "--out", str(on), "--freeze-index"]) == 0
    table = pd.read_csv(on / "freezes.csv")
    s_on = json.loads((on / "summary.json").read_text())
    assert s_on["n_freezes"] == len(table) == 4 and s_on["freeze_time_s"] == pytest.approx(14.5)
    assert any("W215" in w for w in s_on["info"]["warnings"])
    assert (s_on["n_steps"], s_on["distance_m"]) == (summary["n_steps"], summary["distance_m"])  # no step changed
    par = tmp_path / "p.json"
    par.write_text(json.dumps({"options": {"freeze_index": True}}))
    via = tmp_path / "via_params"
    assert main(["track", "--no-plot", HA001_TEST11, "--out", str(via), "--params", str(par)]) == 0
    assert json.loads((via / "summary.json").read_text())["n_freezes"] == 4


def test_foot_freeze_index_stays_on_w216(frozen):
    from pdrlearn.track import get_pipeline

    res = get_pipeline("plasys")(frozen)
    summary = res.summary(frozen)
    assert summary["n_freezes"] == 1  # the foot's index by default, the simulated freeze found


def test_run_waist_bundle_follows_the_option_w216(frozen):
    from pdrlearn.track.freezes import freeze_index_on, lower_back_freezes

    assert not freeze_index_on(None) and not freeze_index_on({"freeze_index": False})
    assert freeze_index_on({"freeze_index": True}) and freeze_index_on({"freeze_veto": True})  # the veto implies it
    assert lower_back_freezes(frozen, "runtime-waist", {}) is None
    assert len(lower_back_freezes(frozen, "runtime-waist", {"freeze_index": True})) == 1


def test_run_writes_the_lower_back_freezes_only_with_the_option_w216(frozen, tmp_path):
    """W216: `run` on a waist bundle follows track: freezes.csv and the keys with the bundle's freeze_index option,
    none (null keys) without."""
    from pdrlearn.cli import main
    from pdrlearn.export.waist import export_waist
    from pdrlearn.io import write_session
    from pdrlearn.sim import simulate
    from pdrlearn.waist.calibration import calibrate

    frame = ",".join(f"{k}={v}" for k, v in frozen.require_frame("waist").to_dict().items())
    cal = calibrate([simulate("A", 401, rate_hz=100.0)], "waist-pendulum", distances=[20.0])
    cal.save(tmp_path / "cal.json")
    d = write_session(frozen, tmp_path / "s")
    for on in (False, True):
        p = tmp_path / f"p{on}.json"
        p.write_text(json.dumps({**json.loads((tmp_path / "cal.json").read_text()),
                                 "options": {"freeze_index": on}}))
        export_waist(p, tmp_path / f"b{on}", frame=frame)
        out = tmp_path / f"run{on}"
        assert main(["run", "--no-plot", str(tmp_path / f"b{on}"), str(d), "--out", str(out)]) == 0
        summary = json.loads((out / "summary.json").read_text())
        assert (out / "freezes.csv").exists() is on
        assert summary["n_freezes"] == (1 if on else None)
