"""Decisions L393-L396 and B298 (session 33, review R2 findings 2, 3, 4, 6 and 7): a ride before a foot track's first
stride and after the last step, a window's rides, the foot's barometer line beside L378's rides, and a barometer gap
inside a ride. Simulated users 7460-7479 (seed = user)."""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.io.session import Stream
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import track_summary

LIFT_MID = "straight:10, stand:5, lift:+9, stand:5, straight:10, stand:20, straight:10"


def _sim(route: str, user: int):
    return simulate_path(parse_route(route), UserProfile.from_seed(user), seed=user, scenario="route")


def _track(session, unit: str):
    if unit == "waist":
        from pdrlearn.track.waist import track_waist

        r = track_waist(session, pipeline="waist-pendulum")
        return r, track_summary(r, session, pipeline="waist-pendulum")
    from pdrlearn.track.plasys import track_plasys

    r = track_plasys(session)
    return r, track_summary(r, session)


def test_a_foot_track_reads_a_ride_before_its_first_stride_l393():
    """L393: the lift before the first stride is the foot's ride too, and the reference's floors hold it (before:
    rides.csv empty, floors down 0, floors_down_ref 0)."""
    r, m = _track(_sim("stand:3, lift:-9, stand:3, straight:10", 7460), "foot")
    assert (m["n_rides"], m["floors_down"], m["floors_down_rides"], m["floors_down_ref"]) == (1, 3, 3, 3), m
    assert r.info["rides"][0]["kind"] == "lift" and r.info["rides"][0]["dz_m"] == pytest.approx(-9.0, abs=0.3)


@pytest.mark.parametrize("unit", ["foot", "waist"])
def test_a_ride_after_the_last_step_is_read_l394(unit):
    """L394: the lift after the last step is a ride (row n, no step) and counts its storeys, the reference's too
    (before: none, floors_up_ref 0)."""
    r, m = _track(_sim("straight:10, stand:3, lift:+9, stand:5", 7461), unit)
    assert (m["n_rides"], m["floors_up"], m["floors_up_rides"], m["floors_up_ref"]) == (1, 3, 3, 3), m
    assert r.info["rides"][0]["row"] == len(r.steps) and r.info["rides"][0]["kind"] == "lift"


@pytest.mark.parametrize("window, rides, up", [("0,24", 0, 0), ("30,80", 0, 0), ("0,80", 1, 3)])
def test_a_windows_rides_are_those_inside_it_l395(tmp_path, window, rides, up):
    """L395: rides.csv and n_rides list the rides whose standstill lies inside the window, and the floors agree
    (before: the lift at ~22-27 s listed for 0,24 and 30,80, and 30,80 counted floors up 3)."""
    from pdrlearn.cli import main
    from pdrlearn.io import write_session

    write_session(_sim(LIFT_MID, 7462), tmp_path / "s")
    out = tmp_path / "t"
    assert main(["track", "--no-plot", str(tmp_path / "s"), "--units", "waist", "--window", window, "--out",
                 str(out)]) == 0
    m = json.loads((out / "summary.json").read_text())
    assert len(pd.read_csv(out / "rides.csv")) == rides == m["n_rides"]
    assert (m["floors_up"], m["floors_up_rides"]) == (up, up), m
    steps = pd.read_csv(out / "steps.csv", keep_default_na=False)
    assert int((steps["ride"].astype(str) != "").sum()) == rides


def test_the_foot_barometer_line_leaves_the_rides_out_l396():
    """L396: escalator +6 m and a 17-stair flight: the foot's +2.9 m against the barometer's +8.8 m less the ride's
    +6 m agrees, so no L145 line (before: "disagrees ... wBarometer.csv, not read by foot tracks" by 5.9 m)."""
    from pdrlearn.track.evaluate import barometer_warning

    s = _sim("straight:10, stand:3, escalator:+6, stand:2, straight:10, up:17", 7463)
    r, m = _track(s, "foot")
    assert m["n_rides"] == 1 and (m["floors_up_stairs"], m["floors_up_rides"]) == (1, 2), m
    assert barometer_warning({**m, "info": r.info}) is None
    assert not any("not read by foot tracks" in w for w in m["info"].get("warnings", []))
    # the line, when a foot disagrees beyond the rides, names the barometer as read for rides only
    line = barometer_warning({**m, "altitude_change_m": -3.0, "info": r.info})
    assert line and "read for rides only, L378" in line and "L396" in line


def test_a_barometer_gap_inside_a_ride_is_said_b298():
    """B298: 8 s of wBarometer rows removed across the lift: one line names wBarometer.csv, the ride and the gap
    (before: interpolated silently); the whole barometer says none."""
    s = _sim(LIFT_MID, 7464)
    r, _ = _track(s, "waist")
    assert not any("B298" in w for w in r.info["warnings"])
    ride = r.info["rides"][0]
    b = s["wBarometer"]
    mid = 0.5 * (ride["start_s"] + ride["end_s"])
    keep = np.abs(b.t - mid) > 4.0
    gapped = dataclasses.replace(s, streams={**s.streams, "wBarometer": Stream("wBarometer", b.t[keep],
                                                                              b.values[keep])})
    r, _ = _track(gapped, "waist")
    lines = [w for w in r.info["warnings"] if "B298" in w]
    assert len(lines) == 1 and "wBarometer.csv" in lines[0] and "ride 1" in lines[0] and "gap of 8" in lines[0]


def test_a_ride_after_the_last_step_counts_in_its_period_l394(tmp_path):
    """L394 with L277: periods.csv's floors add up to the summary's with a ride after the last step (before: the
    summary's 3 up, the periods' 0)."""
    from pdrlearn.cli import main
    from pdrlearn.io import write_session

    write_session(_sim("straight:10, stand:3, lift:+9, stand:5", 7461), tmp_path / "s")
    out = tmp_path / "t"
    assert main(["track", "--no-plot", str(tmp_path / "s"), "--units", "waist", "--per", "20", "--out", str(out)]) == 0
    m = json.loads((out / "summary.json").read_text())
    periods = pd.read_csv(out / "periods.csv")
    assert m["floors_up"] == 3 and int(periods["floors_up"].sum()) == 3, periods

