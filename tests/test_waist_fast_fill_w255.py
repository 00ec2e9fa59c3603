"""Decisions W255 / W256: ``fast_fill="outside_freeze"`` -- W242's 5 Hz merged-step fill, but no fill inside an
episode of the lower back's freeze index (W213's, as freezes.csv finds it). Measured, not adopted (W256): a value of
the option, off by default. The kernel's mask, the detector's mask against freezes.csv, the option's values and
reach, a simulated 3 Hz freeze (W243's finding) and the measured real row."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.track.freezes import session_freezes
from pdrlearn.track.waist import FAST_FILL_VALUES, OPTION_DEFAULTS, ignored_options_line, track_waist
from pdrlearn.waist import _kernels as K
from pdrlearn.waist.ahrs import waist_imu
from pdrlearn.waist.events import FAST_FILL_OUTSIDE_FREEZE, InitialContactDetector, frozen_samples


@pytest.fixture(scope="module")
def freeze_3hz():
    """W214's freeze route at the trial's gait, user 6030 (W243's user, trembling 3 Hz at 7 m/s^2: W242 added
    contacts inside its freeze)."""
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "experiments"))
    from waist_freeze_veto import simulate

    return simulate("stand:3, straight:4, freeze:10:3:7.0, straight:4, stand:3", {"bounce": "pendulum"}, 6030,
                    (0.2, 0.55))


def _events(s, **kw):
    return track_waist(s, pipeline="waist-pendulum", **kw).steps["event_s"].to_numpy(float)


def test_no_fill_inside_a_simulated_3hz_freeze(freeze_3hz):
    """W243's finding: W242's fill reads a 3 Hz trembling as steps; W255's value adds none of them."""
    off, on, gated = (_events(freeze_3hz, fast_fill=v) for v in (False, True, FAST_FILL_OUTSIDE_FREEZE))
    fr = freeze_3hz.extras["freezes"]
    added = np.setdiff1d(on, off)
    assert added.size > 0
    inside = np.zeros(added.size, bool)
    for a, b in zip(fr["start_s"], fr["end_s"], strict=True):
        inside |= (added >= a - 0.25) & (added <= b + 0.25)
    assert inside.all()  # W243: every added contact inside the freeze
    np.testing.assert_array_equal(gated, off)


def test_the_detectors_mask_is_freezes_csv(freeze_3hz):
    """W255: the episodes are W213's, as freezes.csv lists them (the accelerometer's norm; acc_nav keeps it)."""
    imu = waist_imu(freeze_3hz)
    mask = frozen_samples(imu)
    rows = session_freezes(freeze_3hz, "waist-pendulum")
    assert rows and mask.any()
    want = np.zeros(imu.t.size, bool)
    for r in rows:
        want |= (imu.t >= r["start_s"]) & (imu.t <= r["end_s"])
    assert np.mean(mask == want) > 0.99


def test_the_kernel_mask_removes_only_the_fill(freeze_3hz):
    """``ic_offline(frozen=...)``: every sample frozen -> the contacts without the fill; none frozen -> W242's."""
    imu = waist_imu(freeze_3hz)
    args = (imu.acc_v, imu.acc_ap, imu.acc_ml, imu.w_z, imu.fs)
    kw = InitialContactDetector().rule_settings()
    base = K.contacts_offline(*args, **kw)[2]
    fill = K.contacts_offline(*args, **(kw | {"fast_fill": True}))[2]
    none = K.contacts_offline(*args, **(kw | {"fast_fill": True, "frozen": np.zeros(imu.t.size, bool)}))[2]
    every = K.contacts_offline(*args, **(kw | {"fast_fill": True, "frozen": np.ones(imu.t.size, bool)}))[2]
    assert fill.size > base.size
    np.testing.assert_array_equal(none, fill)
    np.testing.assert_array_equal(every, base)


def test_the_values_default_and_reach():
    assert OPTION_DEFAULTS["fast_fill"] is False  # W256: not adopted
    assert FAST_FILL_VALUES == (False, True, "outside_freeze")
    det = InitialContactDetector(fast_fill=FAST_FILL_OUTSIDE_FREEZE)
    assert det.rule_settings()["fast_fill"] is True and "frozen" not in det.rule_settings()
    live = InitialContactDetector(fast_fill=FAST_FILL_OUTSIDE_FREEZE, realtime=True)
    assert live.rule_settings()["fast_fill"] is False
    o = dict(OPTION_DEFAULTS, fast_fill=FAST_FILL_OUTSIDE_FREEZE)
    line = ignored_options_line(o, "waist-pendulum", True, "gyro", False, True)
    assert line is not None and 'fast_fill="outside_freeze"' in line and "W242" in line


def test_an_unknown_value_is_refused(freeze_3hz):
    with pytest.raises(DataError, match=r"fast_fill 'outside' is not one of false, true, \"outside_freeze\".*W255"):
        track_waist(freeze_3hz, pipeline="waist-pendulum", fast_fill="outside")


def test_the_measured_real_row_ms001_test11_w256():
    """W256: MS001 Test11's one W242 contact (123.80 s) lies in the lower back's freeze episode 122.25-128.75 s, so the
    gated fill reads as off (in-bout step_f1 0.8913, 82/93 of 91) where ``True`` reads 0.8973 (83/94)."""
    from pdrlearn.io import read_session
    from pdrlearn.waist.evaluate import step_metrics
    from tests.conftest import external_session

    s = read_session(external_session("mobgap_MS001_Test11_Trial1"))
    m = step_metrics(track_waist(s, pipeline="waist-pendulum", fast_fill=FAST_FILL_OUTSIDE_FREEZE,
                                 turn_bridge=False).steps, s)  # W256 was measured before W385's "side"
    assert (m["n_detected"], m["n_reference"], round(m["step_f1"], 4)) == (93, 91, 0.8913)
