"""Decision L791 (session 51, FH, trial s51t2 F2): a re-anchored walk's step lengths along each straight segment's
own axis, and a pass that never spans a turn."""
import numpy as np
import pandas as pd
import pytest

from pdrlearn.track.bilateral import STEP_AXIS_MAX_DEG, STEP_TURN_MAX_DEG, bilateral_gait, step_lengths
from pdrlearn.track.step_anchors import (
    anchor_rows,
    axis_lengths,
    lost_rows,
    pass_corrected,
    pass_starts,
    segment_axes,
    short_strides,
)


def test_segment_axes_split_at_turns_and_bouts():
    kinds = np.array(["start_stop", "level", "level", "turn", "turn", "level", "level", "level"], dtype=object)
    bout = np.array([1, 1, 1, 1, 1, 1, 2, 2])
    d = np.radians([10, -10, 0, 90, 170, 178, -178, 180])
    ax = np.degrees(segment_axes(kinds, bout, d))
    assert np.allclose(ax[:3], 0.0, atol=1e-9) and np.isnan(ax[3:5]).all()
    assert ax[5] == pytest.approx(178.0)  # its own segment, not the next bout's
    assert np.allclose(ax[6:], -179.0)  # -178 and 180 deg: the circular mean, not the arithmetic 1 deg


def test_a_metres_wide_sideways_separation_no_longer_reads_into_the_step_length():
    """The two tracks 3 m apart sideways (never re-anchored) and stride directions wobbling +-4 deg: each step's
    own direction (L310) reads the separation by its sine, the segment's axis does not."""
    n = 12
    side = np.array(["right", "left"] * (n // 2))
    x = np.arange(n) * 0.55
    y = np.where(side == "left", 3.0, 0.0)
    d = np.radians(np.where(np.arange(n) % 4 < 2, 4.0, -4.0))
    both = pd.DataFrame({"x_m": x, "y_m": y, "dir_rad": d})
    k = np.arange(1, n)
    old = step_lengths(both, k)
    assert np.nanmax(np.abs(old - 0.55)) > 0.15  # 3 m x sin 4 deg = 0.21 m
    axes = segment_axes(np.full(n, "level", dtype=object), np.ones(n, int), d)
    new = axis_lengths(x, y, d, k, axes, turn_max_deg=STEP_TURN_MAX_DEG, axis_max_deg=STEP_AXIS_MAX_DEG)
    assert np.allclose(new, 0.55, atol=1e-9)
    # a step over the axis bound (L310's 10 deg) gets none, measured against its segment's axis
    d2 = d.copy()
    d2[5:7] = np.radians(25.0)
    assert np.isnan(axis_lengths(x, y, d2, k, axes, turn_max_deg=STEP_TURN_MAX_DEG,
                                 axis_max_deg=STEP_AXIS_MAX_DEG)[5])


def test_a_pass_that_lost_a_closing_step_starts_after_its_last_turn():
    kinds = np.array(["start_stop", "level", "level", "start_stop", "turn", "turn", "start_stop", "level", "level",
                      "start_stop", "turn", "turn", "start_stop", "level", "level", "start_stop"], dtype=object)
    n = len(kinds)
    side = np.array(["left", "right"] * (n // 2))
    k = np.arange(1, n)
    length = np.full(n - 1, 0.5)
    length[[2, 14]] = 0.0  # the closing steps (contacts 3 and 15)
    length[[3, 4, 8, 9, 10]] = np.nan  # the turns' steps and the closing step at contact 9 without a length
    anchors = anchor_rows(kinds, np.ones(n, int), k, length)
    assert list(anchors) == [2, 14]  # contact 9's closing step is lost: one pass over two turns
    short = short_strides(side, np.where(np.isin(np.arange(n), [0, 3, 6, 9, 12, 15]), 0.5, 1.0))
    x, y, d = np.arange(n) * 0.5, np.zeros(n), np.zeros(n)
    ic = np.arange(n, dtype=float)
    old = pass_starts(kinds, side, ic, x, y, d, short, k, length, anchors)
    assert old[0][0] == 5 and old[0][2] == 5.0  # L760: from the first turn, across the second
    new = pass_starts(kinds, side, ic, x, y, d, short, k, length, anchors, whole_pass=True)
    assert new[0][0] == 11 and new[0][2] == 11.0  # L791: after the turn before its own closing step
    out = pass_corrected(side, length, ic[k], anchors, new, opened=True, start=0.0)
    assert np.isnan(out[5:11]).all() and np.isfinite(out[11:14]).all()
    assert list(lost_rows(length, out, anchors)) == [5, 6, 7]  # L783's line names them


def _wide_stop_walk(wide_m: float = 3.0) -> tuple[pd.DataFrame, pd.DataFrame]:
    """Two 9-step bouts (left 0.45 m, right 0.55 m) with a stop, the feet side by side, between them; the left track
    lies ``wide_m`` sideways of the right (never re-anchored) and zig-zags +-0.06 m stride by stride."""
    pos = {"left": complex(0, wide_m), "right": complex(0, 0.0)}
    rows: dict[str, list] = {"left": [], "right": []}
    t = [0.0]

    def stride(side, new):
        d = new - pos[side]
        rows[side].append({"start_s": t[0] - 0.6, "end_s": t[0] + 0.1, "event_s": t[0], "tc_s": t[0] - 0.4,
                           "length_m": abs(d), "heading_rad": float(np.angle(d)), "turn_angle_rad": 0.0})
        pos[side], t[0] = new, t[0] + 0.6

    for bout in range(2):
        front = pos["right"].real
        for i in range(10):
            side = "right" if i % 2 == 0 else "left"
            front += (0.55 if side == "right" else 0.45) if i < 9 else 0.0
            y = 0.0 if side == "right" else wide_m + (0.06 if (i // 2) % 2 else -0.06)
            stride(side, complex(front, y))
        t[0] += 5.0 * (bout == 0)
    return pd.DataFrame(rows["left"]), pd.DataFrame(rows["right"])


def test_bilateral_gait_per_segment_is_opt_in_and_reads_the_wide_tracks_right():
    left, right = _wide_stop_walk()
    old, new = (bilateral_gait(left, right, per_segment=p)["steps"] for p in (False, True))
    for st in (old, new):
        assert np.isfinite(st["step_length_m"]).sum() >= 12
    err = [np.nanmax(np.abs(st["step_length_m"] - np.where(st["side"] == "left", 0.45, 0.55))) for st in (old, new)]
    assert err[0] > 0.03 and err[1] < 0.01  # the default (L760) reads the 3 m by the sine; L791's axis does not
