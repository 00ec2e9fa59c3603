"""Decisions E146 / L308 (and E147, E148, L309): the live waist tracker and `pdrlearn run WAIST_BUNDLE` apply L296's
``rest_bias`` (by default) and W231's ``pause_ride`` (where the PARAMS.json gives it true: E146's rule for the default
was not met) as the offline track does, decided at the contact that ends the rest or pause (the step after it is
reported then anyway, W64). Before, they integrated a whole rest's gyroscope bias (a heading jump) and kept a whole
pause's barometric drift (phantom floors after a long sit) whatever the options, named only by E145's line.
E148: `run` gives W230's step-jump line, the offline track's (one function, ``kernels.barometer.step_jump_line``).

Simulated users 5920-5949 (session 31's range)."""

from __future__ import annotations

import json
import re

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.export.waist import export_waist
from pdrlearn.io import write_session
from pdrlearn.kernels.barometer import pressure_hpa
from pdrlearn.sim import simulate
from pdrlearn.track.waist import track_waist
from pdrlearn.waist import WaistTracker
from pdrlearn.waist.calibration import calibrate
from tests.test_night_rest_w231_l296 import HELD_DEG, _edit, _sim
from tests.test_runtime_waist import _frame_arg, _push_with_barometer

#: decision E146 / L308: live == offline (``track_waist(realtime=True)``) across the pause and the rest within this
#: (rad for headings, m for altitudes): the same kernels on the same samples, to rounding (measured: 1e-9)
TOL = 1e-6


def _night(user: int):
    """A 10 min sit between two walks, with 6 m of weather drift over the session and a waist gyroscope bias
    walking 1 -> 3 mrad/s about the up axis (as ``test_night_rest_w231_l296``'s)."""
    s = _sim("straight:10, sit:600, straight:10", user)
    s = _edit(s, "wBarometer", lambda t, v: v + (pressure_hpa(0.0, 1013.25) - pressure_hpa(6.0, 1013.25))
              * ((t - t[0]) / (t[-1] - t[0]))[:, None])
    return _edit(s, "wGyroscope", lambda t, v: v + np.outer(0.001 + 0.002 * (t - t[0]) / (t[-1] - t[0]), [0, 1, 0]))


@pytest.fixture(scope="module")
def night():
    return _night(5920)


