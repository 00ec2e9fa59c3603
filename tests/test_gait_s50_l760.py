"""Decisions L760-L763 (session 50, FB, trial s50t2): each pass of a walk with turns re-anchored where the feet stand
side by side, the step-length index's drift bound and its line, the support caveat in clinical.md's words, the
stance line naming its foot."""
import numpy as np
import pandas as pd
import pytest

from pdrlearn.report.spatiotemporal import gait_spatiotemporal_line
from pdrlearn.track.bilateral import drift_warning, stance_warning
from pdrlearn.track.gait import stance_share_warning
from pdrlearn.track.step_anchors import (
    anchor_offsets,
    anchor_rows,
    drift_bound_pct,
    pass_bound_pct,
    pass_corrected,
    pass_starts,
    short_strides,
)


def _two_passes(jump: float = 0.2, drift: float = 0.05):
    """Steps of two 6-step passes (left 0.45 m, right 0.55 m) with a closing step each; the tracks' offset (left
    against right) grows 0 -> ``drift`` over the first pass, jumps by ``jump`` in the turn and grows by ``drift``
    again over the second. Returns side, measured length, time, anchors, the true lengths and the second pass's
    start (row, offset, time)."""
    side = np.array(["right", "left"] * 3 + ["left"] + ["right", "left"] * 3 + ["right"])
    true = np.array([0.55, 0.45] * 3 + [0.0] + [0.55, 0.45] * 3 + [0.0])
    at = np.r_[np.arange(7) * 0.6 + 1.0, np.arange(7) * 0.6 + 8.0]
    off = np.r_[np.linspace(0, drift, 8)[1:], drift + jump + np.linspace(0, drift, 8)[1:]]
    start2 = (7, drift + jump, 7.4)  # the side-by-side pair after the turn, at 7.4 s
    off[7:] = np.interp(at[7:], [7.4, at[13]], [drift + jump, off[13]])
    meas = np.where(side == "left", true + off, true - off)
    return side, meas, at, np.array([6, 13]), true, start2


def test_each_pass_re_anchored_at_its_own_ends_recovers_the_steps():
    side, meas, at, anchors, true, start2 = _two_passes()
    assert np.allclose(anchor_offsets(side, meas, anchors), [0.05, 0.3])
    out = pass_corrected(side, meas, at, anchors, [start2], opened=True, start=0.4)
    ok = np.r_[0:6, 7:13]
    assert np.allclose(out[ok], true[ok], atol=0.003) and np.isnan(out[anchors]).all()
    # L310's one offset over the walk (a scale) leaves the jump in: the second pass is off by ~0.2 m a step
    assert np.abs(meas[7:13] - true[7:13]).max() > 0.19
    # a pass with no known start (a turn that did not end with the feet together) gets no step length
    blind = pass_corrected(side, meas, at, anchors, [None], opened=True, start=0.4)
    assert np.isnan(blind[7:]).all() and np.allclose(blind[:6], true[:6], atol=0.003)
    assert np.isnan(pass_corrected(side, meas, at, anchors, [start2], opened=False)[:7]).all()


def test_anchor_rows_and_the_pair_after_a_turn():
    kinds = np.array(["start_stop", "level", "level", "start_stop", "turn", "turn", "start_stop", "level",
                      "start_stop"], dtype=object)
    side = np.array(["left", "right", "left", "right", "left", "right", "left", "right", "left"])
    bout = np.ones(9, int)
    k = np.arange(1, 9)
    length = np.array([0.5, 0.5, 0.0, np.nan, np.nan, 0.5, 0.5, 0.0])
    anchors = anchor_rows(kinds, bout, k, length)
    assert list(anchors) == [2, 7]  # contact 3 before the turn, contact 8 at the walk's end; not contact 6
    x = np.array([0.0, 0.5, 1.0, 1.0, 1.0, 1.03, 0.5, 0.0, 0.0])  # after the turn the walk runs back (-x)
    y = np.zeros(9)
    d = np.array([0, 0, 0, 0, np.pi / 2, np.pi, np.pi, np.pi, np.pi])
    short = short_strides(side, np.array([0.5, 1.0, 1.0, 0.5, 1.0, 1.0, 0.5, 1.0, 1.0]))
    assert short[[0, 3, 6]].all() and not short[[1, 2, 4, 5, 7, 8]].any()
    st = pass_starts(kinds, side, np.arange(9.0), x, y, d, short, k, length, anchors)
    assert st[0][0] == 5 and st[0][2] == 5.0  # the pass's first step with a length; the pair's time (contact 5)
    assert st[0][1] == pytest.approx(0.03)  # left (contact 4, x 1.0) ahead of right (x 1.03) along -x by 0.03 m
    assert pass_starts(kinds, side, np.arange(9.0), x, y, d, np.zeros(9, bool), k, length, anchors) == [None]


