"""Decisions L345, L346: a lower-back turn's 5-95 % times on its smoothed yaw (the option ``yaw_fractions``; not
adopted: El-Gohary's boundaries stay turns.csv's default and read longer than a 5-95 % turn)."""

from __future__ import annotations

import inspect

import numpy as np
import pytest

from pdrlearn.kernels.yaw_turns import turn_fraction_times, yaw_rate_turns
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.clinical import turn_table

FS = 100.0


def _bump(t, t0, dur, angle):
    """A raised-cosine yaw rate (deg/s) turning ``angle`` deg from ``t0`` over ``dur`` s."""
    x = (t - t0) / dur
    return np.where((x >= 0) & (x <= 1), angle / dur * (1 - np.cos(2 * np.pi * x)), 0.0)


def _truth(t, w):
    """L201's truth of a clean yaw rate: its integral, 1 s moving mean, 5 % / 95 % of the change."""
    y = np.cumsum(w) / FS
    y = np.convolve(np.pad(y, (50, 49), mode="edge"), np.ones(100) / 100, mode="valid")
    frac = (y - y[0]) / (y[-1] - y[0])
    return float(t[np.argmax(frac >= 0.05)]), float(t[np.argmax(frac >= 0.95)])


def test_fraction_times_of_a_turn():
    t = np.arange(0, 30, 1 / FS)
    # a 180 deg left turn over 2 s from 10 s with a 1 Hz walking sway (one stride: the 1 s mean removes it)
    w = _bump(t, 10, 2, 180) + 10 * np.sin(2 * np.pi * t)
    rows = yaw_rate_turns(w, FS)
    assert rows.shape == (1, 4)
    (i0, i1), = turn_fraction_times(w, FS, rows)
    # the sway averages out: the truth of the turn without it, within two samples; El-Gohary's boundaries are
    # over 0.3 s outside each end
    ta, tb = _truth(t, _bump(t, 10, 2, 180))
    assert t[i0] == pytest.approx(ta, abs=0.02) and t[i1] == pytest.approx(tb, abs=0.02)
    assert rows[0, 0] / FS < ta - 0.3 and rows[0, 1] / FS > tb + 0.3
    # a right turn: the fractions of its (negative) change
    (j0, j1), = turn_fraction_times(-w, FS, yaw_rate_turns(-w, FS))
    assert (j0, j1) == (i0, i1)
    assert turn_fraction_times(w, FS, np.zeros((0, 4))).shape == (0, 2)


def test_yaw_fractions_option_times_a_simulated_turn_5_95():
    from pdrlearn.track.waist import track_waist

    route = "straight:3, turn:180, straight:3"  # the trial's TUG turn (seated start and end)
    s = simulate_path(parse_route(route), UserProfile.from_seed(11), speed="normal", seed=11, sit_start_s=5.0,
                      sit_end_s=5.0)
    tr = s.trajectory
    tt_ = tr["t"].to_numpy(float)
    k = int(round(1.0 / np.median(np.diff(tt_))))
    h = np.degrees(np.unwrap(tr["heading_rad"].to_numpy(float)))
    h = np.convolve(np.pad(h, (k // 2, k - 1 - k // 2), mode="edge"), np.ones(k) / k, mode="valid")  # L201: 1 s mean
    frac = (h - h[0]) / (h[-1] - h[0])
    ta, tb = (float(tt_[np.argmax(frac >= f)]) for f in (0.05, 0.95))
    res = track_waist(s, pipeline="waist-pendulum")
    yaw = res.info["yaw_turns"]
    assert {"start_5_s", "end_95_s"} <= set(yaw[0])
    opt = turn_table(res.steps, yaw_turns=yaw, yaw_fractions=True)
    default = turn_table(res.steps, yaw_turns=yaw)
    assert len(opt) == len(default) == 1
    assert opt.loc[0, "start_s"] == pytest.approx(ta, abs=0.2) and opt.loc[0, "end_s"] == pytest.approx(tb, abs=0.2)
    # the mean rate is the 5-95 % share of the angle over that time (L209's heading definition)
    assert opt.loc[0, "mean_rate_dps"] == pytest.approx(0.9 * abs(opt.loc[0, "angle_deg"]) / opt.loc[0, "duration_s"])
    # L346: not adopted - the default keeps El-Gohary's boundaries, which read the turn longer (L346's bias)
    assert inspect.signature(turn_table).parameters["yaw_fractions"].default is False
    assert default.loc[0, "duration_s"] > (tb - ta) + 0.5
    assert default.loc[0, "mean_rate_dps"] < opt.loc[0, "mean_rate_dps"]
    same = ["angle_deg", "peak_rate_dps", "n_rows"]
    assert default[same].equals(opt[same])
