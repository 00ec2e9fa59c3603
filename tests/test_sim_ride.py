"""Decisions S45 / S46: lift and escalator rides (route items ``lift:H``, ``escalator:H``) and trolley walking
(``trolley:M``) in the simulator."""

from __future__ import annotations

import hashlib
import json
import math
import pathlib

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import read_session, write_session
from pdrlearn.sim import Escalator, Lift, Straight, Trolley, UserProfile, simulate_path
from pdrlearn.sim.ride import (
    ESCALATOR_FLAT_M,
    ESCALATOR_RADIUS_M,
    ESCALATOR_SPEED_MPS,
    LIFT_ACC_MPS2,
    LIFT_SPEED_MPS,
)
from pdrlearn.sim.route import parse_route

#: the route of :func:`test_routes_without_rides_are_byte_identical`: every older route item
OLD_ROUTE = "stand:2, straight:6, up:5, pivot:90, slope:4:8, turn:-90, down:5, sit:2, backward:3, curve:45:3, stand:2"
#: SHA-256 over every file of the written sessions, computed on main (9497e78e) before S45 / S46
OLD_DIGESTS = {
    (3330, 20.0, 1): "a4f2066b56977f91ca1356e44fa3473e36578156d9d6a1c7ec27572ae0896196",
    (3331, 100.0, 2): "85711b9f10920d36397487a2826b0f7daa64700e4d912a10c31628007e093ee5",
}


def _digest(session, folder: pathlib.Path) -> str:
    write_session(session, folder)
    h = hashlib.sha256()
    for p in sorted(folder.rglob("*")):
        if p.is_file():
            h.update(str(p.relative_to(folder)).encode())
            h.update(p.read_bytes())
    return h.hexdigest()


@pytest.mark.parametrize("key", list(OLD_DIGESTS))
def test_routes_without_rides_are_byte_identical(tmp_path, key):
    """S45 / S46: a route of the older items (stairs, pivot, slope, turn, sit, backward, curve) writes the same
    bytes as before the rides and the trolley existed (no new random draw, no new file or column)."""
    user, rate, seed = key
    s = simulate_path(parse_route(OLD_ROUTE), UserProfile.from_seed(user), rate_hz=rate, seed=seed, scenario="route")
    assert "rides" not in s.extras
    assert _digest(s, tmp_path / "s") == OLD_DIGESTS[key]


def test_route_items_parse():
    segs = parse_route("lift:+9, lift:-3.5, escalator:+6, escalator:-4, trolley:12, trolley:5:short")
    assert segs == [Lift(9.0), Lift(-3.5), Escalator(6.0), Escalator(-4.0), Trolley(12.0), Trolley(5.0, "short")]


@pytest.mark.parametrize("item, words", [
    ("lift:0", "non-zero"), ("lift:400", "up to 300"), ("lift:up", "not a number"), ("lift:3:4", "takes 1"),
    ("escalator:0.5", "at least 1"), ("escalator:-61", "up to 60"), ("escalator", "takes 1"),
    ("trolley:-3", "positive"), ("trolley:3:brisk", "gait"),
])
def test_bad_route_items_are_one_line(item, words):
    with pytest.raises(DataError) as e:
        parse_route(f"straight:3, {item}")
    assert words in str(e.value) and item in str(e.value) and "\n" not in str(e.value)


@pytest.mark.parametrize("seg", [Lift(float("nan")), Lift(0.0), Escalator(0.2), Escalator(math.inf)])
def test_bad_python_segments_are_one_line(seg):
    with pytest.raises(DataError) as e:
        simulate_path([Straight(2.0), seg], UserProfile.from_seed(3350), noise=False)
    assert "rise" in str(e.value) and "\n" not in str(e.value)


def _ride_window(s, row):
    tr, ft = s.trajectory, s.extras["foot_trajectory"]
    inside = ((tr["t"] >= row.start_s) & (tr["t"] <= row.end_s)).to_numpy()
    return tr, ft, inside