def test_drift_bounds_and_the_line_over_two_points(caplog):
    side = np.array(["left", "right"] * 8)
    length = np.array([0.5, 0.6] * 4 + [0.52, 0.58] * 4)
    anchors = np.array([7, 15])
    length[[7, 15]] = np.nan  # the anchors have no step length (L760)
    assert pass_bound_pct(side, length, anchors, min_steps=4) is None  # 4 left, 3 right steps a pass
    b = pass_bound_pct(side, length, anchors)
    si = [100 * (0.5 - 0.6) / 0.55, 100 * (0.52 - 0.58) / 0.55]
    assert b == pytest.approx(2 * np.std(si, ddof=1) / np.sqrt(2))
    assert drift_bound_pct(-0.011, 0.55) == pytest.approx(2.0) and drift_bound_pct(None, 0.5) is None
    walk = {"step_length_si_drift_pct": 4.4, "step_length_m_si_pct": 8.8, "step_length_m_left": 0.5,
            "step_length_m_right": 0.6}
    line = drift_warning(walk)
    assert "off by about 4 points" in line and "drifted 2 cm" in line and "L761" in line
    assert drift_warning({**walk, "step_length_si_drift_pct": 1.9}) is None
    assert drift_warning({**walk, "step_length_m_si_pct": None}) is None


def test_support_caveat_in_words_and_the_stance_line_names_its_foot():
    walk = {"stride_length_m_left": 1.1, "stride_length_m_right": 1.1, "stance_time_s_left": 0.8,
            "stride_time_s_left": 1.25, "stance_time_s_right": 0.66, "stride_time_s_right": 1.25,
            "double_support_pct": 13.4}
    plain = gait_spatiotemporal_line(walk)
    said = gait_spatiotemporal_line(walk, "double support reads low and single support high from foot units")
    assert "not measured" not in plain and said.startswith(plain)
    assert "not measured values here: double support reads low" in said
    line = stance_warning({"single_support_pct_left": 46.6, "single_support_pct_right": 36.1,
                           "double_support_pct": 17.3})
    assert "the right foot's under 55 %" in line and "the right foot's toe-off" in line and "left foot's" not in line
    steps = pd.DataFrame({"stance_pct": np.full(12, 53.0)})
    right = stance_share_warning(steps, "right")
    assert "of the right foot" in right and "prosthesis" not in right and "if it is one" in right
    assert "of this foot" in stance_share_warning(steps)


def _corridor(jump: float = 0.2):
    """Two feet's tracked step tables of a walk out and back along x with a turn on the spot between: steps onto
    the left foot 0.45 m, onto the right 0.55 m, each pass from the feet side by side to a closing step; the left
    track's turn strides carry ``jump`` m of error along x (the tracks' offset moved in the turn)."""
    pos = {"left": complex(0, 0.1), "right": complex(0, -0.1)}
    rows = {"left": [], "right": []}
    t = [0.0]

    def stride(side, new, turn=0.0, err=0j):
        d = new - pos[side] + err
        rows[side].append({"start_s": t[0] - 0.6, "end_s": t[0] + 0.1, "event_s": t[0], "tc_s": t[0] - 0.4,
                           "length_m": abs(d), "heading_rad": float(np.angle(d)), "turn_angle_rad": turn})
        pos[side] = new
        t[0] += 0.6

    def straight(sign, n, lateral, first="right"):
        front = pos["left"].real
        second = "left" if first == "right" else "right"
        for i in range(n):
            side = first if i % 2 == 0 else second
            front += sign * (0.55 if side == "right" else 0.45)
            stride(side, complex(front, lateral[side]))
        last = second if n % 2 == 1 else first  # the trailing foot closes beside the other
        stride(last, complex(front, lateral[last]))

    straight(1, 9, {"left": 0.1, "right": -0.1})
    x = pos["left"].real
    for side, y in (("left", 0.05), ("right", -0.05), ("left", -0.1), ("right", 0.1)):  # on the spot, 45 deg
        stride(side, complex(x, y), np.pi / 4, complex(jump / 2, 0) if side == "left" else 0j)  # a stride
    straight(-1, 29, {"left": -0.1, "right": 0.1}, "left")  # back past the start: it ends 10 m from it
    return pd.DataFrame(rows["left"]), pd.DataFrame(rows["right"])


def test_bilateral_gait_re_anchors_each_pass_of_a_walk_with_a_turn():
    from pdrlearn.track.bilateral import bilateral_gait

    left, right = _corridor()
    new, old = bilateral_gait(left, right), bilateral_gait(left, right, reanchor=False)
    w = new["walk"]
    assert w["step_length_passes"] == 2 and "step_length_si_drift_pct" not in w  # L761 not adopted: opt-in
    assert w["step_length_m_left"] == pytest.approx(0.45, abs=0.01)
    assert w["step_length_m_right"] == pytest.approx(0.55, abs=0.01)
    assert abs(old["walk"]["step_length_m_si_pct"] - 20.0) > 5  # L310's one scale keeps the turn's 0.2 m
    assert bilateral_gait(left, right, si_drift=True)["walk"]["step_length_si_drift_pct"] is not None
