"""Decision E213 (session 38, trial T5 finding 10): docs/deploying.md shows how an app reads live turn and stop
events from the runtime's per-step output (turn_angle_rad + pivot_rad summed over a turn, a stop from the time
between steps); its example runs on a tracker's steps."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.runtime.tracker import Tracker
from tests.runtime_helpers import replay, trained_dirs

DOCS = Path(__file__).resolve().parents[1] / "docs" / "deploying.md"


def _example() -> str:
    m = re.search(r"<!-- example: tests/test_runtime_events_e213.py -->\n```python\n(.*?)```", DOCS.read_text(), re.S)
    assert m, "the live-events example of docs/deploying.md is gone"
    return m.group(1)


@pytest.fixture(scope="module")
def root(tmp_path_factory):
    return trained_dirs(tmp_path_factory)["root"]


def test_the_live_events_example_reads_a_stop_and_two_turns(root, tmp_path):
    """User 9793 walks 6 m, stands 4 s, turns 90 deg left from standing, walks, curves 90 deg right: the example
    prints one stop of about 4 s, one left turn and one right turn of 70-110 deg, nothing else."""
    ses = tmp_path / "route"
    assert main(["simulate", "--route", "straight:6, stand:4, turn:90, straight:6, curve:-90:2, straight:3",
                 "--user-seed", "9793", "--out", str(ses)]) == 0
    steps = replay(Tracker(root / "bundle"), read_session(ses), 0.5)
    scope: dict = {}
    exec(compile(_example(), "deploying.md", "exec"), scope)  # noqa: S102 - the documented code itself
    events = [e for st in steps for e in scope["events"].on_step(st)]
    assert len(events) == 3, events
    stop = [e for e in events if "stopped" in e]
    assert len(stop) == 1 and 3.5 < float(re.search(r"stopped ([\d.]+) s", stop[0]).group(1)) < 5.5
    turns = {m.group(1): float(m.group(2)) for e in events if (m := re.search(r"turned (\w+) (\d+) deg", e))}
    assert set(turns) == {"left", "right"} and all(70 <= a <= 110 for a in turns.values()), events


def test_a_turn_then_standing_is_closed_while_standing_e214(root, tmp_path):
    """Decision E214 (review R3 finding 2): user 9856 walks, curves 90 deg left and stands 5 s; on_step alone held
    the turn back (no straight stride follows it); the example's close(now), called after each push with the latest
    sample time, gives it while the walker stands, before the tracker's flush."""
    import math

    from tests.runtime_helpers import time_chunks

    ses = tmp_path / "turn_stand"
    assert main(["simulate", "--route", "straight:6, curve:90:2, stand:5", "--user-seed", "9856",
                 "--out", str(ses)]) == 0
    session = read_session(ses)
    scope: dict = {}
    exec(compile(_example(), "deploying.md", "exec"), scope)  # noqa: S102 - the documented code itself
    events, tracker = scope["events"], Tracker(root / "bundle")
    live = []
    for _, chunk in time_chunks(session, 0.5):
        live += [e for st in tracker.push(chunk) for e in events.on_step(st)]
        live += events.close(max(float(t[-1]) for t, _ in chunk.values() if len(t)))
    turns = [e for e in live if "turned" in e]
    assert len(turns) == 1 and "left" in turns[0], live
    assert 70 <= float(re.search(r"turned left (\d+) deg", turns[0]).group(1)) <= 110
    end = [e for st in tracker.flush() for e in events.on_step(st)] + events.close(math.inf)
    assert not [e for e in end if "turned" in e], end  # closed once, not again at the end