def _kinematics(xyz: np.ndarray, dt: float) -> tuple[np.ndarray, np.ndarray]:
    v = np.gradient(xyz, dt, axis=0)
    return v, np.gradient(v, dt, axis=0)


@pytest.mark.parametrize("rise", [30.0, -3.0])
def test_a_lift_rides_its_height_without_a_step(rise):
    """Exact physics (no noise), 100 Hz: the waist and the foot rise by H inside the ride and stay put outside it;
    the speed stays under the rated 1-2.5 m/s (a 3 m ride does not reach it) and the acceleration within 0.5-1 m/s^2;
    no contact in the ride (or within a second of it); the feet do not move horizontally; the strides are level."""
    user = UserProfile.from_seed(3350)
    s = simulate_path([Straight(4.0), Lift(rise), Straight(4.0)], user, rate_hz=100.0, seed=0, noise=False)
    rides = s.extras["rides"]
    assert len(rides) == 1
    row = rides.iloc[0]
    assert row.kind == "lift" and row.dz_m == pytest.approx(rise) and row.dx_m == 0 and row.dy_m == 0
    tr, ft, inside = _ride_window(s, row)
    for track in (tr, ft):
        z, t = track["z"].to_numpy(), track.iloc[:, 0].to_numpy()
        assert z[t > row.end_s][0] - z[t < row.start_s][-1] == pytest.approx(rise, abs=1e-3)  # standing either side
        zi = z[inside]
        assert zi[-1] - zi[0] == pytest.approx(rise, abs=0.02)
        xy = track[["x", "y"]].to_numpy()[inside]
        assert np.ptp(xy, axis=0).max() < 0.03  # the standing walker's sway only (none on the foot)
    v, a = _kinematics(tr[["x", "y", "z"]].to_numpy()[inside], 0.01)
    vz = np.abs(v[:, 2]).max()
    az = np.abs(a[2:-2, 2]).max()
    print(f"lift {rise:+.0f} m: speed {vz:.3f} m/s (table {row.speed_mps}), acceleration {az:.3f} m/s^2")
    assert vz == pytest.approx(row.speed_mps, rel=0.02) and vz <= LIFT_SPEED_MPS[1] + 0.01
    assert LIFT_ACC_MPS2[0] - 0.02 <= az <= LIFT_ACC_MPS2[1] + 0.02
    if abs(rise) >= 30:
        assert vz >= LIFT_SPEED_MPS[0] - 0.01
    else:  # the ramps up and down cover pi v^2 / (2 a) = H: a 3 m ride peaks below the rated speed
        assert vz == pytest.approx(math.sqrt(2 * row.acc_mps2 * abs(rise) / math.pi), rel=0.02)
    ics = s.extras["ics"]["ic_s"].to_numpy()
    assert not np.any((ics > row.start_s - 1.0) & (ics < row.end_s + 1.0))
    assert s.steps["height_m"].abs().max() < 0.02 and set(s.steps["terrain"]) == {"flat"}
    # the waist accelerometer feels the ride: |specific force| departs from g by the lift's acceleration
    acc = s.streams["wAccelerometer"]
    m = (acc.t >= row.start_s) & (acc.t <= row.end_s)
    g = np.linalg.norm(acc.values[m], axis=1)
    assert np.abs(g - 9.80665).max() == pytest.approx(row.acc_mps2, abs=0.1)
    gyr = s.streams["fGyroscope"]
    assert np.abs(gyr.values[(gyr.t >= row.start_s) & (gyr.t <= row.end_s)]).max() < 1e-6  # the foot does not turn


