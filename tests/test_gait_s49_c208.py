"""Decision C208 (session 49, I3; trial T1 finding F7 of session 48, a race-walking coach's track sessions): `gait`'s
closing step anchors the two foot tracks' relative scale (L310) only on a walk that keeps within 2 m of its axis (the
line from its start to its end); a bend that brings the walk back onto its axis beside its start is no anchor."""

from __future__ import annotations

import cmath
import math

import numpy as np
import pandas as pd

from pdrlearn.report.clinical import asymmetry_lines
from pdrlearn.track.bilateral import CLOSURE_LATERAL_MAX_M, bilateral_gait, lateral_reach


def _walk(headings_deg: list[float], s_left: float = 0.45, s_right: float = 0.36,
          left_turn_error_deg: float = 0.0) -> tuple[pd.DataFrame, pd.DataFrame]:
    """Two feet's tracked step tables of a walk from standing (the right foot first), one step per heading (deg),
    steps onto the left foot ``s_left`` long and onto the right ``s_right``, then a closing step. The left track's
    headings read ``left_turn_error_deg`` off once the walk has turned (a bend's gyro difference between the units)."""
    pos = {"left": 0j, "right": 0j}
    rows = {"left": [], "right": []}
    t = 0.0
    for k, h in enumerate([*headings_deg, None]):
        side, other = ("right", "left") if k % 2 == 0 else ("left", "right")
        new = pos[other] if h is None else pos[other] + (s_left if side == "left" else s_right) * cmath.rect(
            1.0, math.radians(h))
        d = new - pos[side]
        turned = k > 0 and any(abs(x - headings_deg[0]) > 1 for x in headings_deg[:k])
        err = math.radians(left_turn_error_deg) if side == "left" and turned else 0.0
        rows[side].append({"start_s": t - 0.6, "end_s": t + 0.1, "event_s": t, "tc_s": t - 0.4, "length_m": abs(d),
                           "heading_rad": (math.atan2(d.imag, d.real) if abs(d) else math.radians(h or 0.0)) + err})
        pos[side] = new
        t += 0.6
    return pd.DataFrame(rows["left"]), pd.DataFrame(rows["right"])


def _bend() -> list[float]:
    """80 steps east, a 180 deg bend to the left in 40 steps (a radius of ~5 m), 40 steps west: the walk ends on its
    axis, 10 m beside it and ~16 m from its start along it."""
    return [0.0] * 80 + list(np.linspace(4.5, 175.5, 40)) + [180.0] * 40


def test_a_bend_is_no_anchor_c208(caplog):
    """The left track's heading 2 deg off after the bend: L310 read the closing step's offset as a relative scale and
    gave step lengths (SI far off the true 22.2 %); C208 gives none and a line naming the bend."""
    left, right = _walk(_bend(), left_turn_error_deg=2.0)
    res = bilateral_gait(left, right)
    w = res["walk"]
    assert w["step_length_scale_pct"] is None and w["step_length_m_si_pct"] is None
    assert res["steps"]["step_length_m"].isna().all()
    line = [x for x in res["warnings"] if "C208" in x]
    assert len(line) == 1 and "left its axis" in line[0], res["warnings"]
    first = asymmetry_lines(w)[0]  # clinical.md's walk block says why the step length is missing
    assert first.startswith("- Asymmetry") and first.endswith("step length not given (the walk is not one straight "
                                                              "length from standing to standing, L311 / C208: see "
                                                              "gait_summary.json warnings)"), first


def test_lateral_reach_and_a_straight_walk_keeps_its_anchor_c208():
    """The reach kernel on positions (a straight walk 0, a point 3 m beside the start-end line 3); a straight walk
    with the left track 2 % long keeps L310's anchor: the same step lengths as before C208."""
    both = pd.DataFrame({"x_m": [0.0, 5.0, 10.0, 10.0], "y_m": [0.0, 3.0, 0.0, 0.0]})
    assert lateral_reach(both) == 3.0
    assert lateral_reach(both.assign(y_m=0.0)) == 0.0
    left, right = _walk([0.0] * 40)
    res = bilateral_gait(left.assign(length_m=left["length_m"] * 1.02), right)
    st = res["steps"].iloc[:-1]
    err = np.where(st["side"] == "left", st["step_length_m"] - 0.45, st["step_length_m"] - 0.36)
    assert np.abs(err).max() < 0.005 and res["walk"]["step_length_scale_pct"] is not None
    assert not any("C208" in x for x in res["warnings"]) and CLOSURE_LATERAL_MAX_M == 2.0
