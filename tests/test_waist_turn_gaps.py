"""Decisions W72-W74: a turn made during undetected steps (a Timed-Up-and-Go tracked with a lower-back unit only)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.waist import track_waist
from pdrlearn.waist import WaistTracker
from pdrlearn.waist.heading import UNTRACKED_TURN_WARN_DEG, untracked_turn

TUG = "stand:3, straight:3, turn:180, straight:3, turn:180, stand:3"
_CACHE: dict = {}


def _tug():
    if "tug" not in _CACHE:  # the trial's walk: user 4, 20 Hz
        _CACHE["tug"] = simulate_path(parse_route(TUG), UserProfile.from_seed(4), speed="normal", rate_hz=20.0,
                                      seed=0, name="tug_u4", scenario="route")
    return _CACHE["tug"]


def _w74(warnings):
    return [w for w in warnings if "W74" in w]


def test_untracked_turn_measures_a_turn_the_headings_drop():
    """A 90 deg turn between t = 4 and 6 s: headings that keep it miss ~0, headings that drop it miss +90 deg."""
    t = np.arange(0, 10, 0.01)
    w = np.where((t > 4) & (t < 6), (np.pi / 2) / 2.0, 0.0)
    imu = SimpleNamespace(t=t, w_z=w)
    ends = np.array([2.0, 3.0, 7.0, 8.0])
    kept = untracked_turn(imu, np.array([1.0]), ends, np.array([0.0, 0.0, np.pi / 2, np.pi / 2]))
    dropped = untracked_turn(imu, np.array([1.0]), ends, np.zeros(4))
    assert abs(kept[0]) < np.radians(1)
    assert dropped[0] == pytest.approx(np.pi / 2, abs=np.radians(1)) and dropped[1] == 7.0
    # a constant bias is measured as the yaw it integrates to (the warning names it as a cause)
    biased = untracked_turn(SimpleNamespace(t=t, w_z=w + 0.01), np.array([1.0]), ends, np.zeros(4), bias_rps=0.01)
    assert biased[0] == pytest.approx(dropped[0], abs=1e-9)
    assert untracked_turn(imu, np.zeros(0), np.zeros(0), np.zeros(0))[0] == 0.0


def test_untracked_turn_wraps_the_difference_of_wrapped_headings():
    """W80: a 190 deg turn whose step headings are wrapped to -170 deg is kept, not a missed 360 deg."""
    t = np.arange(0, 10, 0.01)
    turn = np.radians(190.0)
    w = np.where((t > 4) & (t < 6), turn / 2.0, 0.0)
    ends = np.array([2.0, 3.0, 7.0, 8.0])
    wrapped = np.angle(np.exp(1j * np.array([0.0, 0.0, turn, turn])))
    assert wrapped[-1] < 0  # the input really is wrapped at +-180 deg
    diff, _ = untracked_turn(SimpleNamespace(t=t, w_z=w), np.array([1.0]), ends, wrapped)
    assert abs(diff) < np.radians(1)


def test_w74_line_names_the_curve_remedies():
    """W82: with integrate_stops on, the line names what tracks a curve (slow_turn_rps, ellipse heading, waist-pll)
    and the bias fit."""
    from pdrlearn.waist.heading import untracked_turn_message

    line = untracked_turn_message(184.0, 30.0, True)
    assert '"slow_turn_rps": 0.035' in line and '"heading": "ellipse"' in line and "--pipeline waist-pll" in line
    assert "--fit-turns" in line


def test_gentle_curves_are_kept_with_the_slow_turn_option():
    """W82: the indoor trial's gentle curves (15 and 25 m radii, 0.09 / 0.05 rad/s, under the GMM's 0.136 rad/s
    boundary) are dropped by seed 003's classifier (the default, with the W74 warning) and kept by the 5-stride
    window (k-3..k+1) of ``slow_turn_rps``."""
    from pdrlearn.waist import heading as H

    s = simulate_path(parse_route("straight:10, curve:90:15, straight:10, curve:90:25, straight:10"),
                      UserProfile.from_seed(3), speed="normal", rate_hz=50.0, seed=4, name="g", scenario="route",
                      bounce="pendulum")
    dropped = track_waist(s, pipeline="waist-pendulum", gentle_curves=False)  # seed 003 alone (W543 off)
    kept = track_waist(s, pipeline="waist-pendulum", slow_turn_rps=H.SLOW_TURN_RPS, gentle_curves=False)
    assert evaluate_track(dropped, s)["final_position_error_m"] > 50.0 and _w74(dropped.info["warnings"])
    assert evaluate_track(kept, s)["final_position_error_m"] < 15.0 and not _w74(kept.info["warnings"])
    mrz = np.array([0.0, 0.03, 0.04, 0.05, 0.04, 0.03, 0.0])
    assert H.slow_turn_strides(mrz, 0.0).sum() == 0 and H.slow_turn_strides(mrz, 0.035)[4]
    assert not H.slow_turn_strides(np.full(9, 0.02), 0.035).any()
    assert not H.slow_turn_strides(np.tile([0.06, -0.06], 5), 0.035)[3:-1].any()  # a sway, not a curve


def test_tug_turns_made_during_undetected_steps_are_kept_by_default():
    """W72/W73: the default keeps the yaw turned between walking sequences; without it the track warns (W74)."""
    s = _tug()
    # turn_bridge false: the turning steps missed, as before W385 ("side" now finds some of them, so the track
    # without integrate_stops turns by them too; this test is about the turn in a gap)
    on = track_waist(s, pipeline="waist-pendulum", turn_bridge=False)
    off = track_waist(s, pipeline="waist-pendulum", integrate_stops=False, turn_bridge=False)
    assert on.info["options"]["integrate_stops"] is True
    # the turning steps are missed, so the walk splits into sequences and the 180 deg turn lies in a gap
    mv_on = on.steps[on.steps["length_m"] > 0]
    mv_off = off.steps[off.steps["length_m"] > 0]
    assert abs(np.degrees(np.angle(np.exp(1j * mv_off["heading_rad"].iloc[-1])))) < 30  # turn dropped
    assert abs(abs(np.degrees(np.angle(np.exp(1j * mv_on["heading_rad"].iloc[-1])))) - 180) < 20  # turn kept
    err_on = evaluate_track(on, s)["final_position_error_m"]
    err_off = evaluate_track(off, s)["final_position_error_m"]
    assert err_on < 1.0 < 4.0 < err_off
    assert len(_w74(off.info["warnings"])) == 1 and "integrate_stops" in _w74(off.info["warnings"])[0]
    assert not _w74(on.info["warnings"])
    assert abs(off.info["untracked_turn_deg"]) >= UNTRACKED_TURN_WARN_DEG > abs(on.info["untracked_turn_deg"])


def test_harmonic_heading_reports_no_untracked_turn():
    """The A-HE heading is an absolute direction: the W74 check is for the gyro heading only."""
    res = track_waist(_tug(), pipeline="waist-pll")
    assert res.info["untracked_turn_deg"] is None and not _w74(res.info["warnings"])


def test_live_tracker_warns_as_track_waist():
    """WaistTracker: the same default and the same one warning when the turn is dropped."""
    s = _tug()
    a, g = s["wAccelerometer"], s["wGyroscope"]
    for integ, n_warn in ((False, 1), (None, 0)):
        tr = WaistTracker(a.rate_hz, meta=s.meta, frame=s.require_frame("waist"), integrate_stops=integ)
        for i in range(0, len(a.t), 20):
            tr.push(a.t[i:i + 20], a.values[i:i + 20], g.values[i:i + 20])
        tr.flush()
        assert len(_w74(tr.warnings)) == n_warn, tr.warnings


def test_turn_gate_option_finds_the_turning_steps():
    """Steps decision 28 (an option, not the default): the gate opened by the pelvis's yaw rate finds the turning
    steps the std gate closes on; the default detector is unchanged by the option's existence."""
    from pdrlearn.steps.evaluate import score_events
    from pdrlearn.waist.ahrs import waist_imu
    from pdrlearn.waist.events import InitialContactDetector, walking_gate

    s = _tug()
    imu = waist_imu(s)
    ref = s.extras["ics"]["ic_s"].to_numpy(float)
    kinds = s.extras["ics"]["kind"].to_numpy(str)
    turn_ics = ref[kinds == "turn"]
    std_gate = walking_gate(imu)
    turn_gate = walking_gate(imu, turn_gate_rps=0.45)
    idx = np.searchsorted(imu.t, turn_ics)
    assert not std_gate[idx].all() and turn_gate[idx].all()
    assert (turn_gate >= std_gate).all()  # the option only opens the gate

    def tp(det):
        return score_events(imu.t[det.detect(imu).ic_], ref)["true_positives"]

    assert tp(InitialContactDetector(turn_gate_rps=0.45)) > tp(InitialContactDetector()) + 3
    assert InitialContactDetector().turn_gate_rps is None
