"""Decision W358 (W357's next candidate; measured by W366): ``pll_edge_lock="trailing"`` judges only a gated run's last
PLL peak (kept only when the loop is locked at it) and keeps its first as the option off does."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.kernels.step_events import EDGE_LOCK_DEG, EDGE_LOCK_VALUES, edge_lock_params, pll_params
from pdrlearn.steps import PLLStepDetector
from tests.test_pll_edge_lock_w356 import _events, _walk, track_times


def test_trailing_drops_the_unlocked_trailing_peak_and_keeps_the_unlocked_leading_one():
    t, v = _walk(3.0)  # W356's test signal: the centred gate lets in a free-running peak at either end
    off, trailing, both = _events(t, v, False), _events(t, v, "trailing"), _events(t, v, True)
    assert abs(off[0][4]["phase_err_deg"]) > EDGE_LOCK_DEG and abs(off[-1][4]["phase_err_deg"]) > EDGE_LOCK_DEG
    assert [e[0] for e in trailing] == [e[0] for e in off[:-1]]  # the unlocked leading peak stays, the trailing goes
    assert [e[0] for e in both] == [e[0] for e in off[1:-1]]  # W356's mode unchanged: both edges judged
    assert [e[0] for e in _events(t, v, "both")] == [e[0] for e in both]  # "both" is True


def test_trailing_keeps_a_locked_trailing_peak():
    t, v = _walk(2.0)  # W356's signal whose trailing peak is locked: nothing to drop at the trailing edge
    off, trailing = _events(t, v, False), _events(t, v, "trailing")
    assert abs(off[-1][4]["phase_err_deg"]) <= EDGE_LOCK_DEG
    assert [e[0] for e in trailing] == [e[0] for e in off]


def test_trailing_is_chunk_invariant():
    t, v = _walk(3.0, seed=5)
    cuts = np.r_[0, np.sort(np.random.default_rng(2).choice(np.arange(1, t.size), 40, replace=False)), t.size]
    whole = _events(t, v, "trailing")
    chunked = _events(t, v, "trailing", chunks=list(zip(cuts[:-1], cuts[1:], strict=True)))
    assert [e[:4] for e in chunked] == [e[:4] for e in whole]
    assert len(whole) == len(_events(t, v, False)) - 1  # the chunks judge the same trailing peak


def test_edge_lock_modes_and_a_bad_value_is_one_line():
    assert EDGE_LOCK_VALUES == (False, True, "both", "trailing", "walk-end", "walk-edges")  # W367, W372 added
    assert edge_lock_params(False) == {"edge_lock_deg": 0.0, "edge_lock_leading": True, "walk_end_var": 0.0,
                                       "walk_start_var": 0.0}
    assert edge_lock_params(True) == edge_lock_params("both") == {"edge_lock_deg": EDGE_LOCK_DEG,
                                                                   "edge_lock_leading": True, "walk_end_var": 0.0,
                                                                   "walk_start_var": 0.0}
    assert pll_params(PLLStepDetector(edge_lock="trailing")).edge_lock_leading is False
    for bad in ("leading", "true"):
        with pytest.raises(DataError, match="edge_lock .* is not one of .*W358"):
            pll_params(PLLStepDetector(edge_lock=bad))
    # decision steps 82: a value of the wrong type is refused by the settings' type check, when the detector is made
    with pytest.raises(DataError, match="step detector pll: edge_lock=2 is not a bool or str"):
        PLLStepDetector(edge_lock=2)


def test_the_trailing_mode_reaches_the_waist_pll_track():
    # W366: "trailing" not adopted (the default is W373's "walk-edges" since session 35)
    base, trail, both = track_times(8160, (False, "trailing", "both"), bad="last")
    assert set(trail) < set(base) and set(both) <= set(trail)  # trailing drops a subset of what both drops
    assert trail.size == base.size - 1 == 20  # W369 (review R1 item 2): 8160's trailing peak is dropped
