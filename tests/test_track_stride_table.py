"""The foot pipeline's strides table (session 15 trial findings 2, 3, 6; decisions L65-L67,
docs/decisions/localization.md): no negative length without a backward class, the gait columns, one row of
0 m for the strides dropped at a foot gap."""

from __future__ import annotations

import logging
import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.io.session import Stream

REAL = Path(__file__).resolve().parents[1] / "datasets" / "real"
EXTERNAL = Path(__file__).resolve().parents[1] / "datasets" / "external"


@pytest.fixture(autouse=True)
def _quiet():
    logging.disable(logging.WARNING)
    yield
    logging.disable(logging.NOTSET)


# -- L65: the sign of a reported stride ------------------------------------------------------------------
def test_travel_sign_gives_length_the_measured_travel_sign():
    """Decisions L65 / L654: the reported sign is the stride's measured travel (its x along the foot), not the class."""
    from pdrlearn.kernels.stride import travel_sign, travel_sign_one

    assert travel_sign_one(-1.3, 0.2, 0.4) == (1.3, 0.2 + math.pi)  # measured forward: positive, the same path
    assert travel_sign_one(-1.3, 0.2, -1.3) == (-1.3, 0.2)  # measured backward: negative, whatever the class
    assert travel_sign_one(1.3, 0.2, -1.3) == (-1.3, 0.2 + math.pi)  # L654: a class rule's + on a backward stride
    assert travel_sign_one(1.3, 0.2) == (1.3, 0.2)  # no measurement (a gap row): positive
    L, h = travel_sign(np.array([-1.0, 1.0, -0.5]), np.zeros(3), np.array([1.0, 1.0, -0.5]))
    assert L.tolist() == [1.0, 1.0, -0.5] and h.tolist() == [math.pi, 0.0, 0.0]


def _turned(monkeypatch, k: int):
    """FootDisplacement whose stride ``k`` moves the other way (its displacement turned by 180 deg in its own
    start frame): the stride of a foot that turns around within it."""
    from pdrlearn.displace import FootDisplacement

    orig = FootDisplacement.estimate

    def estimate(self, *a, **kw):
        out = orig(self, *a, **kw)
        out.disp_ = out.disp_.copy()
        out.disp_[k, :2] *= -1.0
        return out

    monkeypatch.setattr(FootDisplacement, "estimate", estimate)


def test_a_turnaround_stride_has_a_positive_length_along_its_displacement(monkeypatch):
    from pdrlearn.sim import simulate
    from pdrlearn.track import get_pipeline

    s = simulate("A", user_seed=2)
    plain = get_pipeline("plasys")(s)
    k = 6
    _turned(monkeypatch, k)
    turned = get_pipeline("plasys")(s)
    t = turned.steps
    assert t["raw_length_m"].iloc[k] < 0  # the measured x points backwards, the foot not turning: backward travel
    # decision L654 (amends L65): length_m's sign is that measured travel (a real turnaround turns: L578 keeps it +)
    assert (t["length_m"] < 0).tolist() == [i == k for i in range(len(t))] and t["direction"].isna().all()
    step = np.diff(turned.trajectory[["x", "y"]].to_numpy(), axis=0)
    step0 = np.diff(plain.trajectory[["x", "y"]].to_numpy(), axis=0)
    np.testing.assert_allclose(step[k], -step0[k], atol=1e-9)  # it goes along its (turned) displacement
    h = t["heading_rad"].to_numpy()
    np.testing.assert_allclose(step[:, 0], t["length_m"] * np.cos(h), atol=1e-9)  # the row says where it goes
    np.testing.assert_allclose(step[:, 1], t["length_m"] * np.sin(h), atol=1e-9)


def test_a_turnaround_classed_forward_goes_along_its_displacement_offline(monkeypatch):
    """L65 = the streamed L37 offline: the thesis rule makes a turnaround classed forward positive; it used to be
    placed ~180 deg the wrong way (the heading folded with the measured x)."""
    from pdrlearn.sim import simulate
    from pdrlearn.track import get_pipeline

    s = simulate("A", user_seed=2)
    k = 6
    plain = get_pipeline("plasys")(s, model="oracle")
    _turned(monkeypatch, k)
    res = get_pipeline("plasys")(s, model="oracle")
    assert res.steps["direction"].iloc[k] == "forward" and res.steps["raw_length_m"].iloc[k] < 0
    assert res.steps["length_m"].iloc[k] < 0  # decision L654: the measured travel's sign, not the class's
    step = np.diff(res.trajectory[["x", "y"]].to_numpy(), axis=0)
    step0 = np.diff(plain.trajectory[["x", "y"]].to_numpy(), axis=0)
    np.testing.assert_allclose(step[k], -step0[k], atol=1e-9)


