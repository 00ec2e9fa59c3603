"""Decision L690 (session 46, FH, trial T2 finding F1): a stride's own turn is not wrapped.

The foot's twist over a stride (L30) is exact only modulo one turn; each path wrapped the stride's turn into
(-180, 180] deg, so a dancer's spin of 180-360 deg inside one stride read as the opposite turn (T2: ``curve:270:0.3``
one turn of -89.8 deg for +270). One kernel (:func:`pdrlearn.kernels.turn.unwrapped_turn`) puts the twist on the
branch of the vertical rate integrated over the stride; offline, ``track --streaming`` and the live Tracker call it."""

from __future__ import annotations

import logging
import math

import numpy as np
import pytest

from pdrlearn.kernels.turn import unwrapped_turn

#: L690's adoption tolerance (deg) on a single-stride turn of 180-360 deg
TOL_DEG = 5.0


def test_the_kernel_takes_the_integrals_branch():
    """The twist keeps its value (exact modulo 2 pi); the integral only picks the whole turns."""
    assert unwrapped_turn(-math.pi / 2, math.radians(265.0)) == pytest.approx(1.5 * math.pi)  # +270 read as -90
    assert unwrapped_turn(math.radians(-176.2), math.radians(186.0)) == pytest.approx(math.radians(183.8))
    assert unwrapped_turn(0.3, 0.25) == 0.3  # an ordinary stride: unchanged, bit for bit
    assert unwrapped_turn(0.3, math.nan) == 0.3
    out = unwrapped_turn(np.array([-math.pi / 2, 0.3, 3.0]), np.array([4.6, 0.35, -3.2]))
    np.testing.assert_allclose(out, [1.5 * math.pi, 0.3, 3.0 - 2 * math.pi])


def test_the_streamed_stride_kernel_reads_a_three_quarter_spin():
    """``foot_levelled`` (the streamed stride kernel of track --streaming and the runtime): a foot at rest, spinning
    +270 deg about the vertical in 1 s, at rest again, reads +270 deg (it read -90 before L690)."""
    from pdrlearn.kernels.window import foot_levelled

    fs = 100.0
    t = np.arange(0.0, 2.0, 1.0 / fs)
    rate = np.where((t >= 0.5) & (t < 1.5), math.radians(270.0), 0.0)  # rad/s about the body z (vertical)
    gyr = np.column_stack([np.zeros_like(t), np.zeros_like(t), rate])
    acc = np.tile([0.0, 0.0, 9.81], (len(t), 1))  # flat foot: gravity only
    dpsi = foot_levelled(t, acc, gyr, np.array([1.0, 0.0, 0.0]), rest_search_s=0.3, heading="declared")[3]
    assert math.degrees(dpsi) == pytest.approx(270.0, abs=1.0)


@pytest.fixture(scope="module")
def spins():
    """User 12900 (50 Hz): a single-stride +270 deg and -300 deg spin (the simulator's truth), tracked offline,
    streamed and live."""
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route
    from pdrlearn.track.plasys import track_plasys
    from tests.test_live_heading_s45_e289 import _live

    out = {}
    for deg in (270, -300):
        s = simulate_path(parse_route(f"stand:2, straight:2, curve:{deg}:0.3, straight:2, stand:2"),
                          UserProfile.from_seed(12900), rate_hz=50, seed=0, scenario="route")
        logging.disable(logging.WARNING)
        try:
            off, st = track_plasys(s), track_plasys(s, streaming=True, method="M2")
        finally:
            logging.disable(logging.NOTSET)
        out[deg] = (s, off, st, _live(s))
    return out


@pytest.mark.parametrize("deg", [270, -300])
def test_a_single_stride_spin_is_itself_offline_streamed_and_live(spins, deg):
    """Offline, the spin's stride reads its truth within 5 deg (+270.0 / -300.1 printed); streamed, whose causal rests
    cut the spin into three strides (+29.1, +224.8, +15.7 / -32.1, -249.9, -18.1), the largest has the truth's sign
    and the three sum to it within 5 deg; the live Tracker equals track --streaming (one kernel); turns.csv's turn
    follows on both. Fails without the kernel's branch (offline -90.0 / +59.9) and with the streamed output's wrap put
    back (-135.2 / +110.1). (This two-unit session's streamed heading is the lower back's yaw rate, L61, already
    unwrapped; the foot's own streamed kernel is the test above.)"""
    from pdrlearn.track.clinical import turn_table

    s, off, st, live = spins[deg]
    truth = s.steps["heading_change_deg"].to_numpy(float)
    assert (np.abs(truth) > 180).sum() == 1 and truth[np.argmax(np.abs(truth))] == pytest.approx(deg)
    turn = np.degrees(off.steps["turn_angle_rad"].to_numpy(float))
    assert turn[np.argmax(np.abs(turn))] == pytest.approx(deg, abs=TOL_DEG)
    turn = np.degrees(st.steps["turn_angle_rad"].to_numpy(float))
    big = int(np.argmax(np.abs(turn)))
    assert abs(turn[big]) > 180 and np.sign(turn[big]) == np.sign(deg)
    assert turn[big - 1: big + 2].sum() == pytest.approx(deg, abs=TOL_DEG)
    np.testing.assert_allclose([x.turn_angle_rad for x in live], st.steps["turn_angle_rad"].to_numpy(float),
                               rtol=0, atol=1e-9)
    for steps in (off.steps, st.steps):
        turns = turn_table(steps)
        assert len(turns) == 1 and turns["angle_deg"].iloc[0] == pytest.approx(deg, abs=TOL_DEG)
