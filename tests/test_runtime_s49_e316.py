"""Decisions E316-E318 (trial s49t2 F1, F8): the lean runtime ``python -m pdrlearn.runtime`` reports the walked
distance as ``pdrlearn run`` does (main netted a back-pedal out: -15.9 to -17.3 %), writes run's ``travel`` column
and keeps run's warning lines in replay.json; a stream's first stride, which L505 does not judge backward, is
reported with a positive ``length_m`` (main: -0.39 m with ``backward_travel`` False). One short simulated walk that
starts backward and side-steps to the left (fresh user 16619, shipped bundle), replayed by both entry points
in-process; E319: a streamed side step's ``travel`` is left / right (main: side) by its new ``lateral_m``."""

from __future__ import annotations

import json
import logging

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main as cli_main
from pdrlearn.io import write_session
from pdrlearn.kernels.backward import backward_mask, first_unjudged
from pdrlearn.kernels.travel import classed_backward_lines, travel_label_array, travel_rows, walked_distance
from pdrlearn.runtime.__main__ import main as lean_main
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.travel import side_labels, travel_labels
from tests.lean_helpers import ROOT

BUNDLE = ROOT / "models" / "plasys-sim-default"
ROUTE = "stand:2, backward:4, stand:2, straight:5, stand:2, side:3, stand:2"


@pytest.fixture(scope="module")
def replays(tmp_path_factory):
    d = tmp_path_factory.mktemp("e316")
    s = simulate_path(parse_route(ROUTE), UserProfile.from_seed(16619), speed="normal", rate_hz=20.0, seed=3,
                      scenario="route")
    write_session(s, d / "walk")
    logging.disable(logging.WARNING)
    try:
        assert cli_main(["run", "--no-plot", str(BUNDLE), str(d / "walk"), "--out", str(d / "run")]) == 0
        assert lean_main([str(BUNDLE), str(d / "walk"), "--out", str(d / "lean")]) == 0
    finally:
        logging.disable(logging.NOTSET)
    read = {k: pd.read_csv(d / k / "steps.csv", keep_default_na=False, na_values=["", "nan"]) for k in ("run", "lean")}
    return {"truth": s.steps, "steps": read, "run": json.loads((d / "run" / "summary.json").read_text()),
            "lean": json.loads((d / "lean" / "replay.json").read_text())}


def test_both_entry_points_walk_the_same_distance(replays):
    lean, run = replays["lean"], replays["run"]
    steps = replays["steps"]["lean"]
    assert (steps["length_m"] < 0).sum() >= 2  # backward strides, negative (L654): main summed them signed
    true = float(replays["truth"]["length_m"].abs().sum())
    assert lean["distance_m"] == pytest.approx(run["distance_m"], abs=1e-6)  # main: lower by twice the back-pedal
    assert abs(lean["distance_m"] / true - 1) <= abs(run["distance_m"] / true - 1) + 1e-9
    assert abs(run["distance_error_pct"]) < 10


def test_the_lean_table_has_runs_travel_and_warnings(replays):
    lean, run = replays["steps"]["lean"], replays["steps"]["run"]
    assert list(lean.columns).index("travel") == list(lean.columns).index("backward_travel") + 1
    assert "side" not in set(lean["travel"]) and {"left"} <= set(lean["travel"])  # E319: main wrote side
    assert lean["travel"].fillna("").tolist() == run["travel"].fillna("").tolist()  # main: no travel column
    assert "backward" in set(lean["travel"])
    assert lean["backward_travel"].tolist() == run["backward_travel"].tolist()
    said = [w for w in replays["run"]["info"]["warnings"] if any(f"(decision {c})" in w for c in ("C137", "L578",
                                                                                                 "L652"))]
    assert set(said) <= set(replays["lean"]["warnings"])


def test_the_first_streamed_stride_is_reported_as_judged(replays):
    for table in replays["steps"].values():  # E318: main's first backward stride -0.39 m, backward_travel False
        assert ((table["length_m"] < 0) == table["backward_travel"]).all()
        assert table["length_m"].iloc[0] > 0
    assert replays["truth"]["direction"].iloc[0] == "backward"  # the walk starts backward (the edge E318 reports)


def test_the_kernels():
    assert walked_distance([1.0, -0.5, np.nan]) == 1.5 and walked_distance([]) == 0.0
    assert first_unjudged(3, [1.0, 0.0, 0.0]).tolist() == [False, True, False]
    assert not first_unjudged(2, None, streamed=False).any()
    assert backward_mask([-1.0, -1.0], streamed=True).tolist() == [False, True]
    rows = [{"length_m": v, "gap_s": g, "turn_angle_rad": t, "pivot_rad": 0.0, "sideways": False, "impossible": False}
            for v, g, t in ((-0.5, 0.0, 0.0), (0.05, 0.0, 0.0), (-0.8, 0.0, 0.0), (0.3, 0.0, 1.2), (0.0, 2.0, 0.0),
                            (1.2, 0.0, 0.0))]
    assert travel_label_array([0.4, 0.4, 0.4], [False] * 3, [True] * 3, lateral_m=[0.3, -0.3, np.nan]).tolist() == [
        "left", "right", "side"]  # decision E319: a streamed side step's side by its lateral_m, as offline's
    # review R2 F6: no lateral part (exactly 0) is no side, streamed and offline (main: right)
    assert travel_label_array([0.4], [False], [True], lateral_m=[0.0]).tolist() == ["side"]
    assert side_labels([True, True, False], [0.0, -0.2, 0.3]).tolist() == [None, "right", None]
    assert travel_rows(rows) == travel_labels(pd.DataFrame(rows).assign(unit="foot")).tolist() == [
        "forward", "", "backward", "turn", "", "forward"]
    lines = classed_backward_lines(["backward", "forward"], [False, False], [0.5, 0.5], ["forward", "forward"],
                                   unjudged=[True, False])
    assert lines == []  # E318: the first stride's positive length is no measured forward travel (L652)
    assert len(classed_backward_lines(["backward"], [False], [0.5], ["forward"])) == 1
