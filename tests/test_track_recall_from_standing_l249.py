"""Decision L249 (amends L36): a tracked stride matched to a labelled stride is always scored, so a walk that
starts from standing is not one stride short in ``track``'s step recall (it read (n-1)/n; ``steps`` read 1.0)."""

from __future__ import annotations

import pandas as pd
import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.base import TrackResult
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.plasys import track_plasys


@pytest.fixture(scope="module")
def walkway():
    return simulate_path(parse_route("stand:2, straight:12, stand:2"), UserProfile.from_seed(4940), rate_hz=100,
                         seed=0)


def test_a_walk_from_standing_has_full_recall(walkway):
    m = evaluate_track(track_plasys(walkway), walkway)
    n = len(walkway.steps)
    assert m["stride_length_matched"] == n
    assert m["step_recall"] == 1.0 and m["step_precision"] == 1.0 and m["step_f1"] == 1.0


def test_the_first_stride_before_the_first_contacts_interval_is_scored(walkway):
    ref = walkway.steps[["start_s", "end_s"]].to_numpy(float).copy()
    ref[0, 0] -= 0.1  # the tracked first stride starts a little earlier: its middle precedes first IC - 0.25 s
    steps = pd.DataFrame(ref, columns=["start_s", "end_s"]).assign(length_m=1.0, heading_rad=0.0, unit="foot")
    res = TrackResult(steps=steps, trajectory=pd.DataFrame({"t": [0.0], "x": [0.0], "y": [0.0], "z": [0.0]}), info={})
    assert evaluate_track(res, walkway)["step_recall"] == 1.0
    unmatched = pd.concat([steps, steps.iloc[[0]].assign(start_s=ref[0, 0] - 3.0, end_s=ref[0, 0] - 2.0)])
    assert evaluate_track(TrackResult(steps=unmatched, trajectory=res.trajectory, info={}), walkway)[
        "step_precision"] == 1.0  # an unmatched stride in the standing before the walk is still unscored
