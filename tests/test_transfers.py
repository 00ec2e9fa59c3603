"""Decisions W182, W183: transfers.csv (each sit-to-stand / stand-to-sit from W104's trunk-flexion events) and the
summary's transfer keys and ``tug_time_s``, on synthetic signals and a simulated seated-start, seated-end TUG."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.columns import TRANSFERS, undocumented
from pdrlearn.io import write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.waist.transfers import (
    MOVING_DPS,
    SIT_TO_STAND,
    STAND_TO_SIT,
    TRANSFER_COLUMNS,
    TRANSFER_SUMMARY_KEYS,
    height_change_m,
    movement_bounds,
    transfer_summary,
)


def test_bounds_are_where_the_trunk_stops_moving():
    fs = 100.0
    t = np.arange(0, 10, 1 / fs)
    # rest at 20 deg, a bell up to 50 deg from 3 to 5 s, rest at 2 deg
    u = np.clip((t - 3.0) / 2.0, 0, 1)
    tilt = 20.0 + 30.0 * np.sin(np.pi * u) ** 2 - 18.0 * (3 * u ** 2 - 2 * u ** 3)
    a, b = movement_bounds(t, tilt, int(np.argmax(tilt)), fs)
    rate = np.gradient(tilt, t)
    assert 3.0 <= t[a] <= 3.2 and 4.8 <= t[b] <= 5.0, (t[a], t[b])
    assert abs(rate[a - 5]) < MOVING_DPS  # at rest before
    still = np.full(t.size, 5.0)
    still[500] = 6.0
    a, b = movement_bounds(t, still, 500, fs)  # no movement: the bounds stay within the top window of the peak
    assert 500 - 26 <= a and b <= 500 + 26


def test_height_change_removes_a_constant_error():
    fs = 100.0
    t = np.arange(0, 2.0 + 1e-9, 1 / fs)
    z = 0.45 * (10 * (t / 2) ** 3 - 15 * (t / 2) ** 4 + 6 * (t / 2) ** 5)  # a rest-to-rest rise of 0.45 m
    acc = np.gradient(np.gradient(z, t), t)
    assert height_change_m(t, acc, 0, t.size - 1) == pytest.approx(0.45, abs=0.005)
    assert height_change_m(t, acc + 0.3, 0, t.size - 1) == pytest.approx(0.45, abs=0.005)  # a 0.3 m/s^2 offset
    assert height_change_m(t, -acc, 0, t.size - 1) == pytest.approx(-0.45, abs=0.005)


def _rows(*kinds_times):
    return [{"transfer": i + 1, "kind": k, "start_s": a, "end_s": b, "duration_s": b - a, "peak_s": a,
             "peak_tilt_deg": 40.0, "height_change_m": 0.4 if k == SIT_TO_STAND else -0.4}
            for i, (k, a, b) in enumerate(kinds_times)]


def test_tug_time_only_from_seat_to_seat():
    steps = pd.DataFrame({"start_s": [8.0, 9.0, 20.0]})
    tug = _rows((SIT_TO_STAND, 5.0, 7.0), (STAND_TO_SIT, 22.0, 24.0))
    s = transfer_summary(tug, steps)
    assert set(s) == set(TRANSFER_SUMMARY_KEYS)
    assert s["tug_time_s"] == pytest.approx(19.0) and s["n_sit_to_stand"] == 1 and s["n_stand_to_sit"] == 1
    assert s["median_sit_to_stand_s"] == pytest.approx(2.0)
    assert transfer_summary(tug, pd.DataFrame({"start_s": [4.0, 9.0]}))["tug_time_s"] is None  # a step before
    assert transfer_summary(tug, pd.DataFrame({"start_s": [9.0, 25.0]}))["tug_time_s"] is None  # a step after
    assert transfer_summary(tug, pd.DataFrame({"start_s": [6.0, 9.0]}))["tug_time_s"] == pytest.approx(19.0)
    middle = _rows((SIT_TO_STAND, 5.0, 7.0), (STAND_TO_SIT, 12.0, 14.0), (SIT_TO_STAND, 20.0, 22.0),
                   (STAND_TO_SIT, 30.0, 32.0))
    assert transfer_summary(middle, steps)["tug_time_s"] is None and transfer_summary(middle)["n_sit_to_stand"] == 2
    assert transfer_summary(list(reversed(tug)), steps)["tug_time_s"] is None  # starts standing, ends standing
    assert transfer_summary(None) == dict.fromkeys(TRANSFER_SUMMARY_KEYS)  # a foot track
    assert transfer_summary([])["n_sit_to_stand"] == 0


@pytest.fixture(scope="module")
def tug(tmp_path_factory):
    """User 3531 (slow; W183's measurement user): seated 5 s, TUG with a 180 deg turn, seated 5 s."""
    d = tmp_path_factory.mktemp("tug") / "tug"
    s = simulate_path(parse_route("straight:3, turn:180, straight:3"), UserProfile.from_seed(3531), speed="slow",
                      seed=3531, sit_start_s=5.0, sit_end_s=5.0)
    write_session(s, d)
    return d


@pytest.mark.parametrize("veto", [False, True])
def test_waist_track_writes_the_two_transfers_and_the_tug_time(tug, tmp_path, capsys, veto):
    truth = pd.read_csv(tug / "transfers.csv") / 1000.0  # _ms columns: rise 5.00-7.22 s, sit 29.25-31.74 s
    out = tmp_path / "w"
    args = ["track", "--no-plot", str(tug), "--pipeline", "waist-pendulum", "--out", str(out)]
    if veto:
        (tmp_path / "p.json").write_text('{"options": {"sit_veto": "rhythm"}}')
        args += ["--params", str(tmp_path / "p.json")]
    assert main(args) == 0
    printed = capsys.readouterr().out
    assert "transfers.csv" in printed and "1 sit-to-stand, 1 stand-to-sit (transfers.csv), TUG time" in printed
    tr = pd.read_csv(out / "transfers.csv")
    assert list(tr.columns) == list(TRANSFER_COLUMNS)  # no clock columns: the simulated session gives no start
    assert [c[0] for c in TRANSFERS] == list(TRANSFER_COLUMNS) + ["start_time", "end_time", "peak_time"]  # L298
    assert undocumented("transfers.csv", tr.columns) == []
    assert tr["kind"].tolist() == [SIT_TO_STAND, STAND_TO_SIT]
    rise = (truth["rise_ms"].iloc[0], truth["end_ms"].iloc[0])
    sit = (truth["start_ms"].iloc[1], truth["seated_ms"].iloc[1])
    assert np.abs(tr[["start_s", "end_s"]].to_numpy() - np.array([rise, sit])).max() < 0.4
    assert 0.3 < tr["height_change_m"].iloc[0] < 0.7 and -0.7 < tr["height_change_m"].iloc[1] < -0.3
    summary = json.loads((out / "summary.json").read_text())
    assert summary["tug_time_s"] == pytest.approx(sit[1] - rise[0], abs=0.5)
    assert summary["n_sit_to_stand"] == 1 and summary["n_stand_to_sit"] == 1
    assert "transfers" not in summary["info"]  # the rows are transfers.csv's
    win = tmp_path / "win"  # decision W182: a window keeps the transfers inside it only
    assert main(["track", "--no-plot", str(tug), "--pipeline", "waist-pendulum", "--window", "8,28", "--out",
                 str(win)]) == 0
    assert pd.read_csv(win / "transfers.csv").empty
    assert json.loads((win / "summary.json").read_text())["tug_time_s"] is None