def test_an_escalator_travels_forward_and_up_at_half_a_metre_per_second():
    """Exact physics: heading 45 deg, +6 m: the ride moves along the heading by the landings, transitions and the
    30 deg incline (horizontal 6 m / tan 30 deg - the transitions' shortening + 2 x 0.8 m), rises 6 m, at 0.5 m/s
    along the path (vertical 0.25 m/s on the incline), with no contact; the strides stay level."""
    user = UserProfile.from_seed(3351)
    s = simulate_path([Straight(3.0), Escalator(6.0), Straight(3.0)], user, rate_hz=100.0, seed=0, noise=False,
                      heading0_deg=45.0)
    row = s.extras["rides"].iloc[0]
    th, r = math.radians(30), ESCALATOR_RADIUS_M
    incline = (6.0 - 2 * r * (1 - math.cos(th))) / math.sin(th)
    horizontal = 2 * ESCALATOR_FLAT_M + 2 * r * math.sin(th) + incline * math.cos(th)
    assert row.kind == "escalator" and row.dz_m == pytest.approx(6.0)
    assert math.hypot(row.dx_m, row.dy_m) == pytest.approx(horizontal, abs=1e-6)
    assert math.degrees(math.atan2(row.dy_m, row.dx_m)) == pytest.approx(45.0, abs=1e-6)
    tr, ft, inside = _ride_window(s, row)
    for track in (tr, ft):
        p = track[["x", "y", "z"]].to_numpy()[inside]
        assert p[-1] - p[0] == pytest.approx([row.dx_m, row.dy_m, row.dz_m], abs=0.02)
    v, _ = _kinematics(ft[["x", "y", "z"]].to_numpy()[inside], 0.01)
    speed = np.linalg.norm(v, axis=1)
    assert speed.max() == pytest.approx(ESCALATOR_SPEED_MPS, abs=0.005)
    assert v[:, 2].max() == pytest.approx(ESCALATOR_SPEED_MPS * math.sin(th), abs=0.005)
    ics = s.extras["ics"]["ic_s"].to_numpy()
    assert not np.any((ics > row.start_s - 1.0) & (ics < row.end_s + 1.0))
    assert set(s.steps["terrain"]) == {"flat"}


def test_trolley_walking_halves_the_pelvic_rotation_and_leaves_the_foot():
    """S46: the same walk pushing a trolley: the foot's streams are the same bytes (no new draw), the waist
    heading's oscillation (the pelvic rotation, exact physics) is half the free walk's (0.5 +- 0.1)."""
    user = UserProfile.from_seed(3352)
    kw = dict(rate_hz=100.0, seed=0, noise=False)
    free = simulate_path([Straight(20.0)], user, **kw)
    push = simulate_path([Trolley(20.0)], user, **kw)
    for name in ("fAccelerometer", "fGyroscope"):
        assert np.array_equal(free.streams[name].values, push.streams[name].values)

    def wobble(s):
        tr = s.trajectory
        t0, t1 = s.steps["ic_s"].iloc[2], s.steps["ic_s"].iloc[-3]  # the steady strides
        h = np.unwrap(tr["heading_rad"].to_numpy()[((tr["t"] > t0) & (tr["t"] < t1)).to_numpy()])
        return float(np.std(h - h.mean()))

    ratio = wobble(push) / wobble(free)
    print(f"user 3352: waist heading oscillation, trolley / free = {ratio:.3f}")
    assert ratio == pytest.approx(0.5, abs=0.1)


def test_cli_writes_the_rides(tmp_path, capsys):
    out = tmp_path / "mall"
    code = main(["simulate", "--route", "straight:5, lift:+9, trolley:10, escalator:-9, straight:5",
                 "--user-seed", "3353", "--out", str(out), "--json"])
    assert code == 0
    assert json.loads(capsys.readouterr().out)["route"].startswith("straight:5, lift")
    s = read_session(out)
    rides = s.extras["rides"]
    assert list(rides["kind"]) == ["lift", "escalator"]
    assert list(rides["dz_m"]) == [9.0, -9.0]
    z = s.trajectory["z"].to_numpy()
    t = s.trajectory["t"].to_numpy()
    lift = rides.iloc[0]
    assert z[t > lift.end_s + 0.5][0] - z[t < lift.start_s - 0.5][-1] == pytest.approx(9.0, abs=0.1)
    assert abs(z[-1] - z[0]) < 0.1  # up 9 m by lift, down 9 m by escalator


