"""Decision E48: `pdrlearn run` (and `track --streaming`) fill the L79 walking time and gait speed and the L82
distance error scope from their steps table, with `pdrlearn.track.gait`'s functions; what the streamed table
cannot give (no initial contact: stride time, cadence, per-stride speed, the straight strides' speed) stays
None / 0."""

from __future__ import annotations

import json
import logging
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.track.gait import gait_summary

BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"


@pytest.fixture(autouse=True)
def _quiet():  # restored after each test: a level left behind hides other tests' warnings
    logging.disable(logging.WARNING)
    yield
    logging.disable(logging.NOTSET)


def test_a_streamed_foot_table_gets_walking_time_and_gait_speed():
    # run's columns: no event_s / stride_time_s; two strides, a gap row (0 m), two strides, a 4 s stop, one stride
    t = pd.DataFrame({"start_s": [0.0, 1.0, 2.0, 5.0, 6.0, 11.0], "end_s": [1.0, 2.0, 5.0, 6.0, 7.0, 12.0],
                      "length_m": [1.2, 1.2, 0.0, 1.3, 1.3, 1.0], "heading_rad": 0.0,
                      "gap_s": [0.0, 0.0, 2.5, 0.0, 0.0, 0.0], "unit": "foot"})
    g = gait_summary(t)
    assert g["walking_time_s"] == pytest.approx(2.0 + 2.0 + 1.0)  # split at the gap row and at the stop
    assert g["gait_speed_mps"] == pytest.approx(6.0 / 5.0)
    # no initial contact in a streamed table: nothing per stride
    assert g["median_speed_straight_mps"] is None and g["n_straight_strides"] == 0
    assert g["median_stride_time_s"] is None and g["n_stride_times"] == 0 and g["median_cadence_spm"] is None
    # a table of no known unit (e.g. the synthetic drift pipeline) is left as before
    assert gait_summary(t.drop(columns="unit"))["walking_time_s"] is None


def test_run_summary_has_walking_time_gait_speed_and_error_scope(tmp_path, capsys):
    from pdrlearn.io import write_session
    from pdrlearn.sim import simulate

    write_session(simulate("A", user_seed=42), tmp_path / "A")
    assert main(["run", "--no-plot", str(BUNDLE), str(tmp_path / "A"), "--out", str(tmp_path / "r")]) == 0
    assert "gait speed" in capsys.readouterr().out
    assert main(["track", "--no-plot", str(tmp_path / "A"), "--out", str(tmp_path / "t")]) == 0
    run, trk = (json.loads((tmp_path / d / "summary.json").read_text()) for d in ("r", "t"))
    assert run["distance_error_pct"] is not None and run["distance_error_scope"] == "whole track"  # L82
    # the same walk, rest to rest: within 0.1 s of track's walking time (17.35 vs 17.36 s when written)
    assert run["walking_time_s"] == pytest.approx(trk["walking_time_s"], abs=0.1)
    assert run["gait_speed_mps"] == pytest.approx(run["distance_m"] / run["walking_time_s"])
    assert 0.9 < run["gait_speed_mps"] < 1.4
    # decision L222 (was E48's None / 0): no contacts, so the straight strides' speed comes from their gait cycle
    assert run["median_speed_straight_mps"] == pytest.approx(trk["median_speed_straight_mps"], abs=0.1)
    assert run["n_straight_strides"] >= 5
    steps = pd.read_csv(tmp_path / "r" / "steps.csv")
    assert run["walking_time_s"] <= float(steps["end_s"].iloc[-1] - steps["start_s"].iloc[0]) + 1e-9


def test_run_and_track_streaming_split_the_walking_time_at_a_gap(tmp_path_factory):
    from pdrlearn.cli.export import streamed_result
    from pdrlearn.runtime.tracker import Tracker
    from pdrlearn.track import get_pipeline
    from tests.runtime_helpers import replay, synthetic_session, trained_dirs, without

    root = trained_dirs(tmp_path_factory)["root"]
    # a gentle curve (0.1 rad a stride): the gap's heading change (~23 deg) stays under L194's 30 deg, so the gap is a
    # break, not a turn's time; at 0.3 rad a stride E354's bridge reads ~73 deg across it and L194 rightly times the
    # gap as turning (the walker walked through it), which is no longer E48's case
    walk = synthetic_session(24, seed=11, name="walk", turn_rad_per_step=0.1)
    whole = gait_summary(streamed_result(replay(Tracker(root / "bundle"), walk, 1.0)).steps)
    s = without(walk, 10.2, 11.7)
    run = gait_summary(streamed_result(replay(Tracker(root / "bundle"), s, 1.0)).steps)
    st = gait_summary(get_pipeline("plasys")(s, model=str(root / "model"), streaming=True).steps)
    assert run["walking_time_s"] == pytest.approx(st["walking_time_s"], abs=1e-6)
    assert run["gait_speed_mps"] == pytest.approx(st["gait_speed_mps"], rel=1e-6)
    # the gap row's stretch (about 1.5 s of missing foot data and the strides it cuts) is not walking time
    assert np.isfinite(whole["walking_time_s"]) and run["walking_time_s"] < whole["walking_time_s"] - 1.0
