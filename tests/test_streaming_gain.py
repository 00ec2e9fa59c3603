"""The streamed stride kernel's own distance gain (docs/decisions/localization.md L41): estimated from the
calibration exercises with ``track --streaming``'s kernel, stored beside the offline gain in the model and
the bundle, applied by ``track --streaming`` and the runtime; offline M3 keeps the offline gain."""

from __future__ import annotations

import copy
import json
import shutil

import numpy as np
import pytest

from pdrlearn.displace import calibrate_distance, calibrate_streaming, streaming_calibration
from pdrlearn.runtime import Tracker
from pdrlearn.runtime.bundle import MANIFEST_SHA, sha256_file
from pdrlearn.sim import simulate
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.plasys import _distance_gain, track_plasys
from tests.runtime_helpers import calibrated_length_model, replay, scaled_foot_acc


@pytest.fixture(scope="module")
def exercises():
    """User 2's calibration exercises at three speeds (the experiments' calibration, S22 unit)."""
    return [simulate(ex, user_seed=2, speed=sp) for sp in ("slow", "normal", "fast")
            for ex in ("terrain", "direction", "length")]


@pytest.fixture(scope="module")
def calibrated(tmp_path_factory):
    return calibrated_length_model(tmp_path_factory.mktemp("streamgain"))


def test_streaming_record_beside_an_unchanged_offline_record(exercises):
    rec = calibrate_distance(exercises)
    old = calibrate_distance(exercises, streaming=False)
    assert "streaming" not in old
    assert {k: v for k, v in rec.items() if k != "streaming"} == old  # offline: bit for bit as before L41
    st = rec["streaming"]
    assert st["reason"] is None and st["n_strides"] >= 200 and "streaming" in st["engine"]
    assert st["rate_hz"] == pytest.approx(20.0) and not st["sessions_skipped"]
    assert st == calibrate_streaming(exercises)
    # the streamed kernel measures longer strides than the offline engine (L40: +0.8 % on the simulator)
    assert st["gain"] < rec["gain"] - 0.002


def test_streaming_gain_recovers_an_injected_accelerometer_scale_error():
    ex = simulate("length", user_seed=2, speed="normal", noise=False)
    base = calibrate_streaming([ex])
    scaled = calibrate_streaming([scaled_foot_acc(ex, 1.01)])
    assert base["reason"] is None and base["n_strides"] >= 40
    assert scaled["gain"] * 1.01 == pytest.approx(base["gain"], abs=0.001)


def test_streamed_tracking_takes_the_streaming_record_and_older_records_keep_the_offline_gain():
    class _Model:
        def __init__(self, rec):
            self.data_summary = {"distance_calibration": rec}

    sub = {"gain": 0.992, "stride_sd": 0.008, "reason": None, "rate_hz": 20.0}
    rec = {"gain": 1.004, "rate_hz": 20.0, "stride_sd": 0.006, "reason": None, "streaming": sub}
    w: list[str] = []
    assert _distance_gain(None, _Model(rec), 20.0, w) == (1.004, "model", 0.006)  # offline
    assert _distance_gain(None, _Model(rec), 20.0, w, streaming=True) == (0.992, "model", 0.008)
    old = {k: v for k, v in rec.items() if k != "streaming"}
    assert streaming_calibration(old) is old and streaming_calibration(None) is None
    assert _distance_gain(None, _Model(old), 20.0, w, streaming=True) == (1.004, "model", 0.006)
    # the rate check is the record's (one rate per record, as the bundle carries one)
    g, _, sd = _distance_gain(None, _Model(rec), 100.0, w, streaming=True)
    assert (g, sd) == (1.0, None) and "recalibrate" in w[-1]
    # a refused streamed estimate applies gain 1 and no sd, as a refused offline one
    refused = {**rec, "streaming": {**sub, "gain": 1.0, "reason": "5 usable strides (< 10)"}}
    assert _distance_gain(None, _Model(refused), 20.0, w, streaming=True) == (1.0, "model", None)


def test_streamed_walk_is_measured_as_long_as_the_reference_with_the_streaming_gain(exercises):
    """L40's finding: with the offline gain, streamed strides came out ~0.8 % long. User 2's own scenario A
    (same S22 unit), every class gated out (the measured strides and the gain only): the streaming gain
    removes the bias."""
    from pdrlearn.classify import train_user

    model = train_user(exercises[2::3], tasks=["length"], methods=["svm"], units=["foot"], cv=2)
    rec = calibrate_distance(exercises)
    model.data_summary["distance_calibration"] = rec
    older = copy.copy(model)
    older.data_summary = {"distance_calibration": {k: v for k, v in rec.items() if k != "streaming"}}
    errs = {}
    for speed in ("slow", "normal", "fast"):
        s = simulate("A", user_seed=2, speed=speed)
        new = track_plasys(s, method="M3", model=model, streaming=True, rules="bayes", min_confidence=1.0)
        old = track_plasys(s, method="M3", model=older, streaming=True, rules="bayes", min_confidence=1.0)
        assert new.info["distance_gain"] == pytest.approx(rec["streaming"]["gain"])
        assert old.info["distance_gain"] == pytest.approx(rec["gain"])
        errs[speed] = (evaluate_track(new, s)["distance_error_pct"], evaluate_track(old, s)["distance_error_pct"])
    new_mean = np.mean([v[0] for v in errs.values()])
    old_mean = np.mean([v[1] for v in errs.values()])
    assert old_mean > 0.3, errs  # the bias of the offline gain on the streamed kernel
    assert abs(new_mean) < 0.5 * old_mean, errs


