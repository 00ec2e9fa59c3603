"""Decision L795 (session 51, FM, trial s51t2 F6): the minimum toe clearance of each stride (the toe point of a rigid
foot from the sensor's path and attitude, Mariani et al. 2012), each side's median in gait and the clearly lower side
named; cohort C260: clinical.md's line. Kernel-level and hand-made step tables (no tracking)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

from pdrlearn.kernels.clearance import min_clearance, toe_height
from pdrlearn.track.bilateral import bilateral_gait, lower_clearance_side


def _pitch_q(theta: np.ndarray) -> np.ndarray:
    """(1, L, 4) [w, x, y, z]: the foot pitched by ``theta`` (rad, + toes up) about the body y axis (x forward, z up:
    a rotation of -theta about y lifts x)."""
    h = -theta / 2.0
    return np.stack([np.cos(h), np.zeros_like(h), np.sin(h), np.zeros_like(h)], axis=-1)[None]


def test_the_toe_point_follows_the_foot_pitch_l795():
    theta = np.radians(np.r_[0.0, -30.0, -10.0, 5.0, 0.0])  # toes down at push-off, up before the contact
    pos = np.zeros((1, 5, 3))
    pos[0, :, 0] = np.linspace(0.0, 1.0, 5)  # the sensor moves forward at one height
    mask = np.ones((1, 5), bool)
    h = toe_height(pos, _pitch_q(theta), mask, 0.14)
    np.testing.assert_allclose(h[0], 0.14 * np.sin(theta), atol=1e-12)
    np.testing.assert_allclose(toe_height(pos, _pitch_q(theta), mask, 0.0)[0], 0.0, atol=1e-12)  # the sensor itself


def test_the_clearance_is_the_lowest_toe_after_its_first_peak_l795():
    # a swing: the toe rises to 0.10 m, dips to 0.015 m in mid-swing, rises to 0.05 m, lands (0.0) at the contact
    h = np.array([[0.0, 0.0, 0.04, 0.10, 0.06, 0.015, 0.03, 0.05, 0.02, 0.0, 0.0, 0.0]])
    assert min_clearance(h, np.array([1]), np.array([8]))[0] == pytest.approx(0.015)
    assert min_clearance(h, np.array([-1]), np.array([8]))[0] == pytest.approx(0.015)  # no toe-off: the toe's rise
    assert min_clearance(h, np.array([1]), np.array([9]))[0] == pytest.approx(0.0)  # a flat landing: at the contact
    assert np.isnan(min_clearance(h, np.array([1]), np.array([-1]))[0])  # no contact in the stride
    assert np.isnan(min_clearance(h, np.array([1]), np.array([3]))[0])  # under 5 samples


def test_the_foot_track_writes_the_clearance_after_the_lift_l795():
    from pdrlearn.track.plasys import swing_columns

    table = pd.DataFrame({"event_s": [1.0, 2.0], "tc_s": [0.6, np.nan], "stride_time_s": [np.nan, 1.0]})
    seen = {}
    fd = SimpleNamespace(lift_m_=np.array([0.1, 0.1]), sole_angle=lambda t: np.zeros(len(np.atleast_1d(t))),
                         min_toe_clearance=lambda tc, ic: seen.update(tc=tc, ic=ic) or np.array([0.012, 0.03]))
    swing_columns(table, fd, np.array([True, False]))
    cols = list(table.columns)
    assert cols.index("min_toe_clearance_m") == cols.index("max_sensor_lift_m") + 1
    assert table["min_toe_clearance_m"].iloc[0] == 0.012 and np.isnan(table["min_toe_clearance_m"].iloc[1])
    np.testing.assert_array_equal(seen["ic"], [1.0, 2.0])
    from pdrlearn.columns import undocumented

    assert undocumented("steps.csv (foot)", ["min_toe_clearance_m"]) == []


def test_the_toe_offset_is_a_checked_setting_l795():
    from pdrlearn.displace.foot import FootDisplacement, check_settings
    from pdrlearn.errors import DataError

    assert FootDisplacement().toe_offset_m == 0.14 and FootDisplacement(toe_offset_m=0.1).toe_offset_m == 0.1
    with pytest.raises(DataError, match="toe_offset_m"):
        check_settings({"toe_offset_m": -0.1})


def test_the_lower_side_is_named_only_when_clearly_lower_l795():
    assert lower_clearance_side({"min_toe_clearance_m_left": -0.006, "min_toe_clearance_m_right": 0.003}) == "left"
    assert lower_clearance_side({"min_toe_clearance_m_left": 0.027, "min_toe_clearance_m_right": 0.029}) is None
    assert lower_clearance_side({"min_toe_clearance_m_left": 0.03, "min_toe_clearance_m_right": 0.0}) == "right"
    assert lower_clearance_side({"min_toe_clearance_m_left": None, "min_toe_clearance_m_right": 0.03}) is None


N = 14


def _foot(ic, mtc) -> pd.DataFrame:
    ic = np.asarray(ic, float)
    return pd.DataFrame({"start_s": ic - 0.6, "end_s": ic + 0.2, "event_s": ic, "tc_s": ic - 0.45, "length_m": 1.2,
                         "gap_s": 0.0, "unit": "foot", "min_toe_clearance_m": mtc})


def test_gait_gives_each_sides_clearance_and_the_clinical_line_l795_c260():
    from pdrlearn.cli.gait import gait_lines
    from pdrlearn.report.clinical import asymmetry_lines

    left = np.r_[0.08, np.full(N - 1, 0.004)]  # one stray stride: the median holds
    w = bilateral_gait(_foot(np.arange(N) * 1.2, left), _foot(0.6 + np.arange(N) * 1.2, 0.021))["walk"]
    assert (w["min_toe_clearance_m_left"], w["min_toe_clearance_m_right"]) == (0.004, 0.021)
    assert w["toe_clearance_lower"] == "left"
    assert ("toe clearance (minimum in mid-swing, medians) left 0.004 m / right 0.021 m: left lower by 17 mm (a "
            "dragging toe, e.g. foot drop - or the measure's error: in simulated symmetric walkers the sides' "
            "difference read off by a median 6 mm, up to 38 mm, L804) (L795)") in gait_lines(w)
    page = "\n".join(asymmetry_lines(w, affected="left"))
    assert ("- Toe clearance (minimum in mid-swing, medians) affected 0.004 m / unaffected 0.021 m: affected "
            "lower") in page
    same = bilateral_gait(_foot(np.arange(N) * 1.2, 0.02), _foot(0.6 + np.arange(N) * 1.2, 0.022))["walk"]
    assert same["toe_clearance_lower"] is None
    assert not any("dragging toe" in line for line in gait_lines(same))
