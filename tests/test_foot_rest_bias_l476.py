"""Decisions L476 / L477: the foot gyroscope's bias re-read from every rest over a minute, opt-in
(docs/decisions/localization.md)."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.kernels.rest_heading import block_bias, rest_rotation
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.plasys import track_plasys

DRIFT_RPS = 0.02  # the foot bias's change over the rest (rad/s, ~1.1 deg/s: a unit warming up)


@pytest.fixture(scope="module")
def rest_walk():
    """User 9490: 10 m, a 150 s rest, 10 m back the same way; and the same session whose foot gyroscope's bias
    grows by DRIFT_RPS about the vertical during the rest (a ramp over its first minute, then held)."""
    s = simulate_path(parse_route("stand:5, straight:10, stand:150, straight:10, stand:5"), UserProfile.from_seed(9490),
                      rate_hz=20, seed=0)
    steps = track_plasys(s, method="M3", model="oracle", heading="foot").steps
    gap = steps["start_s"].to_numpy(float)[1:] - steps["end_s"].to_numpy(float)[:-1]
    k = int(np.argmax(gap))
    assert gap[k] > 120.0
    t_rest = float(steps["end_s"].iloc[k])
    drifted = s.copy()
    g, a = drifted.streams["fGyroscope"], s.streams["fAccelerometer"]
    at_rest = (a.t > t_rest + 5) & (a.t < t_rest + 60)
    up = a.values[at_rest].mean(axis=0)
    up /= np.linalg.norm(up)  # the vertical in the foot's frame (it rests flat: the rate about it turns the heading)
    ramp = np.clip((g.t - t_rest - 10.0) / 60.0, 0.0, 1.0)
    g.values = g.values + DRIFT_RPS * ramp[:, None] * up[None, :]
    return s, drifted, k


def _last_heading(session, on: bool) -> float:
    return float(track_plasys(session, method="M3", model="oracle", heading="foot",
                              params={"rest_bias": on}).steps["heading_rad"].iloc[-1])


def _turned_deg(a: float, b: float) -> float:
    return abs(float(np.degrees(np.angle(np.exp(1j * (b - a))))))


def test_foot_bias_drifting_in_a_long_rest_does_not_turn_the_heading_after_it_l476(rest_walk):
    s, drifted, _ = rest_walk
    # the setup standstill's one bias (the old rule): the drift turns the return leg (0.02 rad/s x its ~10 s)
    assert _turned_deg(_last_heading(s, False), _last_heading(drifted, False)) > 5.0
    # the bias read from the rest's still samples: the return leg's heading keeps within 1 deg of the undrifted one
    assert _turned_deg(_last_heading(s, True), _last_heading(drifted, True)) < 1.0


def test_walk_without_a_long_rest_is_unchanged_l476():
    s = simulate_path(parse_route("stand:5, straight:10, stand:30, straight:10, stand:5"), UserProfile.from_seed(9491),
                      rate_hz=20, seed=0)
    h = [track_plasys(s, method="M3", model="oracle", heading="foot", params={"rest_bias": on}).steps["heading_rad"]
         .to_numpy(float) for on in (False, True)]
    assert np.array_equal(h[0], h[1])


def test_block_bias_reads_each_axis_as_the_waist_reads_one_l476():
    rng = np.random.default_rng(9492)
    t = np.arange(0.0, 200.0, 0.05)
    w = np.column_stack([0.01 + 1e-4 * t, -0.02 * np.ones_like(t), 0.003 * np.sin(t / 50)])
    w += 1e-3 * rng.standard_normal(w.shape)
    still = rng.random(len(t)) > 0.2
    centres, bias = block_bias(t, w, still)
    assert bias.shape == (7, 3)
    for j in range(3):
        c1, b1 = block_bias(t, w[:, j], still)
        assert np.array_equal(c1, centres) and np.array_equal(b1, bias[:, j])
    assert abs(bias[-1, 0] - (0.01 + 1e-4 * centres[-1])) < 5e-4  # the last block's mean rate: the bias at its end
    # the waist's rest rotation (L296) is the kernel's: a still-only rest turns by nothing
    assert rest_rotation(t, w[:, 1], np.ones(len(t), bool), 0.0, 199.0) == 0.0


def test_rest_bias_is_opt_in_and_the_summary_says_which_ran_l477(rest_walk):
    s, _, _ = rest_walk
    assert track_plasys(s, method="M3", model="oracle").info["settings"]["rest_bias"] is False  # L477: not adopted
    on = track_plasys(s, method="M3", model="oracle", params={"rest_bias": True}).info["settings"]["rest_bias"]
    assert on is True
