"""Decision B465 (session 47, FG, trial T3 F7): a calibration made at another rate warns / is dropped only when the
lower of the two rates is under 50 Hz, and the lines say the measured size."""

from __future__ import annotations

from pdrlearn.kernels.distance import RATE_MATTERS_HZ, applicable_calibration
from pdrlearn.kernels.waist import rate_mismatch_line


def test_waist_k_line_only_under_50_hz_and_says_the_size():
    assert RATE_MATTERS_HZ == 50.0
    assert rate_mismatch_line(1000.0, 1125.0, "cal.json") is None  # T3: K moved 0.27 % there
    assert rate_mismatch_line(100.0, 1000.0, "cal.json") is None
    line = rate_mismatch_line(100.0, 25.0, "cal.json")
    assert line.startswith("cal.json: step length calibrated at 100 Hz, applied to a 25 Hz recording")
    assert "3.2-5.1 %" in line and "B465" in line and "pdrlearn calibrate" in line


def test_foot_gain_applies_between_high_rates_and_drops_under_50_hz():
    rec = {"gain": 1.0035, "rate_hz": 100.0, "stride_sd": 0.006, "reason": None}
    assert applicable_calibration(rec, 1000.0) == (rec, None)  # T3: a 100 Hz model's gain at 1000 Hz
    assert applicable_calibration({**rec, "rate_hz": 1000.0}, 1125.0)[0] is not None
    none, line = applicable_calibration({**rec, "rate_hz": 20.0}, 100.0)
    assert none is None and "not applied" in line and "B465" in line and "0.09 %" in line
