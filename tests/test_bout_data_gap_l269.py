"""Decision L269: a foot-data gap (L67's gap row) longer than the bout rule's break ends a walking bout (the gap
row in neither bout) in ``track``, ``track --streaming`` and ``run`` alike (one mechanism,
``clinical.split_at_data_gaps``); bouts.csv's ``data_gap_s`` holds a bout's shorter gaps (the session's gap time
is L275's ``time_no_data_s``). The trial (session 29, finding 2) had a 70 s foot gap inside one bout: 140.66 s,
0.49 m/s, two real bouts merged."""

from __future__ import annotations

import json
import logging

import numpy as np
import pandas as pd
import pytest

from pdrlearn.io import Stream, write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.bouts import BoutRule, detected_bouts
from pdrlearn.track.clinical import bout_rows, clinical_summary

ROUTE = "straight:40"
CUT = (12.0, 16.0)  # a 4 s foot-data gap in the middle of one walk


def _cut_session():
    s = simulate_path(parse_route(ROUTE), UserProfile.from_seed(5200), rate_hz=20.0, seed=5200, scenario="route")
    for name in [n for n in s.streams if n.startswith("f")]:
        x = s.streams[name]
        keep = (x.t < CUT[0]) | (x.t >= CUT[1])
        s.streams[name] = Stream(name, x.t[keep], x.values[keep])
    return s


def test_a_long_gap_row_ends_the_bout_and_a_short_one_is_flagged():
    t = pd.DataFrame({"start_s": [0.0, 1.0, 2.0, 3.0, 8.0, 9.0, 10.0], "end_s": [1.0, 2.0, 3.0, 8.0, 9.0, 10.0, 11.0],
                      "event_s": [0.5, 1.5, 2.5, np.nan, 8.5, 9.5, 10.5], "length_m": [1.2, 1.2, 1.2, 0, 1.2, 1.2, 1.2],
                      "heading_rad": 0.0, "gap_s": [0, 0, 0, 4.0, 0, 0, 0], "unit": "foot"})
    assert bout_rows(t) == [(0, 3), (4, 7)]  # main: [(0, 7)], the gap row inside one bout
    b = detected_bouts(t)
    assert len(b) == 2 and b["end_s"].tolist() == [3.0, 11.0] and b["start_s"].tolist() == [0.0, 8.0]
    assert b["data_gap_s"].tolist() == [0.0, 0.0] and b["distance_m"].tolist() == pytest.approx([3.6, 3.6])
    mob = detected_bouts(t, BoutRule(break_s=3.0, gap="contact"))
    assert len(mob) == 2 and (mob["data_gap_s"] == 0).all()  # the contact rule cuts it the same way
    longer = detected_bouts(t, BoutRule(break_s=5.0))
    assert len(longer) == 1 and longer["data_gap_s"].tolist() == [4.0]  # a gap under the break is flagged
    s = clinical_summary(t)
    assert s["n_walking_bouts"] == 2 and s["n_pauses"] == 0


@pytest.mark.parametrize("streaming", [False, True])
def test_track_splits_the_bout_at_the_gap(tmp_path, streaming):
    from pdrlearn.cli import main

    write_session(_cut_session(), tmp_path / "s")
    args = ["track", "--no-plot", str(tmp_path / "s"), "--out",
            str(tmp_path / "o")] + (["--streaming"] if streaming else [])
    logging.disable(logging.WARNING)
    try:
        assert main(args) == 0
    finally:
        logging.disable(logging.NOTSET)
    _check(tmp_path / "o")


def _check(out):
    steps = pd.read_csv(out / "steps.csv")
    gap = steps[steps["gap_s"] > 0]
    assert len(gap) == 1 and gap["gap_s"].iloc[0] > 3.0
    bouts = pd.read_csv(out / "bouts.csv")
    summary = json.loads((out / "summary.json").read_text())
    assert len(bouts) == 2 and (bouts["data_gap_s"] == 0).all()
    assert bouts["end_s"].iloc[0] <= gap["start_s"].iloc[0] + 1e-6
    assert bouts["start_s"].iloc[1] >= gap["end_s"].iloc[0] - 1e-6  # no bout spans the gap
    assert not (bouts["longest_contact_gap_s"] > 2.5).any()  # (NaN streamed without --contacts)
    assert summary["n_bouts"] == summary["n_walking_bouts"] == 2
    assert summary["time_no_data_s"] == pytest.approx(float(gap["gap_s"].sum()), abs=0.2)  # L275's key


@pytest.fixture(scope="module")
def root(tmp_path_factory):
    from tests.runtime_helpers import trained_dirs

    return trained_dirs(tmp_path_factory)["root"]


def test_run_splits_the_bout_at_the_gap(root, tmp_path):
    from pdrlearn.cli import main

    write_session(_cut_session(), tmp_path / "s")
    logging.disable(logging.WARNING)
    try:
        assert main(["run", "--no-plot", str(root / "bundle"), str(tmp_path / "s"), "--out", str(tmp_path / "o")]) == 0
    finally:
        logging.disable(logging.NOTSET)
    _check(tmp_path / "o")
