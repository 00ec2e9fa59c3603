"""Decision W338: a phone-only lower-back track warns where its contacts lack walking's stride rhythm (a standing
passenger's bounce in a vehicle, S71) - W339: its rule was not met, so only with the PARAMS.json option
``rhythm_warning``. Users 7184-7185."""

from __future__ import annotations

import dataclasses

import numpy as np
import pandas as pd
import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.units import keep_units
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.rhythm import MIN_STRIDE_REGULARITY, arrhythmic_sequences, stride_regularity


def _bounce(fs: float, n: int, seed: int) -> np.ndarray:
    """Broad-band 1-3 Hz noise (S71's vibration band) as a sum of 30 random tones."""
    rng = np.random.default_rng(seed)
    t = np.arange(n) / fs
    return sum(np.sin(2 * np.pi * f * t + p) for f, p in zip(rng.uniform(1, 3, 30), rng.uniform(0, 6.3, 30),
                                                              strict=True))


def test_regularity_is_high_for_a_gait_and_low_for_a_bounce():
    """Pure kernel at 100 Hz: a step at 0.55 s with a stride asymmetry (a fundamental, its harmonic and noise) reads
    over 0.7; S71's 1-3 Hz broad-band bounce under MIN_STRIDE_REGULARITY; too short a signal is NaN."""
    fs, step = 100.0, 0.55
    t = np.arange(0, 20, 1 / fs)
    gait = np.sin(2 * np.pi * t / step) + 0.3 * np.sin(np.pi * t / step) + 0.2 * np.sin(4 * np.pi * t / step)
    gait += 0.2 * np.random.default_rng(1).standard_normal(t.size)
    assert stride_regularity(gait, fs, step) > 0.7
    assert stride_regularity(_bounce(fs, t.size, 2), fs, step) < MIN_STRIDE_REGULARITY
    assert np.isnan(stride_regularity(gait[:150], fs, step))


def test_sequences_are_judged_in_chunks():
    """A sequence of 32 contacts: 16 over a gait, 16 over a bounce -> one run, the bounce's chunk only."""
    fs, step = 100.0, 0.55
    t = np.arange(0, 40, 1 / fs)
    gait = np.sin(2 * np.pi * t / step) + 0.3 * np.sin(np.pi * t / step)
    sig = np.where(t < 16 * step, gait, _bounce(fs, t.size, 3))
    ev = np.arange(32) * step + 0.1
    steps = pd.DataFrame({"event_s": ev, "has_next": np.r_[np.ones(31, bool), False]})
    runs = arrhythmic_sequences(steps, t, sig, fs)
    assert [(a, b) for a, b, _ in runs] == [(16, 31)]


@pytest.fixture(scope="module")
def ride():
    route = parse_route("stand:3, straight:12, vehicle:60:1.0, straight:12, stand:3")
    return simulate_path(route, UserProfile.from_seed(7184), rate_hz=100.0, seed=7184)


ON = {"options": {"rhythm_warning": True}}  # decision W339: opt-in


def _phone(s):
    return dataclasses.replace(keep_units(s, ("waist",)), _left_out={})


@pytest.mark.parametrize("pipeline", ["waist-pendulum", "waist-pll"])
def test_a_phone_only_ride_is_named(ride, pipeline):
    """Phone only, with the option: a W338 line overlapping the ride; with the foot unit in the session W336 speaks
    instead; without the option (W339's default) no W338 line."""
    row = ride.extras["rides"].iloc[0]
    assert not [w for w in track_waist(_phone(ride), pipeline=pipeline).info["warnings"] if "W338" in w]
    lines = [w for w in track_waist(_phone(ride), pipeline=pipeline, params=ON).info["warnings"] if "W338" in w]
    print(pipeline, lines)
    assert lines
    spans = [tuple(float(x) for x in w.split(" at ", 1)[1].split(" s ", 1)[0].split("-")) for w in lines]
    assert any(a < row.end_s and b > row.start_s for a, b in spans)
    assert all(b > row.start_s - 2.0 and a < row.end_s + 2.0 for a, b in spans)  # the walks are not named
    with_foot = track_waist(ride, pipeline=pipeline, params=ON).info["warnings"]
    assert not [w for w in with_foot if "W338" in w] and [w for w in with_foot if "W336" in w]


def test_a_phone_only_walk_is_not_named():
    walk = simulate_path(parse_route("stand:3, straight:20, turn:180, straight:20, stand:3"),
                         UserProfile.from_seed(7185), rate_hz=100.0, seed=7185)
    for pipeline in ("waist-pendulum", "waist-pll"):
        assert not [w for w in track_waist(_phone(walk), pipeline=pipeline, params=ON).info["warnings"]
                    if "W338" in w]
