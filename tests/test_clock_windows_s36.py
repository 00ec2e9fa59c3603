"""Steps decision 64 and L446 (session 36, trial T2 finding 1): the unit clocks are estimated window by window from
the recording's start, so a drift that moved the clock past half a step period is followed instead of being read as
the other foot's offset; an estimate that cannot be trusted is neither applied nor named as an offset."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.kernels.align import align_events, offset_locked, untrusted_message, untrusted_reason

STRIDE_S = 1.1  # a stride; the waist sees both feet, a step every 0.55 s


def trains(bout_starts, ppm: float, offset_s: float, strides: int = 30, seed: int = 8880):
    """Foot stride events (foot clock) and waist step events (waist clock ``t * (1 + drift) + offset``, the
    simulator's convention) of bouts of ``strides`` strides starting at ``bout_starts`` s, with 15 ms jitter."""
    rng = np.random.default_rng(seed)
    foot = np.concatenate([b + STRIDE_S * np.arange(strides) for b in bout_starts])
    steps = np.sort(np.concatenate([foot, foot + STRIDE_S / 2]))  # both feet's contacts (foot clock)
    waist = steps * (1 + ppm * 1e-6) + offset_s + rng.normal(0, 0.015, steps.size)
    return foot + rng.normal(0, 0.015, foot.size), waist


def test_a_drift_past_half_a_step_is_followed_from_the_start_64():
    """Walks every few minutes, 1000 ppm: the clock moves 0.1 -> 0.9 s (more than a step period) over the
    recording; the one-offset estimate read the other foot's offset (a step off), the windowed one the truth."""
    foot, waist = trains([5, 100, 400, 700, 800], 1000.0, 0.1)
    est = align_events(foot, waist, window_s=60.0)  # decision 64's option (not adopted as the default: 64, 66)
    truth = 0.1 + 1000e-6 * est["ref_s"]
    assert est["offset_s"] == pytest.approx(truth, abs=0.02)
    assert est["drift"] * 1e6 == pytest.approx(1000, abs=50)
    assert offset_locked(est) and untrusted_reason(est) is None
    assert est["matched"] >= 0.95 * est["foot_events"] and est["windows"] >= 5
    old = align_events(foot, waist)  # the default: one offset, a step off here, and L446 says it cannot be trusted
    assert abs(old["offset_s"] - (0.1 + 1000e-6 * old["ref_s"])) > 0.1
    assert "from the fitted clock" in untrusted_reason(old)
    # L446's line names the windows' clock (steps 64's line at the clock's 0) as the likely fix
    line = untrusted_message(old)
    off0, ppm = (float(line.rsplit(flag, 1)[1].split()[0]) for flag in ("read --clock-offset", "--clock-drift-ppm"))
    assert off0 == pytest.approx(0.1, abs=0.03) and ppm == pytest.approx(1000, abs=50)


def test_a_drift_not_followable_between_walks_is_flagged_l446():
    """Walks 330 s apart at 1000 ppm: the clock moves 0.33 s between walks before any drift is known, so which
    foot the waist steps belong to is lost; the estimate is wrong, and L446 says it cannot be trusted."""
    foot, waist = trains([5, 335, 665], 1000.0, 0.1, strides=22)
    est = align_events(foot, waist)
    assert abs(est["offset_s"] - (0.1 + 1000e-6 * est["ref_s"])) > 0.1  # no method can tell (decision 66)
    why = untrusted_reason(est)
    assert why is not None and "walking windows jumped" in why
    line = untrusted_message(est)
    assert line.startswith("--align-units kept the unit clocks") and "--clock-offset SECONDS" in line
    assert "--clock-drift-ppm PPM" in line and "decision L446" in line
    assert untrusted_message(est, None).startswith("the unit clocks could not be checked")


def test_few_matched_events_are_not_trusted_l446():
    """Half the foot events without a waist step at the fitted clock: not trusted, the numbers named."""
    est = {"offset_s": 0.26, "drift": 22e-6, "matched": 227, "foot_events": 436, "residual_sd_s": 0.03,
           "windows": 1, "windows_inconsistent": 0, "window_residual_max_s": 0.0, "step_period_s": 0.55}
    assert "227 of 436 foot events matched" in untrusted_reason(est)
    assert untrusted_reason({**est, "matched": 420}) is None


def test_a_short_walk_is_estimated_as_before_64():
    """A recording inside one window: the one-offset estimate, bit for bit."""
    foot, waist = trains([5], 0.0, 0.3, strides=40)
    assert align_events(foot, waist) == align_events(foot, waist, window_s=None)


FOLLOWED = "stand:5, straight:30, stand:60, straight:30, sit:200, straight:30, sit:200, straight:30"  # steps 66
LOST = "straight:30, sit:300, straight:30, sit:300, straight:30"  # steps 64's first route: 0.33 s per sit


def _sim(route: str, user: int):
    import logging

    from pdrlearn.sim import simulate_path
    from pdrlearn.sim.route import parse_route
    from pdrlearn.sim.user import UserProfile

    logging.disable(logging.WARNING)
    try:
        return simulate_path(parse_route(route), UserProfile.from_seed(user), rate_hz=50.0, seed=0, name=f"u{user}",
                             scenario="route", clock_offset_s=0.1, clock_drift_ppm=1000.0)
    finally:
        logging.disable(logging.NOTSET)


def test_track_align_units_follows_a_drifting_clock_and_refuses_a_lost_one_l446():
    """`track --align-units`' path (track_plasys(align=True)) on a 1000 ppm clock whose one-offset estimate is a
    step off: it had been applied silently; now it is not applied, and one L446 line says why and what to do."""
    from pdrlearn.track.plasys import track_plasys

    for route, user in ((FOLLOWED, 8887), (LOST, 8880)):
        r = track_plasys(_sim(route, user), method="M2", align=True)
        assert r.info["unit_alignment"] is None
        # L446's line, or L186's when the one-offset line did not even lock (L183); either names the by-hand fix
        (line,) = [w for w in r.info["warnings"] if "decision L446" in w or "decision L186" in w]
        assert "--align-units kept the unit clocks" in line and "--clock-offset" in line
    assert "decision L446" in line and "--clock-drift-ppm PPM" in line  # the lost clock's
