"""`waist-ic` step detector: the waist-pendulum pipeline's IC detector behind the steps interface
(docs/decisions/steps.md decision 17)."""

from __future__ import annotations

import json
import shutil

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pdrlearn.cli import main
from pdrlearn.errors import DataError, MissingSensorError
from pdrlearn.io import read_session
from pdrlearn.steps import DETECTORS, STEPS_COLUMNS, get_detector, score_steps
from pdrlearn.steps.waist_ic import WaistICStepDetector
from pdrlearn.track.waist import MAX_STEP_S, track_waist
from pdrlearn.waist.ahrs import MADGWICK_GAIN, waist_imu
from pdrlearn.waist.events import WALK_THRESHOLD_MPS2, InitialContactDetector
from tests.steps_helpers import chunked

_CACHE: dict = {}


def _test5(mobgap_test5):
    if "s" not in _CACHE:
        s = read_session(mobgap_test5)
        det = get_detector("waist-ic")
        _CACHE["s"] = (s, det, det.detect(s), det._inputs(s))
    return _CACHE["s"]


def test_registered_with_the_pipeline_defaults():
    assert DETECTORS["waist-ic"] is WaistICStepDetector
    det = get_detector("waist-ic")
    # decision steps 35: None = track's gate (W4's 0.5, lowered by W76 for a session whose trunk moves little)
    assert det.walk_threshold is None and det.ic_detector().walk_threshold == WALK_THRESHOLD_MPS2
    assert det.max_step_s == MAX_STEP_S
    assert det.ahrs_gain == MADGWICK_GAIN


@pytest.mark.parametrize("name", ["mobgap_HA001_Test5_Trial1", "mobgap_HA001_Test11_Trial1"])
def test_offline_equals_track_waist_pendulum_contacts(real_dir, name):
    s = read_session(real_dir / name)
    steps = get_detector("waist-ic").detect(s)
    assert list(steps.columns[:5]) == list(STEPS_COLUMNS) and (steps["unit"] == "waist").all()
    tr = track_waist(s, pipeline="waist-pendulum", sit_veto=False,  # the veto is the track's (W185), not the detector's
                     stand_veto=False)  # W199's stand veto too
    np.testing.assert_array_equal(steps["event_s"].to_numpy(), tr.steps["event_s"].to_numpy())
    np.testing.assert_array_equal(steps["end_s"].to_numpy(), tr.steps["end_s"].to_numpy())
    # and the IC detector itself on the AHRS data, with its defaults
    ic = InitialContactDetector().detect(waist_imu(s))
    np.testing.assert_array_equal(steps["event_s"].to_numpy(), s["wAccelerometer"].t[ic.ic_])
    assert len(steps) > 5


@settings(max_examples=6, deadline=None)
@given(cuts=st.lists(st.integers(0, 400), min_size=1, max_size=8))
def test_online_in_random_chunks_equals_offline(mobgap_test5, cuts):
    s, det, offline, (t, v, ctx) = _test5(mobgap_test5)

    def nothing_before_flush(part):
        assert len(part) == 0  # decision 17: every contact is decided at flush

    got = chunked(det, (t, v, ctx), cuts, each=nothing_before_flush)
    assert len(offline) > 5
    pd.testing.assert_frame_equal(offline.reset_index(drop=True), got, check_dtype=False)


def test_online_on_sensor_frame_samples_with_the_rotation(mobgap_test5):
    s, det, offline, _ = _test5(mobgap_test5)
    acc, gyr = s["wAccelerometer"], s["wGyroscope"]
    r = s.require_frame("waist").matrix()
    online = det.online(1.0 / np.median(np.diff(acc.t)), rotation=r)
    v = np.column_stack([acc.values, np.asarray([np.interp(acc.t, gyr.t, gyr.values[:, k]) for k in range(3)]).T])
    got = pd.concat([online.push(acc.t[:500], v[:500]), online.push(acc.t[500:], v[500:]), online.flush()],
                    ignore_index=True)
    np.testing.assert_allclose(got["event_s"].to_numpy(), offline["event_s"].to_numpy())


