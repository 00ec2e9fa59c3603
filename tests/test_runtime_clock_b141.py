"""Decision B141 (docs/decisions/bad-input.md): a push whose clock jumps far ahead is refused, not taken as a gap.

A new-user trial (session 22, "integrator") pushed one chunk with timestamps +1000 s ahead (a clock glitch): it was
accepted with a gap warning, and every later push of the true clock was refused ("pushed timestamps are not
increasing"): 130 errors, 9 of 69 steps, and nothing said only a new Tracker recovers.
"""

from __future__ import annotations

import math

import pytest

from pdrlearn.errors import DataError
from pdrlearn.runtime.tracker import MAX_GAP_S, Tracker
from tests.runtime_helpers import per_timestamp, synthetic_session, time_chunks

CHUNK_S = 0.5


@pytest.fixture(scope="module")
def walk():
    return synthetic_session(30, seed=5, name="walk", turn_rad_per_step=0.2)


def _chunks(s, shift_at=None, shift=0.0):
    for k, (_, c) in enumerate(time_chunks(s, CHUNK_S)):
        yield {n: (tt + shift, v) for n, (tt, v) in c.items()} if k == shift_at else c


def _replay(tr, chunks):
    steps, errors = [], []
    for c in chunks:
        try:
            steps += tr.push(c)
        except DataError as exc:
            errors.append(str(exc))
    return steps + tr.flush(), errors


def _state(tr) -> tuple:
    return ({n: (len(r), r.last) for n, r in tr._buf.items()}, tr._latest, tr.n_steps, len(tr.warnings),
            tr.segmenter.last_boundary, [len(p[0]) for p in tr.inputs._probe.values()])


def test_a_chunk_whose_clock_jumps_ahead_is_refused_in_one_line_and_the_walk_goes_on(synthetic_bundle, walk):
    ref, _ = _replay(Tracker(synthetic_bundle), _chunks(walk))
    tr = Tracker(synthetic_bundle)
    chunks = list(_chunks(walk, shift_at=30, shift=1000.0))
    first = [s for c in chunks[:30] for s in tr.push(c)]
    before = _state(tr)
    with pytest.raises(DataError, match=r"^\w+: pushed timestamps jump \+1000\.\d\d s ahead \(.* more than max_gap_s "
                                        r"= 60 s: a clock glitch\? The push is refused and the tracker is unchanged"):
        tr.push(chunks[30])
    assert _state(tr) == before
    steps, errors = _replay(tr, chunks[31:])
    assert errors == []
    got = first + steps
    assert len(ref) >= 25 and len(got) >= len(ref) - 1  # the glitched 0.5 s is missing, bridged as a gap
    assert [s.end_s for s in got if s.end_s < 14.0] == [s.end_s for s in ref if s.end_s < 14.0]


def test_one_sample_pushes_are_refused_the_same(synthetic_bundle, walk):
    pushes = per_timestamp(walk)
    tr = Tracker(synthetic_bundle)
    for p in pushes[:200]:
        tr.push(p)
    before = _state(tr)
    bad = {n: (t + 500.0, v) for n, (t, v) in pushes[200].items()}
    with pytest.raises(DataError, match="jump \\+500\\.\\d\\d s ahead .* max_gap_s = 60 s.* old\\.flush\\(\\) "):
        tr.push(bad)
    assert _state(tr) == before
    tr.push(pushes[200])  # the right times go on


def test_accepted_jumps_name_the_glitch_and_the_recovery_and_real_gaps_below_the_limit_are_gaps(synthetic_bundle,
                                                                                                   walk):
    tr = Tracker(synthetic_bundle, max_gap_s=math.inf)
    steps, errors = _replay(tr, _chunks(walk, shift_at=30, shift=1000.0))
    assert errors and all(re_ok in e for e in errors for re_ok in (
        "pushed timestamps are not increasing", "the tracker accepted a jump of its clock from",
        "only old.flush() and a new Tracker(bundle, start=tuple(old.position), heading_rad=old.heading) go on "
        "(decision B141"))
    # a real gap of 40 s (under MAX_GAP_S) is a gap, as before: a 0 m gap row, warned, no refusal
    gap = 40.0
    assert gap < MAX_GAP_S
    chunks = list(_chunks(walk))
    late = [{n: (t + gap, v) for n, (t, v) in c.items()} for c in chunks[30:]]
    tr = Tracker(synthetic_bundle)
    steps, errors = _replay(tr, chunks[:30] + late)
    assert errors == [] and any(s.gap_s >= gap for s in steps)
    assert any("no samples for 40." in w for w in tr.warnings)


@pytest.mark.parametrize("bad", [0.5, 1.0, float("nan")])
def test_max_gap_s_at_or_below_a_long_gap_is_refused(synthetic_bundle, bad):
    with pytest.raises(DataError, match="max_gap_s .*: give a number of seconds above 1"):
        Tracker(synthetic_bundle, max_gap_s=bad)
