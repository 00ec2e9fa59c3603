"""Decision L605 (session 43): L80's 3 s stride cap follows a slow foot's own stride rhythm (1.5 periods), so a
continuous 3.5-5 s stride walk gets its stride times, cadence and one walking bout; a normal rhythm keeps 3 s."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.cli.track import track_session, track_settings
from pdrlearn.kernels import contact
from pdrlearn.track.clinical import bout_rows


def test_the_cap_is_l80s_at_a_normal_rhythm_and_follows_a_slow_one_l605():
    assert contact.stride_cap_s(1.45, 1.45) == contact.MAX_STRIDE_S  # the slowest normal simulated period (L597)
    assert contact.stride_cap_s(float("nan"), 2.9) == contact.MAX_STRIDE_S
    assert contact.stride_cap_s(4.0, 2.9) == pytest.approx(6.0)
    # an order picker's 1.41 s strides in a 3.42 s walk-and-stand cycle (L482's route): the cycle is no stride
    assert contact.stride_cap_s(3.42, 1.41) == contact.MAX_STRIDE_S


def _slow_table(stride_time: bool) -> pd.DataFrame:
    """Ten strides every 4.0 s whose rest-to-rest windows last 2.9 s (a continuous 2 s-step walk, L605's user)."""
    start = 2.0 + 4.0 * np.arange(10) + np.r_[0.0, 0.05, -0.04, 0.02, 0.06, -0.03, 0.0, 0.04, -0.05, 0.01]
    t = pd.DataFrame({"start_s": start, "end_s": start + 2.9, "event_s": start + 2.4, "length_m": 0.4,
                      "gap_s": 0.0, "unit": "foot"})
    t["stride_time_s"] = contact.stride_times(t["start_s"], t["end_s"], t["event_s"],
                                              max_s=contact.stride_cap_s(4.0, 2.9) if stride_time else 3.0)
    return t


def test_a_slow_foots_own_stride_times_set_the_pause_rhythm_l605():
    assert len(bout_rows(_slow_table(True))) == 1
    assert len(bout_rows(_slow_table(False))) > 1  # L500's window bound alone: ~1 s foot-flats read as pauses


@pytest.fixture(scope="module")
def slow_walk(tmp_path_factory):
    """0.45 m steps every 2.5 s, 3.6 m (4 strides; L605's measurement: 7 bouts and no cadence before)."""
    out = tmp_path_factory.mktemp("l605") / "slow"
    assert main(["simulate", "--route", "stand:2, straight:3.6, stand:2", "--step-length", "0.45", "--step-time",
                 "2.5", "--bounce", "pendulum", "--rocker", "smooth", "--user-seed", "11975", "--rate", "100",
                 "--out", str(out)]) == 0
    return out


def test_a_continuous_slow_walk_is_one_bout_with_its_cadence_l605(slow_walk):
    out = track_session(slow_walk, track_settings(pipeline="plasys"))
    s, steps = out["summary"], out["result"].steps
    assert s["n_walking_bouts"] == 1 and s["n_pauses"] == 0
    assert s["median_cadence_spm"] == pytest.approx(24.0, rel=0.05)  # 60 / 2.5 s
    assert (steps["stride_time_s"].dropna() > contact.MAX_STRIDE_S).all()
    line = [w for w in out["result"].info.get("warnings", []) if "decision L605" in w]
    assert line and "count as strides" in line[0]
    assert "+2.56 to +46.54 % at 2.5 s steps" in line[0] and "L606" in line[0]  # decision L607
