"""Session 48 FB, review R1-F3 (decision E310): with live-sized pushes the live rate-change line (E309) waits until
every stream has judged the change's blocks, so it names every stream that changed - bounded, and said at flush."""

from __future__ import annotations

import numpy as np

from pdrlearn.kernels.rate_change import BLOCK_S, STRETCH_BLOCKS
from pdrlearn.runtime.rate_watch import HOLD_BLOCKS, RateWatch

NAMES = ("fAccelerometer", "fGyroscope", "wAccelerometer")


def _times(change: bool, end_s: float = 30.0) -> np.ndarray:
    """100 Hz from 0.003 s; with ``change`` every other sample from 12 s on (50 Hz)."""
    t = 0.003 + np.arange(int(end_s * 100)) / 100.0
    return t[(t < 12.0) | (np.arange(t.size) % 2 == 0)] if change else t


def _push(watch: RateWatch, streams: dict, step_s: float = 0.01) -> list[tuple[float, str]]:
    """``streams`` pushed in ``step_s`` slices; the lines said, each with the push's end (s)."""
    said = []
    for a in np.arange(0.0, max(t[-1] for t in streams.values()) + step_s, step_s):
        p = {n: (t[(t >= a) & (t < a + step_s)], None) for n, t in streams.items()}
        said += [(a + step_s, x) for x in watch.push({n: v for n, v in p.items() if len(v[0])})]
    return said + [(np.inf, x) for x in watch.flush()]


def test_small_pushes_name_every_stream_that_changed_e310():
    # the foot's two streams change at 12 s, the waist's does not: the line names the foot's two only
    streams = {"fAccelerometer": _times(True), "fGyroscope": _times(True), "wAccelerometer": _times(False)}
    watch = RateWatch(NAMES)
    said = _push(watch, streams)
    assert [x.split(":")[0] for _, x in said] == ["fAccelerometer, fGyroscope"], said
    assert "100 -> 50 Hz at 12.0 s" in said[0][1]
    # found when the new stretch's last block closes (about 17 s); said within one block more, not at the walk's end
    assert said[0][0] < 12.0 + (STRETCH_BLOCKS + 1) * BLOCK_S
    assert [c["streams"] for c in watch.changes] == [["fAccelerometer", "fGyroscope"]]


def test_a_stream_that_stops_does_not_hold_the_line_e310():
    # the waist stream stops at 13 s: the foot's line is said within HOLD_BLOCKS blocks of its first stream's, not at
    # flush
    streams = {"fAccelerometer": _times(True), "fGyroscope": _times(True), "wAccelerometer": _times(False, 13.0)}
    said = _push(RateWatch(NAMES), streams)
    assert len(said) == 1 and said[0][1].startswith("fAccelerometer, fGyroscope:"), said
    assert said[0][0] < 12.0 + (STRETCH_BLOCKS + HOLD_BLOCKS) * BLOCK_S + 0.1


def test_a_held_line_is_said_at_flush_e310():
    # the recording ends while the line is held: flush says it, naming both streams
    streams = {n: _times(True, 17.5) for n in NAMES[:2]}
    said = _push(RateWatch(NAMES[:2]), streams, 0.5)
    assert [x.split(":")[0] for _, x in said] == ["fAccelerometer, fGyroscope"], said