def test_rides_warn_on_the_foot_and_the_waist_counts_them():
    """Decisions L192 / L193 / S47 on simulated rides (user 3354, seed = user, offline, no model): a lift up gives
    L145's net line, an escalator up and back down L180's climb line (the foot's height integrates strides only); the
    waist-pendulum track's barometric altitude follows the lift (within 0.3 m) and counts its three storeys; the
    foot's horizontal error on an escalator ride is the ride's horizontal travel (dead reckoning cannot see it);
    the altitude reference of a ride session is the trajectory's (S47), not the strides' 0."""
    from pdrlearn.track.evaluate import barometer_warning, track_summary
    from pdrlearn.track.plasys import track_plasys
    from pdrlearn.track.waist import track_waist

    user = UserProfile.from_seed(3354)
    lift = simulate_path(parse_route("straight:10, lift:+9, straight:10"), user, seed=3354, scenario="route")
    foot = track_summary(track_plasys(lift), lift)
    assert "disagrees with the waist barometer" in barometer_warning(foot)
    assert foot["altitude_change_ref_m"] == pytest.approx(9.0, abs=0.2)
    assert foot["altitude_ref_source"].startswith("trajectory.csv")
    waist = track_summary(track_waist(lift, pipeline="waist-pendulum"), lift, pipeline="waist-pendulum")
    print(f"lift: foot altitude {foot['altitude_change_m']:+.2f} m, waist {waist['altitude_change_m']:+.2f} m "
          f"(truth {waist['altitude_change_ref_m']:+.2f}), waist floors up {waist['floors_up']} "
          f"(reference {waist['floors_up_ref']})")
    assert waist["altitude_change_m"] == pytest.approx(waist["altitude_change_ref_m"], abs=0.3)
    assert waist["floors_up"] == 3 == waist["floors_up_ref"]
    esc = simulate_path(parse_route("straight:10, escalator:+6, straight:5, turn:180, escalator:-6, straight:10"),
                        user, seed=3354, scenario="route")
    m = track_summary(track_plasys(esc), esc)
    line = barometer_warning(m)
    assert "L180" in line and "misses" in line and "although the net changes agree" in line
    up = simulate_path(parse_route("straight:10, escalator:+6, straight:10"), user, seed=3354, scenario="route")
    m = track_summary(track_plasys(up), up)
    travel = float(np.hypot(up.extras["rides"]["dx_m"].iloc[0], up.extras["rides"]["dy_m"].iloc[0]))
    print(f"escalator +6 m: foot horizontal error {m['final_position_error_m']:.2f} m, ride travel {travel:.2f} m")
    assert m["final_position_error_m"] == pytest.approx(travel, abs=1.5)


@pytest.mark.parametrize("item", ["lift:0", "escalator:90", "trolley:x"])
def test_bad_cli_route_items_are_one_line(tmp_path, capsys, item):
    out = tmp_path / "bad"
    assert main(["simulate", "--route", f"straight:3, {item}", "--user-seed", "3355", "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("error: --route item") and item in err and "\n" not in err and "Traceback" not in err
    assert not out.exists()


def test_cli_help_names_the_ride_items(capsys):
    assert main(["simulate", "--help"]) == 0
    text = " ".join(capsys.readouterr().out.replace("\u2502", " ").split())
    assert "'lift:+9'" in text and "'escalator:+6'" in text and "'trolley:20'" in text and "escalator:-9" in text


def test_rides_in_parts_give_the_whole_grid_session(monkeypatch):
    """S44 with S45 / S46: the ride's offset and sway and the trolley's gain are pointwise in time, so parts of 1000
    samples of the 500 Hz grid give the whole grid's streams exactly (user 3356)."""
    from tests.sim_helpers import whole_and_parts

    route = parse_route("straight:3, lift:+6, trolley:4, escalator:-2")
    whole, parts = whole_and_parts(monkeypatch, route, UserProfile.from_seed(3356), 100.0, 2)
    assert np.array_equal(whole.trajectory.to_numpy(), parts.trajectory.to_numpy())
