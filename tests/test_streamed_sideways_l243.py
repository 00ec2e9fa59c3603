"""Decision L243: L228's ``sideways`` column for the streamed foot tracks (``track --streaming``, ``pdrlearn run``,
``Tracker``, the lean runtime): each stride flagged when it is decided, from a side-stepping run's third stride on
(E124's test, whatever the heading source); a reader of the whole table (the CVs, the straight speed) adds back the
run's first two strides (``kernels.sideways.whole_runs``)."""

from __future__ import annotations

import logging
import math

import numpy as np
import pandas as pd
import pytest

from pdrlearn.kernels import sideways as KS
from pdrlearn.kernels.sideways import SideRun, whole_runs
from pdrlearn.runtime.tracker import Step, Tracker
from pdrlearn.sim import UserProfile, simulate, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline
from pdrlearn.track.clinical import clinical_summary
from pdrlearn.track.gait import sideways_rows
from tests.runtime_helpers import replay, trained_dirs

ROUTE = "straight:12, side:3, straight:12"


def _sim(route: str, user: int):
    return simulate_path(parse_route(route), UserProfile.from_seed(user), rate_hz=20.0, seed=1, scenario="route")


def _streamed(s, **kw):
    logging.disable(logging.WARNING)
    try:
        return get_pipeline("plasys")(s, streaming=True, **kw)
    finally:
        logging.disable(logging.NOTSET)


def test_decided_from_the_third_sideways_stride_and_whole_runs_adds_back_the_first_two(monkeypatch):
    monkeypatch.setattr(KS, "MIN_SIDE_STRIDES", 3)  # the run mechanism at L219's former 3 (L486 made it 1)
    run = SideRun()
    decided = []
    for d in (4, 6, 90, 92, 91, 89, 5, 90, 88, 3):
        a = math.radians(d)
        run.stride(0.4 * math.cos(a), 0.4 * math.sin(a), 0.4)
        decided.append(run.decided)
    assert decided == [False, False, False, False, True, True, False, False, False, False]
    assert whole_runs(decided, np.ones(10, bool)).tolist() == [False, False, True, True, True, True] + [False] * 4
    # a gap row (never given to SideRun) is skipped: the two measured strides before it are the run's
    assert whole_runs([0, 1, 1, 0, 1, 0], [1, 1, 1, 0, 1, 1]).tolist() == [True, True, True, False, True, False]
    assert Step(0.0, 1.0).sideways is False and Step(0.0, 1.0).to_dict()["sideways"] is False


def test_track_streaming_marks_the_side_run_and_the_cvs_leave_it(monkeypatch):
    monkeypatch.setattr(KS, "MIN_SIDE_STRIDES", 3)  # the run mechanism at L219's former 3 (L486 made it 1)
    st = _streamed(_sim(ROUTE, 4742), contacts=True).steps
    flags = st["sideways"].to_numpy(bool)
    whole = sideways_rows(st)
    assert flags.sum() >= 3 and whole.sum() == flags.sum() + 2  # the run's first two strides added back
    assert (np.abs(st["length_m"].to_numpy()[whole]) < 0.8).all()  # side steps, not walk strides
    with_col = clinical_summary(st)
    # the control without the column: L408's backward-travel test (a side stride's chord read along the foot) would
    # keep these strides out of the CVs too, so it is switched off for the control (session 34, lead)
    monkeypatch.setattr("pdrlearn.track.evaluate.backward_travel", lambda steps: None)
    before = clinical_summary(st.assign(sideways=False))
    assert before["stride_length_cv_pct"] > 40 and with_col["stride_length_cv_pct"] < 5
    plain = _streamed(simulate("A", 4743, rate_hz=20.0, seed=1)).steps
    assert "sideways" in plain and not plain["sideways"].to_numpy(bool).any()


def test_an_offline_table_is_read_as_it_is(monkeypatch):
    monkeypatch.setattr(KS, "MIN_SIDE_STRIDES", 3)  # the run mechanism at L219's former 3 (L486 made it 1)
    t = pd.DataFrame({"sideways": [False, False, True, True, True], "gap_s": 0.0})
    assert sideways_rows(t).tolist() == [False, False, True, True, True]  # no pivot_rad: offline's whole runs
    assert sideways_rows(t.assign(pivot_rad=0.0)).tolist() == [True] * 5


@pytest.fixture(scope="module")
def root(tmp_path_factory):
    return trained_dirs(tmp_path_factory)["root"]


def test_tracker_and_run_give_track_streamings_column(root, tmp_path):
    from pdrlearn.cli import main
    from pdrlearn.io import write_session

    s = _sim(ROUTE, 4744)
    logging.disable(logging.WARNING)
    try:
        steps = replay(Tracker(root / "bundle"), s, 0.5)
        ref = get_pipeline("plasys")(s, model=str(root / "model"), streaming=True).steps
        write_session(s, tmp_path / "walk")
        assert main(["run", "--no-plot", str(root / "bundle"), str(tmp_path / "walk"), "--out",
                     str(tmp_path / "out")]) == 0
    finally:
        logging.disable(logging.NOTSET)
    flags = ref["sideways"].to_numpy(bool)
    assert flags.any() and [st.sideways for st in steps] == flags.tolist()
    written = pd.read_csv(tmp_path / "out" / "steps.csv")
    assert written["sideways"].astype(bool).tolist() == flags.tolist()
