"""Decision L73: toe-off (terminal contact), stance and swing time of foot strides (pdrlearn.track.toeoff)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from scipy.spatial.transform import Rotation

from pdrlearn.track.gait import TOE_OFF_COLUMNS, add_gait_columns, gait_summary, stance_swing
from pdrlearn.track.toeoff import sagittal_axis, toe_off_times

ROOT = Path(__file__).resolve().parents[1] / "datasets" / "real"


def _strides(fs: float, tc: list[float], ic: list[float], mount: np.ndarray, seed: int = 0):
    """A foot gyroscope with known toe-offs: per stride a toe-down push-off peak (-5 rad/s) at ``tc``, a toe-up
    swing peak (+6 rad/s) midway to ``ic``, the heel-strike slap (toe-down, -3 rad/s) just after ``ic``, rest
    between; the sagittal rate is about the foot's right axis (toe-up positive), seen through the mounting
    rotation ``mount``, plus a little yaw/roll and noise."""
    rng = np.random.default_rng(seed)
    t = np.arange(0.0, ic[-1] + 1.5, 1.0 / fs)
    pitch = np.zeros_like(t)
    other = np.zeros((len(t), 2))
    for a, b in zip(tc, ic, strict=True):
        pitch += -5.0 * np.exp(-0.5 * ((t - a) / 0.04) ** 2)
        pitch += 6.0 * np.exp(-0.5 * ((t - 0.5 * (a + b)) / 0.07) ** 2)
        pitch += -3.0 * np.exp(-0.5 * ((t - b - 0.05) / 0.03) ** 2)
        other[:, 0] += 0.8 * np.exp(-0.5 * ((t - 0.5 * (a + b)) / 0.1) ** 2)
        other[:, 1] += -0.5 * np.exp(-0.5 * ((t - a - 0.1) / 0.08) ** 2)
    w_foot = np.column_stack([other[:, 0], -pitch, other[:, 1]])  # x forward, y left, z up: toe-up is about -y
    gyr = w_foot @ mount.T + rng.normal(0.0, 0.02, (len(t), 3))
    start = [a - 0.45 for a in tc]
    end = [b + 0.35 for b in ic]
    return t, gyr, np.array(start), np.array(end), np.array(ic)


@pytest.mark.parametrize("fs", [50.0, 100.0, 204.8])
@pytest.mark.parametrize("mount_seed", [0, 1, 2])
def test_hand_made_toe_off_any_rate_any_mounting(fs, mount_seed):
    tc = [1.0, 2.1, 3.22, 4.3]
    ic = [1.37, 2.48, 3.6, 4.69]
    mount = Rotation.random(random_state=mount_seed).as_matrix()
    t, gyr, st, en, ev = _strides(fs, tc, ic, mount, seed=mount_seed)
    axis = sagittal_axis(t, gyr, st, en, ev)
    right = mount @ np.array([0.0, -1.0, 0.0])  # the foot's right axis in the sensor frame: toe-up positive
    assert axis @ right > 0.99
    est = toe_off_times(t, gyr, st, en, ev)
    assert np.abs(est - np.array(tc)).max() < 0.004  # seconds, at 50 Hz too (sub-sample peak)


def test_missing_push_off_and_short_windows_are_nan():
    t, gyr, st, en, ev = _strides(100.0, [1.0, 2.1, 3.2], [1.37, 2.48, 3.6], np.eye(3))
    # a stride window starting after the push-off: its toe-down minimum sits on the first sample -> NaN
    est = toe_off_times(t, gyr, [1.05, 1.65, 2.75], [1.72, 2.83, 3.95], [1.37, 2.48, 3.6])
    assert np.isnan(est[0]) and abs(est[1] - 2.1) < 0.004 and abs(est[2] - 3.2) < 0.004
    assert np.isnan(toe_off_times(t, gyr, [1.0], [1.005], [1.003])).all()  # under three samples
    assert len(toe_off_times(t, gyr, [], [], [])) == 0


def test_bad_input_is_one_clear_error():
    t = np.arange(0.0, 1.0, 0.01)
    with pytest.raises(ValueError, match=r"gyr must be \(N, 3\)"):
        toe_off_times(t, np.zeros((len(t), 2)), [0.0], [0.5], [0.4])
    with pytest.raises(ValueError, match="increase strictly"):
        toe_off_times(t[::-1], np.zeros((len(t), 3)), [0.0], [0.5], [0.4])
    g = np.zeros((len(t), 3))
    g[3, 1] = np.nan
    with pytest.raises(ValueError, match="finite"):
        toe_off_times(t, g, [0.0], [0.5], [0.4])


def test_stance_swing_split_and_gap_rows():
    table = pd.DataFrame({"start_s": [0.0, 1.0, 2.0, 3.0], "end_s": [1.0, 2.0, 3.0, 4.0],
                          "event_s": [0.8, 1.9, 2.8, 3.9], "length_m": [1.2, 1.3, 0.0, 1.3]})
    tc = np.array([0.4, 1.5, 2.4, 3.95])  # the last one after its IC: no toe-off
    valid = np.array([True, True, False, True])  # the third row is a gap row
    add_gait_columns(table, valid=valid, tc_s=tc)
    assert list(table.columns[-4:]) == list(TOE_OFF_COLUMNS)
    assert np.isnan(table["tc_s"][2]) and np.isnan(table["tc_s"][3])
    assert table["swing_time_s"][1] == pytest.approx(0.4)
    assert table["stance_time_s"][1] == pytest.approx(1.5 - 0.8)
    assert table["stance_pct"][1] == pytest.approx(100 * 0.7 / 1.1)
    assert np.isnan(table["stance_time_s"][0])  # no previous IC
    summ = gait_summary(table)
    assert summ["n_stance_times"] == 1 and summ["median_swing_time_s"] == pytest.approx(0.4, abs=1e-9)
    assert gait_summary(table.drop(columns=list(TOE_OFF_COLUMNS)))["median_stance_time_s"] is None
    tcs, stance, swing, pct = stance_swing([0.0], [1.0], [0.8], [0.9], [1.0])  # TC after IC
    assert np.isnan(tcs).all() and np.isnan(stance).all() and np.isnan(swing).all() and np.isnan(pct).all()
