"""Decisions E248 and E249 (docs/decisions/export.md): ``ClockWentBack.offset_s`` puts the rebased unit's first new
sample 1 ms after the other unit's newest input sample, with a drifting waist clock and with resampled streams.

Review R0 of session 40, findings 2 and 3 (E227's reconnect path): with ``waist_clock_drift_ppm`` the offset left out
the drift (an hour after power-on at 150 ppm the rebased waist landed 0.54 s early; at 500 ppm the push after the
documented rebase was refused as late); with ``resample=True`` "the other unit's newest" was read from the resampled
output grid, 0.84 s behind the input at 50 -> 20 Hz (the rebased waist landed 0.65 s early).
Simulated users 11390-11391.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from pdrlearn.errors import ClockWentBack
from pdrlearn.runtime import Tracker, links, load_bundle
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from tests.runtime_helpers import time_chunks

BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"
AT, GONE_S = 15.0, 1.0  # the waist pod is gone GONE_S before AT s and comes back with its clock restarted at 0


@pytest.fixture(scope="module")
def bundle():
    return load_bundle(BUNDLE)


def _walk(user: int, rate_hz: float):
    return simulate_path(parse_route("straight:15, turn:90, straight:12"), UserProfile.from_seed(user),
                         speed="normal", rate_hz=rate_hz, seed=user, name="pods", scenario="route")


def _rebased(tracker, walk, t0_s=0.0, drift=0.0):
    """Push ``walk`` as 0.2 s packets (the foot's, then the waist's), the foot clock ``t + t0_s``, the waist clock
    ``(t + t0_s)(1 + drift)`` until it restarts at 0 at AT s; on ClockWentBack rebase and push again (E227's loop).
    Returns the error and, on the tracker's clock, where the waist's first new sample went and the foot's newest
    input sample then."""
    err = None
    for (a, f), (_, w) in zip(time_chunks(walk, 0.2, "f"), time_chunks(walk, 0.2, "w"), strict=True):
        foot = {n: (t + t0_s, v) for n, (t, v) in f.items() if len(t)}
        tracker.push(foot)
        if AT - GONE_S <= a < AT:
            continue
        clock = (lambda t: (t - AT) * (1 + drift)) if a >= AT else (lambda t: (t + t0_s) * (1 + drift))
        waist = {n: (clock(t), v) for n, (t, v) in w.items() if len(t)}
        try:
            tracker.push(waist)
        except ClockWentBack as e:
            err = e
            tracker.rebase_clock(e.unit, e.offset_s)
            tracker.push(waist)  # before E248, refused at 500 ppm an hour after power-on
            first = (waist["wAccelerometer"][0][0] - tracker.waist_clock_offset_s) / (1 + drift)
            return err, float(first), max(float(t[-1]) for t, _ in foot.values())
    raise AssertionError("no ClockWentBack")


@pytest.mark.parametrize("ppm", [150.0, 500.0])
def test_the_rebase_offset_holds_the_waist_drift_over_an_hour_e248(bundle, ppm):
    walk = _walk(11390, 20.0)
    tr = Tracker(bundle, waist_clock_drift_ppm=ppm)
    err, first, foot_newest = _rebased(tr, walk, t0_s=3600.0, drift=ppm * 1e-6)
    assert err.unit == "waist" and err.beside
    assert first == pytest.approx(foot_newest + 1e-3, abs=1e-6)  # before E248: 0.54 s early at 150 ppm
    assert 0.0 < first - (3600.0 + AT) < 0.25  # the foot's packet length after the truth, by design (E227)


@pytest.mark.parametrize("rate_hz", [20.0, 50.0])
def test_the_rebase_offset_reads_the_other_units_newest_input_sample_when_resampled_e249(bundle, rate_hz):
    walk = _walk(11391, rate_hz)
    tr = Tracker(bundle, resample=rate_hz != 20.0)
    err, first, foot_newest = _rebased(tr, walk)
    assert err.unit == "waist" and err.beside
    assert first == pytest.approx(foot_newest + 1e-3, abs=1e-6)  # before E249: 0.85 s early at 50 Hz
    assert 0.0 < first - AT < 0.25


@pytest.mark.parametrize("drift", [0.0, 150e-6, 500e-6])
def test_the_order_refusal_offset_places_the_sample_beside_the_other_units_newest_e248(drift):
    offset, t_raw = -2.0, 0.0  # the waist clock restarted: its first new sample reads 0 s
    t0 = (t_raw - offset) / (1 + drift)  # E229's model, where the tracker put it
    e = links.order_error("wGyroscope", t0, 3613.95, duplicate=False, max_lag_s=2.0, offset_s=offset,
                          other_newest=3615.2, drift={"waist": drift})
    assert isinstance(e, ClockWentBack) and e.beside
    assert (t_raw - e.offset_s) / (1 + drift) == pytest.approx(3615.2 + 1e-3, abs=1e-9)
    alone = links.order_error("wGyroscope", t0, 3613.95, duplicate=False, max_lag_s=2.0, offset_s=offset,
                              other_newest=None, drift={"waist": drift})
    assert not alone.beside and (t_raw - alone.offset_s) / (1 + drift) == pytest.approx(3613.95 + 1e-3, abs=1e-9)
    assert np.isfinite(alone.offset_s)


@pytest.mark.parametrize("drift", [0.0, 500e-6])
def test_both_clocks_back_in_one_push_hold_the_waist_drift_e248(drift):
    # decision E243's one refusal for both units: each unit's first new sample 1 ms after the tracker's newest
    foot_off, waist_off = 0.0, 3.0
    t0 = (0.0 - waist_off) / (1 + drift)  # the waist's first new sample (its clock reads 0) on the tracker's clock
    e = links.order_error("wGyroscope", t0, 3613.95, duplicate=False, max_lag_s=2.0, offset_s=waist_off,
                          other_newest=3614.0, also_back={"foot": (0.0 - foot_off, 3614.0, foot_off)},
                          drift={"waist": drift})
    assert isinstance(e, ClockWentBack) and set(e.offsets) == {"waist", "foot"}
    assert (0.0 - e.offsets["waist"]) / (1 + drift) == pytest.approx(3614.0 + 1e-3, abs=1e-9)
    assert 0.0 - e.offsets["foot"] == pytest.approx(3614.0 + 1e-3, abs=1e-9)
