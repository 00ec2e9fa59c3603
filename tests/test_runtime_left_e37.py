"""Decisions E37-E41 (docs/decisions/export.md): the runtime items left by the session-13 review.

- E37: ``pdrlearn run``'s steps.csv has the ``gap_s`` column of ``Step``;
- E38: a non-finite heading or position after a step is an ``InternalError`` (a bug, not bad data), state unchanged;
- E39: the held-values warning (E31) is relative to each stream's own rate: a 0.2 Hz barometer is not "held";
- E40: an empty push is a no-op for ``Tracker`` and ``WaistTracker``;
- E41: ``Tracker._rate_checked`` (written, never read) is gone.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pandas as pd
import pytest

from pdrlearn.errors import DataError, InternalError
from pdrlearn.io import Stream, write_session
from pdrlearn.runtime import tracker as T
from pdrlearn.runtime.tracker import Tracker
from tests.runtime_helpers import per_timestamp, replay, synthetic_session, trained_dirs, without


@pytest.fixture(scope="module")
def root(tmp_path_factory):
    return trained_dirs(tmp_path_factory)["root"]


@pytest.fixture(scope="module")
def walk():
    return synthetic_session(24, seed=11, name="walk", turn_rad_per_step=0.3)




# -- E37 ---------------------------------------------------------------------------------------------------------
def test_run_writes_the_gap_s_of_each_stride_in_steps_csv(root, walk, tmp_path, capsys):
    from pdrlearn.cli import main

    write_session(without(walk, 10.2, 11.7), tmp_path / "gap")
    assert main(["run", "--no-plot", str(root / "bundle"), str(tmp_path / "gap"), "--out", str(tmp_path / "run"),
                 "--json"]) == 0
    capsys.readouterr()
    steps = pd.read_csv(tmp_path / "run" / "steps.csv")
    assert "gap_s" in steps.columns
    gap = steps[steps.gap_s > 0]
    assert 1 <= len(gap) <= 2 and np.allclose(gap.gap_s, 1.55) and (gap.length_m == 0).all()
    assert (steps.gap_s[steps.gap_s > 0].index == gap.index).all() and (steps.gap_s >= 0).all()


def test_run_writes_gap_s_0_for_strides_without_a_gap(root, walk, tmp_path, capsys):
    from pdrlearn.cli import main

    write_session(walk, tmp_path / "w")
    assert main(["run", "--no-plot", str(root / "bundle"), str(tmp_path / "w"), "--out", str(tmp_path / "r"),
                 "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    steps = pd.read_csv(tmp_path / "r" / "steps.csv")
    assert (steps.gap_s == 0).all() and out["n_steps"] == len(steps)


# -- E38 ---------------------------------------------------------------------------------------------------------
def test_a_non_finite_heading_or_position_after_a_step_is_an_internal_error(root, walk, monkeypatch):
    real = T.stride_motion
    calls = []

    def broken(lev, src, **kw):  # a bug in the stride kernel, on data that passed every check
        disp, dyaw = real(lev, src, **kw)
        calls.append(1)
        return (disp * np.nan, dyaw) if len(calls) == 5 else (disp, dyaw)

    monkeypatch.setattr(T, "stride_motion", broken)
    tr = Tracker(root / "bundle", speculative=False)
    with pytest.raises(InternalError, match=r"^internal error in pdrlearn\.runtime: the stride .* gave a non-finite "
                                            r"(heading|position).*this is a bug, not bad data"):
        replay(tr, walk, 0.37)
    assert tr.n_steps == 4 and np.isfinite(tr.position).all() and math.isfinite(tr.heading)  # not taken


# -- E39 ---------------------------------------------------------------------------------------------------------
def _slow_baro(s, every: int):
    c = s.copy()
    b = s.streams["wBarometer"]
    c.streams["wBarometer"] = Stream("wBarometer", b.t[::every], b.values[::every])
    return c


@pytest.mark.parametrize("pushes", ["per sample", "chunks"])
def test_a_slow_barometer_is_not_held_and_a_stuck_accelerometer_is(root, walk, pushes):
    s = _slow_baro(walk, 100)  # 0.2 Hz (5 s between samples)
    tr = Tracker(root / "bundle", max_lag_s=float("inf"))
    steps = (replay(tr, s, 0.37) if pushes == "chunks"
             else [st for c in per_timestamp(s) for st in tr.push(c)] + tr.flush())
    assert len(steps) >= 20 and not [w for w in tr.warnings if "last values held" in w], tr.warnings
    stuck = without(s, 12.0, 1e9, names=("wAccelerometer",))
    tr = Tracker(root / "bundle", max_lag_s=float("inf"))
    steps = (replay(tr, stuck, 0.37) if pushes == "chunks"
             else [st for c in per_timestamp(stuck) for st in tr.push(c)] + tr.flush())
    held = [w for w in tr.warnings if "last values held" in w]
    assert len(held) == 1 and held[0].startswith("wAccelerometer: no samples since 11.95 s"), tr.warnings


# -- E40 ---------------------------------------------------------------------------------------------------------
def _state(tr: Tracker) -> tuple:
    return ({n: (len(r), r.last) for n, r in tr._buf.items()}, {n: len(p[0]) for n, p in tr.inputs._probe.items()},
            tr._latest, list(tr._foot_q), tr.n_steps, tr._pending[:], tr._spec is None, tr._lag_next,
            tuple(tr.position), tr.heading, len(tr.warnings))


@pytest.mark.parametrize("k", [0, 150])
def test_an_empty_push_is_a_no_op(root, walk, k):
    chunks = per_timestamp(walk)
    tr = Tracker(root / "bundle")
    for c in chunks[:k]:
        tr.push(c)
    before = _state(tr)
    for empty in ({}, [], {"fAccelerometer": ([], [])}, {"fAccelerometer": (np.empty(0), np.empty((0, 3))),
                                                         "wBarometer": ([], [])}):
        assert tr.push(empty) == []
        assert _state(tr) == before
    with pytest.raises(DataError, match="^fAccelerometer: pushed values of shape"):
        tr.push({"fAccelerometer": ([], [[1.0, 2.0, 3.0]])})  # no times for a sample: still refused


def test_an_empty_push_of_the_waist_tracker_is_a_no_op():
    from pdrlearn.waist.live import WaistTracker

    sim = pytest.importorskip("pdrlearn.sim")
    s = sim.simulate("A", 1)
    a, g = s.streams["wAccelerometer"], s.streams["wGyroscope"]
    tr = WaistTracker(a.rate_hz, frame=s.frames["waist"])
    ref = WaistTracker(a.rate_hz, frame=s.frames["waist"])
    got, want = [], []
    for i in range(0, len(a.t), 7):
        got += tr.push([], [], [])
        got += tr.push(np.empty(0), np.empty((0, 3)), np.empty((0, 3)))
        got += tr.push(a.t[i:i + 7], a.values[i:i + 7], g.values[i:i + 7])
        want += ref.push(a.t[i:i + 7], a.values[i:i + 7], g.values[i:i + 7])
    assert tr.push([], [], []) == []
    got += tr.flush()
    want += ref.flush()
    assert [(st.t, st.length_m) for st in got] == [(st.t, st.length_m) for st in want] and len(want) >= 20


# -- E41 ---------------------------------------------------------------------------------------------------------
def test_the_tracker_has_no_write_only_rate_set(root):
    assert not hasattr(Tracker(root / "bundle"), "_rate_checked")
