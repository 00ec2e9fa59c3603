"""Decision W583 (trial s50 T3 finding F4): a slow (3-6 s) seated period with no walk around it - a stand-pivot
between two sits, a seated start and end - is read as W450's sit-and-rise pair."""

from __future__ import annotations

import functools

import pandas as pd
import pytest

import pdrlearn.track.waist as track_mod
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.waist.transfers import SIT_TO_STAND, STAND_TO_SIT, chair_transfers_upright


@pytest.fixture(scope="module")
def pivot():
    return simulate_path(parse_route("sit:12, stand:3, sit:12, straight:2"), UserProfile.from_seed(5), rate_hz=20.0,
                         seed=0, scenario="route", bounce="pendulum", transfer_s=(4.0, 5.0))


def _kinds(session) -> list[str]:
    return list(pd.DataFrame(track_mod.track_waist(session, pipeline="waist-pendulum").info["transfers"] or [],
                             columns=["kind"])["kind"])


def test_a_slow_stand_pivot_is_read_w583(pivot):
    assert _kinds(pivot) == [STAND_TO_SIT, SIT_TO_STAND, STAND_TO_SIT, SIT_TO_STAND]


def test_without_w583_the_pivot_is_missed(pivot, monkeypatch):
    monkeypatch.setattr(track_mod, "chair_transfers_upright", functools.partial(chair_transfers_upright,
                                                                                slow_pairs=False))
    assert len(_kinds(pivot)) < 4
