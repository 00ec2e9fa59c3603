"""Decisions E46 (one 0 m row per foot gap in the streamed tracks, as L67 offline), E47 (`pdrlearn run` gives the
altitude warnings L69 / C28 of `track`, from the same code) and L76 (a gap row's heading is the previous row's)."""

from __future__ import annotations

import json
import logging
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.io import read_session, write_session
from pdrlearn.kernels.altitude_check import integrated_altitude_check
from pdrlearn.orient import wrap_angle
from pdrlearn.runtime.stream import HeightLog
from pdrlearn.runtime.tracker import Tracker
from pdrlearn.track import get_pipeline
from tests.runtime_helpers import replay, synthetic_session, trained_dirs, without

REAL = Path(__file__).resolve().parents[1] / "datasets" / "real"


@pytest.fixture(scope="module")
def root(tmp_path_factory):
    return trained_dirs(tmp_path_factory)["root"]


@pytest.fixture(scope="module")
def walk():
    return synthetic_session(24, seed=11, name="walk", turn_rad_per_step=0.3)


def _rows(steps) -> pd.DataFrame:
    return pd.DataFrame([{"start_s": s.start_s, "end_s": s.end_s, "length_m": s.length_m, "gap_s": s.gap_s,
                          "heading_rad": s.heading_rad, "x": s.x, "y": s.y} for s in steps])


def _same_heading(a, b) -> bool:
    return bool(np.all(np.abs(wrap_angle(np.asarray(a, float) - np.asarray(b, float))) < 1e-6))


# 10.2-11.7 s: one stride ends just after the gap starts, the next starts just before it ends (two touching
# strides, two rows before E46); 9.5-11.0 s: no stride touches the gap (no row before E46)
@pytest.mark.parametrize("cut", [(10.2, 11.7), (9.5, 11.0)])
def test_run_and_track_streaming_make_one_gap_row_per_foot_gap(root, walk, cut):
    s = without(walk, *cut)
    tr = Tracker(root / "bundle")
    run = _rows(replay(tr, s, 1.0))
    st = get_pipeline("plasys")(s, model=str(root / "model"), streaming=True)
    t = st.steps
    assert len(run) == len(t) == tr.n_steps
    for rows in (run, t):
        gap = rows.index[rows["gap_s"] > 0]
        assert len(gap) == 1, rows
        i = int(gap[0])
        assert rows["start_s"].iloc[i] < cut[0] and rows["end_s"].iloc[i] > cut[1] - 0.01
        assert rows["gap_s"].iloc[i] == pytest.approx(cut[1] - cut[0], abs=0.06)
        assert rows["length_m"].iloc[i] == 0
        # the row spans from the stride before to the stride after it: no hole, no overlap
        assert rows["start_s"].iloc[i] == rows["end_s"].iloc[i - 1]
        assert rows["end_s"].iloc[i] == rows["start_s"].iloc[i + 1]
        assert _same_heading(rows["heading_rad"].iloc[i], rows["heading_rad"].iloc[i - 1])  # decision L76
    np.testing.assert_allclose(run[["start_s", "end_s", "gap_s"]], t[["start_s", "end_s", "gap_s"]], atol=1e-9)
    assert _same_heading(run["heading_rad"], t["heading_rad"])
    traj = st.trajectory
    assert len(traj) == len(t) + 1
    np.testing.assert_allclose(traj[["x", "y"]].to_numpy()[1:], run[["x", "y"]].to_numpy(), atol=1e-3)
    np.testing.assert_allclose(traj["t"].to_numpy()[1:], t["end_s"].to_numpy())


def test_a_gap_row_keeps_the_position_and_the_tracker_heading(root, walk):
    """The held gap row is emitted at the next stride, at the position before it (E46)."""
    tr = Tracker(root / "bundle")
    steps = replay(tr, without(walk, 10.2, 11.7), 1.0)
    i = next(k for k, s in enumerate(steps) if s.gap_s > 0)
    assert (steps[i].x, steps[i].y, steps[i].z) == (steps[i - 1].x, steps[i - 1].y, steps[i - 1].z)
    assert np.hypot(steps[i + 1].x - steps[i].x, steps[i + 1].y - steps[i].y) == pytest.approx(
        abs(steps[i + 1].length_m), abs=1e-9)


def test_run_bridges_a_foot_gyroscope_gap_by_default_as_track_streaming(root, walk):
    """Decision L99: `Tracker` (so `pdrlearn run`) turns the stride across a 1.5 s foot-gyroscope gap by the waist
    gyroscope by default, as `track --streaming` does; ``waist_bridge=False`` keeps L90's turn 0."""
    s = without(walk, 10.0, 11.5, names=["fGyroscope"])
    clean = replay(Tracker(root / "bundle"), walk, 1.0)[-1].heading_rad
    run, off = (_rows(replay(Tracker(root / "bundle", **kw), s, 1.0)) for kw in ({}, {"waist_bridge": False}))
    st = get_pipeline("plasys")(s, model=str(root / "model"), streaming=True).steps
    assert (run["gap_s"] > 1.0).sum() == 1
    assert _same_heading(run["heading_rad"], st["heading_rad"])  # parity, 1e-6 rad
    assert np.degrees(abs(wrap_angle(run["heading_rad"].iloc[-1] - clean))) < 5.0
    assert np.degrees(abs(wrap_angle(off["heading_rad"].iloc[-1] - clean))) > 20.0


