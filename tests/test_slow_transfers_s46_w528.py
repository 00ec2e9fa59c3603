"""Decision W528 (forty-sixth session, trial T1 finding F4): a slow (3-5 s) seated period between two walks is read
again with W450's bounds at the inner bouts' edges, and kept only as a whole sit-and-rise pair."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

import pdrlearn.waist.transfers as T
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.base import get_pipeline
from pdrlearn.track.evaluate import track_summary

SIT, RISE = T.STAND_TO_SIT, T.SIT_TO_STAND
#: walking contacts (s): a walk to 10 s, a 30 s gap, a walk from 40 s
CONTACTS = np.r_[np.arange(1.0, 10.5, 0.75), np.arange(40.0, 50.0, 0.75)]


def _row(kind: str, a: float, b: float) -> dict:
    return {"transfer": 0, "kind": kind, "start_s": a, "end_s": b, "duration_s": b - a, "peak_s": 0.5 * (a + b),
            "peak_tilt_deg": 35.0, "height_change_m": 0.4 if kind == RISE else -0.4, "flag": ""}


def _frame(*rows) -> pd.DataFrame:
    return pd.DataFrame(list(rows), columns=list(T.TRANSFER_COLUMNS))


@pytest.fixture
def slow_reading(monkeypatch):
    """W450's reading replaced by the given rows (the pair logic is what is tested here)."""
    def use(*rows):
        monkeypatch.setattr(T, "transfers_from_tilt", lambda imu, tilt, slow_bounds=None: _frame(*rows))
    return use


def test_a_slow_sit_and_rise_pair_is_added(slow_reading):
    slow_reading(_row(SIT, 11.0, 15.0), _row(RISE, 35.0, 39.0), _row(SIT, 60.0, 64.0))
    out = T.with_slow_seats(None, None, _frame(), CONTACTS)
    assert out["kind"].tolist() == [SIT, RISE] and out["transfer"].tolist() == [1, 2]
    assert out["start_s"].tolist() == [11.0, 35.0]  # the one after the last walk is L648's business, not W528's


def test_the_missing_side_is_added_to_w182s_other_side(slow_reading):
    slow_reading(_row(SIT, 11.2, 15.5), _row(RISE, 35.0, 39.0))
    out = T.with_slow_seats(None, None, _frame(_row(SIT, 11.0, 13.0)), CONTACTS)
    assert out["kind"].tolist() == [SIT, RISE] and out["start_s"].tolist() == [11.0, 35.0]


@pytest.mark.parametrize("rows", [
    [_row(SIT, 11.0, 15.0)],  # one-sided: nothing
    [_row(RISE, 35.0, 39.0)],
    [_row(SIT, 20.0, 24.0), _row(RISE, 35.0, 39.0)],  # the sit starts 10 s after the walk: not at its edge
    [_row(SIT, 11.0, 15.0), _row(RISE, 25.0, 29.0)],  # the rise ends 11 s before the next walk
])
def test_no_pair_adds_nothing(slow_reading, rows):
    slow_reading(*rows)
    assert T.with_slow_seats(None, None, _frame(), CONTACTS).empty


def test_w182s_whole_seated_period_is_left_alone(monkeypatch):
    def fail(*a, **k):
        raise AssertionError("W450's reading is not asked for")
    monkeypatch.setattr(T, "transfers_from_tilt", fail)
    rows = _frame(_row(SIT, 11.0, 13.0), _row(RISE, 36.0, 38.0))
    pd.testing.assert_frame_equal(T.with_slow_seats(None, None, rows, CONTACTS), rows)
    short = np.r_[np.arange(1.0, 10.5, 0.75), np.arange(19.0, 30.0, 0.75)]  # a 8.5 s gap: under UNMATCHED_SIT_S
    assert T.with_slow_seats(None, None, _frame(), short).empty


def _track(monkeypatch, w528: bool):
    if not w528:
        monkeypatch.setattr(T, "with_slow_seats", lambda imu, tilt, rows, contacts: rows)
        monkeypatch.setattr(T, "with_slow_pairs", lambda imu, tilt, rows, contacts: rows)  # W583 reads it too
    s = simulate_path(parse_route("stand:3, straight:5, sit:40, straight:5, stand:3"),
                      UserProfile.from_seed(14270), rate_hz=100.0, seed=0, scenario="route", transfer_s=(3.0, 5.0))
    r = get_pipeline("waist-pendulum")(s)
    return track_summary(r, s, pipeline="waist-pendulum"), s.extras["transfers"]


def test_a_slow_seat_between_walks_is_found_end_to_end(monkeypatch):
    """A 3-5 s sit and rise between two walks (trial T1's post-operative transfers): both found, and the seat
    counted as sitting; W182 + L648 alone miss them (checked here, so the test fails without W528)."""
    summ, truth = _track(monkeypatch, True)
    assert (summ["n_stand_to_sit"], summ["n_sit_to_stand"]) == (1, 1)
    seated = float((truth["rise_s"] - truth["seated_s"]).sum())
    assert summ["sitting_time_s"] == pytest.approx(seated, abs=10.0)
    before, _ = _track(monkeypatch, False)
    assert before["n_sit_to_stand"] + before["n_stand_to_sit"] < 2
