"""Decision L482: a foot track's pauses are judged against its rows' own stride windows, so a stop-and-go walk
(1-3 strides between stands, trial T2 finding 1) keeps its walking bouts and pauses."""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd
import pytest

from pdrlearn.track import clinical
from pdrlearn.track.clinical import bout_rows, pauses

#: walks of 1, 2, 1, 3, 1 strides (1.2 s windows) with a 2 s stand between two walks
WALKS = (1, 2, 1, 3, 1)


def _stop_and_go(unit: str = "foot") -> pd.DataFrame:
    starts, ends, t = [], [], 0.0
    for k, n in enumerate(WALKS):
        if k:
            t += 2.0  # the stand: the foot rests outside any stride window
        for _ in range(n):
            starts.append(t)
            t += 1.2
            ends.append(t)
    n = len(starts)
    return pd.DataFrame({"start_s": starts, "end_s": ends, "heading_rad": np.zeros(n), "turn_angle_rad": np.zeros(n),
                         "gap_s": 0.0, "unit": unit})


def test_stop_and_go_walk_keeps_its_pauses_and_bouts():
    st = _stop_and_go()
    p = pauses(st)
    assert len(p) == len(WALKS) - 1  # was 0: the median interval (3.2 s) was the stand itself
    assert np.allclose(p, 2.0)  # each stand's own length beyond the 1.2 s stride
    assert [b - a for a, b in bout_rows(st)] == list(WALKS)


def test_continuous_walk_and_lower_back_table_are_unchanged():
    """L104's median gave these (1 pause of 1.3 s; none on the lower back); W413: L482 is the rule, no switch."""
    t = np.cumsum([0] + [1.2] * 5 + [2.5] + [1.2] * 5)  # windows touch: one stride to the next
    walk = pd.DataFrame({"start_s": t, "end_s": np.append(t[1:], t[-1] + 1.2), "heading_rad": 0.0, "gap_s": 0.0,
                         "unit": "foot"})
    assert np.allclose(pauses(walk), [1.3])
    assert len(pauses(_stop_and_go(unit="waist"))) == 0  # the lower back keeps L104's median (both feet's steps)
    assert not hasattr(clinical, "STRIDE_WINDOW_RHYTHM")


@pytest.mark.slow
def test_simulated_order_picker_route_gives_the_route_s_walks():
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route
    from pdrlearn.track.evaluate import evaluate_track
    from pdrlearn.track.plasys import track_plasys

    route = ("stand:3, straight:0.7, stand:2, straight:1.4, stand:2, straight:0.7, stand:2, straight:2.1, stand:2, "
             "backward:1, stand:2, straight:0.7, stand:2, backward:1, stand:2, straight:1.4, stand:3")
    logging.disable(logging.WARNING)
    try:
        s = simulate_path(parse_route(route), UserProfile.from_seed(9556), rate_hz=100.0, seed=0)
        summary = evaluate_track(track_plasys(s), s)
    finally:
        logging.disable(logging.NOTSET)
    assert (summary["n_walking_bouts"], summary["n_pauses"]) == (8, 7)  # was 1 / 0 (trial T2: 8 walks, 7 stands)
