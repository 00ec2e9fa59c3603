"""Decision W169: calibrating the waist step length on fewer than 20 steps warns (the gain of a short walk varies
from walk to walk more than the defaults' error on straight walks); the uncalibrated warning names the length."""
from pathlib import Path

import pytest

from pdrlearn.io import read_session
from pdrlearn.waist.calibration import MIN_CALIBRATION_STEPS, calibrate
from pdrlearn.waist.params import default_params

REAL = Path(__file__).resolve().parents[1] / "datasets" / "real"
T5 = [REAL / "mobgap_HA001_Test5_Trial1", REAL / "mobgap_HA001_Test5_Trial2"]


@pytest.mark.skipif(not T5[0].exists(), reason="bundled real recordings missing")
def test_one_short_walk_warns(caplog):
    p = calibrate([read_session(T5[0])], "waist-pendulum")
    short = [n for n in p.notes if "decision W169" in n]
    assert len(short) == 1 and f"(< {MIN_CALIBRATION_STEPS})" in short[0]
    assert any("W169" in r.getMessage() and r.levelname == "WARNING" for r in caplog.records)


@pytest.mark.skipif(not T5[0].exists(), reason="bundled real recordings missing")
def test_enough_steps_do_not_warn():
    sessions = [read_session(f) for f in T5 + [REAL / "mobgap_HA001_Test11_Trial1"]]
    p = calibrate(sessions, "waist-pendulum")
    assert not [n for n in p.notes if "decision W169" in n]


@pytest.mark.skipif(not T5[0].exists(), reason="bundled real recordings missing")
def test_uncalibrated_warning_names_the_length():
    _, warnings = default_params(read_session(T5[0]))
    assert "20 steps or more" in warnings[0]
