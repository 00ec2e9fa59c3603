"""Decision C233: a stride whose integrated height clearly contradicts its terrain class is counted and said
(kernels.altitude_check.terrain_dz_check: offline track, track --streaming and the runtime Tracker / run)."""

from __future__ import annotations

import numpy as np

from pdrlearn.kernels import altitude_check as AC


def check(terrain, raw, **kw):
    raw = np.asarray(raw, dtype=float)
    return AC.terrain_dz_check(np.array(terrain, dtype=object), raw, raw, **kw)


def test_level_strides_classed_down_are_said_with_their_count():
    # trial s49t2 F4: 4 of 10 level short strides classed down, each falling 0.01-0.03 m (C28: not against the sign)
    terr = ["flat", "down", "flat", "down", "flat", "down", "flat", "down", "flat", "flat"]
    raw = [0.01, -0.02, 0.0, -0.01, 0.02, -0.03, 0.01, -0.01, 0.0, 0.01]
    msg, info = check(terr, raw)
    assert info["stairs_against_sign"] == 0 and info["clear_level_as_stairs"] == 4
    assert msg is not None and msg.startswith("4 of 10 strides' terrain classes clearly contradict")
    assert "terrain_dz" in msg and "C233" in msg


def test_a_staircase_stride_classed_flat_is_counted_though_next_to_stairs():
    # patient 16401: up-stair strides (0.34 m each) classed flat between up strides (C30 does not count them)
    terr = ["flat", "up", "flat", "up", "flat", "up", "flat"]
    raw = [0.0, 0.34, 0.33, 0.35, 0.34, 0.17, 0.0]
    msg, info = check(terr, raw)
    assert info["flat_with_height"] == 0  # C28 / C30 alone: silent
    assert info["clear_stairs_as_flat"] == 2 and info["clear_level_as_stairs"] == 0
    assert msg is not None and "2 classed flat" in msg


def test_right_classes_ramps_and_a_staircase_first_stride_stay_silent():
    # a 1:12 ramp's up strides (0.06-0.09 m), a staircase's first / last strides classed flat (one riser, C30),
    # a level walk's flat strides with integration noise under 0.15 m
    terr = ["flat", "up", "up", "up", "flat", "flat", "up", "up", "flat", "flat", "down", "down", "flat"]
    raw = [0.02, 0.06, 0.08, 0.09, 0.12, 0.19, 0.34, 0.33, 0.18, 0.05, -0.07, -0.34, -0.2]
    msg, info = check(terr, raw)
    assert msg is None
    assert info["clear_level_as_stairs"] == 0 and info["clear_stairs_as_flat"] == 0


def test_c28s_line_carries_the_clear_count():
    terr = ["down"] * 3 + ["flat"] * 7
    raw = [0.2, -0.01, -0.02] + [0.0] * 7  # one against its sign (C28), two under 0.05 m
    msg, info = check(terr, raw)
    assert info["stairs_against_sign"] == 1 and info["clear_level_as_stairs"] == 2
    assert check(terr, raw, clear_line=False)[0] is None  # C28 alone stays under its thresholds
    terr = ["up"] * 4 + ["flat"] * 6
    raw = [-0.3, -0.2, -0.25, 0.02] + [0.0] * 6
    msg = check(terr, raw)[0]
    assert "contradict their integrated height change" in msg and "1 strides clearly contradict it" in msg
