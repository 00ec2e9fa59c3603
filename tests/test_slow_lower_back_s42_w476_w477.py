"""Session 42, trial T2 findings F5 and F6: a slow walker's lower-back contacts that W442 calls no step count give no
cadence (decision W476), `steps --detector waist-ic` runs the same count cross-check, and waist-pll's W208 line words
its direction from the numbers and judges both counts by the pelvic gyro's (decision W477)."""

from __future__ import annotations

import dataclasses
import logging

import pytest
from typer.testing import CliRunner

from pdrlearn.cli import app
from pdrlearn.cli.common import count_phrase
from pdrlearn.io import write_session
from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.sim.user import SPEED_FACTORS
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.plausibility import WITHHELD_STEP_KEYS, pll_missed_steps_message, uncountable_steps_line


@pytest.fixture(scope="module")
def slow():
    """W475's fresh user 11831 at 0.2 m every 1.2 s (50 steps/min), 6 m (30 steps), 50 Hz."""
    f_len, f_time = SPEED_FACTORS["normal"]
    u = dataclasses.replace(UserProfile.from_seed(11831), step_length_m=0.2 / f_len, step_time_s=1.2 / f_time)
    return simulate_path([Stand(2), Straight(6), Stand(2)], u, speed="normal", rate_hz=50, seed=11831,
                         bounce="pendulum", rocker="smooth")


def test_w442_contacts_withhold_the_cadence_and_step_times_w476(slow):
    r = track_waist(slow, pipeline="waist-pendulum")
    assert r.info["step_count_unusable"] is True  # measured: 77 contacts, the pelvic gyro 31 steps
    sm = r.summary(slow)
    assert all(sm[k] is None for k in WITHHELD_STEP_KEYS), {k: sm[k] for k in WITHHELD_STEP_KEYS}
    reason = sm["step_count_withheld"]
    assert "W476" in reason and f"{r.info['n_pelvic_gyro_steps']} steps" in reason and "steps/min" in reason
    assert count_phrase(sm).startswith(f"{sm['n_steps']} contacts (no step count, decision W476")


def test_steps_cli_runs_the_count_cross_check_w476(slow, tmp_path, caplog):
    folder = write_session(slow, tmp_path / "slow")
    with caplog.at_level(logging.WARNING):
        res = CliRunner().invoke(app, ["steps", str(folder), "--detector", "waist-ic"])
    assert res.exit_code == 0, res.output
    lines = [m for m in (*res.output.splitlines(), *(r.getMessage() for r in caplog.records)) if "W476" in m]
    assert len(set(lines)) == 1, lines
    assert uncountable_steps_line((40, 31), "waist-ic") is None  # within 1.5 x: W442 does not fire
    assert "W476" in uncountable_steps_line((77, 31), "waist-ic")


def test_pll_line_words_direction_and_judges_by_the_pelvic_gyro_w477():
    # trial T2's s2: pll 80, the pendulum 263, the pelvic gyro 37; pll's distance is the longer
    line = pll_missed_steps_message(80, 263, 61.52, 35.18, n_gyro=37)
    assert "longer than the pendulum's" in line and "read short" not in line
    assert "neither pipeline's count" in line and "track with --pipeline waist-pendulum" not in line
    # pll near the pelvic gyro, the pendulum doubled: keep waist-pll, no "misses steps"
    near = pll_missed_steps_message(34, 75, 8.92, 13.69, n_gyro=31)
    assert "keep --pipeline waist-pll" in near and "misses steps" not in near and "shorter than" in near
    # pll misses, the pendulum near the pelvic gyro: W208's advice stands
    missed = pll_missed_steps_message(10, 40, 3.0, 12.0, n_gyro=38)
    assert "misses steps" in missed and "track with --pipeline waist-pendulum" in missed
    assert "W477" not in pll_missed_steps_message(10, 40, 3.0, 12.0)  # no gyroscope: W208's line


def test_pll_track_line_names_the_pelvic_count_w477(slow):
    r = track_waist(slow, pipeline="waist-pll")
    line, = [w for w in r.info["warnings"] if "W208" in w]
    assert "decision W477" in line and "read short" not in line
