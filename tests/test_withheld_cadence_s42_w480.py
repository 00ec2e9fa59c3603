"""Decision W480 (session 42, fixer FT, review R2 finding 3): when W442 finds a lower-back track's contacts no step
count, W476 withholds its cadence in summary.json, but bouts.csv still gave each bout's contact cadence (126.8
steps/min; the pelvic gyro: 52.6) and L95's slow line quoted the withheld median cadence ("median cadence 133
steps/min ... slower than the walking the pipelines were validated on"). Both now leave that cadence out."""

from __future__ import annotations

import dataclasses
import json
import logging

import pandas as pd
import pytest
from typer.testing import CliRunner

from pdrlearn.cli import app
from pdrlearn.io import write_session
from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.sim.user import SPEED_FACTORS
from pdrlearn.track.gait import gait_range_warning


@pytest.fixture(scope="module")
def slow_folder(tmp_path_factory):
    """test_slow_lower_back_s42_w476_w477's slow walker (0.2 m every 1.2 s, 50 Hz) with user 11882 (review R2)."""
    f_len, f_time = SPEED_FACTORS["normal"]
    u = dataclasses.replace(UserProfile.from_seed(11882), step_length_m=0.2 / f_len, step_time_s=1.2 / f_time)
    s = simulate_path([Stand(2), Straight(6), Stand(2)], u, speed="normal", rate_hz=50, seed=11882,
                      bounce="pendulum", rocker="smooth")
    return write_session(s, tmp_path_factory.mktemp("w480") / "slow")


def test_bouts_csv_gives_no_contact_cadence_when_the_step_count_is_withheld(slow_folder, tmp_path, caplog):
    out = tmp_path / "t"
    with caplog.at_level(logging.WARNING):
        res = CliRunner().invoke(app, ["track", str(slow_folder), "--pipeline", "waist-pendulum", "--out", str(out),
                                       "--no-plot"])
    assert res.exit_code == 0, res.output
    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    assert summary["step_count_withheld"] and summary["median_cadence_spm"] is None  # W476 fired
    bouts = pd.read_csv(out / "bouts.csv")
    assert len(bouts) >= 1 and bouts["cadence_spm"].isna().all(), bouts["cadence_spm"].tolist()
    lines = [m for m in (*res.output.splitlines(), *(r.getMessage() for r in caplog.records)) if "L95" in m]
    assert lines and not any("median cadence" in m for m in lines), lines


def test_slow_line_judges_and_quotes_the_speed_alone_when_the_count_is_withheld():
    summary = {"median_cadence_spm": 133.0, "median_speed_mps": 0.3, "info": {"step_count_unusable": True}}
    line = gait_range_warning(summary)
    assert line is not None and "speed 0.30 m/s" in line and "cadence" not in line.split(":")[0], line
    # a slow cadence alone is the contacts' (no step count): no line; without W442 the same figures warn
    assert gait_range_warning({**summary, "median_cadence_spm": 40.0, "median_speed_mps": 1.2}) is None
    assert "median cadence 40" in gait_range_warning({"median_cadence_spm": 40.0, "median_speed_mps": 1.2})
