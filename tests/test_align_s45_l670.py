"""Decision L670: the clock estimate's step twin closer to 0 wins when it locks (trial T3 finding F1: a walkway
session on identical clocks read -0.582 s and warned, while its line said the estimate is the one closer to 0)."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.kernels.align import align_events, twin_line, unit_offset_message
from pdrlearn.steps.align import align_estimate
from pdrlearn.track.plasys import unit_offset_line

ROUTE = "stand:3, straight:12, turn:180, straight:12, turn:180, straight:12, stand:3"


def _trains(own_jitter_s: float = 0.01):
    """Foot strides (3 passes of 9) and lower-back contacts of both feet 0.57 s apart: the lower back misses 3 of the
    foot's own contacts and has the other foot's contact after each pass too, so offset 0 matches fewer foot events
    than -0.57 s (one step period off) does; its own contacts scatter uniformly by +-``own_jitter_s``."""
    rng = np.random.default_rng(0)
    foot = np.concatenate([t0 + 1.14 * np.arange(9) for t0 in (5.0, 20.0, 35.0)])
    own = np.delete(foot, [1, 10, 19])
    own = own + rng.uniform(-own_jitter_s, own_jitter_s, own.size)
    other = np.concatenate([foot - 0.57, foot[[8, 17, 26]] + 0.57]) + rng.normal(0, 0.01, 30)
    return foot, np.sort(np.concatenate([own, other]))


def test_the_twin_at_zero_wins_when_it_locks():
    foot, waist = _trains()
    est = align_events(foot, waist)
    assert abs(est["offset_s"]) < 0.05  # before: -0.57, one step period off
    assert unit_offset_message(est["offset_s"], est["drift"], estimate=est) is None
    assert twin_line(est) is None


def test_a_twin_that_does_not_lock_is_not_taken():
    foot, waist = _trains(own_jitter_s=0.11)  # the own contacts scatter 0.064 s (SD): over L183's 0.05 s lock
    est = align_events(foot, waist)
    assert est["offset_s"] == pytest.approx(-0.57, abs=0.03)


@pytest.fixture(scope="module")
def walkway(tmp_path_factory):
    """Trial T3's walkway session u12780_normal (three 12 m passes, no insoles), clocks identical and +0.3 s."""
    out = {}
    logging.disable(logging.WARNING)
    try:
        for off in (0.0, 0.3):
            d = tmp_path_factory.mktemp("t3") / f"u12780_{off}"
            assert main(["simulate", "--route", ROUTE, "--speed", "normal", "--rate", "100", "--rocker", "smooth",
                         "--user-seed", "12780", "--clock-offset", str(off), "--out", str(d)]) == 0
            for f in d.glob("fForce*.csv"):
                f.unlink()
            out[off] = read_session(d)
    finally:
        logging.disable(logging.NOTSET)
    return out


def test_t3_walkway_on_identical_clocks_reads_zero_and_does_not_warn(walkway):
    est = align_estimate(walkway[0.0])
    assert abs(est["offset_s"]) < 0.05  # before: -0.582
    assert unit_offset_line(walkway[0.0]) is None


def test_t3_walkway_offset_by_a_third_of_a_second_still_warns(walkway):
    line = unit_offset_line(walkway[0.3])
    assert line is not None and "decision L161" in line
