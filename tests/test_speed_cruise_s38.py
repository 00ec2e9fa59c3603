"""Decision L480: L474's speed range is taken over, and compared on, the same cruise strides (level, forward,
straight, not the first or last stride of a walking bout), so a slow walk is flagged and a start is not."""

from __future__ import annotations

import numpy as np
import pandas as pd


def _walk(speeds: list[float], *, pause_after: int | None = None, turn_at: int | None = None,
          climb_at: int | None = None) -> pd.DataFrame:
    """A foot table of strides of 1.1 s at ``speeds`` (m/s), a 5 s pause after row ``pause_after``, a 90 deg turn on
    row ``turn_at``, a 0.3 m climb on row ``climb_at``."""
    n = len(speeds)
    start = 1.1 * np.arange(n) + np.where(np.arange(n) > (pause_after if pause_after is not None else n), 5.0, 0.0)
    heading = np.where(np.arange(n) >= (turn_at if turn_at is not None else n), np.pi / 2, 0.0)
    dz = np.where(np.arange(n) == (climb_at if climb_at is not None else -1), 0.3, 0.0)
    v = np.asarray(speeds, float)
    return pd.DataFrame({"start_s": start, "end_s": start + 1.1, "raw_length_m": 1.1 * v, "dz_m": dz,
                         "heading_rad": heading, "speed_mps": v, "stride_time_s": 1.1})


def test_cruise_strides_leave_out_bout_edges_turns_and_climbs_l480():
    from pdrlearn.track.speed_domain import cruise_strides

    st = _walk([1.0] * 20, pause_after=9, turn_at=15, climb_at=5)
    got = np.flatnonzero(cruise_strides(st)).tolist()
    # 0 / 9 (bout 1's ends), 10 / 19 (bout 2's), 5 (a climb), 14-15 (the turn between 14 and 15) are not cruise
    assert got == [1, 2, 3, 4, 6, 7, 8, 11, 12, 13, 16, 17, 18]


def test_a_cruise_model_flags_a_slow_walk_but_not_a_start_or_a_pause_l480():
    from pdrlearn.track.speed_domain import flag_speeds

    normal = _walk([0.5] + [1.3] * 8 + [0.6, 0.5] + [1.3] * 8 + [0.6], pause_after=9)  # starts and stops slow
    lines: list[str] = []
    info = flag_speeds(normal, [1.0, 1.6], lines, "cruise")
    assert not normal["speed_out_of_range"].any() and lines == [] and info["strides"] == "cruise"
    assert info["n_strides"] == 16
    flag_speeds(normal, [1.0, 1.6], lines, "all")  # L474's old comparison flags the starts and stops
    assert normal["speed_out_of_range"].sum() == 4 and len(lines) == 1
    slow = _walk([0.35] * 30)
    lines = []
    info = flag_speeds(slow, [1.0, 1.6], lines, "cruise")
    assert slow["speed_out_of_range"].sum() == 28 and info["n_out"] == 28  # all but the first and last stride
    assert "28 of 28 level straight strides" in lines[0]


def test_the_calibration_records_its_range_over_the_cruise_strides_l480(monkeypatch):
    from pdrlearn.displace import calibration
    from pdrlearn.track import speed_domain
    from pdrlearn.track.base import TrackResult

    st = _walk([0.2] + [1.2] * 28 + [0.2])
    st["length_m"] = st["raw_length_m"]

    class S:
        name, steps = "walk", st

        def has(self, *names):
            return True

    monkeypatch.setattr("pdrlearn.io.resample.recorded_rate", lambda s, name: (100.0, None))
    res = TrackResult(steps=st.copy(), trajectory=pd.DataFrame(), info={})
    out = calibration._estimate([S()], lambda s, p: res, None, {})
    assert (out["speed_range_mps"], out["speed_range_strides"]) == ([1.2, 1.2], "cruise")  # L481 (L474: low end 0.2)
    assert not hasattr(speed_domain, "SPEED_CRUISE")  # W413: L480 / L481 adopted, no module switch


def test_a_stride_after_a_gap_is_no_cruise_stride_under_rule_b_l481():
    """L481 rule B: a turn on the spot between two strides (a gap shorter than a pause, no bout split) leaves the
    strides on either side of the gap out of the cruise strides."""
    from pdrlearn.track import speed_domain

    st = _walk([1.0] * 12)
    st.loc[6:, ["start_s", "end_s"]] += 0.4  # 0.4 s between rows 5 and 6: under the 1 s pause, no bout split
    assert speed_domain.contiguous_strides(st).tolist() == [False] + [True] * 4 + [False, False] + [True] * 4 + [False]
    assert not hasattr(speed_domain, "CRUISE_CONTIGUOUS")  # W413: rule B adopted (rule A kept rows 5 and 6)
    assert np.flatnonzero(speed_domain.cruise_strides(st)).tolist() == [1, 2, 3, 4, 7, 8, 9, 10]
