"""Decision L250: ``gait_speed_mps`` is a timed walk from standing (distance / the strides' rest-to-rest span, gait
initiation and termination included); an instrumented walkway's steady speed is ``median_speed_straight_mps``, and
the docs say so."""

from __future__ import annotations

import dataclasses

import pytest

from pdrlearn.columns import expanded
from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.plasys import track_plasys


@pytest.fixture(scope="module")
def fast_walkway():
    user = dataclasses.replace(UserProfile.from_seed(4941), step_length_m=0.84, step_time_s=0.42)  # 2.0 m/s
    s = simulate_path([Stand(2), Straight(20), Stand(2)], user, speed="normal", rate_hz=100, seed=0)
    r = track_plasys(s)
    return r, evaluate_track(r, s)


def test_gait_speed_is_distance_over_the_rest_to_rest_span(fast_walkway):
    r, m = fast_walkway
    span = float(r.steps["end_s"].max() - r.steps["start_s"].min())
    assert m["walking_time_s"] == pytest.approx(span)
    assert m["gait_speed_mps"] == pytest.approx(m["distance_m"] / span)
    assert m["gait_speed_mps"] < 0.95 * 2.0  # initiation, termination and the standing in the first / last rows
    assert m["median_speed_straight_mps"] == pytest.approx(2.0, abs=0.05)  # the walkway's steady speed


def test_the_docs_point_walkway_users_to_the_straight_speed():
    meaning = expanded("sessions.csv")["gait_speed_mps"][3]
    assert "L250" in meaning and "median_speed_straight_mps" in meaning