def test_cli_json_contract(mobgap_test5, capsys):
    assert main(["steps", str(mobgap_test5), "--detector", "waist-ic", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["detector"] == "waist-ic" and out["unit"] == "waist"
    for k in ("count", "reference_count", "precision", "recall", "f1", "count_error_pct"):
        assert k in out, k
    s, _, offline, _ = _test5(mobgap_test5)
    sc = score_steps(offline, s)
    assert out["count"] == len(offline) and out["f1"] == pytest.approx(sc["f1"]) and out["f1"] == 1.0


def test_auto_picks_waist_ic_without_a_foot_unit_and_pll_without_a_waist_gyroscope(mobgap_test5, tmp_path,
                                                                                    capsys):
    assert main(["steps", str(mobgap_test5), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["detector"] == "waist-ic"
    no_gyro = tmp_path / "no_gyro"
    shutil.copytree(mobgap_test5, no_gyro)
    (no_gyro / "wGyroscope.csv").unlink()
    assert main(["steps", str(no_gyro), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["detector"] == "pll"


def test_no_lower_back_accelerometer_is_one_line_naming_the_folder(gaitmap_level_left, mobgap_test5, tmp_path,
                                                                   capsys):
    with pytest.raises(MissingSensorError, match="wAccelerometer") as exc:
        get_detector("waist-ic").detect(read_session(gaitmap_level_left))
    assert str(gaitmap_level_left) in str(exc.value) and "\n" not in str(exc.value)
    no_acc = tmp_path / "no_acc"
    shutil.copytree(mobgap_test5, no_acc)
    (no_acc / "wAccelerometer.csv").unlink()
    assert main(["steps", str(no_acc), "--detector", "waist-ic"]) == 2
    err = [ln for ln in capsys.readouterr().err.splitlines() if ln.strip()]
    assert len(err) == 1 and err[0].startswith("error: ") and str(no_acc) in err[0] and "wAccelerometer" in err[0]


def test_online_rejects_wrong_columns():
    online = get_detector("waist-ic").online(100.0)
    with pytest.raises(DataError, match="shape"):
        online.push(np.arange(3.0), np.zeros((3, 3)))
    assert len(online.flush()) == 0


# -- delay_s: the realtime IC detector (W31) on a stream --------------------------------------------------
@pytest.mark.parametrize("name", ["mobgap_HA001_Test5_Trial1", "mobgap_HA001_Test11_Trial1"])
def test_realtime_equals_track_realtime_contacts(real_dir, name):
    s = read_session(real_dir / name)
    steps = WaistICStepDetector(delay_s=1.75).detect(s)
    tr = track_waist(s, pipeline="waist-pendulum", realtime=True)
    np.testing.assert_array_equal(steps["event_s"].to_numpy(), tr.steps["event_s"].to_numpy())
    np.testing.assert_array_equal(steps["end_s"].to_numpy(), tr.steps["end_s"].to_numpy())
    assert len(steps) > 5


@settings(max_examples=5, deadline=None)
@given(cuts=st.lists(st.integers(0, 300), min_size=1, max_size=10))
def test_realtime_online_in_random_chunks_equals_its_detect(mobgap_test5, cuts):
    s = read_session(mobgap_test5)
    det = WaistICStepDetector(delay_s=1.75)
    if "rt" not in _CACHE:
        _CACHE["rt"] = (det.detect(s), det._inputs(s))
    offline, (t, v, ctx) = _CACHE["rt"]
    pd.testing.assert_frame_equal(offline.reset_index(drop=True), chunked(det, (t, v, ctx), cuts),
                                  check_dtype=False)


def test_realtime_reports_each_contact_within_a_bounded_delay_and_state(real_dir):
    s = read_session(real_dir / "mobgap_HA001_Test11_Trial1")
    det = WaistICStepDetector(delay_s=1.75)
    t, v, ctx = det._inputs(s)
    online = det.online(1.0 / np.median(np.diff(t)), **ctx)
    chunk, late, longest = 25, [], 0
    for i in range(0, len(t), chunk):
        new = online.push(t[i:i + chunk], v[i:i + chunk])
        late += list(t[min(i + chunk, len(t)) - 1] - new["event_s"].to_numpy())
        longest = max(longest, len(online._proc.buf.get("t", ())))
    assert len(late) > 50
    # decided 1.75 to < 2.0 s after the contact (W31), reported when the next contact is decided or
    # max_step_s has passed without one, plus one chunk of 0.25 s
    assert min(late) >= 1.75 - 1e-9 and max(late) < 1.75 + 0.25 + det.max_step_s + 0.25 + 1e-9
    assert longest <= (10 + 1.75 + 0.25 + 0.25) * 100 + 2 * chunk  # history + delay + hop (+ chunk), 100 Hz


def test_realtime_settings_checked(mobgap_test5):
    with pytest.raises(DataError, match="hop_s"):
        WaistICStepDetector(delay_s=1.75, hop_s=0).online(100.0)
