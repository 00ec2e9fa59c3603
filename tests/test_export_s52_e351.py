"""Decision E351: the live waist tracker's ``stairs_length="climbs"`` - W108's climbs read one reported step at a
time (:func:`pdrlearn.kernels.barometer.live_climb_run`), the tread (half of it step to step, W433) shared with the
offline bound (:func:`pdrlearn.kernels.barometer.climb_tread`). The live tracker's parity with
``track_waist(realtime=True)`` is pinned in ``tests/test_runtime_waist.py``."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.kernels.barometer import STAIR_TREAD_M, climb_tread, live_climb_run, step_to_step_mask


def _bounds(signs, rise_per_step, **kw):
    run, out, h = None, [], 0.0
    for s, r in zip(signs, rise_per_step, strict=True):
        run, b = live_climb_run(run, s, h, h + r, **kw)
        out.append(b)
        h += r
    return out


def test_a_step_over_step_climb_is_bounded_by_the_tread_once_it_has_risen_half_a_metre():
    out = _bounds([1] * 6, [0.17] * 6)  # 0.17, 0.34, 0.51 m: the third step on
    assert out[:2] == [None, None] and out[2:] == [STAIR_TREAD_M] * 4


def test_a_step_to_step_climb_takes_half_a_tread_and_a_descent_its_own_sign():
    out = _bounds([-1] * 8, [-0.085] * 8)
    assert out[:5] == [None] * 5 and out[5:] == [0.5 * STAIR_TREAD_M] * 3  # -0.51 m after six steps
    assert _bounds([1] * 8, [-0.085] * 8) == [None] * 8  # proposed up while the altitude falls: no climb


def test_one_unproposed_step_is_bridged_two_end_the_run_and_a_new_sign_starts_another():
    out = _bounds([1, 1, 1, 0, 1, 0, 0, 1, -1], [0.17, 0.17, 0.17, 0.17, 0.17, 0.0, 0.0, 0.17, -0.17])
    assert out[:5] == [STAIR_TREAD_M if i >= 2 else None for i in range(5)]
    assert out[5] == STAIR_TREAD_M  # one unproposed step inside a climbing run: bridged (W433)
    assert out[6:] == [None, None, None]  # the second ends it; the next proposals start new runs


def test_the_least_height_is_a_keyword_and_the_tread_is_offline_s():
    assert _bounds([1] * 3, [0.17] * 3, min_height_m=0.3)[1] == STAIR_TREAD_M
    climbs = [(0, 20, 1.7), (25, 35, -1.7)]  # 0.085 (step to step) and 0.17 m per step
    mask = step_to_step_mask(40, climbs)
    assert mask[:20].all() and not mask[25:35].any()
    assert climb_tread(1.7, 20) == pytest.approx(0.5 * STAIR_TREAD_M) and climb_tread(-1.7, 10) == STAIR_TREAD_M
    assert np.isclose(climb_tread(0.0, 0), 0.5 * STAIR_TREAD_M)
