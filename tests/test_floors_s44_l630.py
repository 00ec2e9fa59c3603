"""Decisions L630-L634 (session 44, helper FA; trial T3 findings F1, F3, F6): trajectory.csv's ride-inclusive altitude
(z_rides) and floor, the GPX / GeoJSON elevation and final_altitude_error_m with the rides, the barometer lines that
leave out rides.csv's lifts, one line where two said the same, and `--units foot` keeping the barometer for rides.
Simulated users 12240-12245 (seed = user)."""

from __future__ import annotations

import json
import re

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route

#: one storey up by a U-shaped stairwell (20 stairs of 0.17 m = 3.4 m), then a lift two storeys down
ROUTE = "stand:5, straight:8, up:10, curve:180:0.6, up:10, straight:6, stand:3, lift:-6.8, stand:3, straight:8, stand:3"
STOREY = "3.4"


@pytest.fixture(scope="module")
def session_dir(tmp_path_factory):
    d = tmp_path_factory.mktemp("l630") / "lift"
    write_session(simulate_path(parse_route(ROUTE), UserProfile.from_seed(12240), seed=12240, scenario="route"), d)
    return d


def _track(session_dir, out, *extra):
    assert main(["track", str(session_dir), "--storey-height", STOREY, "--no-plot", "--out", str(out), *extra]) == 0
    return (pd.read_csv(out / "trajectory.csv"), json.loads((out / "summary.json").read_text()),
            pd.read_csv(out / "rides.csv"))


def test_trajectory_has_the_ride_inclusive_altitude_and_floor_l630_l631(session_dir, tmp_path, capsys):
    """L630 / L631: z stays the strides' height (ends one storey up); z_rides adds the lift (ends one storey down, as
    the truth); floor steps 0 -> +1 -> -1 and ends on the summary's end floor; the elevation of track.gpx /
    track.geojson is z_rides; final_altitude_error_m compares it (main: z ended +3.51 m, final_altitude_error_m 6.91,
    no floor column; now 0.08)."""
    traj, summary, rides = _track(session_dir, tmp_path / "t", "--start", "41.178,-8.598,100")
    printed = capsys.readouterr().out
    assert len(rides) == 1 and rides["kind"][0] == "lift"
    dz = float(rides["dz_m"][0])
    assert dz == pytest.approx(-6.8, abs=0.4)
    assert traj["z"].iloc[-1] - 100 == pytest.approx(3.4, abs=0.5)  # the strides' height, as before
    np.testing.assert_allclose(traj["z_rides"], traj["z"] + np.where(traj["t"] >= rides["end_s"][0], dz, 0.0))
    assert traj["z_rides"].iloc[-1] - 100 == pytest.approx(-3.4, abs=0.6)
    floors = traj["floor"].tolist()
    assert [f for i, f in enumerate(floors) if i == 0 or f != floors[i - 1]] == [0, 1, -1]
    assert floors[-1] == summary["storeys_changed"] == -1
    assert summary["altitude_change_rides_m"] == pytest.approx(summary["altitude_change_m"] + dz)
    assert summary["final_altitude_error_m"] < 0.6
    assert "m with its rides (rides.csv; trajectory.csv z_rides, L630)" in printed
    gpx = (tmp_path / "t" / "track.gpx").read_text()
    ele = [float(v) for v in re.findall(r"<trkpt[^>]*>\s*<ele>([-0-9.]+)</ele>", gpx)]
    assert ele and ele[-1] == pytest.approx(traj["z_rides"].iloc[-1], abs=0.01)
    line = json.loads((tmp_path / "t" / "track.geojson").read_text())["features"][0]["geometry"]["coordinates"]
    assert line[-1][-1] == pytest.approx(traj["z_rides"].iloc[-1], abs=0.01)


def test_a_fused_track_subtracts_its_rides_and_sends_no_one_to_the_lower_back_l632(session_dir, tmp_path, capsys):
    """L632: `--altitude fused` keeps the lift out of z as the foot does; its barometer line left the rides in and
    sent the user to `--pipeline waist-pendulum` (main: "foot altitude change +3.20 m disagrees with the waist
    barometer's -3.47 m")."""
    traj, summary, _ = _track(session_dir, tmp_path / "f", "--altitude", "fused")
    err = capsys.readouterr().err
    assert "disagrees with the waist barometer" not in err, err
    assert "--pipeline waist-pendulum`" not in err
    assert traj["floor"].iloc[-1] == summary["storeys_changed"] == -1


