"""Decision S88: a straight walk's own pace inside a route (``straight:M[:GAIT][:PACE]``, e.g. a burst of fast
walking inside a walk), the session's speed factors per item; no running gait (S48). Session 38, trial T1 finding 6.
Simulated users 9680-9699 only."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.sim.path import Straight
from pdrlearn.sim.route import parse_route
from pdrlearn.sim.user import SPEED_FACTORS


def test_route_item_takes_a_pace_and_refuses_a_run():
    assert parse_route("straight:10:fast") == [Straight(10.0, "normal", "fast")]
    assert parse_route("straight:10:long:slow") == [Straight(10.0, "long", "slow")]
    assert parse_route("straight:10:short") == [Straight(10.0, "short")]  # a gait alone, as before
    with pytest.raises(DataError, match=r"'run' must be a gait .* or a pace \(slow, normal, fast.*no running gait"):
        parse_route("straight:10:run")
    with pytest.raises(DataError, match="pace 'zoom' must be one of slow, normal, fast"):
        parse_route("straight:10:long:zoom")


def test_a_fast_walk_inside_a_walk_steps_faster_and_longer(tmp_path):
    out = tmp_path / "burst"
    assert main(["simulate", "--route", "stand:2, straight:12, straight:12:fast, straight:12:slow, stand:2",
                 "--user-seed", "9684", "--seed", "1", "--out", str(out)]) == 0
    truth = pd.read_csv(out / "steps.csv")  # the simulator's own strides of the right foot, in time order
    length = truth["length_m"].to_numpy(float)
    stride = np.diff(truth["ic_ms"].to_numpy(float), prepend=np.nan) / 1000.0
    assert 24 <= len(truth) <= 32  # ~9 normal, ~8 fast (longer steps), ~11 slow strides over the three 12 m
    parts = {"normal": slice(2, 7), "fast": slice(11, 15), "slow": slice(-7, -2)}  # inside each walk
    med = {k: (np.median(length[p]), np.median(stride[p])) for k, p in parts.items()}
    for pace in ("fast", "slow"):  # thesis Table 1's speed factors (pdrlearn.sim.user.SPEED_FACTORS), per walk
        assert med[pace][0] / med["normal"][0] == pytest.approx(SPEED_FACTORS[pace][0], abs=0.05)
        assert med[pace][1] / med["normal"][1] == pytest.approx(SPEED_FACTORS[pace][1], abs=0.05)
