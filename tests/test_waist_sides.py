"""Decision W129: a lower-back steps table carries each contact's side (left / right / empty), read from W20's
lateral velocity with a sign fixed a priori (v > 0, towards the left, = the left foot); decisions W130 / B189: a
lower-back session without a gyroscope is refused with a line naming the accelerometer-only detector."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.sim import simulate
from pdrlearn.steps import PLLStepDetector
from pdrlearn.steps.evaluate import match_events
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.plausibility import contact_sides


@pytest.fixture(scope="module")
def walk():
    return simulate("A", 1906, rate_hz=100.0)


def test_contact_sides_reads_w20s_sign_and_leaves_weak_ones_undecided():
    t = np.arange(0.0, 10.0, 0.01)
    v = np.array([0.2, -0.25, 0.01, 0.18, -0.02, -0.2])  # median |v| 0.19: under a third of it is undecided
    got = contact_sides(t, np.zeros_like(t), 100.0, np.arange(6.0), v_at=v)
    assert list(got) == ["left", "right", "", "left", "", "right"]
    assert contact_sides(t, np.zeros_like(t), 100.0, np.zeros(0)).size == 0


@pytest.mark.parametrize("pipeline", ["waist-pendulum", "waist-pll"])
def test_the_side_is_the_simulated_foot(walk, pipeline):
    steps = track_waist(walk, pipeline=pipeline).steps
    ics = walk.extras["ics"]
    i_d, i_r = match_events(steps["event_s"].to_numpy(float), ics["ic_s"].to_numpy(float), 0.25)
    side = steps["side"].to_numpy(object)[i_d]
    dec = side != ""
    assert i_d.size >= 20 and dec.mean() >= 0.8
    assert np.mean(side[dec] == ics["foot"].to_numpy(object)[i_r][dec]) >= 0.95
    assert set(steps["side"]) <= {"left", "right", ""}


def test_a_realtime_track_leaves_the_side_empty(walk):
    steps = track_waist(walk, pipeline="waist-pendulum", realtime=True).steps
    assert len(steps) > 10 and (steps["side"] == "").all()


def test_an_accelerometer_only_session_names_the_pll_detector(walk):
    s = dataclasses.replace(walk, streams={k: v for k, v in walk.streams.items() if k != "wGyroscope"})
    for pipeline in ("waist-pendulum", "waist-pll"):
        with pytest.raises(DataError) as e:
            track_waist(s, pipeline=pipeline)
        msg = str(e.value)
        assert "no wGyroscope.csv" in msg and "--detector pll" in msg and "W130" in msg and "\n" not in msg
    assert len(PLLStepDetector().detect(s)) >= 20  # what the line names works without the gyroscope
