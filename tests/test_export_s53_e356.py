"""Decision E356: a live foot ``Tracker`` stopped, saved (``restart_state``, through JSON) and restored
(``Tracker(resume=state)``) gives the rows of an uninterrupted one, also with ``altitude="fused"`` (E339's barometer,
filter and rows waiting for it) and across a dropout of every sensor (E354's held waist gap, the contacts it reads the
stride before from, E46's pending gap row). One short simulated walk (user 5356), every sensor silent 10.2-13.2 s."""

from __future__ import annotations

import json
import logging
from pathlib import Path

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.runtime import Tracker, load_bundle
from tests.runtime_helpers import without, written_route

SHIPPED = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"
KW = {"clock_check": False, "stream_checks": False}


@pytest.fixture(scope="module")
def dropout(tmp_path_factory):
    from pdrlearn.io import read_session

    folder = written_route(tmp_path_factory.mktemp("e356") / "walk", "stand:2, straight:20, stand:2", 5356)
    return without(read_session(folder, streamed=True), 10.2, 13.2), load_bundle(SHIPPED)


def _run(s, bundle, split: int | None = None, seen: list | None = None, **kw) -> list:
    """Push ``s`` in 0.5 s chunks; before chunk ``split`` save the state through JSON and go on in a new tracker."""
    tr, out = Tracker(bundle, **KW, **kw), []
    k = {n: np.floor(st.t / 0.5 + 1e-9).astype(int) for n, st in s.streams.items() if n in tr.used_sensors}
    for c in range(int(max(v.max() for v in k.values())) + 1):
        if c == split:
            state = json.loads(json.dumps(tr.restart_state()))
            if seen is not None:
                seen.append(state)
            tr = Tracker(bundle, resume=state, **KW, **kw)
        out += tr.push({n: (s[n].t[i == c], s[n].values[i == c]) for n, i in k.items() if (i == c).any()})
    return out + tr.flush()


def _same(got, ref):
    assert len(got) == len(ref) >= 9
    for a, r in zip(got, ref, strict=True):
        assert (a.start_s, a.end_s, a.classes, a.gap_s) == (r.start_s, r.end_s, r.classes, r.gap_s)
        np.testing.assert_allclose([a.length_m, a.dz_m, a.heading_rad, a.x, a.y, a.z],
                                   [r.length_m, r.dz_m, r.heading_rad, r.x, r.y, r.z], rtol=0, atol=1e-9)


@pytest.fixture(scope="module")
def fused_ref(dropout):
    return _run(*dropout, altitude="fused")


# chunk 19 (9.5 s): a fused row waits for the barometer; 28 (14.0 s): E354's gap turn and E46's gap row are held
@pytest.mark.parametrize("split", [19, 28, 33])
def test_a_restored_fused_tracker_gives_the_uninterrupted_rows_across_a_dropout(dropout, fused_ref, split):
    seen = []
    _same(_run(*dropout, split, seen, altitude="fused"), fused_ref)
    state = seen[0]
    if split == 19:
        assert state["fused"]["held"], "the split holds a row waiting for the barometer"
    if split == 28:
        assert state["bridge_cycle"]["gap_s"] > 2.9 and state["gap_row"] is not None and state["contacts"]


def test_a_state_saved_before_e356_restores_and_the_other_altitude_is_refused(dropout, caplog):
    s, bundle = dropout
    seen = []
    _run(s, bundle, 28, seen, altitude="fused")
    state = seen[0]
    with pytest.raises(DataError, match=r"^Tracker\(resume=state\): the state was saved by a Tracker\("
                                        r"altitude='fused'\) and this one tracks altitude='foot'; resume with "
                                        r"altitude='fused'"):
        Tracker(bundle, resume=state, **KW)
    old = {k: v for k, v in state.items() if k not in ("bridge_cycle", "gap_row", "row_gaps", "contacts", "altitude",
                                                       "fused")}
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        tr = Tracker(bundle, resume=old, altitude="fused", **KW)
    assert any("saved before decision E356" in w for w in tr.warnings)
    foot = Tracker(bundle, resume=old, **KW)  # as before E356: no line
    assert not any("E356" in w for w in foot.warnings)
    with pytest.raises(DataError, match=r"^Tracker\(resume=state\): .*not finite"):
        Tracker(bundle, resume={**state, "bridge_cycle": {"gap_s": float("nan"), "before": None}}, altitude="fused",
                **KW)
    with pytest.raises(DataError, match=r"^Tracker\(resume=state\): .*gap_row, contacts, .* are malformed"):
        Tracker(bundle, resume={**state, "gap_row": [9.0]}, altitude="fused", **KW)
    with pytest.raises(DataError, match=r"^Tracker\(resume=state\): the state's fused altitude is malformed"):
        Tracker(bundle, resume={**state, "fused": {"held": []}}, altitude="fused", **KW)


@pytest.mark.skipif(not (Path(__file__).resolve().parents[1] / "datasets" / "external" / "gaitmap_ms_left").is_dir(),
                    reason="needs `make external` (datasets/external)")
def test_a_restored_tracker_keeps_the_contacts_on_a_real_recording():
    """E356's ``contacts`` (steps decision 87) on the real gaitmap_ms_left (foot only, ``contacts=True``): before E356 a
    tracker restarted after 26 s gave 7 rows another ``event_s`` / ``stride_time_s`` (positions equal)."""
    from pdrlearn.io import read_session
    from pdrlearn.runtime.replay import session_frames

    s = read_session(Path(__file__).resolve().parents[1] / "datasets" / "external" / "gaitmap_ms_left", streamed=True)
    bundle = load_bundle(SHIPPED)
    kw = {"units": ("foot",), "frames": session_frames(s.meta, bundle, ("foot",), "gaitmap_ms_left"), "contacts": True,
          "sensors": list(s.streams)}
    t0 = min(st.t[0] for st in s.streams.values())
    for st in s.streams.values():
        st.t = st.t - t0  # 1 s chunks from the first sample, as _run's 0.5 s ones from 0
    ref, got = _run(s, bundle, **kw), _run(s, bundle, 52, **kw)
    assert len(got) == len(ref) > 60
    for a, r in zip(got, ref, strict=True):
        np.testing.assert_allclose([a.event_s, a.stride_time_s, a.x, a.y, a.heading_rad],
                                   [r.event_s, r.stride_time_s, r.x, r.y, r.heading_rad], rtol=0, atol=1e-9)
