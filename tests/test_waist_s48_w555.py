"""Session 48, trial T2 finding F6: a TUG's slow rise (or sit) read past a standstill - L648's 5 s window does not
count the time the trunk stands upright (decision W555) - and a walk with sitting read but no rise says why it has
no TUG time (decision W556)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

import pdrlearn.waist.transfers as T
from pdrlearn.cli.common import transfer_line

SIT, RISE = T.STAND_TO_SIT, T.SIT_TO_STAND
#: a TUG's walking contacts (s): 14-24 s (T2: a 3.8 s rise ending ~8.5 s, 5 s standing still, then the walk)
CONTACTS = np.arange(14.0, 24.1, 0.6)
FS = 100.0
TIMES = np.arange(0.0, 45.0, 1.0 / FS)


def _row(kind: str, a: float, b: float) -> dict:
    return {"transfer": 0, "kind": kind, "start_s": a, "end_s": b, "duration_s": b - a, "peak_s": 0.5 * (a + b),
            "peak_tilt_deg": 40.0, "height_change_m": 0.4 if kind == RISE else -0.4, "flag": ""}


def _frame(*rows) -> pd.DataFrame:
    return pd.DataFrame(list(rows), columns=list(T.TRANSFER_COLUMNS))


def _tilt(*bent: tuple[float, float]) -> np.ndarray:
    """3 deg from the upright (standing or walking), 30 deg inside each ``bent`` span (seated, bent)."""
    tilt = np.full(TIMES.size, 3.0)
    for a, b in bent:
        tilt[(TIMES >= a) & (TIMES <= b)] = 30.0
    return tilt


@pytest.fixture
def slow_reading(monkeypatch):
    """W450's reading replaced by the given rows (the window is what is tested here)."""
    def use(*rows):
        monkeypatch.setattr(T, "transfers_from_tilt", lambda imu, tilt, slow_bounds=None: _frame(*rows))
    return use


def test_not_upright_time_is_a_pure_kernel_w555():
    tilt = _tilt((10.0, 12.0))
    assert T.not_upright_s(TIMES, tilt, 8.0, 14.0) == pytest.approx(2.0, abs=0.05)
    assert T.not_upright_s(TIMES, _tilt(), 8.0, 14.0) == 0.0
    assert T.not_upright_s(TIMES, tilt, 14.0, 8.0) == 0.0


def test_a_rise_before_a_standstill_is_read_w555(slow_reading):
    imu = SimpleNamespace(t=TIMES, fs=FS)
    slow_reading(_row(RISE, 5.0, 8.5), _row(SIT, 31.0, 35.0))  # 5.5 s and 7 s from the walk, upright between
    out = T.with_slow_edges(imu, _tilt(), _frame(), CONTACTS, final_turn=False)
    assert out["kind"].tolist() == [RISE, SIT] and out["start_s"].tolist() == [5.0, 31.0]
    old = T.with_slow_edges(imu, _tilt(), _frame(), CONTACTS, final_turn=False, standstill=False)
    assert old.empty  # L648 alone: both more than 5 s from the walk (T2's missed rises)


def test_a_seated_or_bent_gap_still_counts_w555(slow_reading):
    imu = SimpleNamespace(t=TIMES, fs=FS)
    slow_reading(_row(RISE, 1.0, 4.0), _row(SIT, 31.0, 35.0))
    # seated (tilted) from the rise's end to 13 s: 9 s not upright before the walk; bent 25-31 s before the sit
    out = T.with_slow_edges(imu, _tilt((4.0, 13.0), (25.0, 31.0)), _frame(), CONTACTS, final_turn=False)
    assert out.empty


def test_a_walk_with_sitting_and_no_rise_says_why_w556():
    note = T.no_rise_note(_frame(), CONTACTS, 16.1)
    assert note.startswith("no TUG time: no sit-to-stand found (no chair transfer, sitting 16.1 s")
    assert "W556" in note and "14.0-23.6 s" in note
    assert "1 stand-to-sit" in T.no_rise_note(_frame(_row(SIT, 31.0, 35.0)), CONTACTS, 0.0)
    assert T.no_rise_note(_frame(_row(RISE, 5.0, 8.0)), CONTACTS, 16.1) is None  # a rise found: W183's notes
    assert T.no_rise_note(_frame(), CONTACTS, 0.0) is None  # no sitting, no sit: nothing to explain
    assert T.no_rise_note(_frame(), np.r_[CONTACTS, 200.0], 16.1) is None  # a walk over 120 s: no TUG
    assert T.no_rise_note(_frame(), [], 16.1) is None
    line = transfer_line({"n_sit_to_stand": 0, "n_stand_to_sit": 0, "tug_time_s": None, "tug_time_note": note})
    assert line == f"0 sit-to-stand, 0 stand-to-sit (transfers.csv), {note}"


@pytest.fixture(scope="module")
def t2_tug():
    """T2's TUG at a normal gait (user 15981 of W555's measurement): 2-4 s transfers, the default 5 s standstill."""
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    return simulate_path(parse_route("straight:3, turn:180, straight:3, turn:180"), UserProfile.from_seed(15981),
                         rate_hz=100.0, seed=0, scenario="route", transfer_s=(2.0, 4.0), sit_start_s=5.0,
                         sit_end_s=5.0)


def _summary(session, monkeypatch, standstill: bool) -> dict:
    from functools import partial

    from pdrlearn.track.base import get_pipeline
    from pdrlearn.track.evaluate import track_summary

    monkeypatch.setattr(T, "with_slow_edges", partial(T.with_slow_edges, standstill=standstill))
    return track_summary(get_pipeline("waist-pendulum")(session), session, pipeline="waist-pendulum")


def test_t2s_tug_is_timed_end_to_end_w555(t2_tug, monkeypatch):
    truth = t2_tug.extras["transfers"]
    true_s = float(truth["seated_s"].iloc[-1] - truth["rise_s"].iloc[0])
    got = _summary(t2_tug, monkeypatch, True)
    assert got["tug_time_s"] == pytest.approx(true_s, abs=1.0)


def test_untimed_tug_with_sitting_says_why_end_to_end_w556(t2_tug, monkeypatch):
    got = _summary(t2_tug, monkeypatch, False)  # without W555: no transfer found, only sitting read
    assert got["tug_time_s"] is None and got["n_sit_to_stand"] == 0 and got["sitting_time_s"] > 0
    assert got["tug_time_note"].startswith("no TUG time: no sit-to-stand found (no chair transfer, sitting ")