def test_no_gap_row_before_the_first_stride(root, walk):
    tr = Tracker(root / "bundle")
    steps = replay(tr, without(walk, walk.streams["fAccelerometer"].t[0], 1.6), 1.0)
    assert steps and steps[0].gap_s == 0 and all(s.gap_s == 0 for s in steps)


@pytest.mark.parametrize("cut", [(10.0, 11.3), (10.0, 12.0), (20.0, 22.0)])
def test_offline_and_streamed_agree_on_the_rows_of_a_real_walk_with_a_gap(cut):
    """gaitmap_level_right with the foot streams cut: offline (L67) and --streaming (E46) have the same number of
    rows and one gap row each, whose heading is the previous row's (L76). Before E46 a 2 s cut had no streamed
    row (29 against offline's 30)."""
    logging.disable(logging.WARNING)
    try:
        s = read_session(REAL / "gaitmap_level_right")
        s = without(s, *cut, names=[n for n in s.streams if n.startswith("f")])
        off = get_pipeline("plasys")(s).steps
        st = get_pipeline("plasys")(s, streaming=True).steps
    finally:
        logging.disable(logging.NOTSET)
    assert len(off) == len(st)
    for t in (off, st):
        gap = t.index[t["gap_s"] > 0]
        assert len(gap) == 1
        i = int(gap[0])
        assert t["start_s"].iloc[i] < cut[0] and t["end_s"].iloc[i] > cut[1]
        assert _same_heading(t["heading_rad"].iloc[i], t["heading_rad"].iloc[i - 1])


def test_offline_gap_row_heading_follows_a_stride_turned_by_l65():
    """Decision L76: a stride that L65 reports along heading + pi (negative length, no backward class) is
    followed by a gap row along the same reported heading, not the one before L65's turn."""
    logging.disable(logging.WARNING)
    try:
        s = read_session(REAL / "gaitmap_level_right")
        s = without(s, 10.0, 11.5, names=[n for n in s.streams if n.startswith("f")])
        t = get_pipeline("plasys")(s).steps
    finally:
        logging.disable(logging.NOTSET)
    i = int(t.index[t["gap_s"] > 0][0])
    assert _same_heading(t["heading_rad"].iloc[i], t["heading_rad"].iloc[i - 1])


# -- E47 ---------------------------------------------------------------------------------------------------------


def test_run_gives_the_terrain_dz_check_of_track_streaming(root, walk, tmp_path, capsys, caplog):
    """The synthetic walk's terrain classes contradict its heights (a toy model): `track --streaming` warns
    (C28); `run` on the exported bundle prints the same line and writes the same info in summary.json."""
    from pdrlearn.cli import main

    s = without(walk, 10.2, 11.7)
    st = get_pipeline("plasys")(s, model=str(root / "model"), streaming=True)
    want = st.info["terrain_dz_check"]
    assert want is not None and st.info["altitude_check"] is None
    line = next(w for w in st.info["warnings"] if "terrain classes contradict" in w)
    write_session(s, tmp_path / "gap")
    caplog.clear()
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        assert main(["run", "--no-plot", str(root / "bundle"), str(tmp_path / "gap"), "--out", str(tmp_path / "run"),
                     "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["info"]["terrain_dz_check"] == pytest.approx(want)
    assert out["info"]["altitude_check"] is None
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert summary["info"]["terrain_dz_check"] == pytest.approx(want)
    assert sum(line in r.getMessage() for r in caplog.records) == 1  # printed once, track's words


def test_tracker_without_a_terrain_classifier_says_the_altitude_is_integrated(root, walk):
    """L69's streamed line (no L39 level rule) from the same function as track's, over the processed strides."""
    tr = Tracker(root / "bundle", tasks=["direction"])
    steps = replay(tr, walk, 1.0)
    checks = tr.height_checks()
    assert checks["terrain_dz_check"] is None
    dz = np.array([s.dz_m for s in steps])
    msg, info = integrated_altitude_check(dz, levelled=False)
    assert checks["altitude_check"] == info
    if msg:  # warned once, even after a second call
        tr.height_checks()
        assert tr.warnings.count(msg) == 1 and "streamed: no L39 level rule" in msg
    else:
        assert info["strides_with_height"] == 0


def _log(rows) -> HeightLog:
    log = HeightLog(capacity=2)
    for row in rows:
        log.append(*row)
    return log


def test_tracker_checks_the_heights_it_was_given():
    """The check's inputs, not only its plumbing: a tracker whose strides climb 0.3 m without terrain classes
    warns, one whose strides are level does not (the kernel's threshold, L39's 0.10 m)."""
    tr = Tracker.__new__(Tracker)
    tr.classifiers, tr.warnings = {}, []
    tr.bundle = type("B", (), {"path": "b"})()
    tr._heights = _log([(None, 0.3, 0.3)] * 4 + [(None, 0.0, 0.0)])
    c = tr.height_checks()["altitude_check"]
    assert c["strides_with_height"] == 4 and c["altitude_change_m"] == pytest.approx(1.2) and len(tr.warnings) == 1
    tr._heights, tr.warnings = _log([(None, 0.05, 0.05)] * 5), []
    assert tr.height_checks()["altitude_check"]["strides_with_height"] == 0 and tr.warnings == []
    tr.classifiers = {"terrain": object()}
    tr._heights = _log([("flat", 0.3, 0.3)] * 4)
    c = tr.height_checks()["terrain_dz_check"]
    assert c["flat_with_height"] == 4 and len(tr.warnings) == 1 and "terrain classes contradict" in tr.warnings[0]
