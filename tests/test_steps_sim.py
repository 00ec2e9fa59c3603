"""Step detectors and unit alignment on simulated PLASYS sessions (pdrlearn.sim)."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.sim import simulate
from pdrlearn.steps import get_detector, score_steps
from pdrlearn.steps.align import align_units

_CACHE: dict = {}


def _sim(scenario, user, speed, **knobs):
    key = (scenario, user, speed, tuple(sorted(knobs.items())))
    if key not in _CACHE:
        _CACHE[key] = simulate(scenario, user, speed=speed, **knobs)
    return _CACHE[key]


# bounds per detector: foot detectors must find every stride; waist detectors within the thesis' worst
# case (Tables 20-21: gyroscope 5.6 %) with one step of slack for these short sessions
@pytest.mark.parametrize("detector,min_f1,max_err", [("accel", 0.97, 3.0), ("accel-force", 0.97, 3.0),
                                                      ("pll", 0.95, 5.0), ("pelvic-gyro", None, 9.0)])
@pytest.mark.parametrize("scenario,speed", [("A", "fast"), ("B", "normal")])
def test_detectors_on_simulated_sessions(detector, min_f1, max_err, scenario, speed):
    s = _sim(scenario, 2, speed)
    sc = score_steps(get_detector(detector).detect(s), s)
    assert sc["count_error_pct"] <= max_err, sc
    if min_f1 is not None:
        assert sc["f1"] >= min_f1, sc
    if detector.startswith("accel"):
        assert sc["reference"].startswith("steps.ic_s")
    else:
        assert "ics" in sc["reference"]


def test_pll_step_frequency_matches_simulated_cadence():
    s = _sim("A", 2, "normal")
    steps = get_detector("pll").detect(s)
    ics = np.sort(s.extras["ics"]["ic_s"].to_numpy())
    true_f = 1.0 / np.median(np.diff(ics))
    assert np.median(steps["step_freq_hz"]) == pytest.approx(true_f, rel=0.03)


@pytest.mark.parametrize("scenario", ["A", "B"])
def test_alignment_recovers_simulated_clock_offset_within_one_sample(scenario):
    s = _sim(scenario, 3, "normal")
    base = align_units(s)
    fs = s["wAccelerometer"].rate_hz
    # Same clock: the residual offset is the gap between the two detectors' events (the foot detector's
    # swing-acceleration peak vs the waist PLL's contact phase). That gap depends on the gait timing (it
    # moves by ~50 ms between a 60 % and a 68 % stance, decisions S14), so it is not asserted to be ~0;
    # it must stay well inside half a step so that the periodic matching cannot pick a neighbouring step.
    step_s = float(np.median(np.diff(np.sort(s.extras["ics"]["ic_s"].to_numpy()))))
    assert abs(base[0]) <= 0.25 * step_s, (base, step_s)
    for offset in (0.2, -0.2):
        est, drift = align_units(_sim(scenario, 3, "normal", clock_offset_s=offset))
        assert abs((est - base[0]) - offset) <= 1.0 / fs, (est, base)


@pytest.mark.parametrize("detector", ["accel", "accel-force"])
def test_foot_detectors_on_stairs_and_turns(detector):
    # the terrain exercise: 10-step stair flights up and down with turns on the spot between them
    s = _sim("terrain", 1, "normal")
    sc = score_steps(get_detector(detector).detect(s), s)
    assert sc["recall"] >= 0.95 and sc["f1"] >= 0.95, sc


def test_foot_detectors_with_dropped_packets():
    s = _sim("B", 1, "normal", drop_rate=0.05)
    for name in ("accel", "accel-force"):
        sc = score_steps(get_detector(name).detect(s), s)
        assert sc["f1"] >= 0.97, (name, sc)


def test_accel_detector_slow_swing_is_one_stride_at_20hz():
    # at 20 Hz a single quiet sample in the middle of a slow swing must not split the stride
    # (MIN_STILL_SAMPLES, docs/decisions/steps.md)
    for scenario, user in (("A", 3), ("B", 3)):
        s = _sim(scenario, user, "slow")
        assert s["fAccelerometer"].rate_hz == pytest.approx(20.0)
        sc = score_steps(get_detector("accel").detect(s), s)
        assert sc["false_positives"] <= 1 and sc["recall"] >= 0.95, (scenario, sc)


def test_pelvic_turn_highpass_keeps_steps_in_sharp_turns():
    """Decision 12: scenario B fast (sharp corners at 20 Hz), users 1-4: the 0.6 Hz turn high-pass counts
    better than the former 0.5 Hz (printed 0.7 % vs 2.9 %), well within the thesis' 5.6 % (Table 21)."""
    err = {}
    for cut in (0.6, 0.5):
        d = r = 0
        for user in (1, 2, 3, 4):
            s = _sim("B", user, "fast")
            sc = score_steps(get_detector("pelvic-gyro", turn_cutoff_hz=cut).detect(s), s)
            d += abs(sc["scored_count"] - sc["reference_count"])
            r += sc["reference_count"]
        err[cut] = 100.0 * d / r
    assert err[0.6] <= 2.0, err
    assert err[0.6] < err[0.5], err
