"""Decision L223 (amends D23; session 28 navigation trial, finding 5): a 40 steps/min crawl (0.25 m steps every
1.5 s) was refused as a reversed foot frame from 5 strides with a resultant of 0.54, and the printed fix would have
reversed the track. D23 now refuses only on REFUSE_MIN_STRIDES strides with a resultant of REFUSE_MIN_RESULTANT;
on less the declared frame is used with one line naming the slow walk and suggesting no other frame."""

from __future__ import annotations

import logging

import pytest

import pdrlearn.track.frame_inference as F
from pdrlearn.errors import DataError


@pytest.fixture(scope="module")
def walk():
    from pdrlearn.sim import simulate

    return simulate("walk", user_seed=501, length_m=30.0, rate_hz=100.0)


def _reversed_finding(session, n: int, r: float):
    """The frame check's inference as the crawl gave it: the strides' direction opposite the declared forward."""
    declared = session.frames["foot"]
    up = declared.matrix()[2]
    fwd = -declared.matrix()[0]
    return F.InferredFrame("foot", F._turned(declared, {"forward", "left"}), up=up, forward=fwd, n_strides=n,
                           resultant=r, evidence={"forward": f"from {n} strides (resultant {r:.2f})"})


def test_the_crawls_evidence_is_not_enough_to_refuse(walk, monkeypatch, caplog):
    monkeypatch.setattr(F, "infer_session_frame", lambda s, p, max_s=None: _reversed_finding(s, 5, 0.54))
    chk = F.check_declared_frame(walk, "foot", walk.frames["foot"])
    assert not chk.refuse
    assert "too little evidence to refuse" in chk.message and "from 5 strides" in chk.message
    assert "resultant 0.54" in chk.message and "decision L95" in chk.message and "decision L223" in chk.message
    assert "write" not in chk.message and '"backward"' not in chk.message  # no frame to write: it would reverse it
    walk._checked.pop("foot", None)
    with caplog.at_level(logging.WARNING):
        assert walk.require_frame("foot") == walk.frames["foot"]  # used, with the line
    walk._checked.pop("foot", None)
    assert any("too little evidence" in r.getMessage() for r in caplog.records)


@pytest.mark.parametrize(("n", "r"), [(F.REFUSE_MIN_STRIDES, F.REFUSE_MIN_RESULTANT), (60, 1.0)])
def test_enough_evidence_still_refuses(walk, monkeypatch, n, r):
    monkeypatch.setattr(F, "infer_session_frame", lambda s, p, max_s=None: _reversed_finding(s, n, r))
    chk = F.check_declared_frame(walk, "foot", walk.frames["foot"])
    assert chk.refuse and "decision D23" in chk.message
    walk._checked.pop("foot", None)
    with pytest.raises(DataError, match="decision D23"):
        walk.require_frame("foot")
    walk._checked.pop("foot", None)


def test_the_thresholds_bound_the_evidence():
    assert F.weak_reversal(F.REFUSE_MIN_STRIDES - 1, 1.0) and F.weak_reversal(100, F.REFUSE_MIN_RESULTANT - 0.01)
    assert not F.weak_reversal(F.REFUSE_MIN_STRIDES, F.REFUSE_MIN_RESULTANT)
    assert not F.weak_reversal(None, None)  # nothing measured: D22 / D23 as before
    assert F.REFUSE_MIN_STRIDES > 5 and F.REFUSE_MIN_RESULTANT > 0.54  # the trial's crawl is below both