def test_units_foot_keeps_the_barometer_for_rides_l634(session_dir, tmp_path):
    """L634: `--units foot` leaves the waist's motion out, not its barometer: the lift is read and the end floor is
    right (main: no rides.csv row, end floor +1)."""
    traj, summary, rides = _track(session_dir, tmp_path / "u", "--units", "foot")
    assert len(rides) == 1 and rides["kind"][0] == "lift"
    assert summary["storeys_changed"] == -1 and traj["floor"].iloc[-1] == -1


def _summary(**kw):
    base = {"barometer_unused": True, "grade_source": None, "barometer_ascent_m": 0.0, "barometer_descent_m": 6.82,
            "flights_rise_m": 0.0, "flights_drop_m": 0.0, "info": {"rides": [{"dz_m": -6.82, "kind": "lift"}]}}
    return {**base, **kw}


def test_the_ramps_line_leaves_out_the_rides_l632():
    """L632: L602's line counts no lift that rides.csv holds (main: "descended 6.82 m ... ramps / grades need
    --altitude fused" for T3's lift); a descent the rides do not explain still warns, naming both."""
    from pdrlearn.track.evaluate import ramps_need_fused_warning

    assert ramps_need_fused_warning(_summary()) is None
    line = ramps_need_fused_warning(_summary(barometer_descent_m=8.82, flights_drop_m=1.0))
    assert line is not None and "(0.00 m / 1.00 m more than stairs.csv's flights and rides.csv's rides" in line
    # L624's vibration rides have no height: they subtract none
    assert ramps_need_fused_warning(_summary(info={"rides": [{"dz_m": float("nan"), "kind": "vehicle"}]}))


def test_one_line_when_both_barometer_checks_fire_l632():
    """L632: where L145 / L180's line fires (it names lifts and ramps, and `--altitude fused`), L602's says nothing
    more (main, `--streaming` on T3's lifts: two lines on the same 7.7 m)."""
    from pdrlearn.track.evaluate import barometer_warning, ramps_need_fused_warning

    s = _summary(info={}, barometer_ascent_m=7.52, barometer_descent_m=7.44, ascent_m=0.0, descent_m=0.0,
                 barometer_altitude_change_m=0.08, barometer_climb_change_m=0.08, altitude_change_m=0.0,
                 barometer_disagree_limit_m=0.56)
    assert barometer_warning(s) is not None and "--altitude fused" in barometer_warning(s)
    assert ramps_need_fused_warning(s) is None
    alone = {k: v for k, v in s.items() if k not in ("ascent_m", "descent_m", "altitude_change_m")}
    assert barometer_warning(alone) is None and ramps_need_fused_warning(alone) is not None


def test_floor_levels_is_count_floors_rule():
    """L631: the per-row band rule (the floor column's fallback) is the one count_floors counts on."""
    from pdrlearn.track.evaluate import count_floors, floor_levels

    z = np.array([0.0, 1.0, 1.6, 2.9, 3.1, 1.5, np.nan, -0.2, -3.0, -5.9])
    assert floor_levels(z, 3.0).tolist() == [0, 0, 0, 1, 1, 1, 1, 0, -1, -2]
    assert count_floors(z, 3.0) == (1, 3, -2)


def test_a_row_inside_a_climb_takes_the_storeys_climbed_so_far_l631():
    """L631: inside a walking climb the floor is the storeys its height has climbed, rounded and within the climb's
    (ipin3 of trial T3: 7 of 95 waypoints on the wrong floor when the floor changed only at the climb's end, 4 so)."""
    from pdrlearn.track.floor_column import climb_floor

    t = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0]
    assert climb_floor(t, [0, 0, 1, 2, 3, 3], [(1.0, 4.0, 1)], 3.0).tolist() == [0, 0, 0, 1, 1, 1]
    assert climb_floor(t, [0, 0, -1, -5, -3, -3], [(1.0, 4.0, -1)], 3.0).tolist() == [0, 0, 0, -1, -1, -1]
    assert climb_floor(t, [0, 0, 0, 0, 0, 0], [(2.0, 2.0, -2)], 3.0).tolist() == [0, 0, -2, -2, -2, -2]  # a ride
