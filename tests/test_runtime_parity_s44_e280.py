"""Decision E280 (session 44, I1): the live ``Tracker`` (``pdrlearn run``) skips pedalling strides (decision L611) as
``track --streaming`` does, by the same kernel (``kernels.pedal.closed_loop_strides``) and with the same warning line.

Before E280 `run` kept every crank half-turn of a bike ride as a stride (46 steps where ``track --streaming`` had 13 on
the ride below). A stride's verdict reads up to two strides after it, so the tracker holds a stride only while the
verdict could still be "pedalling" (``kernels.pedal.LiveLoops``): walking strides are emitted at once."""

from __future__ import annotations

import json
import logging
from pathlib import Path

import numpy as np
import pytest

from pdrlearn.kernels.pedal import CHAIN_PAUSE_S, REACH, LiveLoops, closed_loop_strides
from tests import test_pedal_s43_l611

ROOT = Path(__file__).resolve().parents[1]
ride = test_pedal_s43_l611.ride  # L611's 40 rpm ride: its fixture, shared
DIST_TOL_M = 1e-9  # the same strides, placed by the same arithmetic: rounding only


def _live(session, restart_at: float | None = None):
    """``pdrlearn run``'s Tracker (the shipped bundle, no classifier: ``track --streaming``'s M2) fed 1 s chunks;
    with ``restart_at`` a new tracker resumed from the old one's JSON restart state there (L134)."""
    from pdrlearn.runtime import Tracker, load_bundle
    from tests.runtime_helpers import time_chunks

    bundle = load_bundle(ROOT / "models" / "plasys-sim-default")
    kw = {"tasks": [], "sensors": list(session.streams)}
    tr, steps, held = Tracker(bundle, **kw), [], None
    logging.disable(logging.WARNING)
    try:
        for t0, chunk in time_chunks(session, 1.0):
            if restart_at is not None and held is None and t0 >= restart_at:
                held = len(tr._loops.held)
                tr = Tracker(bundle, resume=json.loads(json.dumps(tr.restart_state())), **kw)
            steps += tr.push(chunk)
        steps += tr.flush()
    finally:
        logging.disable(logging.NOTSET)
    return tr, steps, held


def _streamed(session):
    from pdrlearn.track.plasys import track_plasys

    logging.disable(logging.WARNING)
    try:
        return track_plasys(session, streaming=True, method="M2")
    finally:
        logging.disable(logging.NOTSET)


def test_run_skips_the_ride_as_track_streaming_e280(ride):
    s, a, b = ride
    tr, steps, _ = _live(s)
    res = _streamed(s)
    st = res.steps
    assert [(x.start_s, x.end_s) for x in steps] == list(zip(st["start_s"], st["end_s"], strict=True))  # main: 46/13
    assert not any(x.end_s > a and x.start_s < b for x in steps)
    assert abs(sum(abs(x.length_m) for x in steps) - float(st["length_m"].abs().sum())) < DIST_TOL_M
    end = res.trajectory.iloc[-1]
    assert abs(steps[-1].x - end["x"]) < DIST_TOL_M and abs(steps[-1].y - end["y"]) < DIST_TOL_M
    assert abs(steps[-1].heading_rad - float(st["heading_rad"].iloc[-1])) < 1e-9  # the ride's turns kept
    live = [w for w in tr.warnings if "cycling?" in w]
    assert live == [w for w in res.info["warnings"] if "cycling?" in w] and len(live) == 1 and "L611" in live[0]


def test_a_restart_inside_the_ride_gives_the_uninterrupted_track_e280(ride):
    """The strides held for their verdict are measured again by the resumed tracker (the state restarts before the
    first held one, with the verdicts' neighbours)."""
    s, a, b = ride
    _, ref, _ = _live(s)
    for at in (a + 6.0, a + 6.5, b - 1.0):
        _, got, held = _live(s, at)
        assert held >= 1  # the case: strides were held at the restart
        assert [(x.start_s, x.end_s) for x in got] == [(x.start_s, x.end_s) for x in ref]
        assert np.allclose([(x.x, x.y, x.heading_rad) for x in got], [(x.x, x.y, x.heading_rad) for x in ref],
                           rtol=0, atol=1e-9)


