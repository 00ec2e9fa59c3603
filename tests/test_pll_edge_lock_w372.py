"""Decision W372 (W368's leading-edge twin): ``pll_edge_lock="walk-edges"`` is W367's ``"walk-end"`` plus a gated
run's FIRST PLL peak judged the mirror way: an unlocked first peak is dropped only where the walk starts after it (the
vertical acceleration's SD over the stride before it below W76's floor, 0.15 m/s^2); one with more motion before it
lies inside a walk already going (a run broken inside a walk) and is kept."""

from __future__ import annotations

import math

import numpy as np

from pdrlearn.kernels.step_events import EDGE_LOCK_DEG, edge_lock_params, pll_params
from pdrlearn.kernels.waist import RELATIVE_GATE_FLOOR_MPS2
from pdrlearn.steps import PLLStepDetector
from tests.test_pll_edge_lock_w356 import FS, _events, _walk, track_times
from tests.test_pll_edge_lock_w367 import bad_values_are_one_line, chunk_invariant_events

#: simulated user 8700 (W372's range): its walk starts on an unlocked free-running peak after standing, which
#: walk-edges drops (contacts: the option not given, "walk-end", "walk-edges")
USER, COUNTS = 8700, (17, 18, 17)


def _broken_walk(seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """30 s: standing, a 1.7 Hz bounce of 3 m/s^2 from 5 s to 12 s, 4 s of a low 2.6 Hz bounce (0.4 m/s^2: SD 0.28,
    under W4's 0.5, over W76's 0.15: a shuffle the loop does not lock on), the strong bounce again, a quarter period
    shifted, from 16 s to 23 s, standing (2 cm/s^2 noise throughout)."""
    t = np.arange(0.0, 30.0, 1.0 / FS)
    s1, s2, low = (t >= 5.0) & (t < 12.0), (t >= 16.0) & (t < 23.0), (t >= 12.0) & (t < 16.0)
    v = (np.where(s1, 3.0 * np.sin(2 * math.pi * 1.7 * (t - 5.0)), 0.0)
         + np.where(s2, 3.0 * np.sin(2 * math.pi * 1.7 * (t - 16.0) + math.pi / 2), 0.0)
         + np.where(low, 0.4 * np.sin(2 * math.pi * 2.6 * (t - 12.0)), 0.0))
    return t, v + 0.02 * np.random.default_rng(seed).standard_normal(t.size)


def _times(ev) -> list[float]:
    return [e[0] for e in ev]


def _unlocked(e) -> bool:
    return abs(e[4]["phase_err_deg"]) > EDGE_LOCK_DEG


def test_walk_edges_keeps_an_unlocked_leading_peak_inside_a_walk_that_went_on():
    t, v = _broken_walk()
    off, both, edges = _events(t, v, False), _events(t, v, True), _events(t, v, "walk-edges")
    second = [e for e in off if 15.0 < e[0] < 15.9]
    assert len(second) == 1 and _unlocked(second[0])  # the second run's first peak, after the shuffle, unlocked
    assert second[0][0] not in _times(both)  # W356's edge lock drops it
    assert second[0][0] in _times(edges)  # the stride before it moves (SD >= 0.15 m/s^2): the walk went on
    assert off[0][0] < 5.0 and _unlocked(off[0]) and not _unlocked(off[-1])  # the walk's real start, free-running
    assert _times(edges) == _times(off[1:])  # only the real start goes (the locked end and the shuffle's edges stay)
    assert _times(_events(t, v, "walk-end")) == _times(off)  # W367 judges no first peak


def test_walk_edges_drops_the_unlocked_leading_peak_where_the_walk_starts():
    t, v = _walk(3.0)  # W356's signal: a free-running peak at either end, standing before and after the walk
    off, walk_end, edges = _events(t, v, False), _events(t, v, "walk-end"), _events(t, v, "walk-edges")
    assert _unlocked(off[0]) and _unlocked(off[-1])
    assert _times(walk_end) == _times(off[:-1])  # W367 keeps the leading one
    assert _times(edges) == _times(off[1:-1]) == _times(_events(t, v, True))  # W372 drops it: quiet before it


def test_walk_edges_is_chunk_invariant():
    t, v = _broken_walk()
    whole = chunk_invariant_events(t, v, "walk-edges", 5)
    assert len(whole) == len(_events(t, v, False)) - 1  # the chunks judge the same edges


def test_walk_edges_mode_parameters_and_a_bad_value_is_one_line():
    floor = RELATIVE_GATE_FLOOR_MPS2 ** 2  # W76's floor, squared, before and after
    assert edge_lock_params("walk-edges") == {"edge_lock_deg": EDGE_LOCK_DEG, "edge_lock_leading": True,
                                              "walk_end_var": floor, "walk_start_var": floor}
    assert pll_params(PLLStepDetector(edge_lock="walk-end")).walk_start_var == 0.0  # W367's mode unchanged
    bad_values_are_one_line(("walk_edges", "edges"), "edge_lock .* is not one of .*\"walk-edges\" .*W372")


def test_the_default_is_walk_edges_and_it_reaches_the_waist_pll_track():
    from pdrlearn.track.waist import OPTION_DEFAULTS

    # W373: adopted as the track option's default; the detector's own default (pdrlearn steps) stays off
    assert OPTION_DEFAULTS["pll_edge_lock"] == "walk-edges" and PLLStepDetector().edge_lock is False
    default, walk_end, edges = track_times(USER, (None, "walk-end", "walk-edges"), bad="walk_edges")
    assert (default.size, walk_end.size, edges.size) == COUNTS
    np.testing.assert_array_equal(default, edges)
    assert set(edges) < set(walk_end)  # walk-edges drops the leading peak walk-end keeps
