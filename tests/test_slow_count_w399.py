"""Decision W399: L95's slow line of a lower-back track says that n_steps, the cadence and the stride length are not
validated either, and (calibrated at this gait, W227) that the calibration corrects the distance, not the count."""

from __future__ import annotations

import pytest

from pdrlearn.track.gait import gait_range_warning


def _line(info: dict) -> str:  # T6's slow PD walk: 63 steps/min, 0.37 m/s
    return gait_range_warning({"median_cadence_spm": 63.5, "median_speed_straight_mps": 0.37,
                               "n_straight_strides": 50, "info": info})


@pytest.mark.parametrize("source", ["defaults", "calibrated"])
def test_slow_lower_back_line_names_the_step_count_w399(source):
    line = _line({"pipeline": "waist-pendulum", "params_source": source, "calibration_covers_cadence": True})
    assert "n_steps" in line and "stride_length_m" in line and "W399" in line
    assert ("the calibration corrects the distance, not the step count" in line) is (source == "calibrated")


def test_slow_foot_line_is_unchanged_w399():
    assert "W399" not in _line({"pipeline": "plasys"})


def test_the_line_keeps_its_warning_code_w399():
    """E155: a line's code is the last "decision X" it names; W399's clause names none, so the code stays L351."""
    from pdrlearn.warning_lines import warning_code

    assert warning_code(_line({"pipeline": "waist-pendulum", "params_source": "defaults"})) == "L351"
