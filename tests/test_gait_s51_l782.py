"""Session 51 (FB), review s51r1 finding F2 (docs/decisions/localization.md): L782 (a pass that follows a stop starts
where the feet stood side by side) and L783 (a walk whose passes leave steps without a step length says so)."""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd
import pytest

from pdrlearn.track.bilateral import bilateral_gait
from pdrlearn.track.step_anchors import lost_rows, pass_starts


def _stop_walk(drift_m: float = 0.0) -> tuple[pd.DataFrame, pd.DataFrame]:
    """Two 9-step bouts (left 0.45 m, right 0.55 m steps) with a 5 s stop, the feet side by side, between them
    (review s51r1's l760_stop.py); ``drift_m``: the left track drifts that far ahead along the walk over the second
    bout (linear in its strides), as a foot track's drift does."""
    pos = {"left": complex(0, 0.1), "right": complex(0, -0.1)}
    rows: dict[str, list] = {"left": [], "right": []}
    t = [0.0]
    shift = [0.0]

    def stride(side, new):
        d = new - pos[side]
        rows[side].append({"start_s": t[0] - 0.6, "end_s": t[0] + 0.1, "event_s": t[0], "tc_s": t[0] - 0.4,
                           "length_m": abs(d), "heading_rad": float(np.angle(d)), "turn_angle_rad": 0.0})
        pos[side] = new
        t[0] += 0.6

    def straight(n, drift):
        front = pos["right"].real
        for i in range(n + 1):
            side = "right" if i % 2 == 0 else "left"
            if i < n:
                front += 0.55 if side == "right" else 0.45
            else:
                side = "left" if n % 2 == 1 else "right"
            if side == "left":
                shift[0] += drift / ((n + 2) // 2)
            stride(side, complex(front + (shift[0] if side == "left" else 0.0), 0.1 if side == "left" else -0.1))

    straight(9, 0.0)
    t[0] += 5.0  # the stop, feet side by side
    straight(9, drift_m)
    return pd.DataFrame(rows["left"]), pd.DataFrame(rows["right"])


@pytest.fixture(scope="module")
def walks():
    return {"plain": _stop_walk(), "drift": _stop_walk(0.1)}


def test_a_pass_after_a_stop_gets_its_step_lengths_l782(walks):
    for name, (left, right) in walks.items():
        g = bilateral_gait(left, right)
        st = g["steps"]
        length = st["step_length_m"].to_numpy(float)
        assert g["walk"]["step_length_passes"] == 2, name
        assert int(np.isfinite(length).sum()) == 16, name  # before L782: 8 (the second pass NaN)
        want = np.where(st["side"] == "left", 0.45, 0.55)
        ok = np.isfinite(length)
        # the 0.1 m drift taken out but for its steps inside a stride (linear in time, the strides' drift in jumps)
        np.testing.assert_allclose(length[ok], want[ok], atol=1e-6 if name == "plain" else 0.01, err_msg=name)
        assert not [w for w in g["warnings"] if "no step length" in w], name


def test_pass_starts_reads_a_stop_only_with_the_bouts_l782():
    # left, right, left(closing, bout end) | right (opens, short), left, right(closing)
    side = np.array(["right", "left", "right", "left", "right", "left", "right", "left"])
    kinds = np.array(["start_stop", "level", "level", "start_stop", "start_stop", "level", "level", "start_stop"],
                     dtype=object)
    bout = np.array([1, 1, 1, 1, 2, 2, 2, 2])
    ic = np.array([0.0, 0.6, 1.2, 1.8, 7.0, 7.6, 8.2, 8.8])
    x = np.array([0.55, 1.0, 1.55, 1.6, 2.15, 2.6, 3.15, 3.15])
    y, d = np.zeros(8), np.zeros(8)
    short = np.array([True, False, False, True, True, False, False, True])
    k = np.array([1, 2, 3, 5, 6, 7])
    length = np.array([0.45, 0.55, 0.05, 0.45, 0.55, 0.0])
    anchors = np.array([2, 5])
    assert pass_starts(kinds, side, ic, x, y, d, short, k, length, anchors) == [None]  # L760 alone: no turn
    (row, off, t0), = pass_starts(kinds, side, ic, x, y, d, short, k, length, anchors, bout=bout)
    assert (row, t0) == (3, 7.0)  # the new bout's first contact's time, not the closing step's
    assert off == pytest.approx(0.05)  # the right foot (j - 1) at 1.55, the left (j) at 1.6: the left 0.05 ahead


def test_steps_left_without_a_length_get_a_line_l783(walks, caplog):
    left, right = walks["plain"]
    assert lost_rows(np.array([0.4, 0.5, 0.0, 0.4]), np.array([0.4, np.nan, np.nan, np.nan]),
                     np.array([2])).tolist() == [1, 3]  # the anchor is no lost step
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        g = bilateral_gait(left.iloc[1:].reset_index(drop=True), right.iloc[1:].reset_index(drop=True))
    assert g["walk"]["step_length_passes"] == 2  # not opened from standing: the first pass has no start
    line = [w for w in g["warnings"] if "have no step length" in w]
    assert len(line) == 1 and line[0].startswith("bilateral gait: 6 of the walk's 16 steps have no step length (at ")
    assert "L783" in line[0] and line[0] in caplog.text