def test_bundle_carries_both_gains_and_the_runtime_streams_with_the_streaming_one(calibrated, tmp_path):
    root, model, s = calibrated
    rec = model.data_summary["distance_calibration"]
    disp = json.loads((root / "bundle" / "manifest.json").read_text())["displacement"]
    assert disp["distance_gain"] == pytest.approx(rec["gain"])  # the offline record stays (older runtimes)
    assert disp["streaming_distance_gain"] == pytest.approx(rec["streaming"]["gain"])
    assert disp["streaming_stride_sigma_rel"] == pytest.approx(rec["streaming"]["stride_sd"])
    assert disp["streaming_distance_calibration_reason"] is None
    assert rec["streaming"]["gain"] != pytest.approx(rec["gain"], abs=1e-4)
    res = track_plasys(s, method="M3", model=str(root / "model"), streaming=True, heading="foot")
    tr = Tracker(root / "bundle", heading_source="foot")
    steps = replay(tr, s, 0.5)
    assert tr.distance_gain == pytest.approx(rec["streaming"]["gain"]) == res.info["distance_gain"]
    assert tr.stride_sd == pytest.approx(rec["streaming"]["stride_sd"])
    xyz = np.array([[st.x, st.y, st.z] for st in steps])
    assert len(steps) == len(res.steps) and np.abs(xyz - res.trajectory[["x", "y", "z"]].to_numpy()[1:]).max() < 1e-3
    # a bundle exported before L41 (no streaming_* fields) streams with its offline gain, as before
    old = tmp_path / "old_bundle"
    shutil.copytree(root / "bundle", old)
    m = json.loads((old / "manifest.json").read_text())
    for k in ("streaming_distance_gain", "streaming_stride_sigma_rel", "streaming_distance_calibration_reason"):
        del m["displacement"][k]
    (old / "manifest.json").write_text(json.dumps(m))
    (old / MANIFEST_SHA).write_text(f"{sha256_file(old / 'manifest.json')}  manifest.json\n")
    tr_old = Tracker(old, heading_source="foot")
    replay(tr_old, s, 0.5)
    assert tr_old.distance_gain == pytest.approx(rec["gain"]) and tr_old.stride_sd == pytest.approx(rec["stride_sd"])


def test_an_explicit_gain_at_export_overrides_both_gains(calibrated, tmp_path):
    """E14: ``export_model(displacement={"distance_gain": g})`` overrides the model's calibration; since L41
    the runtime would take the model's streamed gain first, so the explicit gain drops it."""
    from pdrlearn.export.from_model import export_model

    root, model, s = calibrated
    export_model(None, tmp_path / "b", model=model, displacement={"distance_gain": 1.02})
    disp = json.loads((tmp_path / "b" / "manifest.json").read_text())["displacement"]
    assert disp["distance_gain"] == 1.02 and "streaming_distance_gain" not in disp
    tr = Tracker(tmp_path / "b", heading_source="foot")
    replay(tr, s, 0.5)
    assert tr.distance_gain == 1.02


def test_a_model_calibrated_before_l41_streams_with_the_thesis_rule_and_says_why(calibrated, tmp_path, caplog):
    """L41: the adopted streamed default is the pair (bayes + the streamed gain); with only the offline gain
    (a model trained before L41) the bayes rule was measured worse than thesis on C and D, so such a model
    keeps the thesis rule streamed (track --streaming and its export), with a warning to retrain."""
    import logging

    from pdrlearn.displace import PRE_L41_CALIBRATION
    from pdrlearn.export.from_model import export_model

    root, model, s = calibrated
    older = copy.copy(model)
    older.data_summary = copy.deepcopy(model.data_summary)
    del older.data_summary["distance_calibration"]["streaming"]
    res = track_plasys(s, method="M3", model=older, streaming=True, heading="foot")
    assert (res.info["rules"], res.info["min_confidence"]) == ("thesis", 0.0)
    assert PRE_L41_CALIBRATION in res.info["warnings"]
    assert res.info["distance_gain"] == pytest.approx(model.data_summary["distance_calibration"]["gain"])
    new = track_plasys(s, method="M3", model=model, streaming=True, heading="foot")
    assert new.info["rules"] == "bayes" and PRE_L41_CALIBRATION not in new.info["warnings"]
    asked = track_plasys(s, method="M3", model=older, streaming=True, heading="foot", rules="bayes")
    assert asked.info["rules"] == "bayes"  # asked for: applied
    with caplog.at_level(logging.WARNING):
        export_model(None, tmp_path / "b", model=older)
    assert any("predates decision L41" in r.getMessage() for r in caplog.records)
    disp = json.loads((tmp_path / "b" / "manifest.json").read_text())["displacement"]
    assert (disp["rules"], disp["min_confidence"]) == ("thesis", 0.0) and "streaming_distance_gain" not in disp
    tr = Tracker(tmp_path / "b", heading_source="foot")
    steps = replay(tr, s, 0.5)
    assert (tr.rules, tr.min_confidence) == ("thesis", 0.0)
    xyz = np.array([[st.x, st.y, st.z] for st in steps])
    assert np.abs(xyz - res.trajectory[["x", "y", "z"]].to_numpy()[1:]).max() < 1e-3
