"""Session 51 (FK), trial s51t3: a lower-back unit clipped at the side of the waistband.
- W607: ``mount_frame="inferred"`` (``track --mount-frame inferred``) tracks a unit whose declared frame its data
  contradict with confidence (D10) in the frame the data give; the default keeps the declared frame; track-all says
  D10's line once (it was logged located and kept bare in the summary, W334).
- W609 (not adopted: PARAMS.json ``{"options": {"walked_ride": true}}``): a barometric "ride" between detected steps
  that shakes like walking is stairs with missed steps, not an escalator: rides.csv kind ``stairs``, its own line.
- W610: a walked climb beside L394's ride after the last step crashed the floor count."""

from __future__ import annotations

import logging
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli.cohort import job_warnings
from pdrlearn.cohort import JobResult
from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.io.session import Session
from pdrlearn.kernels.pause_ride import walked_ride
from pdrlearn.track.rides import ride_lines, ride_rows
from tests.frame_helpers import yawed_lower_back


@pytest.fixture(scope="module")
def yawed(tmp_path_factory) -> Path:
    """The mobgap lower-back recording turned 90 deg about its up axis (tests.frame_helpers)."""
    return yawed_lower_back(tmp_path_factory.mktemp("w607") / "w")


def test_mount_frame_inferred_uses_the_data_frame_w607(yawed, caplog):
    declared = read_session(yawed)
    with caplog.at_level(logging.WARNING):
        kept = declared.require_frame("waist")
    assert kept == declared.frames["waist"]  # the default: the declared frame, D10's line
    assert declared.frame_status("waist") == "contradicted" and not declared.frames_inferred
    d10 = [r.getMessage() for r in caplog.records if "is still used (decision D8)" in r.getMessage()]
    assert d10 and not any("--mount-frame" in m for m in d10)  # decision W615: read outside track / track-all
    caplog.clear()
    s = read_session(yawed)
    s.mount_frame = "inferred"
    with caplog.at_level(logging.WARNING):
        used = s.require_frame("waist")
        assert s.require_frame("waist") == used
    lines = [r.getMessage() for r in caplog.records if "W607" in r.getMessage()]
    assert len(lines) == 1 and "the frame the data give is used instead" in lines[0]
    assert used != kept and used.to_dict()["y"] != kept.to_dict()["y"]  # the turned horizontal axes
    assert used.to_dict()["x"] == "up"  # the yaw keeps up
    assert s.frame_status("waist") == "inferred" and s.frames_inferred == {"waist": used.to_dict()}
    assert s.frame_checks()["waist"]["source"] == "inferred"


def test_mount_frame_is_checked_w607():
    with pytest.raises(DataError, match="mount_frame='sideways'"):
        Session("s", mount_frame="sideways")


def test_track_all_says_a_located_line_once_w607():
    text = "the waist unit's frame {...} contradicts its data ...; the meta.json frame is still used (decision D8)"
    r = JobResult("a", True, value={"warnings": ["d/a: other", f"d/a/meta.json: session 'a': {text}", text]})
    assert job_warnings(r, "d/a") == ["other", f"meta.json: session 'a': {text}"]  # C265: located in the folder


def _ride(shake: float, walked_kind: bool = True):
    """A 2 m descent between two detected steps (a 5 s standstill), the lower back shaking at 2 Hz by ``shake``
    m/s^2 (amplitude) during it."""
    fs = 100.0
    t = np.arange(0.0, 30.0, 1.0 / fs)
    dz = np.clip((t - 12.0) / 5.0, 0.0, 1.0) * -2.0
    p = 1013.25 * (1.0 - 2.25577e-5 * dz) ** 5.25588  # the standard atmosphere
    acc = np.tile([0.0, 9.81, 0.0], (len(t), 1))
    inside = (t > 11.5) & (t < 17.5)
    acc[inside, 1] += shake * np.sin(2 * np.pi * 2.0 * t[inside])
    steps = pd.DataFrame({"start_s": [10.5, 18.0], "end_s": [11.0, 18.5], "event_s": [10.5, 18.0]})
    z = np.array([0.0, 0.0, -2.0])
    kinds, rides = ride_rows(t, p, steps, 0.0, z, np.array([0.0, -2.0]), acc=(t, acc, "wAccelerometer"),
                             walked_kind=walked_kind)
    return kinds, rides


def test_a_shaking_descent_is_stairs_a_quiet_one_an_escalator_w609():
    assert walked_ride(1.64) and not walked_ride(0.99) and not walked_ride(float("nan"))
    kinds, rides = _ride(0.05)
    assert list(kinds) == ["", "escalator"] and rides[0]["horizontal_est_m"] > 3.0
    kinds, rides = _ride(2.5)
    assert list(kinds) == ["", "stairs"] and rides[0]["horizontal_est_m"] is None
    lines = ride_lines(rides)
    assert len(lines) == 1 and "decision W609" in lines[0] and "escalator ride(s)" not in lines[0]
    assert list(_ride(2.5, walked_kind=False)[0]) == ["", "escalator"]  # W609 not adopted: the option only


def test_a_walked_climb_and_a_ride_after_the_last_step_count_floors_w610():
    """W610: L394's ride after the last step lengthened the climb parts by a row and L302's kind of a walked climb
    crashed (shapes (40,) (41,)): trial s51t3's cut ending in a stair descent its steps missed."""
    from pdrlearn.track.evaluate import floors_by_kind

    n = 40
    dz = np.zeros(n)
    dz[5:23] = 0.17  # 18 stair steps up, 3.06 m
    st = pd.DataFrame({"unit": "waist", "start_s": np.arange(n) * 0.5, "end_s": np.arange(n) * 0.5 + 0.5, "dz_m": dz,
                       "pause_dz_m": np.zeros(n), "length_m": np.where(dz > 0, 0.3, 0.7), "ride": [""] * n,
                       "climb": dz > 0, "stairs": dz > 0})
    info = {"rides": [{"ride": 1, "row": n, "kind": "escalator", "dz_m": -4.0, "start_s": 30.0, "end_s": 45.0}]}
    got = floors_by_kind(st, 3.0, info)
    assert got["floors_up_stairs"] == 1 and got["floors_down_rides"] == 1


def test_d10_line_names_the_option_w607():
    from pdrlearn.io.frames import AxisFrame
    from pdrlearn.track.frame_inference import declared_frame_warning

    class Found:
        frame = AxisFrame(x="backward", y="up", z="left")

        def describe(self):
            return "measured"

    declared = AxisFrame(x="left", y="up", z="forward")
    line = declared_frame_warning("waist", declared, Found(), 'declared in "frames"', off={"forward": 92.0},
                                  command="track")  # decision W615: only a command that has the option names it
    assert "is still used (decision D8)" in line and "--mount-frame inferred, decision W607" in line
