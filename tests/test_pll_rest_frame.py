"""Decisions W285-W286: a rest over a minute turns the AHRS frame by the gyroscope's bias, not the walk; the harmonic
headings (``waist-pll``'s ``ahe``) are read less that turn with ``rest_frame``."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.kernels.rest_heading import REST_BIAS_MIN_S, rest_frame_drift
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline
from pdrlearn.track.waist import OPTION_DEFAULTS, ignored_options_line

FS = 20.0


def _rest(duration_s: float, bias: float, turn_rad: float = 0.0):
    """A rest of ``duration_s`` s: a constant rate ``bias``, plus ``turn_rad`` turned over 2 s in its middle (the
    moving samples)."""
    t = np.arange(0.0, duration_s, 1.0 / FS)
    still = np.ones(t.size, dtype=bool)
    w = np.full(t.size, bias)
    mid = (t >= duration_s / 2) & (t < duration_s / 2 + 2.0)
    w[mid] += turn_rad / 2.0
    still[mid] = False
    return t, w, still


def test_the_frame_turn_of_a_long_rest_is_its_bias_integral_not_its_turn_w285():
    t, w, still = _rest(300.0, 0.003, turn_rad=np.pi / 2)
    drift = rest_frame_drift(t, w, still, t[0], t[-1])
    assert drift == pytest.approx(0.003 * (t[-1] - t[0]), rel=1e-3)  # 51.5 deg of bias; the 90 deg turn kept out


def test_a_short_rest_or_one_never_still_turns_the_frame_by_nothing_w285():
    t, w, still = _rest(REST_BIAS_MIN_S - 1.0, 0.003)
    assert rest_frame_drift(t, w, still, t[0], t[-1]) == 0.0  # L296's bound: no bias taken under a minute
    t, w, still = _rest(300.0, 0.003)
    assert rest_frame_drift(t, w, np.zeros_like(still), t[0], t[-1]) == 0.0  # no still block: no bias known


def _headings_deg(session, on: bool | None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The walking steps' contact times (s) and headings (deg, wrapped), and the track's x / y."""
    params = None if on is None else {"options": {"rest_frame": on}}
    r = get_pipeline("waist-pll")(session, params=params)
    walking = r.steps[r.steps["has_next"].to_numpy(bool)]
    h = np.degrees(walking["heading_rad"].to_numpy(float))
    return walking["event_s"].to_numpy(float), (h + 180.0) % 360.0 - 180.0, r.trajectory[["x", "y"]].to_numpy(float)


def test_a_long_sit_no_longer_turns_the_harmonic_heading_w285():
    """The failing-before test (user 6503, looked at while writing W285): a walk, 600 s seated, the walk on the same
    way (heading 0). The frame's turn over the sit put the walk on 61 deg off (median over its steps); less the
    frame's turn it is within 10 deg, and the walk before the sit is untouched."""
    logging.disable(logging.WARNING)
    try:
        s = simulate_path(parse_route("stand:5, straight:10, sit:600, straight:10, stand:5"),
                          UserProfile.from_seed(6503), rate_hz=FS, seed=6503)
        ev, on, _ = _headings_deg(s, True)
        ev_off, off, _ = _headings_deg(s, False)
    finally:
        logging.disable(logging.NOTSET)
    assert np.array_equal(ev, ev_off)
    after = ev > ev[int(np.argmax(np.diff(ev)))]  # the steps after the sit
    print(f"median heading after the sit: {np.median(off[after]):+.1f} deg (frame turn kept) -> "
          f"{np.median(on[after]):+.1f} deg (W285)")
    assert np.array_equal(on[~after], off[~after])
    assert abs(np.median(on[after])) < 10.0 < 40.0 < abs(np.median(off[after]))


def test_a_session_without_a_rest_over_a_minute_is_tracked_as_before_w285():
    logging.disable(logging.WARNING)
    try:
        s = simulate_path(parse_route("stand:3, straight:8, stand:40, turn:180, straight:8, stand:3"),
                          UserProfile.from_seed(6501), rate_hz=FS, seed=6501)
        _, a, xy_a = _headings_deg(s, True)
        _, b, xy_b = _headings_deg(s, False)
    finally:
        logging.disable(logging.NOTSET)
    assert np.array_equal(a, b) and np.array_equal(xy_a, xy_b)


def test_the_gyro_heading_names_rest_frame_ignored_w193():
    o = dict(OPTION_DEFAULTS, rest_frame=not OPTION_DEFAULTS["rest_frame"])
    line = ignored_options_line(o, "waist-pendulum", False, "gyro", False, True)
    if o["rest_frame"]:
        assert "rest_frame=true applies to the harmonic headings" in line and "W285" in line
    else:  # an option set off does nothing anywhere: no line (W199)
        assert line is None
    assert ignored_options_line(dict(OPTION_DEFAULTS, rest_frame=True), "waist-pll", False, "ahe", False,
                                True) is None


def test_the_default_is_off_w287():
    assert OPTION_DEFAULTS["rest_frame"] is False  # W287: W286's rule was not met ((b)); an option
