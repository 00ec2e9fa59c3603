"""Decision W150's candidate, option ``pivot_steps``: a step that turns the pelvis 45 deg or more keeps at most the
chord of its turn on a 0.2 m radius -- the kernel by hand, the option end to end on the S41 turn on the spot (both
pipelines, realtime, calibration sums what the tracker sums, W21; the live tracker equals the realtime replay), a
bad value refused in one line, and the measured demo row (HA001 Test11 calibrated on Test5 Trial1)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.waist import _kernels as K

ROOT = Path(__file__).resolve().parents[1]
REAL = ROOT / "datasets" / "real"


def test_kernel_caps_only_pivot_steps_at_the_chord_of_their_turn():
    lengths = np.array([0.6, 0.6, 0.1, 0.6, 0.6, 0.0, 0.6])
    dpsi = np.radians([10.0, 44.9, 60.0, -45.0, 90.0, 90.0, 200.0])
    out = K.pivot_step_factor(lengths, dpsi)
    chord = lambda deg: 2 * 0.2 * math.sin(math.radians(deg) / 2)  # noqa: E731
    np.testing.assert_allclose(out, [1.0, 1.0,  # under 45 deg: no pivot
                                     1.0,  # a pivot step already under its chord (0.2 m at 60 deg) keeps its length
                                     chord(45) / 0.6,  # either turning direction
                                     chord(90) / 0.6,
                                     1.0,  # a step without length
                                     0.4 / 0.6])  # more than half a turn: the diameter
    assert out[3] * 0.6 == pytest.approx(0.153, abs=1e-3) and out[4] * 0.6 == pytest.approx(0.283, abs=1e-3)
    # the threshold and radius are settings of the kernel
    assert K.pivot_step_factor(lengths[:1], dpsi[:1], min_deg=5.0, radius_m=1.0)[0] == pytest.approx(
        2 * math.sin(math.radians(5.0)) / 0.6)


@pytest.fixture(scope="module")
def pivot_walk():
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    route = parse_route("straight:6, pivot:180, straight:6, pivot:-90, straight:4")
    return simulate_path(route, UserProfile.from_seed(2760), rate_hz=100, seed=2760)


@pytest.mark.parametrize("pipeline", ["waist-pendulum", "waist-pll"])
def test_option_caps_the_pivot_steps_of_a_turn_on_the_spot(pivot_walk, pipeline):
    from pdrlearn.sim import simulate
    from pdrlearn.track.evaluate import evaluate_track, path_length
    from pdrlearn.track.waist import track_waist
    from pdrlearn.waist.calibration import calibrate

    # calibrated on the user's own straight walk (experiments/waist.py's protocol; no pivot step in it)
    cal = simulate("walk", 2760, "normal", rate_hz=100.0, seed=1, length_m=20.0)
    ics, tr = cal.extras["ics"]["ic_s"].to_numpy(float), cal.trajectory
    walked = path_length(tr[(tr["t"] >= ics.min()) & (tr["t"] <= ics.max())])  # first to last heel strike (W21)
    params = calibrate([cal], pipeline, distances=[walked])
    off = track_waist(pivot_walk, pipeline=pipeline, params=params)
    on = track_waist(pivot_walk, pipeline=pipeline, params=params, pivot_steps=True)
    a, b = off.steps, on.steps
    assert "pivot_factor" not in a
    np.testing.assert_array_equal(a["event_s"], b["event_s"])  # only the lengths change
    f = b["pivot_factor"].to_numpy(float)
    np.testing.assert_allclose(b["length_m"], a["length_m"] * f, rtol=1e-12)
    turned = np.abs(b["dyaw_rad"].to_numpy(float)) >= math.radians(45.0)
    assert (f[~turned] == 1.0).all() and (f[turned] < 1.0).sum() >= 2
    # the capped steps are the simulated pivot's: each within a second of a contact of kind "turn"
    ics = pivot_walk.extras["ics"]
    turn_ic = ics.loc[ics["kind"] == "turn", "ic_s"].to_numpy(float)
    t = b["start_s"].to_numpy(float)[f < 1]
    assert np.abs(t[:, None] - turn_ic[None, :]).min(axis=1).max() < 1.0
    # the route's distance comes closer to the truth
    e_off = abs(evaluate_track(off, pivot_walk)["distance_error_pct"])
    e_on = abs(evaluate_track(on, pivot_walk)["distance_error_pct"])
    assert e_on < e_off


def test_realtime_and_calibration_apply_it(pivot_walk):
    from pdrlearn.track.waist import track_waist
    from pdrlearn.waist.calibration import calibrate
    from pdrlearn.waist.params import resolve_params

    rt = track_waist(pivot_walk, pipeline="waist-pendulum", realtime=True, pivot_steps=True).steps
    assert (rt["pivot_factor"] < 1).any()  # the rotation is known at the step's end: causal
    # W21: calibrated with the option on, tracking the calibration walk sums to its distance
    base, _ = resolve_params(pivot_walk, None)
    base.options = {"pivot_steps": True}
    p = calibrate([pivot_walk], "waist-pendulum", distances=[17.0], params=base)
    st = track_waist(pivot_walk, pipeline="waist-pendulum", params=p).steps
    assert (st["pivot_factor"] < 1).any()
    assert st["length_m"].sum() == pytest.approx(17.0, rel=1e-9)


def test_a_bad_value_is_one_line(pivot_walk):
    from pdrlearn.track.waist import track_waist

    with pytest.raises(DataError, match="pivot_steps='yes' is not true or false") as err:
        track_waist(pivot_walk, pipeline="waist-pendulum", params={"options": {"pivot_steps": "yes"}})
    assert "\n" not in str(err.value)


def test_live_tracker_equals_the_realtime_replay_with_the_option():
    from pdrlearn.io import read_session
    from pdrlearn.track.waist import track_waist
    from pdrlearn.waist import WaistTracker
    from tests.runtime_helpers import push_waist

    s = read_session(REAL / "mobgap_HA001_Test11_Trial1")
    kw = {"merge_fragments": False, "pivot_steps": True}
    ref = track_waist(s, pipeline="waist-pendulum", realtime=True, **kw).steps
    assert (ref["pivot_factor"] < 1).any()
    tr = WaistTracker(s["wAccelerometer"].rate_hz, meta=s.meta, frame=s.require_frame("waist"), **kw)
    out = push_waist(tr, s, list(np.random.default_rng(4).integers(1, 400, 4000)))
    np.testing.assert_allclose([o.length_m for o in out], ref["length_m"], atol=1e-9, rtol=0)


def test_measured_demo_row():
    """W150's measured row (experiments/waist_pivot_steps.py): HA001 Test11 calibrated on Test5 Trial1, total /
    median per bout vs INDIP Length, defaults +17.31 / 11.78 %, pivot_steps +13.85 / 5.87 %."""
    from pdrlearn.io import read_session
    from pdrlearn.track.waist import track_waist
    from pdrlearn.waist.calibration import calibrate
    from pdrlearn.waist.evaluate import distance_metrics
    from pdrlearn.waist.params import resolve_params

    test = read_session(REAL / "mobgap_HA001_Test11_Trial1")
    cal = read_session(REAL / "mobgap_HA001_Test5_Trial1")
    got = {}
    off = {"parity_fill": False, "sit_veto": False}  # measured before W159 / W185
    for label, opts in (("defaults", off), ("pivot", {"pivot_steps": True, **off})):
        base, _ = resolve_params(cal, None)
        base.options = dict(opts)
        p = calibrate([cal], "waist-pendulum", params=base)
        d = distance_metrics(track_waist(test, pipeline="waist-pendulum", params=p, **opts).steps, test)
        got[label] = (round(d["distance_error_pct"], 2), round(d["bout_distance_error_median_pct"], 2))
    assert got == {"defaults": (17.31, 11.78), "pivot": (13.85, 5.87)}
