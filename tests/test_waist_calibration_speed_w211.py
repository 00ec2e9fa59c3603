"""Decision W211 (amends W140): a waist calibration applied at another walking speed warns in one line when the
track's median cadence is more than 10 % outside the calibration walks' cadence range (PARAMS.json
``gait.cadence_range_spm``); a multi-speed calibration covers the speeds between."""

from __future__ import annotations

import dataclasses
import json

import pytest

from pdrlearn.errors import DataError
from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.calibration import calibrate
from pdrlearn.waist.params import load_params
from pdrlearn.waist.plausibility import CALIBRATION_SPEED_MARGIN, calibration_gait, calibration_speed_message

ROUTE = [Stand(2), Straight(12), Stand(2)]


def _walk(v: float, seed: int):
    length = 0.42 + 0.3 * (v - 0.6)  # the trial's speed sweep (trial lab)
    user = dataclasses.replace(UserProfile.from_seed(4968), step_length_m=length, step_time_s=length / v)
    return simulate_path(ROUTE, user, speed="normal", rate_hz=100, seed=seed, bounce="pendulum")


def _w211(r) -> list[str]:
    return [w for w in r.info["warnings"] if "decision W211" in w]


def test_the_range_and_the_message():
    gait = calibration_gait([2.0, 2.0, 1.5, 1.5], 4.0, [[2.0, 2.0], [1.5, 1.5]])
    assert gait["cadence_range_spm"] == [90.0, 120.0]
    m = CALIBRATION_SPEED_MARGIN
    assert calibration_speed_message(gait, 90.0 * (1 - m) * 1.01, 30, "waist-pendulum") is None
    assert calibration_speed_message(gait, 120.0 * (1 + m) * 0.99, 30, "waist-pendulum") is None
    assert calibration_speed_message(gait, 150.0, 9, "waist-pendulum") is None  # too few steps
    line = calibration_speed_message(gait, 140.0, 30, "waist-pendulum")
    assert "90-120 steps/min" in line and "calibrate SLOW NORMAL FAST" in line and "\n" not in line
    old = {"median_cadence_spm": 111.0, "speed_mps": 1.0}  # a file from before W211: its median, both ends
    assert calibration_speed_message(old, 112.0, 30, "waist-pendulum") is None
    assert "111 steps/min, 1.00 m/s" in calibration_speed_message(old, 143.0, 30, "waist-pendulum")


def test_a_calibration_at_one_speed_warns_at_another_and_not_at_its_own(tmp_path):
    params = calibrate([_walk(1.0, 1)], "waist-pendulum", distances=[12.0])
    path = params.save(tmp_path / "p.json")
    assert json.loads(path.read_text())["gait"]["cadence_range_spm"][0] == params.gait["cadence_range_spm"][0]
    fast = track_waist(_walk(2.0, 2), pipeline="waist-pendulum", params=str(path))
    (line,) = _w211(fast)
    assert "waist-pendulum calibration's" in line
    assert not _w211(track_waist(_walk(1.0, 2), pipeline="waist-pendulum", params=str(path)))
    assert not _w211(track_waist(_walk(2.0, 2), pipeline="waist-pendulum", params=str(path), speed_check=False))
    multi = calibrate([_walk(0.6, 1), _walk(2.0, 1)], "waist-pendulum", distances=[12.0, 12.0])
    lo, hi = multi.gait["cadence_range_spm"]
    assert lo < 0.8 * hi  # the two speeds' cadences, not one median
    assert not _w211(track_waist(_walk(1.4, 2), pipeline="waist-pendulum", params=multi))


def test_a_malformed_range_is_one_line(tmp_path):
    params = calibrate([_walk(1.0, 1)], "waist-pendulum", distances=[12.0])
    d = json.loads(params.save(tmp_path / "p.json").read_text())
    for bad in ([120.0, 90.0], "fast", [90.0]):
        d["gait"]["cadence_range_spm"] = bad
        (tmp_path / "bad.json").write_text(json.dumps(d))
        with pytest.raises(DataError, match="cadence_range_spm"):
            load_params(tmp_path / "bad.json")


def test_the_distance_help_names_both_walkway_conventions():
    """Decision W212: `calibrate --help` says what --distance is on a start-to-stop walkway."""
    from typer.testing import CliRunner

    from pdrlearn.cli import app

    out = CliRunner().invoke(app, ["calibrate", "--help"], env={"COLUMNS": "200"}).output
    assert "start-to-stop walkway" in " ".join(out.split()) and "W212" in out