def _live(s, options=None):
    tr = WaistTracker(s["wAccelerometer"].rate_hz, meta=s.meta, frame=s.require_frame("waist"),
                      params=None if options is None else {"options": options})
    return _push_with_barometer(tr, s, [500] * (len(s["wAccelerometer"].t) // 500 + 1)), tr


def _across(h: np.ndarray, t: np.ndarray, end: np.ndarray) -> float:
    k = int(np.argmax(t[1:] - end[:-1]))  # the step before the longest pause
    return float(np.degrees(np.angle(np.exp(1j * (h[k + 1] - h[k])))))


def _compare(out, ref, z_tol=TOL):
    """``z_tol``: with ``pause_ride`` false the offline altitude holds W174's transfers (sitting down, standing up),
    which the live tracker does not (the difference is the transfers' 0.06 m here); with it, a long pause's change is
    its ride on both sides, so the altitudes agree to rounding."""
    st = ref.steps
    assert len(out) == len(st) > 20
    h = np.array([o.heading_rad for o in out])
    assert np.abs(np.angle(np.exp(1j * (h - st["heading_rad"].to_numpy(float))))).max() < TOL
    np.testing.assert_allclose([o.z for o in out], ref.trajectory["z"].to_numpy()[1:], atol=z_tol, rtol=0)
    np.testing.assert_allclose([o.pause_dz_m for o in out], st["pause_dz_m"].to_numpy(float), atol=z_tol, rtol=0)
    np.testing.assert_allclose([o.x for o in out], ref.trajectory["x"].to_numpy()[1:], atol=TOL, rtol=0)
    np.testing.assert_allclose([o.y for o in out], ref.trajectory["y"].to_numpy()[1:], atol=TOL, rtol=0)


def test_live_equals_offline_across_a_night_sit_e146_l308(night):
    ref = track_waist(night, pipeline="waist-pendulum", realtime=True)  # W231 and L296 on by default
    out, tr = _live(night, {"pause_ride": True})  # E146: W231 live where the PARAMS.json gives it
    _compare(out, ref)  # before E146 / L308: the live heading turned ~50 deg and z kept -6 m of drift
    t, end = np.array([o.t for o in out]), np.array([o.end_s for o in out])
    assert abs(_across(np.array([o.heading_rad for o in out]), t, end)) < HELD_DEG
    assert abs(out[-1].z) < 0.5  # no phantom floor
    assert tr.rest_bias_rests == [tuple(r) for r in ref.info["rest_bias_rests"]]  # L309: L306's spans
    (line,) = [w for w in tr.warnings if "decision W231" in w]  # the drift line, at the stream's end
    drift = float(line.split("the barometric altitude drifted ")[1].split(" m ")[0])
    assert drift < -5.0 and "across 1 rest(s) without steps" in line
    assert not [w for w in tr.warnings if "decision W74" in w or "pause_ride" in w or "rest_bias" in w]
    # the live defaults (L308: rest_bias applied; E146: pause_ride not, named by E107's line): the heading as offline
    out_d, tr_d = _live(night)
    h_d = np.array([o.heading_rad for o in out_d])
    assert np.abs(np.angle(np.exp(1j * (h_d - ref.steps["heading_rad"].to_numpy(float))))).max() < TOL
    assert out_d[-1].z < -5.0 and not [w for w in tr_d.warnings if "decision W231" in w]
    # E368: E107's line for the offline defaults is the tracker's not_applied_live (DEBUG), not a warning
    assert not [w for w in tr_d.warnings if "E107" in w]
    assert "pause_ride=true (the offline default)" in tr_d.not_applied_live and "rest_bias" not in tr_d.not_applied_live
    # the options false: W158's whole pause and W72's whole rest, live as offline (what the live tracker did before)
    off = {"pause_ride": False, "rest_bias": False}
    out_off, tr_off = _live(night, off)
    _compare(out_off, track_waist(night, pipeline="waist-pendulum", realtime=True, **off), z_tol=0.1)
    assert abs(_across(np.array([o.heading_rad for o in out_off]), t, end)) > 20.0
    assert out_off[-1].z < -5.0 and tr_off.rest_bias_rests is None
    assert not [w for w in tr_off.warnings if "decision W231" in w]


def test_a_lift_ride_keeps_its_floor_live_e146():
    s = _sim("straight:10, stand:40, lift:+3, stand:40, straight:10", 5921)
    ref = track_waist(s, pipeline="waist-pendulum", realtime=True)
    out, tr = _live(s, {"pause_ride": True})
    _compare(out, ref)
    assert max(o.pause_dz_m for o in out) == pytest.approx(3.0, abs=0.5)
    assert out[-1].z == pytest.approx(3.0, abs=0.5)
    assert not [w for w in tr.warnings if "decision W231" in w]


@pytest.fixture(scope="module")
def bundle(tmp_path_factory):
    d = tmp_path_factory.mktemp("e146_bundle")
    cal = calibrate([simulate("A", 5922, rate_hz=100.0)], "waist-pendulum", distances=[20.0])
    cal.save(d / "cal.json")
    on = json.loads((d / "cal.json").read_text())
    on["options"] = {**(on.get("options") or {}), "pause_ride": True}  # E146: W231 live where given
    (d / "cal.json").write_text(json.dumps(on))
    s = simulate("B", 5922, rate_hz=100.0)
    export_waist(d / "cal.json", d / "wb", frame=_frame_arg(s))
    off = json.loads((d / "cal.json").read_text())
    off["options"] = {**(off.get("options") or {}), "pause_ride": False, "rest_bias": False}
    (d / "cal_off.json").write_text(json.dumps(off))
    export_waist(d / "cal_off.json", d / "wb_off", frame=_frame_arg(s))
    return d / "wb"


def test_run_of_a_night_applies_both_and_names_neither_e146_e147(night, bundle, tmp_path, capsys):
    walk = write_session(night, tmp_path / "night")
    assert main(["run", "--no-plot", str(bundle), str(walk), "--out", str(tmp_path / "r"), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert (summary["floors_up"], summary["floors_down"]) == (0, 0)  # E145's run: floors down 2
    warnings = summary["info"]["warnings"]
    assert [w for w in warnings if "decision W231" in w]
    assert not [w for w in warnings if "pause_ride" in w or "rest_bias" in w]  # E147: E107's line does not name them
    # the same night on a bundle with both options false: E145's run (W158's whole pause, W72's whole rest)
    assert main(["run", "--no-plot", str(bundle.parent / "wb_off"), str(walk), "--json"]) == 0
    old = json.loads(capsys.readouterr().out)
    assert old["floors_down"] >= 1 and not [w for w in old["info"]["warnings"] if "decision W231" in w]
    # L309: run's radius clock skips the rest L296 corrected live, as track's (L306); with the options false it
    # counts the bias over the whole sit
    assert summary["final_position_sigma_m"] < 0.8 * old["final_position_sigma_m"]  # measured 4.43 vs 7.52 m


def _transient(user: int):
    """A level walk whose barometer loses 2 m within 0.2 s at 8 s and keeps it (a door, W230's transient)."""
    s = _sim("stand:2, straight:15, stand:2", user)
    return _edit(s, "wBarometer", lambda t, v: v + (pressure_hpa(0.0, 1013.25) - pressure_hpa(-2.0, 1013.25))
                 * np.clip((t - t[0] - 8.0) / 0.2, 0.0, 1.0)[:, None])


def test_run_names_a_step_jump_as_track_does_e148(bundle, tmp_path, capsys):
    s = _transient(5923)
    ref = track_waist(s, pipeline="waist-pendulum", realtime=True, params=str(bundle.parent / "cal.json"))
    (want,) = [w for w in ref.info["warnings"] if "decision W230" in w]
    walk = write_session(s, tmp_path / "door")
    assert main(["run", "--no-plot", str(bundle), str(walk), "--out", str(tmp_path / "r"), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    (got,) = [w for w in summary["info"]["warnings"] if "decision W230" in w]  # before E148: no line
    # the same steps at the same times, their dz to the written CSV's rounding and the offline W174 transfer hold
    named = [re.findall(r"([+-]\d+\.\d+) m at (\d+\.\d) s", w) for w in (got, want)]
    assert [a for _, a in named[0]] == [a for _, a in named[1]] and named[0]
    np.testing.assert_allclose([float(d) for d, _ in named[0]], [float(d) for d, _ in named[1]], atol=0.05)
    assert "offline `pdrlearn track` with the option step_bound" in got  # the live tracker does not hold them
    assert summary["info"]["barometer_jump_steps"] == ref.info["barometer_jump_steps"] >= 1
    level = write_session(_sim("stand:2, straight:15, stand:2", 5924), tmp_path / "level")
    assert main(["run", "--no-plot", str(bundle), str(level), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert not [w for w in summary["info"]["warnings"] if "decision W230" in w]
    assert summary["info"]["barometer_jump_steps"] == 0
