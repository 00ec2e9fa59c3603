"""Trajectory parity (issue 7): ``Tracker`` streaming a session reproduces ``track_plasys(streaming=True)``
within 1 mm at every step, because both run the stride kernel :mod:`pdrlearn.kernels.stride`."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.kernels import stride as SK
from pdrlearn.orient import wrap_angle
from pdrlearn.runtime.tracker import Tracker
from pdrlearn.track.base import get_pipeline
from tests.runtime_helpers import calibrated_length_model, replay, rest_dirs, synthetic_session, trained_dirs


@pytest.fixture(scope="module")
def trained(tmp_path_factory):
    return trained_dirs(tmp_path_factory)["root"]


def _stream(tr: Tracker, session, chunk_s: float = 0.37) -> list:
    return replay(tr, session, chunk_s)


@pytest.mark.parametrize("heading", ["foot", "auto"])
def test_streamed_trajectory_equals_streaming_track_within_1mm(trained, heading):
    s = synthetic_session(24, seed=11, name="parity", turn_rad_per_step=0.3)
    res = get_pipeline("plasys")(s, method="M3", model=str(trained / "model"), streaming=True, heading=heading)
    steps = _stream(Tracker(trained / "bundle", heading_source=heading), s)
    assert len(steps) == len(res.steps) >= 20
    np.testing.assert_allclose([st.start_s for st in steps], res.steps["start_s"], atol=1e-12)
    np.testing.assert_allclose([st.end_s for st in steps], res.steps["end_s"], atol=1e-12)
    for task, col in (("terrain", "terrain"), ("direction", "direction"), ("length", "length_class")):
        assert [st.classes[task] for st in steps] == list(res.steps[col])
    got = np.array([[st.x, st.y, st.z] for st in steps])
    want = res.trajectory[["x", "y", "z"]].to_numpy()[1:]
    assert np.abs(got - want).max() < 1e-3  # issue 7: within 1 mm at every step
    np.testing.assert_allclose([st.length_m for st in steps], res.steps["length_m"], atol=1e-6)
    # equal modulo 2 pi: a stride reversed by L37 jumps by pi, which np.unwrap may take either way
    dh = np.array([st.heading_rad for st in steps]) - res.steps["heading_rad"].to_numpy(float)
    np.testing.assert_allclose(wrap_angle(dh), 0.0, atol=1e-9)
    # the walk turns (0.3 rad per stride of yaw rate in the synthetic sensor frame), so the heading matters
    assert np.median(np.diff([st.heading_rad for st in steps])) > 0.1


def test_rest_boundary_model_tracks_like_streaming_track(tmp_path_factory):
    """A model on rest-to-rest windows (decision 13): the runtime classifies rest-cut windows like
    predict_steps, the displacement stays stance to stance, so the trajectory still matches within 1 mm."""
    root = rest_dirs(tmp_path_factory)["rest_root"]
    s = synthetic_session(24, seed=11, name="parity", turn_rad_per_step=0.3)
    for name in ("wAccelerometer", "wGyroscope", "wBarometer"):
        del s.streams[name]
    res = get_pipeline("plasys")(s, method="M3", model=str(root / "model"), streaming=True, heading="foot")
    tr = Tracker(root / "bundle", heading_source="foot")
    assert tr.boundaries == "rest"
    steps = _stream(tr, s)
    assert len(steps) == len(res.steps) >= 20
    np.testing.assert_allclose([st.start_s for st in steps], res.steps["start_s"], atol=1e-12)
    for task, col in (("terrain", "terrain"), ("direction", "direction"), ("length", "length_class")):
        assert [st.classes[task] for st in steps] == list(res.steps[col])
    got = np.array([[st.x, st.y, st.z] for st in steps])
    assert np.abs(got - res.trajectory[["x", "y", "z"]].to_numpy()[1:]).max() < 1e-3


def test_streaming_track_rejects_session_wide_options(trained):
    s = synthetic_session(6, seed=2)
    fn = get_pipeline("plasys")
    with pytest.raises(DataError, match="not streamable"):
        fn(s, method="M1", streaming=True)
    with pytest.raises(DataError, match="waist/fused headings"):
        fn(s, method="M2", streaming=True, heading="fused")
    with pytest.raises(DataError, match="not streamable"):
        fn(s, method="M3", model="oracle", streaming=True, steps="labels")
    with pytest.raises(DataError, match="rules 'banana' is not one of thesis, bayes"):  # decision L40
        fn(s, method="M3", model="oracle", streaming=True, rules="banana")


def test_stride_rules_kernel():
    disp = np.array([[0.6, 0.8, 0.3], [-0.3, 0.4, -0.2], [1.2, 0.0, 0.0], [0.5, 0.0, 0.1]])
    bounds = {"short": (0.0, 0.6), "normal": (0.6, 0.9), "long": (0.92, 20.0)}
    length, dz = SK.apply_stride_rules(disp, ["up", "down", "flat", None], ["forward", None, "backward", None],
                                       ["long", "normal", "normal", None], bounds=bounds, down_mode="norm3")
    # (down_mode "norm3": the thesis' placement of the norm; the default "projected" since L178)
    # up: horizontal 1.0 inside long; down: 3-axis norm 0.539 (eq. 61) with the estimate's sign, clamped up
    # to normal's 0.6; backward prevails over the estimate and 1.2 is clamped to normal's 0.9; no class: raw
    np.testing.assert_allclose(length, [1.0, -0.6, -0.9, 0.5])
    np.testing.assert_allclose(dz, [0.3, -0.2, 0.0, 0.1])  # stairs |dz|, flat 0, unknown terrain: estimate


def test_one_stride_rules_equal_the_array_path():
    """The runtime's one-stride call (Python scalars) gives the array path's bits for every combination of
    classes (incl. missing and unknown ones), bounds and down mode."""
    import itertools

    rng = np.random.default_rng(3)
    bounds = {"short": (0.0, 0.6), "normal": (0.6, 0.9), "long": (0.92, 20.0)}
    for te, di, lc, b, dm in itertools.product(["flat", "up", "down", None, "", float("nan")],
                                               ["forward", "backward", "left", None],
                                               ["short", "normal", "long", "huge", None], [bounds, None],
                                               ["norm3", "projected", "horizontal"]):  # L51
        d = rng.normal(size=3) * [1.0, 0.3, 0.2]
        one = SK.apply_stride_rules(d, [te], [di], [lc], bounds=b, down_mode=dm)
        two = SK.apply_stride_rules(np.vstack([d, d]), [te, te], [di, di], [lc, lc], bounds=b, down_mode=dm)
        assert one[0].shape == one[1].shape == (1,)
        assert (one[0][0], one[1][0]) == (two[0][0], two[1][0]), (te, di, lc, b, dm)

def test_zupt_displacement_of_a_known_stride():
    """A stride with acceleration a(t) = A sin(2 pi t / T) forward, starting and ending at rest, moves
    A T^2 / (2 pi) (exact); a constant accelerometer bias is removed by the ZUPT."""
    T, A = 1.0, 3.0
    t = np.linspace(0.0, T, 205)
    acc = np.zeros((len(t), 3))
    acc[:, 0] = A * np.sin(2 * np.pi * t / T) + 0.2  # + bias 0.2 m/s^2
    d = SK.zupt_displacement(t, acc)
    assert d[0] == pytest.approx(A * T**2 / (2 * np.pi), rel=1e-3)
    assert abs(d[1]) < 1e-12 and abs(d[2]) < 1e-12


def test_segmenter_is_chunk_invariant():
    rng = np.random.default_rng(0)
    t = np.arange(0, 20, 0.01)
    moving = (np.sin(2 * np.pi * t) > -0.3)
    gyr = rng.normal(scale=0.05, size=(len(t), 3)) + moving[:, None] * 3.0
    whole = SK.stance_strides(t, gyr)
    seg = SK.StanceSegmenter()
    parts = []
    for i in range(0, len(t), 37):
        parts += seg.update(t[i:i + 37], gyr[i:i + 37])
    assert len(whole) >= 15
    np.testing.assert_array_equal(np.array(parts), whole)


def test_yaw_change_of_consecutive_strides_adds_up():
    """Strides share their boundary: the heading changes of [t0, tb] and [tb, t1] (each cut from samples
    that reach one sample beyond its ends) sum to the change over [t0, t1]."""
    t = np.arange(0.0, 3.0, 0.05)
    rate = np.sin(t) + 0.5
    whole = SK.yaw_change(t, rate, 0.52, 2.47)
    parts = SK.yaw_change(t[8:31], rate[8:31], 0.52, 1.43) + SK.yaw_change(t[28:51], rate[28:51], 1.43, 2.47)
    assert parts == pytest.approx(whole, abs=1e-12)
    assert whole == pytest.approx((np.cos(0.52) - np.cos(2.47)) + 0.5 * 1.95, abs=2e-3)


# -- per-user distance calibration (decisions L26 / E14) ------------------------------------------------
@pytest.fixture(scope="module")
def calibrated(tmp_path_factory):
    """A model trained on a simulated calibration exercise with distance_calibration=True, its bundle, and
    a simulated scenario walk of the same user (same unit: S22 per-device scale errors)."""
    return calibrated_length_model(tmp_path_factory.mktemp("calibrated"))


def _stream_sim(tr: Tracker, session) -> list:
    return replay(tr, session, 0.5)  # 0.5 s = 10 whole samples at 20 Hz: no sample on a chunk edge twice


def _xyz(steps) -> np.ndarray:
    return np.array([[st.x, st.y, st.z] for st in steps])


def test_calibrated_bundle_streams_like_calibrated_streaming_track(calibrated):
    import json

    root, model, s = calibrated
    rec = model.data_summary["distance_calibration"]
    assert rec["reason"] is None and rec["gain"] != 1.0
    disp = json.loads((root / "bundle" / "manifest.json").read_text())["displacement"]
    assert disp["distance_gain"] == pytest.approx(rec["gain"])
    assert disp["distance_gain_rate_hz"] == pytest.approx(rec["rate_hz"])
    assert disp["stride_sigma_rel"] == pytest.approx(rec["stride_sd"])
    res = get_pipeline("plasys")(s, method="M3", model=str(root / "model"), streaming=True, heading="foot")
    st = rec["streaming"]  # decision L41: streamed, the stride kernel's own gain and sd
    assert res.info["distance_gain"] == pytest.approx(st["gain"]) and res.info["distance_gain_source"] == "model"
    tr = Tracker(root / "bundle", heading_source="foot")
    steps = _stream_sim(tr, s)
    assert tr.distance_gain == pytest.approx(st["gain"]) and tr.stride_sd == pytest.approx(st["stride_sd"])
    assert len(steps) == len(res.steps) >= 10
    assert [st.classes["length"] for st in steps] == list(res.steps["length_class"])
    for c in model.tasks["length"].classes:
        np.testing.assert_allclose([st.proba["length"][c] for st in steps], res.steps[f"p_length_{c}"], atol=1e-5)
    want = res.trajectory[["x", "y", "z"]].to_numpy()[1:]
    assert np.abs(_xyz(steps) - want).max() < 1e-3  # issue 7: within 1 mm at every step
    # the gain moved the walk (so the parity above is not the uncalibrated one)
    off = get_pipeline("plasys")(s, method="M3", model=str(root / "model"), streaming=True, heading="foot",
                                 calibration=False)
    assert off.info["distance_gain"] == 1.0
    assert np.abs(off.trajectory[["x", "y"]].to_numpy() - res.trajectory[["x", "y"]].to_numpy()).max() > 5e-3


def test_bundle_without_calibration_fields_runs_with_gain_one(calibrated, tmp_path):
    """A bundle exported before E14 (no distance_* fields) tracks like ``calibration=False``."""
    import json
    import shutil

    root, _, s = calibrated
    old = tmp_path / "old_bundle"
    shutil.copytree(root / "bundle", old)
    m = json.loads((old / "manifest.json").read_text())
    for k in ("distance_gain", "distance_gain_rate_hz", "stride_sigma_rel", "distance_calibration_reason",
              "streaming_distance_gain", "streaming_stride_sigma_rel", "streaming_distance_calibration_reason"):
        del m["displacement"][k]
    (old / "manifest.json").write_text(json.dumps(m))
    from pdrlearn.runtime.bundle import MANIFEST_SHA, sha256_file

    (old / MANIFEST_SHA).write_text(f"{sha256_file(old / 'manifest.json')}  manifest.json\n")  # as re-written
    tr = Tracker(old, heading_source="foot")
    steps = _stream_sim(tr, s)
    # E215's line (the streamed foot-only heading's 0 is the unit's facing, when the first walk heads 10 deg or more
    # from it) is the simulated walk's, not the old bundle's
    assert tr.distance_gain == 1.0 and tr.stride_sd is None and not [w for w in tr.warnings if "E215" not in w]
    off = get_pipeline("plasys")(s, method="M3", model=str(root / "model"), streaming=True, heading="foot",
                                 calibration=False)
    assert np.abs(_xyz(steps) - off.trajectory[["x", "y", "z"]].to_numpy()[1:]).max() < 1e-3


def test_calibration_at_another_rate_warns_and_is_skipped_in_track_and_runtime(calibrated, tmp_path, caplog):
    import copy
    import logging

    from pdrlearn.export.from_model import export_model

    _, model, s = calibrated
    other = copy.copy(model)
    other.data_summary = copy.deepcopy(model.data_summary)
    other.data_summary["distance_calibration"]["rate_hz"] = 100.0  # calibrated on a 100 Hz unit
    export_model(None, tmp_path / "b100", model=other)
    fn = get_pipeline("plasys")
    with caplog.at_level(logging.WARNING):
        stream_res = fn(s, method="M3", model=other, streaming=True, heading="foot")
        offline = fn(s, method="M3", model=other)
        tr = Tracker(tmp_path / "b100", heading_source="foot")
        steps = _stream_sim(tr, s)
    msg = "distance calibration was made at 100 Hz, the foot unit runs at 20 Hz: not applied"
    for info in (stream_res.info, offline.info):
        assert info["distance_gain"] == 1.0 and any(msg in w for w in info["warnings"])
    assert offline.info["stride_sigma_rel"] == 0.03  # the bayes rule keeps the default spread
    assert tr.distance_gain == 1.0 and tr.stride_sd is None and any(msg in w for w in tr.warnings)
    assert sum(msg in r.getMessage() for r in caplog.records) >= 3
    assert np.abs(_xyz(steps) - stream_res.trajectory[["x", "y", "z"]].to_numpy()[1:]).max() < 1e-3


def test_level_gain_kernel_touches_level_strides_only():
    from pdrlearn.kernels.distance import applicable_calibration, apply_level_gain, calibrated_stride_sd

    disp = np.array([[1.0, 0.2, 0.05], [0.8, 0.1, 0.3], [-0.5, 0.0, -0.09]])
    out = apply_level_gain(disp, 1.02)
    np.testing.assert_allclose(out, [[1.02, 0.204, 0.05], [0.8, 0.1, 0.3], [-0.51, 0.0, -0.09]])
    assert out is not disp and disp[0, 0] == 1.0  # a new array
    one = apply_level_gain(disp[0], 1.02)  # the runtime's one stride: the same bits
    assert one.shape == (3,) and (one == out[0]).all()
    rec = {"gain": 1.01, "rate_hz": 20.0, "stride_sd": 0.006, "reason": None}
    assert applicable_calibration(rec, 20.1) == (rec, None)  # within 1 %
    none, warning = applicable_calibration(rec, 20.5)
    assert none is None and "20 Hz" in warning and "20.5 Hz" in warning
    # decision B135: resampled from a lower rate lost something; from a higher one nothing (the gain is still
    # judged at the recording's rate, B113)
    _, low = applicable_calibration({**rec, "rate_hz": 100.0}, 40.0, resampled_hz=100.0)  # B465: 40 Hz, under 50
    assert "(resampled to 100 Hz, which does not restore what the recording rate lost)" in low
    _, high = applicable_calibration(rec, 40.0, resampled_hz=20.0)  # B465: under 50 Hz the rate matters
    assert "was recorded at 40 Hz (resampled to 20 Hz; the gain is judged at the recording's rate, decision " \
           "B113): not applied" in high and "recalibrate on a walk recorded at 40 Hz" in high and "restore" not in high
    assert calibrated_stride_sd(rec) == 0.006 and calibrated_stride_sd({**rec, "reason": "few"}) is None


def test_m3_says_which_rules_a_partial_model_cannot_apply(calibrated):
    # a length-only model: M3 runs, and says the terrain and direction rules are off (no silent half-M3)
    root, _, s = calibrated
    res = get_pipeline("plasys")(s, method="M3", model=str(root / "model"), heading="foot")
    said = " ".join(res.info["warnings"])
    assert "classifies no terrain, direction (" in said  # one line for both (decision C17)


def test_resampled_data_says_why_the_calibration_does_not_apply(calibrated):
    """New-user trial: `run --resample` said "resampling to 20 Hz" and then "the foot unit runs at 50 Hz: not
    applied" -- both true (E22 judges the calibration at the recording's rate) but it read as a contradiction."""
    from pdrlearn.sim import simulate

    root, _, _ = calibrated
    s50 = simulate("A", user_seed=2, speed="normal", rate_hz=50.0)
    tr = Tracker(root / "bundle", heading_source="foot", resample=True)
    replay(tr, s50, 0.5)
    (w,) = [w for w in tr.warnings if "distance calibration" in w]
    assert "was recorded at 50 Hz (resampled to 20 Hz; the gain is judged at the recording's rate, decision " \
           "B113): not applied" in w, w  # 50 -> 20 Hz lost nothing the 50 Hz had (B135)
    assert tr.distance_gain == 1.0 and "runs at" not in w
    native = Tracker(root / "bundle", heading_source="foot")  # tracked at 50 Hz: the plain wording
    replay(native, s50, 0.5)
    assert any("the foot unit runs at 50 Hz: not applied" in w for w in native.warnings)
