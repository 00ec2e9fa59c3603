"""Decision E300 (docs/decisions/localization.md): what a crash-restart from a saved ``restart_state()`` loses.

Trial T2 (session 45, F4) saved the state after every push that returned steps, crashed and resumed, and ended
6-11 m off on a 45 m walk where losing "the same" packets without a restart ended 1.7-7.2 m off. Measured (E300): the
resumed tracker gives exactly what one tracker gives on the samples it was given: those pushed up to the save, then
those pushed after the restart. A crash loses only samples: the pushes after the last save and whatever the gateway
held (its reorder buffer) -- nothing of the tracker's state. An app that logs the chunks it pushes since the last
save and pushes them again into the resumed tracker gets the uninterrupted track.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from pdrlearn.runtime.tracker import Tracker
from tests.runtime_helpers import synthetic_session, time_chunks

CHUNK_S = 0.25


@pytest.fixture(scope="module")
def walk():
    return synthetic_session(40, seed=12830, name="walk", turn_rad_per_step=0.3)


def _same(got: list, ref: list) -> None:
    assert len(got) == len(ref)
    for a, r in zip(got, ref, strict=True):
        assert (a.start_s, a.end_s, a.classes, a.gap_s) == (r.start_s, r.end_s, r.classes, r.gap_s)
        assert np.allclose([a.length_m, a.dz_m, a.heading_rad, a.x, a.y, a.z],
                           [r.length_m, r.dz_m, r.heading_rad, r.x, r.y, r.z], rtol=0, atol=1e-9)


def _crash(bundle, chunks, crash_at: float, down_s: float, replay: bool):
    """The gateway saves the state after each push that returns steps, dies at ``crash_at`` (s of stream time) and
    is back ``down_s`` later: the pushes since the save are lost unless ``replay`` pushes them again (its log).
    Returns the steps and the chunks the trackers were given, in order (what one tracker would have been fed)."""
    tr, steps, saved, fed, n_saved = Tracker(bundle), [], None, [], 0
    crashed = False
    for t0, c in chunks:
        if not crashed and t0 >= crash_at:
            crashed = True
            tr = Tracker(bundle, resume=json.loads(saved))
            if replay:  # the log of the chunks pushed since the save, pushed again
                steps += [s for old in fed[n_saved:] for s in tr.push(old)]
            else:
                del fed[n_saved:]
        if crashed and t0 < crash_at + down_s:
            continue
        new = tr.push(c)
        steps += new
        fed.append(c)
        if new and not crashed:
            saved, n_saved = json.dumps(tr.restart_state()), len(fed)
    return steps + tr.flush(), fed


@pytest.mark.parametrize("crash_at", [9.0, 17.5, 26.25])
def test_a_crash_restart_loses_the_samples_since_the_save_and_nothing_else(synthetic_bundle, walk, crash_at):
    b = synthetic_bundle
    chunks = list(time_chunks(walk, CHUNK_S))
    got, fed = _crash(b, chunks, crash_at, 0.5, replay=False)
    one = Tracker(b)
    ref = [s for c in fed for s in one.push(c)] + one.flush()
    _same(got, ref)
    clean = Tracker(b)
    uninterrupted = [s for _, c in chunks for s in clean.push(c)] + clean.flush()
    assert abs(got[-1].x - uninterrupted[-1].x) + abs(got[-1].y - uninterrupted[-1].y) > 1e-6  # samples were lost


@pytest.mark.parametrize("crash_at", [9.0, 17.5])
def test_the_chunks_logged_since_the_save_pushed_again_give_the_uninterrupted_track(synthetic_bundle, walk, crash_at):
    b = synthetic_bundle
    chunks = list(time_chunks(walk, CHUNK_S))
    got, _ = _crash(b, chunks, crash_at, 0.0, replay=True)
    clean = Tracker(b)
    _same(got, [s for _, c in chunks for s in clean.push(c)] + clean.flush())
