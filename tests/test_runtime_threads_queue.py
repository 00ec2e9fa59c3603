"""Decision L135 (docs/decisions/localization.md): one producer thread per unit into one Tracker, through a queue.

A new-user trial (session 22, "integrator") pushed one Tracker from a foot thread and a waist thread (unpaced
replay, with a lock): the lag check (E23) refused the unit left behind, 13 of 69 steps. docs/deploying.md now gives a
queue pattern; this runs its code.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from pdrlearn.runtime.tracker import Tracker
from tests.runtime_helpers import replay, synthetic_session, time_chunks

DOCS = Path(__file__).resolve().parents[1] / "docs" / "deploying.md"


@pytest.fixture(scope="module")
def walk():
    return synthetic_session(30, seed=3, name="walk", turn_rad_per_step=0.2)


def _example() -> dict:
    m = re.search(r"<!-- example: tests/test_runtime_threads_queue.py -->\n```python\n(.*?)```", DOCS.read_text(), re.S)
    assert m, "the queue example of docs/deploying.md is gone"
    ns: dict = {}
    exec(compile(m.group(1), "deploying.md", "exec"), ns)  # noqa: S102 - the documentation's own example
    return ns


def test_the_queue_example_gives_one_trackers_steps_from_a_thread_per_unit(synthetic_bundle, walk):
    ref = replay(Tracker(synthetic_bundle), walk, 0.25)
    got = _example()["track_from_units"](Tracker(synthetic_bundle), {
        "foot": (c for _, c in time_chunks(walk, 0.05, "f")), "waist": (c for _, c in time_chunks(walk, 0.3, "w"))})
    assert len(ref) >= 25 and [s.end_s for s in got] == [s.end_s for s in ref]
    assert [s.classes for s in got] == [s.classes for s in ref]
    assert np.allclose([(s.x, s.y, s.z, s.heading_rad) for s in got], [(s.x, s.y, s.z, s.heading_rad) for s in ref],
                       rtol=0, atol=1e-9)

