"""Decision W367 (W366's next candidate): ``pll_edge_lock="walk-end"`` judges a gated run's last PLL peak as
"trailing" does (dropped when the loop is not locked at it) only where the walk ends: an unlocked last peak with the
vertical acceleration's SD over the stride after it at W76's floor (0.15 m/s^2) or more lies inside a walk that goes
on (a run broken by a low-bounce turn, W366) and is kept."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.kernels.step_events import EDGE_LOCK_DEG, edge_lock_params, pll_params
from pdrlearn.kernels.waist import RELATIVE_GATE_FLOOR_MPS2
from pdrlearn.steps import PLLStepDetector
from tests.test_pll_edge_lock_w356 import FS, _events, _walk, track_times


def _turn_walk(seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """30 s: standing, a 1.7 Hz bounce of 3 m/s^2 from 5 s to 12 s, then 3 s of a low bounce (0.4 m/s^2: SD 0.28,
    under W4's 0.5 but over W76's 0.15) in opposite phase (a turn: the loop loses lock), the strong bounce again from
    15 s to 22 s, standing (2 cm/s^2 noise throughout)."""
    t = np.arange(0.0, 30.0, 1.0 / FS)
    strong = ((t >= 5.0) & (t < 12.0)) | ((t >= 15.0) & (t < 22.0))
    low = (t >= 12.0) & (t < 15.0)
    ph = 2 * math.pi * 1.7 * (t - 5.0)
    v = np.where(strong, 3.0 * np.sin(ph), 0.0) + np.where(low, 0.4 * np.sin(ph + math.pi), 0.0)
    return t, v + 0.02 * np.random.default_rng(seed).standard_normal(t.size)


def _times(ev) -> list[float]:
    return [e[0] for e in ev]


def test_walk_end_keeps_an_unlocked_trailing_peak_inside_a_walk_that_goes_on():
    t, v = _turn_walk()
    off, trailing, walk_end = _events(t, v, False), _events(t, v, "trailing"), _events(t, v, "walk-end")
    inner = [e for e in off if 12.0 < e[0] < 15.0 and abs(e[4]["phase_err_deg"]) > EDGE_LOCK_DEG]
    assert len(inner) == 1  # the first run's last peak, in the turn, unlocked
    assert inner[0][0] not in _times(trailing)  # W358's "trailing" drops it (W366's lost true contacts)
    assert inner[0][0] in _times(walk_end)  # the stride after it moves (SD >= 0.15 m/s^2): the walk goes on
    end = off[-1]
    assert end[0] > 22.0 and abs(end[4]["phase_err_deg"]) > EDGE_LOCK_DEG  # the walk's real end, unlocked
    assert _times(walk_end) == [e[0] for e in off if e is not end]  # only the real end's free-running peak goes


def test_walk_end_drops_the_unlocked_trailing_peak_where_the_walk_ends_and_keeps_the_leading_one():
    t, v = _walk(3.0)  # W356's signal: a free-running peak at either end, standing after the walk
    off, walk_end = _events(t, v, False), _events(t, v, "walk-end")
    assert abs(off[0][4]["phase_err_deg"]) > EDGE_LOCK_DEG and abs(off[-1][4]["phase_err_deg"]) > EDGE_LOCK_DEG
    assert _times(walk_end) == _times(off[:-1]) == _times(_events(t, v, "trailing"))
    t2, v2 = _walk(2.0)  # W356's signal whose trailing peak is locked: nothing dropped
    assert _times(_events(t2, v2, "walk-end")) == _times(_events(t2, v2, False))


def chunk_invariant_events(t, v, mode, seed: int) -> list:
    """The events of ``mode`` on the whole signal, asserted equal to those of 60 random chunks of it."""
    cuts = np.r_[0, np.sort(np.random.default_rng(seed).choice(np.arange(1, t.size), 60, replace=False)), t.size]
    whole = _events(t, v, mode)
    chunked = _events(t, v, mode, chunks=list(zip(cuts[:-1], cuts[1:], strict=True)))
    assert [e[:4] for e in chunked] == [e[:4] for e in whole]
    return whole


def test_walk_end_is_chunk_invariant():
    t, v = _turn_walk()
    whole = chunk_invariant_events(t, v, "walk-end", 3)
    assert len(whole) == len(_events(t, v, False)) - 1  # the chunks judge the same edges (the turn's peak kept)


def test_walk_end_mode_parameters_and_a_bad_value_is_one_line():
    assert edge_lock_params("walk-end") == {"edge_lock_deg": EDGE_LOCK_DEG, "edge_lock_leading": False,
                                            "walk_end_var": RELATIVE_GATE_FLOOR_MPS2 ** 2,  # W76's floor, squared
                                            "walk_start_var": 0.0}  # W372's leading edge not judged
    assert RELATIVE_GATE_FLOOR_MPS2 == 0.15
    assert pll_params(PLLStepDetector(edge_lock="trailing")).walk_end_var == 0.0  # W358's mode unchanged
    bad_values_are_one_line(("walk_end", "end"), "edge_lock .* is not one of .*\"walk-end\",? .*W367")


def bad_values_are_one_line(bads, match: str) -> None:
    """Each detector ``edge_lock`` of ``bads`` is one DataError line matching ``match``."""
    for bad in bads:
        with pytest.raises(DataError, match=match) as exc:
            pll_params(PLLStepDetector(edge_lock=bad))
        assert "\n" not in str(exc.value)


def test_walk_end_reaches_the_waist_pll_track():
    # W368: adopted as the track option's default, W373 made it "walk-edges" (tests/test_pll_edge_lock_w372.py)
    # W369 (review R1 item 2): user 8160's walk ends on a free-running peak that walk-end drops (21 -> 20 contacts),
    # so a walk-end that did not reach the track (or dropped nothing) fails here
    base, walk_end, trailing = track_times(8160, (False, "walk-end", "trailing"), bad="walk_end")
    assert (base.size, walk_end.size, trailing.size) == (21, 20, 20)
    assert set(trailing) <= set(walk_end) < set(base)  # walk-end drops a subset of what trailing drops
