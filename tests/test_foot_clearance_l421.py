"""Decision L421: the foot track's per-stride sensor lift and sole angles (gaitmap's max_sensor_lift, ic_angle,
tc_angle) against the simulator's truth, and the kernels on known shapes."""

import numpy as np
import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.plasys import track_plasys


def test_max_lift_is_the_height_above_the_line_between_the_rests():
    from pdrlearn.kernels.clearance import max_lift

    s = np.linspace(0.0, 1.0, 101)
    level = np.column_stack([1.4 * s, 0.0 * s, 0.12 * np.sin(np.pi * s)])  # a 12 cm arc, level
    stair = level.copy()
    stair[:, 2] += -0.3 * s  # the same arc over a 0.3 m step down: the lift over the line, not the rise
    pos = np.stack([level, stair])
    assert max_lift(pos, np.ones((2, 101), bool)) == pytest.approx([0.12, 0.12], abs=1e-4)


def test_sole_pitch_is_zero_at_rest_for_a_tilted_mount_and_positive_toes_up():
    from scipy.spatial.transform import Rotation

    from pdrlearn.kernels.clearance import sole_pitch_deg

    mount = Rotation.from_euler("y", 50, degrees=True)  # an instep mount, x axis 50 deg toes-down (D8)
    foot = Rotation.from_euler("y", [[0.0], [-20.0], [30.0]], degrees=True)  # rest, toes up 20 deg, toes down 30 deg
    xyzw = (foot * mount).as_quat()  # body -> nav: the foot's rotation after the mount's
    q = xyzw[:, [3, 0, 1, 2]][None]
    assert sole_pitch_deg(q)[0] == pytest.approx([0.0, 20.0, -30.0], abs=1e-6)


@pytest.fixture(scope="module")
def walk():
    s = simulate_path(parse_route("stand:2, straight:8, stand:2"), UserProfile.from_seed(8104), rate_hz=100.0,
                      seed=8104)
    return s, track_plasys(s, toe_off=True).steps


def test_lift_and_angles_match_the_simulator_truth(walk):
    from pdrlearn.kernels.clearance import max_lift

    s, st = walk
    ft = s.extras["foot_trajectory"]
    t = ft["t_s"].to_numpy(float)
    rows = st[np.isfinite(st["max_sensor_lift_m"])]
    assert len(rows) >= 4
    err = []
    for r in rows.itertuples():
        sel = (t >= r.start_s) & (t <= r.end_s)
        pos = ft[["x", "y", "z"]].to_numpy(float)[sel][None]
        err.append(r.max_sensor_lift_m - max_lift(pos, np.ones(pos.shape[:2], bool))[0])
    assert np.median(np.abs(err)) < 0.015  # decision L421's tolerance
    # heel strike lands toes up, toe-off leaves toes down (the simulator: toe-off -50..-58 deg, S23)
    assert np.nanmedian(rows["ic_angle_deg"]) > 10.0
    assert np.nanmedian(rows["tc_angle_deg"]) < -30.0
    # decision L795: the toe's lowest point in mid-swing, a centimetre or so on the simulator, under the sensor lift
    mtc = rows["min_toe_clearance_m"].to_numpy(float)
    assert np.isfinite(mtc).all() and -0.01 < np.median(mtc) < 0.04 and (mtc < rows["max_sensor_lift_m"]).all()


def test_tc_angle_needs_the_toe_off():
    s = simulate_path(parse_route("stand:2, straight:5, stand:2"), UserProfile.from_seed(8105), rate_hz=100.0,
                      seed=8105)
    st = track_plasys(s).steps
    assert st["tc_angle_deg"].isna().all()
    assert np.isfinite(st["max_sensor_lift_m"]).sum() >= 2 and np.isfinite(st["ic_angle_deg"]).sum() >= 2
    assert np.isfinite(st["min_toe_clearance_m"]).sum() >= 2  # decision L795: from the toe's rise without a toe-off
