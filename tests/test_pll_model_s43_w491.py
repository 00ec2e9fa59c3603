"""Session 43, fixer FC: W491 - an uncalibrated waist-pll track reading over 1.25 x the pendulum model, with no
earlier length line, says its step length is a population model (trial T1 F1: MS001 Test11 +103.60 %, no line)."""

from __future__ import annotations

import pytest

from pdrlearn.io import read_session
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.plausibility import PLL_MODEL_RATIO, pll_model_message
from tests.conftest import external_session


def test_pll_model_message_kernel_w491():
    line = pll_model_message(1.28, 66.49, 52.11)
    assert line.startswith("waist-pll reads 66.49 m, 1.28 x the pendulum model's 52.11 m")
    assert "population model" in line and "pdrlearn calibrate" in line and "--pipeline waist-pendulum" in line
    assert line.endswith("(decision W491)")
    assert pll_model_message(PLL_MODEL_RATIO, 25.0, 20.0) is None  # not over 1.25
    assert pll_model_message(0.87, 37.46, 43.2) is None and pll_model_message(None, 1.0, 1.0) is None


@pytest.mark.parametrize(("name", "fires"), [("mobgap_MS001_Test11_Trial1", True),
                                             ("mobgap_HA001_Test11_Trial1", False)])
def test_uncalibrated_pll_says_so_on_the_patient_not_the_healthy_walker_w491(name, fires):
    r = track_waist(read_session(external_session(name)), pipeline="waist-pll")
    lines = [w for w in r.info["warnings"] if "decision W491" in w]
    assert len(lines) == int(fires), r.info["pll_pendulum_ratio"]
    # the rule is W186's ratio over 1.25 (MS001 1.28, HA001 0.87 on this data)
    assert (r.info["pll_pendulum_ratio"] > PLL_MODEL_RATIO) is fires