def test_streamed_turning_strides_are_not_negative():
    """The sim C walk of user 3 has turning strides whose streamed step frame points backwards (L37)."""
    from pdrlearn.sim import simulate
    from pdrlearn.track import get_pipeline

    res = get_pipeline("plasys")(simulate("C", user_seed=3), streaming=True)
    t = res.steps
    turning = t["turn_angle_rad"].abs() >= np.radians(30.0)
    assert turning.any() and (t.loc[turning, "raw_length_m"] > 0).all()  # L692: judged at the mid-stride facing
    assert (t["length_m"] >= 0).all()
    step = np.diff(res.trajectory[["x", "y"]].to_numpy(), axis=0)
    np.testing.assert_allclose(step[:, 0], t["length_m"] * np.cos(t["heading_rad"]), atol=1e-9)


@pytest.mark.skipif(not (EXTERNAL / "gaitmap_ms_left").exists(), reason="datasets/external not linked")
def test_gaitmap_ms_turnarounds_are_not_negative():
    from pdrlearn.io import read_session
    from pdrlearn.track import get_pipeline

    t = get_pipeline("plasys")(read_session(EXTERNAL / "gaitmap_ms_left")).steps
    # the turnaround at 8.7 s (trial finding 2: length_m -1.329) read -1.3 m along its start facing; L692 signs it
    # against its mid-stride facing: forward
    turnaround = (t["turn_angle_rad"].abs() > 2.0) & (t["start_s"].between(8.0, 9.5))
    assert turnaround.sum() == 1 and (t.loc[turnaround, "raw_length_m"] > 1.0).all()
    assert t["length_m"].min() > 0.5


# -- L66: gait columns -------------------------------------------------------------------------------------
def test_stride_times_between_consecutive_strides_with_their_own_events():
    from pdrlearn.track.gait import stride_times

    st = stride_times([0.0, 1.0, 2.0, 3.5, 4.5], [1.0, 2.0, 3.0, 4.5, 5.5], [0.8, 1.9, 2.8, 4.3, 5.35],
                      valid=[True, True, True, True, True])
    assert np.isnan(st[0])  # the first stride has no previous contact
    # decision L80: a short rest before stride 3 (3.0 -> 3.5, a turn) keeps its IC-to-IC time (L66 dropped it)
    np.testing.assert_allclose(st[1:], [1.1, 0.9, 1.5, 1.05])
    # a stop: contacts more than 3 s apart (Mobilise-D's longest stride) give none; an invalid row none
    st = stride_times([0.0, 1.0, 5.0, 6.0], [1.0, 2.0, 6.0, 7.0], [0.8, 1.8, 5.8, 6.8], valid=[1, 1, 1, 0])
    assert np.isnan(st[2]) and np.isnan(st[3]) and st[1] == pytest.approx(1.0)
    st = stride_times([0.0, 0.9], [1.0, 2.0], [0.5, 1.6])  # overlapping windows: not the next stride
    assert np.isnan(st).all()
    st = stride_times([0.0, 1.0, 2.0], [1.0, 2.0, 3.0], [0.8, 2.5, 2.8])  # the 2nd event outside its stride
    assert np.isnan(st).all()


def test_gait_columns_against_the_level_walk_mocap():
    """gaitmap level walk (right foot, mocap ICs): the IC-to-IC stride time and the speed per stride."""
    from pdrlearn.io import read_session
    from pdrlearn.track import get_pipeline
    from pdrlearn.track.evaluate import evaluate_track
    from pdrlearn.track.gait import GAIT_COLUMNS

    s = read_session(REAL / "gaitmap_level_right")
    res = get_pipeline("plasys")(s)
    t, ref = res.steps, s.steps
    assert set(GAIT_COLUMNS) <= set(t.columns)
    ev = t["event_s"].to_numpy(float)
    j = np.array([np.argmin(np.abs(ev - x)) for x in ref["ic_s"]])
    ok = np.abs(ev[j] - ref["ic_s"].to_numpy(float)) < 0.15
    r_st = (ref["ic_s"] - ref["pre_ic_s"]).to_numpy(float)
    err = t["stride_time_s"].to_numpy(float)[j][ok] - r_st[ok]
    assert ok.sum() >= 25 and np.isfinite(err).all()
    assert np.std(err) < 0.03 and np.abs(err).max() < 0.1  # measured SD 14.4 ms, max 53.7 ms (L66)
    v_err = t["speed_mps"].to_numpy(float)[j][ok] - (ref["length_m"].to_numpy(float) / r_st)[ok]
    assert abs(np.mean(v_err)) < 0.05 and np.abs(v_err).max() < 0.2
    np.testing.assert_allclose(t["cadence_spm"], 120.0 / t["stride_time_s"])
    assert np.isnan(t["stride_time_s"].iloc[0])  # a bout start has no previous contact
    turn = t["turn_angle_rad"].to_numpy(float)
    assert np.all(np.abs(turn) <= math.pi) and np.abs(turn).max() > 1.0 and np.median(np.abs(turn)) < 0.1
    summary = evaluate_track(res, s)
    assert summary["median_stride_time_s"] == pytest.approx(np.nanmedian(t["stride_time_s"]))
    assert 100 < summary["median_cadence_spm"] < 120 and 1.0 < summary["median_speed_mps"] < 1.5


