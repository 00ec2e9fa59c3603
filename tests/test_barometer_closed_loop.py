"""Decision L225 (session 28 navigation trial, finding 11): on a closed multi-floor loop the foot ended +0.14 m from
its start (truth 0, 8 storeys up and 8 down) and the barometer's climbs -0.88 m; L145's line suggested `--altitude
fused`, which would add the barometer's error. When the foot's floors close the loop the line says to keep the
foot's altitude."""

from __future__ import annotations

from pdrlearn.track.evaluate import barometer_warning

#: user 3840's offline summary (the trial's nav/u3840.off)
U3840 = {"storey_height_m": 2.89, "altitude_change_m": 0.14, "floors_up": 8, "floors_down": 8, "ascent_m": 23.04,
         "descent_m": 22.91, "barometer_unused": True, "barometer_altitude_change_m": -0.53,
         "barometer_climb_change_m": -0.88, "barometer_ascent_m": 22.65, "barometer_descent_m": 23.52,
         "barometer_disagree_limit_m": 1.0}


def test_a_closed_loop_keeps_the_foot_altitude():
    line = barometer_warning(U3840)
    assert line is not None and "disagrees with the waist barometer's -0.88 m" in line
    assert "climbed 8 and descended 8 storeys of 2.89 m and ends +0.14 m" in line
    assert "keep the foot's altitude" in line and "(decision L225)" in line
    head = line.split("otherwise")[0]
    assert "fuse the barometer" not in head  # the fused advice only for a walk that did not end where it began


def test_an_open_walk_keeps_l145s_advice():
    line = barometer_warning({**U3840, "floors_down": 7, "altitude_change_m": 3.0, "barometer_climb_change_m": 1.5})
    assert line is not None and "L225" not in line and "fuse the barometer, `--altitude fused`" in line
    fused = barometer_warning({**U3840, "barometer_unused": False})  # already fused: no advice to keep the foot's
    assert fused is not None and "L225" not in fused
