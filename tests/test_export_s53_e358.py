"""Decision E358: the live waist tracker's ``stairs_length="climbs"`` with ``live_climbs="hold"`` - the steps of an
open run of W91's proposals are held until the run is a climb (W108's 1.5 m, read causally) or has ended
(:class:`pdrlearn.kernels.barometer.LiveClimbHold`), and ``track_waist(realtime=True)`` reads the same kernel
(:func:`pdrlearn.kernels.barometer.live_climb_bounds`). The live tracker's parity with the realtime track is pinned in
``tests/test_runtime_waist.py::test_live_climbs_hold_applies_stairs_length_climbs_live_as_the_realtime_track_e358``."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.kernels.barometer import (
    STAIR_TREAD_M,
    LiveClimbHold,
    climb_runs,
    climb_tread,
    live_climb_bounds,
    runs_mask,
    step_to_step_mask,
)


def _walk(signs, rises):
    """Each step's start / end altitude from its rise (m)."""
    end = np.cumsum(rises)
    return np.asarray(signs), end - np.asarray(rises), end


def test_level_steps_are_reported_at_once_and_a_climb_releases_its_held_steps_bounded_at_1_5_m():
    hold = LiveClimbHold()
    assert hold.push("a", 0, 0.0, 0.0) == [("a", None)]  # no run: never delayed
    h = 0.0
    for i in range(8):  # 0.17 m a step (step over step): 1.36 m after the eighth, 1.53 m after the ninth
        assert hold.push(i, 1, h, h + 0.17) == []  # held while the run is open
        h += 0.17
    assert hold.size() == 8
    assert hold.push(8, 1, h, h + 0.17) == [(i, STAIR_TREAD_M) for i in range(9)]  # decided: all, in order, bounded
    h += 0.17
    assert hold.push(9, 1, h, h + 0.17) == [(9, STAIR_TREAD_M)]  # later steps of the climb: at once


def test_a_run_that_ends_under_1_5_m_releases_its_steps_unbounded_and_w433_bridges_one_unproposed_step():
    hold = LiveClimbHold()
    assert hold.push(0, 1, 0.0, 0.2) + hold.push(1, 1, 0.2, 0.5) + hold.push(2, 0, 0.5, 0.72) == []
    assert hold.push(3, 1, 0.72, 0.9) == []  # the unproposed step 2 bridged: still one open run (0.9 m)
    assert hold.push(4, -1, 0.9, 0.8) == [(k, None) for k in range(4)]  # another sign ends it: no climb
    assert hold.push(5, 0, 0.8, 0.8) == []  # step 5 may be bridged ...
    assert hold.push(6, 0, 0.8, 0.8) == [(4, None), (5, None), (6, None)]  # ... two unproposed steps end the run
    assert hold.push(7, 1, 0.8, None) == [(7, None)] and hold.flush() == []  # no altitude: no run


def test_a_step_to_step_flight_takes_half_a_tread_and_the_whole_track_kernel_matches_w108_on_clean_flights():
    s, a, b = _walk([0] * 5 + [1] * 24 + [0] * 6 + [-1] * 12 + [0] * 5,
                    [0.0] * 5 + [0.085] * 24 + [0.0] * 6 + [-0.17] * 12 + [0.0] * 5)
    bound, released = live_climb_bounds(s, a, b)
    runs = climb_runs(s, a, b, 0.0)  # offline W108 (no still-period noise)
    np.testing.assert_array_equal(np.isfinite(bound), runs_mask(len(s), runs))
    half = step_to_step_mask(len(s), runs)
    np.testing.assert_allclose(bound[half], 0.5 * STAIR_TREAD_M)
    np.testing.assert_allclose(bound[np.isfinite(bound) & ~half], STAIR_TREAD_M)
    # the up flight is decided at its 18th step (18 x 0.085 = 1.53 m), the down one at its 9th
    assert released[5] == 5 + 17 and (released[5:23] == 22).all() and (released[23:29] == np.arange(23, 29)).all()
    assert released[35] == 35 + 8 and (released[:5] == np.arange(5)).all()
    assert climb_tread(-1.7, 10) == STAIR_TREAD_M and climb_tread(1.7, 20) == 0.5 * STAIR_TREAD_M
    bound, released = live_climb_bounds(s[:20], a[:20], b[:20])  # the stream ends inside the open run
    assert not np.isfinite(bound).any() and (released[5:] == 20).all()


def test_a_misspelt_live_climbs_is_one_line():
    from pdrlearn.waist.live import live_options
    from pdrlearn.waist.params import WaistParams

    p = WaistParams(options={"stairs_length": "climbs", "live_climbs": "held"})
    with pytest.raises(DataError, match=r"live_climbs 'held' is not one of false, \"hold\" \(decision E358\)"):
        live_options(p, [])