def _rows(rng, n):
    dur = rng.uniform(0.6, 1.1, n)
    start = np.r_[0.0, np.cumsum(dur[:-1] + rng.choice([0.0, 0.0, 0.0, 0.5, 2.0], n - 1))]
    dz = rng.choice([-1, 1], n) * rng.uniform(0.0, 0.4, n)
    unrested = rng.uniform(size=n) < 0.3
    travel = rng.uniform(0.0, 1.5, n)
    judged = rng.uniform(size=n) < 0.9
    return start, start + dur, dz, unrested, travel, judged


@pytest.mark.parametrize("seed", range(30))
def test_the_stride_by_stride_verdicts_are_the_kernel_s_e280(seed):
    """L611's kernel on the whole recording (``track --streaming``'s call, unjudged rows at dz 0 and never
    pedalling) and LiveLoops fed one stride at a time give the same verdicts, released in order."""
    rng = np.random.default_rng(seed)
    s0, s1, dz, unrested, travel, judged = _rows(rng, 40)
    want = closed_loop_strides(np.where(judged, dz, 0.0), s0, s1, unrested & judged, travel) & judged
    loops, got, at_once = LiveLoops(), [], 0
    for i in range(len(s0)):
        out = loops.add((s0[i], s1[i], dz[i], unrested[i], travel[i], judged[i]), i)
        at_once += any(p == i for p, _ in out)
        got += out
    got += loops.flush()
    assert [p for p, _ in got] == list(range(len(s0)))
    assert [v for _, v in got] == want.tolist()
    assert len(loops.history) <= REACH  # decision L640: one more than L611's NEIGHBOURS


def test_walking_strides_are_released_at_once_and_a_pause_ends_a_chain_e280():
    loops = LiveLoops()
    for i in range(10):  # level strides: 1.4 m, a few cm of height, rested
        out = loops.add((i * 1.0, i * 1.0 + 1.0, 0.03 * (-1) ** i, False, 1.4, True), i)
        assert out == [(i, False)]
    crank = [(20.0 + 0.75 * k, 20.75 + 0.75 * k, 0.2 * (-1) ** k, True, 0.1, True) for k in range(2)]
    assert loops.add(crank[0], "a") == [] and loops.add(crank[1], "b") == []  # held: could be pedalling
    assert loops.expire(21.5 + CHAIN_PAUSE_S, 1.0) == []  # not quiet long enough
    assert loops.expire(23.0, 1.0) == [("a", False), ("b", False)]  # two strides alone: too few reversals


def test_pdrlearn_run_writes_the_whole_line_once_and_no_ride_row_e280(ride, tmp_path):
    """`pdrlearn run` (the shipped bundle, its classifiers) on the ride: no row inside it, and summary.json's warnings
    hold L611's line once, with every removed stride (the line is logged at the flush, not at the first stride)."""
    import pandas as pd

    from pdrlearn.cli import main
    from pdrlearn.io import write_session

    s, a, b = ride
    write_session(s, tmp_path / "ride")
    assert main(["run", "--no-plot", str(ROOT / "models" / "plasys-sim-default"), str(tmp_path / "ride"), "--out",
                 str(tmp_path / "o")]) == 0
    st = pd.read_csv(tmp_path / "o" / "steps.csv")
    assert len(st) == 13 and not ((st["end_s"] > a) & (st["start_s"] < b)).any()  # main: 46 rows, 33 in the ride
    lines = [w for w in json.loads((tmp_path / "o" / "summary.json").read_text())["info"]["warnings"]
             if "cycling?" in w]
    assert len(lines) == 1 and "33 stride(s) at 27.40-52.30 s (33)" in lines[0], lines
