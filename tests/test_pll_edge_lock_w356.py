"""Decision W356 (W345's candidate; measured by W357): a gated run's first / last PLL peak counts only when the loop
is locked at it (phase error within 45 deg over the period ending at the peak)."""

from __future__ import annotations

import logging
import math

import numpy as np
import pytest

from pdrlearn.kernels.step_events import (
    EDGE_LOCK_DEG,
    PLLState,
    phase_error_deg,
    pll_flush,
    pll_kernel,
    pll_params,
)
from pdrlearn.steps import PLLStepDetector

FS = 100.0


def _walk(amp: float, seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """20 s of vertical acceleration: standing (2 cm/s^2 noise), 10 s of a 1.7 Hz bounce of ``amp`` m/s^2 from 5 s,
    standing."""
    t = np.arange(0.0, 20.0, 1.0 / FS)
    walk = (t >= 5.0) & (t < 15.0)
    v = np.where(walk, amp * np.sin(2 * math.pi * 1.7 * (t - 5.0)), 0.0)
    return t, v + 0.02 * np.random.default_rng(seed).standard_normal(t.size)


def _events(t, v, edge_lock: bool, chunks=None):
    p = pll_params(PLLStepDetector(edge_lock=edge_lock, refine_frac=0.0))  # W356's setting through the detector's
    st, out = PLLState(), []
    for a, b in chunks or [(0, t.size)]:
        ev, st = pll_kernel(t[a:b], v[a:b], st, p)
        out += ev
    return out + pll_flush(st, p)


def track_times(user: int, modes: tuple, bad: str | None = None) -> list[np.ndarray]:
    """waist-pll's contact times on simulated ``user``'s 12 m straight walk (standing 4 s either side) with each
    ``pll_edge_lock`` of ``modes`` (None: the option not given); ``bad``: a value that must be one DataError line."""
    from pdrlearn.errors import DataError
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route
    from pdrlearn.track.waist import track_waist

    logging.disable(logging.WARNING)
    try:
        s = simulate_path(parse_route("stand:4, straight:12, stand:4"), UserProfile.from_seed(user), rate_hz=100,
                          seed=user)
        out = [track_waist(s, pipeline="waist-pll", pll_edge_lock=m).steps["event_s"].to_numpy(float) for m in modes]
        if bad is not None:
            with pytest.raises(DataError, match=f"pll_edge_lock '{bad}' is not one of"):
                track_waist(s, pipeline="waist-pll", pll_edge_lock=bad)
    finally:
        logging.disable(logging.NOTSET)
    return out


def test_phase_error_is_the_angle_of_the_quadrature_and_none_without_input():
    assert phase_error_deg(1.0, 0.0) == 0.0 and phase_error_deg(0.0, 2.0) == pytest.approx(90.0)
    assert phase_error_deg(-1.0, -1.0) == pytest.approx(-135.0)
    assert math.isnan(phase_error_deg(0.0, 0.0))  # no input over the period: never counted locked
    assert EDGE_LOCK_DEG == 45.0


def test_edge_lock_drops_the_free_running_leading_peak_and_keeps_the_locked_trailing_one():
    t, v = _walk(2.0)
    off, on = _events(t, v, False), _events(t, v, True)
    first, last = off[0], off[-1]
    # the gated run's leading peak lies before the walk, the loop free-running; its trailing one on the walk's phase
    assert first[0] < 5.0 and abs(first[4]["phase_err_deg"]) > EDGE_LOCK_DEG
    assert abs(last[4]["phase_err_deg"]) <= EDGE_LOCK_DEG
    assert [e[0] for e in on] == [e[0] for e in off[1:]]  # only the unlocked edge went; the locked edge stays


def test_edge_lock_drops_both_unlocked_edges_once_and_keeps_the_interior():
    t, v = _walk(3.0)  # a strong bounce: the centred gate lets in a free-running peak at either end
    off, on = _events(t, v, False), _events(t, v, True)
    edges = [e for e in (off[0], off[-1]) if abs(e[4]["phase_err_deg"]) > EDGE_LOCK_DEG]
    assert len(edges) == 2 and off[-1][0] > 15.0
    assert [e[0] for e in on] == [e[0] for e in off[1:-1]]  # one pass: the new first / last are not judged again


def test_edge_lock_is_chunk_invariant():
    t, v = _walk(3.0, seed=3)
    cuts = np.r_[0, np.sort(np.random.default_rng(1).choice(np.arange(1, t.size), 40, replace=False)), t.size]
    whole = _events(t, v, True)
    chunked = _events(t, v, True, chunks=list(zip(cuts[:-1], cuts[1:], strict=True)))
    assert [e[:4] for e in chunked] == [e[:4] for e in whole]


def test_the_option_reaches_the_waist_pll_track():
    # W357: True not adopted (the default is W373's "walk-edges" since session 35, tests/test_pll_edge_lock_w372.py)
    base, lock = track_times(7790, (False, True))
    assert set(lock) < set(base)  # edge peaks went, nothing was added
    assert lock.size == base.size - 2 == 17  # W369 (review R1 item 2): one pass drops both of 7790's run ends


def test_the_option_on_waist_pendulum_is_named_as_ignored():
    from pdrlearn.track.waist import ignored_options_line

    line = ignored_options_line({"pll_edge_lock": True}, "waist-pendulum", False, "gyro", False, True)
    assert line and "pll_edge_lock=true applies to waist-pll" in line
    assert ignored_options_line({"pll_edge_lock": True}, "waist-pll", False, "ahe", False, True) is None
