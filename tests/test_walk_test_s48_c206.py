"""Decision C206 (session 48, trial T4 finding F3): a declared walkway's time is named by its own timed metres
("7.62 m walk test" for ``--ten-m-walk 1,7.62,3.38``, not "10 m walk test"; a 10 m walkway keeps "10 m walk"), and the
calibrated lower back's T25FW note says the flying 25-foot walk's time is ``ten_m_walk_time_s``, not
``t25fw_time_s``."""
from __future__ import annotations

import pytest

from pdrlearn.cli.common import transfer_line
from pdrlearn.track.walk_test import T25FW_M, lower_back_note, walk_test_name

FLYING = {"ten_m_walk_time_s": 4.75, "ten_m_walk_speed_mps": 1.604, "ten_m_walk_zones_m": [1.0, 7.62, 3.38],
          "ten_m_walk_declared": True, "ten_m_walk_note": None}


@pytest.mark.parametrize(("zones", "name"), [(None, "10 m walk"), ([2.0, 6.0, 2.0], "10 m walk"),
                                             ([0.0, 6.0, 4.0], "10 m walk"), ([1.0, 7.62, 3.38], "7.62 m walk"),
                                             ([2.0, 20.0, 2.0], "20 m walk")])
def test_the_walk_test_is_named_by_its_walkway(zones, name):
    assert walk_test_name({"ten_m_walk_zones_m": zones}) == name


def test_the_console_names_the_flying_25_foot_walk_by_its_metres():
    line = transfer_line(FLYING)
    assert line.startswith("7.62 m walk test 4.75 s, 1.60 m/s (the 7.62 m after the first 1 m of a 12 m walk")
    assert "10 m walk" not in line
    refused = transfer_line({**FLYING, "ten_m_walk_time_s": None, "ten_m_walk_note": "too short"})
    assert refused.startswith("7.62 m walk test not timed (")


def test_the_t25fw_note_says_where_the_flying_time_goes():
    note = lower_back_note(0.0, T25FW_M, calibrated=True, what="the timed 25-foot walk")
    assert "ten_m_walk_time_s" in note and "ten_m_walk_speed_mps" in note and "not this T25FW" in note
    assert "C206" in note
    walkway = lower_back_note(0.0, 10.0, calibrated=True)  # a 10 m walk from standing is no flying T25FW
    assert "C206" not in walkway and "acceleration zone" in walkway
