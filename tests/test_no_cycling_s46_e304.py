"""Decision E304 (session 46, FK, trial T2 finding F5): ``run --no-cycling`` / ``Tracker(cycling=False)`` /
``track --no-cycling`` / ``track_plasys(cycling=False)``: an activity without bicycles judges no stride pedalling
(L611), so the live tracker holds none for that verdict (E280's hold delayed a dancer's short turning strides
1.7-3.8 s); the live and streamed tracks stay one computation with the option. And the rate-mismatch line that
offers ``--resample`` names the delay its filter adds."""

from __future__ import annotations

import logging
import re
from pathlib import Path

import numpy as np

from pdrlearn.kernels.pedal import LiveLoops
from tests import test_pedal_s43_l611
from tests.test_runtime_parity_s44_e280 import DIST_TOL_M

ROOT = Path(__file__).resolve().parents[1]
ride = test_pedal_s43_l611.ride  # L611's 40 rpm ride: its fixture, shared


def _crank_rows(n: int = 8) -> list[tuple]:
    """A chain of crank half-turns: chained, reversing, unrested, no travel (L611 calls them pedalling)."""
    return [(1.0 * k, 1.0 * k + 0.8, 0.3 * (-1) ** k, True, 0.0, True) for k in range(n)]


def test_live_loops_without_judging_release_every_row_at_once_as_walking_e304():
    judged, free = LiveLoops(), LiveLoops(judge=False)
    got_judged, got_free = [], []
    for k, row in enumerate(_crank_rows()):
        got_judged += judged.add(row, k)
        out = free.add(row, k)
        assert out == [(k, False)] and not free.held  # released by the add that brought it, walking
        got_free += out
    got_judged += judged.flush()
    assert any(p for _, p in got_judged)  # the default judges the crank pedalling (the case)
    assert free.flush() == []


def _live(session, **kw):
    """``pdrlearn run``'s Tracker (the shipped bundle, no classifier: ``track --streaming``'s M2) in 1 s chunks; the
    most strides held after any push."""
    from pdrlearn.runtime import Tracker, load_bundle
    from tests.runtime_helpers import time_chunks

    tr = Tracker(load_bundle(ROOT / "models" / "plasys-sim-default"), tasks=[], sensors=list(session.streams), **kw)
    steps, most_held = [], 0
    logging.disable(logging.WARNING)
    try:
        for _, chunk in time_chunks(session, 1.0):
            steps += tr.push(chunk)
            most_held = max(most_held, len(tr._loops.held))
        steps += tr.flush()
    finally:
        logging.disable(logging.NOTSET)
    return tr, steps, most_held


def _streamed(session, **kw):
    from pdrlearn.track.plasys import track_plasys

    logging.disable(logging.WARNING)
    try:
        return track_plasys(session, streaming=True, method="M2", **kw)
    finally:
        logging.disable(logging.NOTSET)


def test_no_cycling_live_equals_streamed_and_holds_nothing_e304(ride):
    s, a, b = ride
    _, ref, held = _live(s)
    assert held >= 1  # the default holds the crank's strides for their verdict
    tr, steps, held = _live(s, cycling=False)
    assert held == 0  # no stride waits for a verdict
    res = _streamed(s, cycling=False)
    st = res.steps
    assert [(x.start_s, x.end_s) for x in steps] == list(zip(st["start_s"], st["end_s"], strict=True))
    assert len(steps) > len(ref)  # the crank's strides are strides now (nothing judged pedalling)
    assert any(x.end_s > a and x.start_s < b for x in steps)
    assert abs(sum(abs(x.length_m) for x in steps) - float(st["length_m"].abs().sum())) < DIST_TOL_M
    end = res.trajectory.iloc[-1]
    assert abs(steps[-1].x - end["x"]) < DIST_TOL_M and abs(steps[-1].y - end["y"]) < DIST_TOL_M
    assert not [w for w in tr.warnings + list(res.info["warnings"]) if "cycling?" in w]


def test_offline_no_cycling_keeps_the_crank_strides_e304(ride):
    from pdrlearn.track.plasys import track_plasys

    s, a, b = ride
    logging.disable(logging.WARNING)
    try:
        kw = {"ignore_force": True, "transfers": False}  # L612's seated span left out: L611 alone
        on, off = track_plasys(s, **kw), track_plasys(s, cycling=False, **kw)
    finally:
        logging.disable(logging.NOTSET)
    inside = [int(((r.steps["end_s"] > a) & (r.steps["start_s"] < b)).sum()) for r in (on, off)]
    assert inside[0] == 0 and inside[1] > 0
    assert any("cycling?" in w for w in on.info["warnings"])
    assert not any("cycling?" in w for w in off.info["warnings"])


def test_tracker_refuses_a_non_boolean_cycling_e304():
    import pytest

    from pdrlearn.errors import DataError
    from pdrlearn.runtime import Tracker, load_bundle

    with pytest.raises(DataError, match="cycling"):
        Tracker(load_bundle(ROOT / "models" / "plasys-sim-default"), cycling="no")


def test_the_native_rate_line_names_resample_s_delay_e304():
    """The line that offers ``--resample`` names the delay the resampler's own line names (840 ms, 100 -> 20 Hz)."""
    from pdrlearn.runtime.resample import StreamResampler, native_message, resample_message

    rates = {"fAccelerometer": 100.0, "fGyroscope": 100.0}
    line = native_message(rates, 20.0)
    said = resample_message({n: StreamResampler(r, 20.0) for n, r in rates.items()}, 20.0)
    delay = re.search(r"(\d+) ms delay", said).group(1)
    assert f"delays every step by {delay} ms more" in line and "`--resample`" in line
    assert "ms" not in native_message({"fAccelerometer": 10.0}, 20.0)  # upsampling: no filter, no delay named
    assert np.isfinite(float(delay))
