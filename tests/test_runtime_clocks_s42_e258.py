"""Decision E258 (session 42, implementer I3): the live clock check reads each window's foot events through the drift
it follows (``t + d (t - r)``, the result read back on the foot clock), so a waist clock drifting up to 3000 ppm keeps
L183's lock where it was lost above ~1500-2000 ppm (E245's limit). Synthetic step events (E245's ``_drifting_check``:
no sample data, 6 min of events)."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.kernels.align import align_events, offset_locked
from pdrlearn.runtime import clocks
from tests.test_runtime_clocks_s41 import _drifting_check


def _locked_after_first(seen):
    first = next(i for i, (e, _) in enumerate(seen) if offset_locked(e))
    return seen[first:]


def _plain(monkeypatch):
    """The check before E258: every window estimated on the raw foot events."""
    monkeypatch.setattr(clocks.ClockCheck, "_estimate",
                        lambda self: align_events(self._foot_events, self._waist_events))


def test_a_3000_ppm_clock_keeps_its_lock_and_is_named_as_it_moves_e258(monkeypatch):
    """3000 ppm over 6 min: every check after the first stays locked within 0.1 s of the true offset and the line
    names the clock again as it moves (4 lines); before E258, 8 of the 16 checks did not lock and 1 line was said."""
    lines, seen = _drifting_check(3000.0, 6.0)
    after = _locked_after_first(seen)
    assert len(after) == 16 and all(offset_locked(e) and abs(e["offset_s"] - true) < 0.1 for e, true in after)
    assert len(lines) >= 3 and max(true for _, true in after) > 0.6
    assert abs(after[-1][0]["drift"] * 1e6 - 3000.0) < 100.0  # the drift followed and added back
    _plain(monkeypatch)
    lines, seen = _drifting_check(3000.0, 6.0)
    assert sum(not offset_locked(e) for e, _ in _locked_after_first(seen)) >= 4
    assert len([x for x in lines if "(decision E271)" not in x]) <= 1  # E271 (session 43) says the lost lock


@pytest.mark.parametrize("ppm", [0.0, 500.0])
def test_a_small_drift_reads_the_same_estimates_e258(monkeypatch, ppm):
    """E258's rule (a): at 0-500 ppm every estimate within 1 ms of the check's before, the same lines."""
    lines, seen = _drifting_check(ppm, 6.0)
    _plain(monkeypatch)
    lines0, seen0 = _drifting_check(ppm, 6.0)
    assert len(seen) == len(seen0) == 16 and lines == lines0
    assert max(abs(e["offset_s"] - e0["offset_s"]) for (e, _), (e0, _) in zip(seen, seen0, strict=True)) < 1e-3


def test_the_drifted_windows_line_is_read_back_on_the_foot_clock_e258():
    """``_with_drift``: the line fitted on foot events moved by ``d`` gives, on the foot clock, the waist-minus-foot
    time of the events (noise-free events of a 2500 ppm clock, -0.1 ... +0.15 s apart, followed with d = 2000 ppm)."""
    foot = np.arange(100.0, 200.0, 1.1)
    waist = foot * (1.0 + 2500e-6) - 0.35
    d, r = 2000e-6, 150.0
    est = clocks._with_drift(align_events(foot + d * (foot - r), waist), d, r)
    np.testing.assert_allclose(est["offset_s"] + est["drift"] * (foot - est["ref_s"]), waist - foot, atol=1e-9)
    assert est["ref_s"] == pytest.approx(foot.mean(), abs=1e-9) and est["drift"] == pytest.approx(2500e-6, abs=1e-9)
