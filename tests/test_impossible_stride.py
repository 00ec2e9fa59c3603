"""Decisions L93 / L94 (docs/decisions/localization.md): the bayes rule's posterior mean of a stride far below
the class it is given stays inside the classes' bounds (the upper-tail mass no longer cancels to 0), and a
stride faster than any human is never summed: offline, ``track --streaming`` and the runtime move it 0 m with
one warning; a non-finite one is an internal error offline as in the runtime (E38)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pdrlearn.errors import InternalError
from pdrlearn.kernels import bayes as KB
from pdrlearn.kernels import stride as SK
from pdrlearn.runtime import tracker as T
from pdrlearn.runtime.tracker import Tracker
from pdrlearn.track import plasys as P
from pdrlearn.track.base import get_pipeline
from tests.runtime_helpers import replay, synthetic_session, trained_dirs

#: the trial's stride (session st_v450, 4.87-5.70 s): estimate 1.333 m, classed short with p 0.974, the
#: user's bounds and the stride sd (sigma_min 0.02 m)
BOUNDS = [(0.0, 1.0241), (1.0241, 1.5196), (1.5196, 10.0)]
PROBA = [0.9737783629, 5.496836084e-74, 0.02622163711]


def test_bayes_length_of_a_stride_far_below_its_class_stays_in_the_bounds():
    one = KB.bayes_length_one(1.333028231, PROBA, BOUNDS, 0.02)
    arr = KB.bayes_length(np.array([1.333028231]), np.array([PROBA]), BOUNDS, np.array([0.02]))
    assert math.isfinite(one) and 0.0 <= one <= 10.0, one  # was 2.465864934e+30
    assert arr.tolist() == [one]
    # the short class is 15 sd away, the long one 9 sd: the long class's lower edge (truncated normal mean)
    assert one == pytest.approx(1.5196 + 0.02 * 0.02 / (1.5196 - 1.333028231), abs=2e-4)
    # far into either tail, with one class certain, the mean stays in that class
    for d in (0.2, 3.0, 12.0):
        for k, (lo, hi) in enumerate(BOUNDS):
            p = [0.0, 0.0, 0.0]
            p[k] = 1.0
            got = KB.bayes_length_one(d, p, BOUNDS, 0.02)
            assert lo - 1e-9 <= got <= hi + 1e-9 or got == d, (d, k, got)


def test_guard_kernel():
    assert not SK.impossible_stride_one(5.5, 0.0, 0.45)  # a sprint stride (12.2 m/s)
    assert SK.impossible_stride_one(2.465864934e30, 0.0, 0.83)
    assert SK.impossible_stride_one(7.0, 0.0, 0.5)
    assert not SK.impossible_stride_one(float("nan"), 0.0, 1.0)  # non-finite: an internal error, not a gap
    got = SK.impossible_strides(np.array([1.3, 1e30, np.inf, 2.0]), np.zeros(4), np.array([1.0, 1.0, 1.0, 0.1]))
    assert got.tolist() == [False, True, False, True]


@pytest.fixture(scope="module")
def walk():
    return synthetic_session(24, seed=11, name="walk")


def _blow_up(arr, i=3):
    arr = np.array(arr, dtype=float)
    arr[i] = arr[i] * 1e30
    return arr


def _break_stride(monkeypatch, streaming, i=3):
    """The stride ``i``'s (default the fourth) length comes out 1e30 times too long in the offline or the streamed
    rules."""
    if streaming:
        real = SK.apply_stride_rules
        monkeypatch.setattr(SK, "apply_stride_rules",
                            lambda *a, **k: (lambda L, dz: (_blow_up(L, i), dz))(*real(*a, **k)))
    else:
        real = P.StepRules.apply
        monkeypatch.setattr(P.StepRules, "apply",
                            lambda self, d, c: real(self, d, c).assign(length_m=lambda t: _blow_up(t["length_m"], i)))


@pytest.mark.parametrize("streaming", [False, True])
def test_track_moves_an_impossible_stride_zero_metres_with_one_warning(walk, monkeypatch, streaming):
    track = get_pipeline("plasys")
    clean = track(walk, model="oracle", streaming=streaming)
    _break_stride(monkeypatch, streaming)
    res = track(walk, model="oracle", streaming=streaming)
    warn = [w for w in res.info["warnings"] if "physically impossible" in w]
    assert len(warn) == 1 and warn[0].startswith("1 stride(s)") and "decision L94" in warn[0], res.info["warnings"]
    got = res.steps["length_m"].to_numpy(float)
    assert np.isfinite(got).all() and got[3] == 0.0
    want = clean.steps["length_m"].to_numpy(float)
    assert np.abs(got).sum() == pytest.approx(np.abs(want).sum() - abs(want[3]), rel=1e-9)
    assert np.isfinite(res.trajectory[["x", "y", "z"]].to_numpy()).all()


def test_track_refuses_a_non_finite_stride_as_an_internal_error(walk, monkeypatch):
    real = P.StepRules.apply
    monkeypatch.setattr(P.StepRules, "apply", lambda self, d, c: real(self, d, c).assign(
        length_m=lambda t: _blow_up(t["length_m"]) * np.where(np.arange(len(t)) == 3, np.nan, 1.0)))
    with pytest.raises(InternalError, match=r"^internal error in pdrlearn\.track \(plasys\): the stride .* non-finite"):
        get_pipeline("plasys")(walk, model="oracle")


def _break_fourth_runtime_stride(monkeypatch):
    """The runtime's fourth stride comes out 1e30 times its length (the L94 guard's case)."""
    real, calls = T.stride_rules_one, []

    def broken(*a, **k):
        length, dz = real(*a, **k)
        calls.append(1)
        return (length * 1e30 if len(calls) == 4 else length), dz

    monkeypatch.setattr(T, "stride_rules_one", broken)


def test_runtime_moves_an_impossible_stride_zero_metres_with_one_warning(tmp_path_factory, walk, monkeypatch):
    root = trained_dirs(tmp_path_factory)["root"]
    _break_fourth_runtime_stride(monkeypatch)
    tr = Tracker(root / "bundle", speculative=False)
    steps = replay(tr, walk, 0.37)
    warn = [w for w in tr.warnings if "physically impossible" in w]
    assert len(warn) == 1 and "decision L94" in warn[0], tr.warnings
    assert steps[3].length_m == 0.0 and np.isfinite(tr.position).all()
    assert max(abs(st.length_m) for st in steps) < 10.0


# -- decision L97: a zeroed stride is no stride for the gait parameters (as a gap row) --------------------------


@pytest.mark.parametrize("streaming", [False, True])
def test_zeroed_stride_is_left_out_of_the_gait_parameters(walk, monkeypatch, streaming):
    from pdrlearn.track.gait import gait_summary

    track = get_pipeline("plasys")
    kw = {"contacts": True} if streaming else {}
    clean = track(walk, model="oracle", streaming=streaming, **kw)
    _break_stride(monkeypatch, streaming)
    res = track(walk, model="oracle", streaming=streaming, **kw)
    warn = [w for w in res.info["warnings"] if "physically impossible" in w][0]
    assert "left out of the distance and of the gait parameters" in warn and "L97" in warn
    s = res.steps
    assert s["impossible"].tolist() == [i == 3 for i in range(len(s))]
    assert np.isfinite(clean.steps["stride_time_s"].iloc[3]) and np.isfinite(clean.steps["speed_mps"].iloc[3])
    for c in ("stride_time_s", "cadence_spm", "speed_mps"):
        assert np.isnan(s[c].iloc[3]), c  # was a stride with speed 0 m/s
    assert (s["speed_mps"].dropna() > 0).all()
    got, want = gait_summary(s), gait_summary(clean.steps)
    assert got["n_stride_times"] <= want["n_stride_times"] - 1
    # the zeroed stride's time is not walking time: the walk is cut there, as at a gap row (from the end of the
    # stride before to the start of the stride after)
    dur = float(s["start_s"].iloc[4] - s["end_s"].iloc[2])
    assert got["walking_time_s"] == pytest.approx(want["walking_time_s"] - dur, abs=1e-6)


def test_runtime_zeroed_stride_is_left_out_of_the_gait_parameters(tmp_path_factory, walk, monkeypatch):
    from pdrlearn.cli.export import streamed_result
    from pdrlearn.track.gait import gait_summary

    root = trained_dirs(tmp_path_factory)["root"]
    clean = replay(Tracker(root / "bundle", speculative=False, contacts=True), walk, 0.37)
    _break_fourth_runtime_stride(monkeypatch)
    tr = Tracker(root / "bundle", speculative=False, contacts=True)
    steps = replay(tr, walk, 0.37)
    assert [st.impossible for st in steps] == [i == 3 for i in range(len(steps))]
    assert math.isfinite(clean[3].stride_time_s) and math.isfinite(clean[4].stride_time_s)
    assert math.isnan(steps[3].stride_time_s) and math.isnan(steps[4].stride_time_s)
    table = streamed_result(steps).steps
    assert table["impossible"].tolist() == [i == 3 for i in range(len(steps))]
    assert np.isnan(table["speed_mps"].iloc[3]) and (table["speed_mps"].dropna() > 0).all()
    got, want = gait_summary(table), gait_summary(streamed_result(clean).steps)
    dur = steps[4].start_s - steps[2].end_s
    assert got["walking_time_s"] == pytest.approx(want["walking_time_s"] - dur, abs=1e-6)


# -- decision L109: a zeroed stride keeps its measured turn, so a turn through it is counted as without the guard --


@pytest.fixture(scope="module")
def turning_walk():
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    return simulate_path(parse_route("straight:8, turn:180, straight:8, turn:90, straight:6"), UserProfile.from_seed(3),
                         rate_hz=20, seed=0)


@pytest.mark.parametrize("streaming", [False, True])
def test_zeroed_stride_inside_a_turn_keeps_its_turn(turning_walk, monkeypatch, streaming):
    """The stride turning most (inside the 180 deg turn) moved 0 m by the guard: its turn_angle_rad is the foot's
    measured turn (it was NaN, and the turn count fell back to the displacement headings for the whole walk: the
    180 deg turn came out -180.5 deg offline, the 90 deg one 99.5 deg; streamed -273.3 deg)."""
    from pdrlearn.track.clinical import clinical_summary, turns

    track = get_pipeline("plasys")
    clean = track(turning_walk, streaming=streaming).steps
    own = clean["turn_angle_rad"].to_numpy(float) + (clean["pivot_rad"].to_numpy(float) if streaming else 0.0)
    i = int(np.nanargmax(np.abs(own)))
    assert np.degrees(abs(own[i])) > 90  # a stride inside the turnaround
    _break_stride(monkeypatch, streaming, i)
    got = track(turning_walk, streaming=streaming).steps
    assert got["impossible"].tolist() == [k == i for k in range(len(got))]
    assert np.isnan(got["speed_mps"].iloc[i]) and got["length_m"].iloc[i] == 0.0  # L97 unchanged
    assert got["turn_angle_rad"].iloc[i] == pytest.approx(clean["turn_angle_rad"].iloc[i], abs=1e-9)
    want = turns(clean)
    assert len(want) == 2 and abs(want[0]) > 170 and abs(want[1]) > 80
    np.testing.assert_allclose(turns(got), want, atol=1e-6)
    assert clinical_summary(got)["turn_count"] == clinical_summary(clean)["turn_count"] == 2


def test_the_warning_blames_the_input_for_a_stride_without_rest():
    """Decision B132 (session 21's responder trial, finding 7): a crawl's 40.6 s "stride" (no rest of the foot inside)
    is non-walking input, not a bug; a stride of walking length that fast may be a sensor fault or a bug."""
    long = SK.impossible_stride_warning(1, 84.6, 125.21, -1146.66, 245.79)  # the trial's crawl (walks/crawl)
    assert "not a bug (decision B132)" in long and "did not rest for 40.6 s" in long and "report" not in long
    assert "decision L94, L97" in long and "moved 0 m" in long
    short = SK.impossible_stride_warning(1, 4.87, 5.70, 2.4e30, 0.0)
    assert "bug in pdrlearn" in short and "please report it" in short and "accelerometer fault" in short
