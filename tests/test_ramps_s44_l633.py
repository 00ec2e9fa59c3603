"""Decision L633 (session 44, fixer FA, trial T3 finding F8): a "ramp" between two stair strides of its own direction
is a stair's landing (a U-shaped stairwell's turn, its strides onto and off the landing each carrying a stair's part),
not a ramp. Simulated user 12242 (seed = user)."""

from __future__ import annotations

import numpy as np

from pdrlearn.track.grade import ramp_runs

#: stair strides (0.33 m over 0.56 m), two landing strides (0.18 m over 1.15 m: 15.7 %), stair strides
STAIRWELL = ([0.56] * 4 + [1.15, 1.15] + [0.56] * 4, [0.33] * 4 + [0.18, 0.18] + [0.33] * 4)


def test_a_landing_between_flights_is_no_ramp():
    """main: one 15.7 % ramp on the landing rows 4-5."""
    assert ramp_runs(*STAIRWELL) == []


def test_a_ramp_meeting_stairs_on_one_side_or_climbing_the_other_way_is_kept():
    length, dz = (np.array(v, dtype=float) for v in STAIRWELL)
    level_after = (np.concatenate([length[:6], [1.2] * 4]), np.concatenate([dz[:6], [0.0] * 4]))
    assert [(r["first"], r["last"]) for r in ramp_runs(*level_after)] == [(4, 5)]
    down_after = (length, np.concatenate([dz[:6], -dz[6:]]))  # a climb's top turning down: not one stair's landing
    assert [(r["first"], r["last"]) for r in ramp_runs(*down_after)] == [(4, 5)]


def test_a_simulated_u_stairwell_with_fused_altitude_writes_no_ramp(tmp_path):
    """User 12242, `--altitude fused`: main wrote 1 ramp, the stairwell's landing (on L633's longer measuring route
    a 14.11 % one at 17.62-19.77 s)."""
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route
    from pdrlearn.track.evaluate import track_summary
    from pdrlearn.track.plasys import track_plasys

    route = "stand:3, straight:6, up:10, curve:180:0.6, up:10, straight:6, stand:3"
    ses = simulate_path(parse_route(route), UserProfile.from_seed(12242), seed=12242, scenario="route")
    r = track_plasys(ses, altitude="fused")
    s = track_summary(r, ses)
    assert s["grade_source"] is not None and s["n_ramps"] == 0, s["n_ramps"]
