"""Decisions L317, L318, L327-L329: `pdrlearn gait` findings of the session 31 treadmill and prosthesis trials."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.track.bilateral import bilateral_gait


def _foot(ic, length=1.4, swing=0.45) -> pd.DataFrame:
    """A foot track's steps.csv: one row per stride, its IC (event_s), the toe-off before it (tc_s), its length."""
    ic = np.asarray(ic, float)
    return pd.DataFrame({"start_s": ic - 0.6, "end_s": ic + 0.2, "event_s": ic, "tc_s": ic - swing,
                         "length_m": np.broadcast_to(np.asarray(length, float), ic.shape).copy(), "gap_s": 0.0,
                         "unit": "foot"})


def test_l317_initiation_and_termination_half_strides_count_in_no_stride_length():
    """Trial finding 1: a symmetric walker whose right foot starts (a half stride from the feet side by side) and
    closes the walk (another half stride) read 14 % stride-length asymmetry; the bout's first and last contact are
    left out, so both feet read their steady 1.4 m."""
    right = _foot(np.arange(6) * 1.2, length=[0.7, 1.4, 1.4, 1.4, 1.4, 0.7])
    left = _foot(0.6 + np.arange(5) * 1.2, length=1.4)
    w = bilateral_gait(left, right)["walk"]
    assert w["stride_length_m_left"] == pytest.approx(1.4) and w["stride_length_m_right"] == pytest.approx(1.4)
    assert w["stride_length_m_si_pct"] == pytest.approx(0.0, abs=1e-9)


def _impacts(rate=100.0, fc=None):
    """A foot's accelerometer: 1 g at rest and a 60 m/s^2 heel-strike spike (two samples) every 1.1 s from 1 s;
    with ``fc`` (Hz) low-passed (2nd-order Butterworth, filtfilt) as the trial softened a prosthetic foot."""
    from scipy.signal import butter, filtfilt

    t = np.arange(0, 12, 1 / rate)
    acc = np.zeros((len(t), 3))
    acc[:, 2] = 9.81
    ics = 1.0 + np.arange(10) * 1.1
    for ic in ics:
        k = int(round(ic * rate))
        acc[k:k + 2, 2] += 60.0
    if fc is not None:
        b, a = butter(2, fc / (rate / 2))
        acc = filtfilt(b, a, acc, axis=0)
    return t, acc, ics


def test_l318_a_soft_impact_foot_makes_the_contacts_not_comparable():
    """Trial finding 1: one foot low-passed at 8 Hz - its impact far less sharp - warns; two alike feet do not."""
    from pdrlearn.track.contact_quality import SHARPNESS_RATIO_MAX, comparability_warning, impact_sharpness

    sharp = impact_sharpness(*_impacts())
    soft = impact_sharpness(*_impacts(fc=8.0))
    assert sharp / soft > SHARPNESS_RATIO_MAX
    line = comparability_warning(sharp, soft)
    assert line is not None and "right foot's contacts" in line and "step times" in line
    assert comparability_warning(sharp, 0.8 * sharp) is None
    assert comparability_warning(None, soft) is None
    assert impact_sharpness(np.arange(2.0), np.ones((2, 3)), [0.5]) is None


def test_l318_gait_warns_on_a_real_pair_with_one_foot_softened(tmp_path):
    """Gaitmap's real level pair with the right foot's accelerometer low-passed at 8 Hz (the trial's gm_soft8_right):
    the tracked step-time SI reads ~18 % (mocap 2.3 %) with no step-time warning before L318; the real pair as
    recorded does not warn."""
    import shutil

    from scipy.signal import butter, filtfilt

    from pdrlearn.track.bilateral import pair_sessions

    root = Path(__file__).resolve().parents[1] / "datasets/real"
    left, right = root / "gaitmap_level_left", root / "gaitmap_level_right"
    soft = tmp_path / "soft_right"
    shutil.copytree(right, soft)
    for f in soft.glob("fForce*.csv"):
        f.unlink()
    acc = pd.read_csv(soft / "fAccelerometer.csv")
    rate = 1000.0 / np.median(np.diff(acc["timestamp"].to_numpy(float)))  # PLASYS timestamps in ms
    b, a = butter(2, 8.0 / (0.5 * rate))
    acc.iloc[:, 1:4] = filtfilt(b, a, acc.iloc[:, 1:4].to_numpy(float), axis=0)
    acc.to_csv(soft / "fAccelerometer.csv", index=False)
    assert any("L318" in w for w in pair_sessions(left, soft)["warnings"])
    assert not any("L318" in w for w in pair_sessions(left, right)["warnings"])


def test_l327_stance_time_per_foot_and_its_asymmetry():
    """Prosthesis trial finding 7: stance per foot (its IC to its toe-off inside the cycle) and its symmetry index.
    Left swing 0.45 s, right 0.35 s of 1.2 s cycles: stance 0.75 / 0.85 s, SI 100 x 0.1 / 0.8 = 12.5 %."""
    from pdrlearn.cli.gait import gait_lines

    r = bilateral_gait(_foot(np.arange(6) * 1.2, swing=0.45), _foot(0.6 + np.arange(6) * 1.2, swing=0.35))
    w = r["walk"]
    assert w["stance_time_s_left"] == pytest.approx(0.75) and w["stance_time_s_right"] == pytest.approx(0.85)
    assert w["stance_time_s_si_pct"] == pytest.approx(12.5) and w["stance_time_s_ratio"] == pytest.approx(0.75 / 0.85)
    assert r["cycles"]["stance_time_s"].notna().all()
    assert any(line.startswith("stance time left/right 0.750 / 0.850 s, symmetry index 12.5 %")
               for line in gait_lines(w))


def test_l328_double_support_difference_printed_only_with_l284s_pattern():
    """Prosthesis trial finding 9: a walker with asymmetric steps and swings (shared clock) gets no clock-offset
    words; step times asymmetric with symmetric swings (L284's pattern) does."""
    from pdrlearn.cli.gait import gait_lines

    walker = bilateral_gait(_foot(np.arange(6) * 1.2, swing=0.35), _foot(0.5 + np.arange(6) * 1.2, swing=0.45))
    assert walker["walk"]["swing_time_s_si_pct"] > 10
    assert not any("double support before" in line for line in gait_lines(walker["walk"]))
    offset = bilateral_gait(_foot(np.arange(6) * 1.2), _foot(0.5 + np.arange(6) * 1.2))  # swings equal
    assert any("double support before" in line and "L284" in line for line in gait_lines(offset["walk"]))


def test_l329_backward_walk_is_noted():
    """Treadmill trial finding 8: a pair of foot tracks whose strides travel backward gets L329's note."""
    from pdrlearn.track.bilateral import backward_note

    back = _foot(np.arange(6) * 1.4).assign(raw_length_m=-0.85, turn_angle_rad=0.0)
    fwd = _foot(np.arange(6) * 1.4).assign(raw_length_m=0.85, turn_angle_rad=0.0)
    line = backward_note([back, back])
    assert line is not None and "6 of 6 / 6 of 6" in line and "backward" in line
    assert backward_note([fwd, fwd]) is None