# -- L67: a stride across a foot gap -----------------------------------------------------------------------
def _cut(s, t0: float, t1: float):
    for name in [n for n in s.streams if n.startswith("f")]:
        x = s.streams[name]
        keep = (x.t < t0) | (x.t >= t1)
        s.streams[name] = Stream(name, x.t[keep], x.values[keep])
    return s


def test_the_strides_across_a_foot_gap_are_one_row_of_zero_metres():
    from pdrlearn.io import read_session
    from pdrlearn.track import get_pipeline

    full = get_pipeline("plasys")(read_session(REAL / "gaitmap_level_right"))
    res = get_pipeline("plasys")(_cut(read_session(REAL / "gaitmap_level_right"), 10.0, 11.5))
    t = res.steps
    gap = t[t["gap_s"] > 0]
    assert len(gap) == 1 and gap["length_m"].iloc[0] == 0 and gap["dz_m"].iloc[0] == 0
    assert gap["start_s"].iloc[0] < 10.0 and gap["end_s"].iloc[0] > 11.5 and gap["gap_s"].iloc[0] > 1.0
    assert np.isnan(gap["stride_time_s"].iloc[0]) and np.isnan(gap["turn_angle_rad"].iloc[0])
    i = int(gap.index[0])
    assert np.isnan(t["stride_time_s"].iloc[i + 1])  # no IC-to-IC across the gap
    assert (t["gap_s"].drop(index=i) == 0).all() and len(t) < len(full.steps)
    assert t["start_s"].is_monotonic_increasing and len(res.trajectory) == len(t) + 1
    xy = res.trajectory[["x", "y"]].to_numpy()
    np.testing.assert_array_equal(xy[i + 1], xy[i])  # the row moves 0 m
    assert any("one row of 0 m with its gap_s" in w for w in res.info["warnings"])
    pd.testing.assert_series_equal(t["length_m"].drop(index=i).reset_index(drop=True),
                                   t.loc[t["gap_s"] == 0, "length_m"].reset_index(drop=True))


def test_the_streamed_track_marks_its_gap_row_as_run_does():
    from pdrlearn.io import read_session
    from pdrlearn.track import get_pipeline

    t = get_pipeline("plasys")(_cut(read_session(REAL / "gaitmap_level_right"), 10.0, 11.5), streaming=True).steps
    gap = t[t["gap_s"] > 0]
    assert len(gap) == 1 and gap["length_m"].iloc[0] == 0 and gap["gap_s"].iloc[0] > 1.0
    assert list(t.columns[-2:]) == ["gap_s", "unit"]


def test_a_gap_row_is_not_scored_as_a_stride_estimate():
    """E30 / L67: the 0 m row across a foot gap is no estimate of the labelled stride it overlaps; the stride
    length scores (offline and --streaming alike) leave it out."""
    from pdrlearn.io import read_session
    from pdrlearn.track import get_pipeline
    from pdrlearn.track.evaluate import evaluate_track, match_by_overlap

    s = _cut(read_session(REAL / "gaitmap_level_right"), 20.0, 21.3)
    ref = s.steps[s.steps["length_m"].notna()].reset_index(drop=True)
    for streaming in (False, True):
        res = get_pipeline("plasys")(s, streaming=streaming)
        t = res.steps
        pairs = match_by_overlap(t, ref)
        assert any(t["gap_s"].iloc[i] > 0 for i, _ in pairs)  # the gap row overlaps a labelled stride
        kept = [(i, j) for i, j in pairs if t["gap_s"].iloc[i] == 0]
        err = [abs(abs(t["length_m"].iloc[i]) - abs(ref["length_m"].iloc[j])) / abs(ref["length_m"].iloc[j])
               for i, j in kept]
        out = evaluate_track(res, s)
        assert out["stride_length_composed"] == 0 and out["stride_length_matched"] == len(kept)
        assert out["stride_length_mae_pct"] == pytest.approx(100.0 * np.mean(err))
