"""Decision steps 48 (session 32 geriatrics trial, finding 1): the ``pll`` step detector shares ``track``'s
session-relative motion gate (W76) by default, and a lower-back run with 0 steps says why (W76's line)."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.kernels import waist as K
from pdrlearn.steps import get_detector, score_steps


@pytest.fixture(scope="module")
def slow_walk(tmp_path_factory):
    """A 0.33 m/s walker (0.3 m steps in 0.9 s, pendulum bounce; user 6538 of this session's range)."""
    out = tmp_path_factory.mktemp("slow") / "w"
    assert main(["simulate", "--route", "stand:3, straight:8, stand:3", "--step-length", "0.3", "--step-time", "0.9",
                 "--bounce", "pendulum", "--user-seed", "6538", "--out", str(out)]) == 0
    return read_session(out)


def test_pll_finds_a_slow_walkers_steps_with_the_relative_gate_steps_48(slow_walk):
    fixed = score_steps(get_detector("pll", relative_gate=False).detect(slow_walk), slow_walk)
    rel_det = get_detector("pll")  # the default since decision steps 48's rule was met
    rel = score_steps(rel_det.detect(slow_walk), slow_walk)
    assert fixed["recall"] < 0.2  # decision 18's fixed 0.25 m^2/s^4 misses this quiet trunk
    assert rel["f1"] >= 0.9
    thr, sigma, source = rel_det.gate_
    assert source == "relative" and K.RELATIVE_GATE_FLOOR_MPS2 <= thr < 0.5
    # W76's one rule (relative_walk_threshold) on the SD the PLL's gate judges
    assert thr == pytest.approx(K.relative_walk_threshold(sigma, 0.5))


def test_streaming_pll_keeps_the_fixed_gate_steps_48():
    det = get_detector("pll")
    assert det.online(100.0)._proc.params.gate_var == pytest.approx(0.25)


def test_pll_with_no_steps_says_why_steps_48(slow_walk, capsys):
    assert main(["steps", str(slow_walk.folder), "--detector", "pll:relative_gate=false"]) == 0
    err = capsys.readouterr().err
    assert "no steps found" in err and "never opened" in err and "pll:relative_gate=true" in err


def test_track_waist_pll_keeps_its_own_gate_steps_48(slow_walk):
    """`track --pipeline waist-pll` passes its own (W76) gate: the detector must not lower it once more."""
    from pdrlearn.track.waist import _pll_steps
    from pdrlearn.waist.ahrs import waist_imu

    imu = waist_imu(slow_walk)
    a = _pll_steps(slow_walk, imu, 0.5)
    b = get_detector("pll", gate_var=0.25, relative_gate=False).detect(slow_walk)
    assert len(a) <= len(b) + 1 and np.all(np.isfinite(a["event_s"]))
