"""Session 34 (I2): work a track did twice is done once, with the same outputs (steps decision 55, W353)."""

from __future__ import annotations

import pandas as pd
import pytest


@pytest.fixture(scope="module")
def force_walk(tmp_path_factory):
    from pdrlearn.io import write_session
    from pdrlearn.sim import UserProfile, simulate

    out = tmp_path_factory.mktemp("reuse") / "A_u7702"
    write_session(simulate("A", UserProfile.from_seed(7702), "normal", rate_hz=100.0), out)
    return out


def _counting(monkeypatch, cls, name="detect"):
    calls = []
    orig = getattr(cls, name)

    def counted(self, *a, **k):
        calls.append(1)
        return orig(self, *a, **k)

    monkeypatch.setattr(cls, name, counted)
    return calls


def _counting_function(monkeypatch, module, name):
    calls = []
    orig = getattr(module, name)

    def counted(*a, **k):
        calls.append(1)
        return orig(*a, **k)

    monkeypatch.setattr(module, name, counted)
    return calls


def test_the_force_detector_runs_once_per_plasys_track_steps_55(force_walk, monkeypatch):
    from pdrlearn.io import read_session
    from pdrlearn.steps import AccelForceStepDetector
    from pdrlearn.track.plasys import track_plasys

    calls = _counting(monkeypatch, AccelForceStepDetector)
    res = track_plasys(read_session(force_walk))
    assert res.info["stance_source"] == "force" and res.info["force_offset_s"] is not None  # L390 ran
    assert res.info["heading_source"] in ("fused", "waist")  # L161's unit check ran on the waist unit
    assert len(calls) == 1  # the strides' detection, reused by L390's and L161's checks (it ran three times)
    calls.clear()
    res = track_plasys(read_session(force_walk), align=True)  # L162: --align-units estimates from it too
    assert res.info.get("unit_alignment") is not None and len(calls) == 1


def test_align_estimate_takes_the_force_table_steps_55(force_walk, monkeypatch):
    from pdrlearn.io import read_session
    from pdrlearn.steps import AccelForceStepDetector
    from pdrlearn.steps.align import align_estimate

    session = read_session(force_walk)
    own = align_estimate(session)
    table = AccelForceStepDetector().detect(session)
    calls = _counting(monkeypatch, AccelForceStepDetector)
    assert align_estimate(session, force_table=table) == own and not calls
    session.streams.pop("fForceA")  # without the insoles the accelerometer detector's events: the table is not used
    assert align_estimate(session, force_table=table) == align_estimate(session) and not calls


def test_force_events_takes_a_detected_table_steps_55(force_walk, monkeypatch):
    from pdrlearn.displace.force_clock import force_events
    from pdrlearn.io import read_session
    from pdrlearn.steps import AccelForceStepDetector

    session = read_session(force_walk)
    own = force_events(session)
    calls = _counting(monkeypatch, AccelForceStepDetector)
    assert force_events(session, detected=own) is own and not calls
    assert force_events(session, detected=pd.DataFrame()) is None and not calls  # a detector that failed
    pd.testing.assert_frame_equal(force_events(session), own)
    assert len(calls) == 1


@pytest.fixture(scope="module")
def waist_walk(tmp_path_factory):
    from pdrlearn.io import write_session
    from pdrlearn.sim import UserProfile, simulate

    out = tmp_path_factory.mktemp("reuse_w") / "walk_u7703"
    write_session(simulate("walk", UserProfile.from_seed(7703), "normal", rate_hz=100.0, length_m=60.0), out)
    return out


def test_gait_quality_reads_the_tracks_own_ahrs_w353(waist_walk, tmp_path, monkeypatch):
    import pdrlearn.waist.ahrs as ahrs
    from pdrlearn.cli import main

    calls = _counting_function(monkeypatch, ahrs, "imu_from_body")
    assert main(["track", "--no-plot", str(waist_walk), "--pipeline", "waist-pendulum", "--gait-quality",
                 "--out", str(tmp_path / "t")]) == 0
    bouts = pd.read_csv(tmp_path / "t" / "bouts.csv")
    assert bouts["hr_ap"].notna().any()  # W350 ran on the bout
    assert len(calls) == 1  # the track's AHRS (it ran a second time for W350)


def test_a_kept_imu_is_the_tracks_unchanged_w353(waist_walk):
    import numpy as np

    from pdrlearn.io import read_session
    from pdrlearn.track.waist import waist_pendulum
    from pdrlearn.waist.ahrs import kept_imu, kept_imus, waist_imu

    session = read_session(waist_walk)
    with kept_imus() as imus:
        waist_pendulum(session)
    assert len(imus) == 1 and imus[0][0] is session
    fresh = waist_imu(session)
    kept = kept_imu(imus, session)
    assert kept is imus[0][3]  # the track's own object, not a new run
    for name in ("t", "acc_nav", "gyr_nav", "yaw", "acc_v", "acc_h", "acc_ap", "acc_ml", "bridged"):
        assert np.array_equal(getattr(kept, name), getattr(fresh, name)), name  # the track changed none in place
    assert kept_imu(imus, read_session(waist_walk)) is not kept  # another session object: computed afresh
    assert kept_imu(imus, session, gain=0.1) is not kept
    waist_imu(session)
    assert len(imus) == 1  # nothing is kept outside the block


def test_a_waist_track_computes_one_standstill_mask_w354(waist_walk, monkeypatch):
    import pdrlearn.kernels.waist as kw
    from pdrlearn.io import read_session
    from pdrlearn.track.waist import waist_pendulum

    session = read_session(waist_walk)
    for name in [n for n in session.streams if n.startswith("f")]:  # the lower back alone (a foot unit's own
        session.streams.pop(name)  # rests are other masks: foot_rest_runs, W336)
    calls = _counting_function(monkeypatch, kw, "still_samples")  # every standstill_mask call runs it
    res = waist_pendulum(session)
    assert "pause_factor" in res.steps  # W122 / W134's standstills were read (pause_steps "standing")
    # W122's step lengths, W105's rest rate and L296 / L372 share one mask (it ran three times); the second call is
    # W441's pelvic-gyro cross-check (session 40), whose thesis detector calibrates its own standstill (ch.5.3)
    assert len(calls) == 2


def test_the_imus_mask_is_standstill_masks_and_read_only_w354(waist_walk):
    from types import SimpleNamespace

    import numpy as np

    from pdrlearn.io import read_session
    from pdrlearn.signal.conditioning import standstill_mask
    from pdrlearn.waist.ahrs import nav_still, waist_imu

    imu = waist_imu(read_session(waist_walk))
    still = imu.still()
    assert still is imu.still() and nav_still(imu) is still
    assert np.array_equal(still, standstill_mask(imu.acc_nav, imu.gyr_nav, imu.fs)) and still.any()
    with pytest.raises(ValueError):
        still[0] = not still[0]  # shared: a reader cannot change it for the others
    plain = SimpleNamespace(acc_nav=imu.acc_nav, gyr_nav=imu.gyr_nav, fs=imu.fs)  # a plug-in's signals: computed
    assert np.array_equal(nav_still(plain), still)
