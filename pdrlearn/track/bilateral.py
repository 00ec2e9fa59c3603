"""Bilateral gait from two foot units of one walk (decisions L259-L263, docs/decisions/localization.md).

A foot track sees one foot: its strides, their initial contacts (IC, ``event_s``) and, with ``--toe-off``
(L73), their terminal contacts (TC, ``tc_s``). Two foot tracks of one walk on one clock give what needs both
feet (L259): the events of the two feet are merged in time and

* a **step** is an IC of one foot whose previous IC of the walk is the other foot's, both in one walking bout
  (no same-foot IC between them: a stride the other track missed makes no step); its time is that interval
  (IC of one foot to the next IC of the other, as commonly defined, e.g. Perry & Burnfield 2010, Gait
  Analysis ch. 1); the **left step** ends on the left foot's IC (the simulator's S35 convention);
* a **gait cycle** of foot F runs from one IC of F to its next; where the other foot's TC and IC and F's own
  TC fall inside it in the order IC_F < TC_o < IC_o < TC_F < next IC_F, its **double support** is
  (TC_o - IC_F) + (TC_F - IC_o) and F's **single support** is IC_o - TC_o (the other foot's swing), both in %
  of the cycle (Perry & Burnfield 2010: two double-support periods of about 10 % each and single support of
  about 40 % of the cycle in healthy walking);
* **asymmetry** of a left and right mean, as commonly defined: the symmetry index
  SI = 100 x |L - R| / (0.5 x (L + R)) (Robinson, Herzog & Nigg 1987,
  :func:`pdrlearn.track.clinical.symmetry_index_pct`) and the symmetry ratio L / R (Patterson et al. 2010,
  Gait Posture 31:241-246; the simulator's ``--step-time-asymmetry a`` makes it 1 + a).

Walking bouts of the pair (L261): the merged ICs split where the interval to the next IC is at least
:data:`pdrlearn.track.clinical.PAUSE_MIN_S` longer than the walk's median step (L104's pause on the merged
contacts, :func:`pdrlearn.track.clinical.bout_rows`). Every function here is pure (tables in, tables / dicts
out); :func:`pair_sessions` tracks two session folders.
"""

from __future__ import annotations

import json
import logging
import math
from contextlib import contextmanager
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.decision_refs import decision_ref
from pdrlearn.errors import DataError

# decision E320: the sides' means and indices, numpy only, shared with the lean runtime's gait summary
from pdrlearn.kernels.gait_values import cycle_support, mean_finite, side_pair
from pdrlearn.kernels.nearest import nearest_index
from pdrlearn.kernels.turn_length import STRAIGHT_MAX_RAD
from pdrlearn.track.clinical import CV_MIN_STRIDES, bout_rows, symmetry_index_pct  # noqa: F401
from pdrlearn.track.contact_quality import comparability_warning, impact_sharpness
from pdrlearn.track.flags import flag_values
from pdrlearn.track.foot_heights import height_warning
from pdrlearn.track.gait_flight import flight_after, flight_warning
from pdrlearn.track.step_anchors import (
    anchor_rows,
    axis_lengths,
    drift_bound_pct,
    lost_rows,
    pass_bound_pct,
    pass_corrected,
    pass_starts,
    segment_axes,
    short_strides,
)
from pdrlearn.track.support_bias import setup_of, support_note

#: the columns :func:`foot_events` gives: one row per initial contact of one foot; ``x_m`` / ``y_m`` (the foot's
#: rest position after the stride, its own track's frame) and ``dir_rad`` (the stride's direction) need a tracked
#: table's ``heading_rad`` (decision L310), else NaN
EVENT_COLUMNS = ("ic_s", "tc_s", "length_m", "x_m", "y_m", "dir_rad", "terrain", "turn_deg", "stride_s", "backward",
                 "ramp")
#: decision L260: a foot's ``meta.json`` key naming which foot the unit is on (gaitmap's ``foot``, the simulator's
#: ``instrumented_foot``)
FOOT_META_KEYS = ("foot", "instrumented_foot")
SIDES = ("left", "right")
#: decision B245: the least share of the merged contacts (in the two tracks' overlap) that follow the other foot's;
#: each stride one track misses puts one contact out of turn, so 0.8 allows one missed stride in five of each foot
#: (gaitmap's level pair: tracked 63 / 63, mocap labels 55 / 56; two walks whose clocks overlap: stairs-down left
#: + level right 30 / 50, stairs-up left + level right 36 / 51)
ALTERNATION_MIN = 0.8
#: decision B245: meta.json keys naming what was recorded; two sessions giving different values are not one walk
WALK_META_KEYS = ("activity", "terrain_recording")
#: decision L283: meta.json's key naming the clock a session's timestamps are on; sessions whose values differ do
#: not share t = 0 (gaitmap's converter writes it; simulated sessions are compared by :func:`sim_walk`, S54; any
#: other folder without it is trusted as before)
CLOCK_META_KEY = "clock_id"
#: decision L284: the clock-offset check runs from this step-time symmetry index (%): below, |L - R| of 0.55 s steps
#: is under 0.055 s = an offset under ~27 ms, within two SDs of a tracked step time (L263: SD 16.3 ms)
OFFSET_CHECK_SI_MIN = 10.0
#: decision L284: ... and warns when the swing-time symmetry index is under this share of the step-time one: a clock
#: offset moves every step time and no swing time (each swing is one unit's toe-off to its IC), while a walker's
#: own step-time asymmetry comes with swing asymmetry (the simulator's S35 walker: the same index; measured L286)
OFFSET_SWING_SHARE_MAX = 0.5
#: decision L285: the least stance (% of the gait cycle) a walking foot is plausibly given: ~60 % at a self-selected
#: speed and more when slower (Perry & Burnfield 2010, Gait Analysis ch. 1); 55 % leaves 10 % of double support.
#: Below it the toe-off is likely early (the tracked support times are biased, SUPPORT_NOTE)
STANCE_MIN_PCT = 55.0


def foot_events(steps: pd.DataFrame, *, ramps: bool = False) -> pd.DataFrame:
    """Decision L259: the IC events of one foot track's ``steps.csv`` (offline plasys: ``event_s``; ``tc_s`` with
    ``--toe-off``, else NaN; ``length_m``, NaN on an ``impossible`` stride) in time order; gap rows (``gap_s`` > 0,
    L67) and rows without an IC left out. A label table (``ic_s`` / ``tc_s`` in s, e.g. a mocap ``steps.csv`` read
    by :func:`pdrlearn.io.read_session`) is taken as it is. ``ramps`` (decision L775, measured and not adopted; off by
    default): ``ramp`` is :func:`stride_ramp`'s and a ramp stride's terrain flat; off, ``ramp`` is all False."""
    ic_col = "event_s" if "event_s" in steps else "ic_s"
    if ic_col not in steps:
        raise DataError("bilateral gait: the foot table has no initial contacts (event_s / ic_s); track the foot "
                        "session offline (pdrlearn track, not --streaming)")
    ok = np.isfinite(steps[ic_col].to_numpy(float))
    x, y, d = stride_positions(steps)  # decision L310: over every row (a gap row is 0 m), before any is left out
    z = stride_heights(steps)  # decision L561: likewise
    if "gap_s" in steps:
        ok &= steps["gap_s"].to_numpy(float) == 0
    st = steps[ok]
    x, y, d, z = x[ok], y[ok], d[ok], z[ok]
    length = st["length_m"].to_numpy(float) if "length_m" in st else np.full(len(st), np.nan)
    if "impossible" in st:
        length = np.where(flag_values(st["impossible"]), np.nan, length)
    terrain_all = stride_terrain(steps)
    # decision L775 (measured, not adopted: off by default): the ramp strides, their own kind
    ramp = stride_ramp(steps, terrain_all)[ok] if ramps else np.zeros(int(ok.sum()), bool)
    # decision L775: a ramp stride is no stair step (the simulator labels a ramp stride rising 0.08 m "up", S3)
    terrain, turn = np.where(ramp, "flat", terrain_all[ok]).astype(object), stride_turn_deg(steps)[ok]  # L538
    span = (st["end_s"].to_numpy(float) - st["start_s"].to_numpy(float) if {"start_s", "end_s"} <= set(st)
            else np.full(len(st), np.nan))  # decision L539: the stride's rest-to-rest time
    out = pd.DataFrame({"ic_s": st[ic_col].to_numpy(float),
                        "tc_s": st["tc_s"].to_numpy(float) if "tc_s" in st else np.full(len(st), np.nan),
                        "length_m": length, "x_m": x, "y_m": y, "z_m": z, "dir_rad": d, "terrain": terrain,
                        "turn_deg": turn, "stride_s": span, "backward": stride_backward(steps)[ok],  # L746
                        **{c: pd.to_numeric(st[c], errors="coerce").to_numpy(float) if c in st
                           else np.full(len(st), np.nan) for c in FOOT_ANGLES},  # cohort C244: L421's angles
                        "ramp": ramp})  # decision L775
    return out.sort_values("ic_s", kind="stable").reset_index(drop=True)


def stride_ramp(steps: pd.DataFrame, terrain: np.ndarray | None = None, *, slope_dz_m: float = 0.04,
                run: int = 3) -> np.ndarray:
    """Decision L775: (rows,) bool, each row's stride climbs or descends a ramp: inside L144's
    :func:`pdrlearn.kernels.distance.sustained_slope` run of the foot's strides - at least ``run`` (3: L304's
    shortest run) consecutive height changes of one sign, each at least ``slope_dz_m`` (0.04 m: L144's 3 % of a 1.3 m
    stride) - on a tracked table's ``raw_dz_m`` (the height before L39's level rule, which zeroes a 1:12 ramp's
    ~0.09 m strides), else a label table's ``height_m`` (the simulator's); all False for a table with neither (an
    older track). A stair stride ends a run and is none: a tracked table's stair-flight rows (``terrain``,
    :func:`stride_terrain`, L603), a label table's ``kind`` stairs_up / stairs_down (the simulator's). A gap row
    (L67, no height) ends a run. Rows in the table's order (walking order)."""
    from pdrlearn.kernels.distance import sustained_slope

    col = "raw_dz_m" if "raw_dz_m" in steps else "height_m" if "height_m" in steps else None
    if col is None or not len(steps):
        return np.zeros(len(steps), bool)
    dz = np.nan_to_num(pd.to_numeric(steps[col], errors="coerce").to_numpy(float), nan=0.0)
    if col == "height_m" and "kind" in steps:
        stair = steps["kind"].astype(str).str.startswith("stairs").to_numpy(bool)
    else:
        stair = np.zeros(len(steps), bool) if terrain is None else np.asarray(terrain, dtype=object) != "flat"
    return sustained_slope(np.where(stair, 0.0, dz), slope_dz_m=slope_dz_m, run=run)


def stride_backward(steps: pd.DataFrame) -> np.ndarray:
    """Decision L746: (rows,) bool, each row's stride travels backward: a foot track's L203 ``backward_travel``
    (:func:`pdrlearn.track.evaluate.backward_travel`, steps.csv's column of that name: L654's measured travel; no
    model's ``direction`` class, which a turn's pivot stride can take, L224), else a label table's ``direction`` ==
    ``backward`` (the simulator's steps.csv); all False for a table with neither."""
    from pdrlearn.track.evaluate import backward_travel

    back = backward_travel(steps)
    if back is not None:
        return np.asarray(back, dtype=bool)
    if "direction" in steps:
        return (steps["direction"].astype(str).str.strip().str.lower() == "backward").to_numpy(bool)
    return np.zeros(len(steps), bool)


def stride_terrain(steps: pd.DataFrame) -> np.ndarray:
    """Decision L538: each row's terrain, ``"up"`` / ``"down"`` / ``"flat"``: on a tracked table the rows of its
    stair flights, by their direction (decision L603: stairs.csv's flights, :func:`pdrlearn.track.stair_flights.
    flight_spans` - L179's stair rows, |``dz_m``| >= 0.10 m, in runs of at least L438's 2 strides of one sign, a ramp
    climb's rows left out; before, every L179 row, so a level walk's lone drifting stride was a stair step); a label
    table's own ``terrain`` (the simulator's and gaitmap's flat / up / down); ``"flat"`` for a table with neither (its
    steps are taken as level). Decision L789: a label table with the simulator's ``kind`` takes a stair from it
    (stairs_up / stairs_down): the simulator labels a slope's walked stride ``terrain`` up / down too (S3: a stride
    rising 0.08 m or more), so its reference called a 15 % hill's strides "stairs up / down"."""
    n = len(steps)
    if "dz_m" in steps:
        from pdrlearn.track.stair_flights import flight_spans

        order = (np.argsort(pd.to_numeric(steps["start_s"], errors="coerce").to_numpy(float), kind="stable")
                 if "start_s" in steps else np.arange(n))
        ordered = np.full(n, "flat", dtype=object)
        for a, b, sign in flight_spans(steps.iloc[order].reset_index(drop=True)):  # decision L603
            ordered[a:b] = "up" if sign > 0 else "down"
        out = np.empty(n, dtype=object)
        out[order] = ordered
        return out
    if "kind" in steps:  # decision L789: the simulator's stair kinds, not its slope-walk terrain
        k = steps["kind"].astype(str).str.strip().str.lower().to_numpy()
        return np.where(k == "stairs_up", "up", np.where(k == "stairs_down", "down", "flat")).astype(object)
    if "terrain" in steps:
        t = steps["terrain"].astype(str).str.strip().str.lower().to_numpy()
        return np.where(np.isin(t, ("up", "down")), t, "flat").astype(object)
    return np.full(n, "flat", dtype=object)


def stride_turn_deg(steps: pd.DataFrame) -> np.ndarray:
    """Decision L538: each row's turn (deg, absolute): a tracked table's ``turn_angle_rad`` (L66), a label table's
    ``heading_change_deg``; 0 without either."""
    if "turn_angle_rad" in steps:
        return np.degrees(np.abs(pd.to_numeric(steps["turn_angle_rad"], errors="coerce").to_numpy(float)))
    if "heading_change_deg" in steps:
        return np.abs(pd.to_numeric(steps["heading_change_deg"], errors="coerce").to_numpy(float))
    return np.zeros(len(steps))


#: decision L310: a step whose two strides (the landing foot's into its contact, the other foot's into the contact
#: before) differ in direction by more than this (deg) is in a turn and has no step length (no document gives one;
#: a straight walk's strides differ by a few degrees, a 180 deg turn of four strides by ~45 deg each)
STEP_TURN_MAX_DEG = 20.0
#: decision L310: a step length is given only while the walking direction is within this (deg) of the walk's first
#: step's direction or of its opposite: the two tracks' origins are joined at the standing start, so their unknown
#: sideways separation (the step width, ~0.1-0.2 m) reads as step length by its sine elsewhere (sin 10 deg = 0.17)
STEP_AXIS_MAX_DEG = 10.0


def stride_positions(steps: pd.DataFrame) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Decision L310: the foot's rest position after each row of a tracked step table (``length_m`` along
    ``heading_rad`` summed from the track's origin, the foot's rest position before its first stride) and each
    row's direction; NaN from an ``impossible`` stride on (its displacement is unknown), and all NaN for a table
    without ``heading_rad`` (a label table)."""
    n = len(steps)
    if "heading_rad" not in steps or "length_m" not in steps:
        return np.full(n, np.nan), np.full(n, np.nan), np.full(n, np.nan)
    length = steps["length_m"].to_numpy(float)
    if "impossible" in steps:
        length = np.where(flag_values(steps["impossible"]), np.nan, length)
    h = steps["heading_rad"].to_numpy(float)
    return np.cumsum(length * np.cos(h)), np.cumsum(length * np.sin(h)), h


def stride_heights(steps: pd.DataFrame) -> np.ndarray:
    """Decision L561: the foot's rest height (m) after each row, its strides' height changes summed from the track's
    origin (0): a tracked table's ``dz_m``, a label table's ``height_m`` (the simulator's steps.csv); a missing
    height counts 0 m; all NaN for a table with neither."""
    col = "dz_m" if "dz_m" in steps else "height_m" if "height_m" in steps else None
    if col is None:
        return np.full(len(steps), np.nan)
    return np.nancumsum(pd.to_numeric(steps[col], errors="coerce").to_numpy(float))


def _wrap(a):
    return (np.asarray(a, float) + np.pi) % (2 * np.pi) - np.pi


def common_frame(left: pd.DataFrame, right: pd.DataFrame) -> pd.DataFrame:
    """Decision L310: ``left`` (:func:`foot_events`) with its positions and directions turned into the right track's
    frame: about the shared origin (both feet at rest side by side before the walk) by the median difference of the
    two feet's stride directions, each left stride against the right stride whose contact is nearest in time (a
    track without a compass starts each unit's heading on its own)."""
    ok_l, ok_r = np.isfinite(left["dir_rad"].to_numpy(float)), np.isfinite(right["dir_rad"].to_numpy(float))
    if not ok_l.any() or not ok_r.any():
        return left
    tl, tr = left["ic_s"].to_numpy(float)[ok_l], right["ic_s"].to_numpy(float)[ok_r]
    near = nearest_index(tl, tr)  # decision L546: no strides x strides matrix
    diff = _wrap(right["dir_rad"].to_numpy(float)[ok_r][near] - left["dir_rad"].to_numpy(float)[ok_l])
    mean = math.atan2(np.sin(diff).mean(), np.cos(diff).mean())
    rot = float(mean + np.median(_wrap(diff - mean)))
    c, s = math.cos(rot), math.sin(rot)
    x, y = left["x_m"].to_numpy(float), left["y_m"].to_numpy(float)
    return left.assign(x_m=c * x - s * y, y_m=s * x + c * y, dir_rad=_wrap(left["dir_rad"].to_numpy(float) + rot))


def step_lengths(both: pd.DataFrame, k: np.ndarray) -> np.ndarray:
    """Decision L310: the length (m) of the steps ending on the merged contacts ``k`` (the step from contact k - 1
    of the other foot): the two feet's rest positions (one frame, :func:`common_frame`) differenced and projected on
    the walking direction, the mean of the two strides' directions. NaN in a turn (:data:`STEP_TURN_MAX_DEG`), off
    the walk's first direction and its opposite (:data:`STEP_AXIS_MAX_DEG`) or without both positions."""
    x, y, d = (both[c].to_numpy(float) for c in ("x_m", "y_m", "dir_rad"))
    a, b = k, k - 1
    ux, uy = np.cos(d[a]) + np.cos(d[b]), np.sin(d[a]) + np.sin(d[b])
    norm = np.hypot(ux, uy)
    with np.errstate(invalid="ignore", divide="ignore"):
        ux, uy = ux / norm, uy / norm
        length = (x[a] - x[b]) * ux + (y[a] - y[b]) * uy
    turn = np.abs(_wrap(d[a] - d[b])) > math.radians(STEP_TURN_MAX_DEG)
    walk = np.arctan2(uy, ux)
    ok = np.flatnonzero(np.isfinite(walk) & ~turn)
    if not len(ok):
        return np.full(len(k), np.nan)
    off = np.abs(np.sin(walk - walk[ok[0]])) > math.sin(math.radians(STEP_AXIS_MAX_DEG))
    return np.where(turn | off, np.nan, length)


#: decision L310: the walk's last step is a closing step (the feet brought side by side at a standing end, the
#: simulator's ``close`` contact) when the landing foot's last stride is under this share of its median stride: it
#: covers one step, about half a stride (judged on the foot's own stride lengths, which the two tracks' relative
#: drift does not touch; a first rule on the step's own length missed a 0.27 m drift, L311)
CLOSING_STRIDE_SHARE = 0.75
#: decision L310: the closing step's offset is read as the two tracks' relative scale only when the walk ends at
#: least this far (m, along its last direction) from where it started: nearer (a return walk) a scale error has
#: not shown and nothing is corrected
CLOSURE_MIN_M = 5.0
#: decision C208 (no document gives one: a corridor's width): the closing step anchors only a walk whose contacts
#: all lie within this distance (m) of its axis, the line from its start to its end (:func:`lateral_reach`); a bend or
#: corner beyond it (a track's 36.5 m bend) puts the two tracks' heading difference into their along-walk offset
CLOSURE_LATERAL_MAX_M = 2.0


def _short_stride(both: pd.DataFrame, side: str, at: int) -> bool:
    own = np.abs(both["length_m"].to_numpy(float)[both["side"].to_numpy() == side])
    rest = np.delete(own, at)
    if len(own) < 3 or not np.isfinite(rest).any():  # no other stride of this foot to compare with
        return False
    return bool(own[at] < CLOSING_STRIDE_SHARE * float(np.nanmedian(rest)))


def opening_step(both: pd.DataFrame) -> bool:
    """Decision L310: whether the walk starts from standing with the feet side by side: the foot that moves first
    (the walk's first contact) covers one step, its first stride under :data:`CLOSING_STRIDE_SHARE` of its median
    (a recording started mid-walk, or a track that missed that stride, does not)."""
    return len(both) >= 3 and _short_stride(both, both["side"].iloc[0], 0)


def closing_step(both: pd.DataFrame, steps: pd.DataFrame) -> bool:
    """Decision L310: whether the walk's last step is a closing step (:data:`CLOSING_STRIDE_SHARE`): it ends on the
    walk's last contact and its landing foot's last stride is short."""
    if len(steps) < 3 or steps["ic_s"].iloc[-1] != both["ic_s"].iloc[-1]:
        return False
    return _short_stride(both, both["side"].iloc[-1], -1)


def lateral_reach(both: pd.DataFrame) -> float:
    """Decision C208: the farthest (m) any contact's rest position (one frame, :func:`common_frame`) lies from the
    walk's axis, the line from the origin (the standing start) to its final position (the mean of its last two
    contacts' positions); 0 without positions or with a final position at the origin."""
    x, y = both["x_m"].to_numpy(float), both["y_m"].to_numpy(float)
    ok = np.isfinite(x) & np.isfinite(y)
    if ok.sum() < 2:
        return 0.0
    ex, ey = x[ok][-2:].mean(), y[ok][-2:].mean()
    norm = math.hypot(ex, ey)
    if not norm > 0.0:
        return 0.0
    return float(np.max(np.abs(x[ok] * ey - y[ok] * ex)) / norm)


def closure_scale(both: pd.DataFrame, steps: pd.DataFrame, *, max_reach: float = CLOSURE_LATERAL_MAX_M
                  ) -> float | None:
    """Decision L310: the relative scale error of the left track against the right one (left lengths read 1 + e
    times the right's) that the walk's closing step implies: at a standing end the two feet rest side by side, so
    the closing step's measured length is the along-walk error of the left foot's position relative to the right's,
    which a scale error e makes e x (the mean final position . the walking direction). None without a closing step
    (:data:`CLOSING_STRIDE_SHARE`), when the walk ends within :data:`CLOSURE_MIN_M` of its start, or (decision C208)
    when it leaves its axis by more than ``max_reach`` (m; :data:`CLOSURE_LATERAL_MAX_M`, :func:`lateral_reach`)."""
    length = steps["step_length_m"].to_numpy(float)
    if not opening_step(both) or not closing_step(both, steps) or not np.isfinite(length[-1]):
        return None
    if lateral_reach(both) > max_reach:  # decision C208: a bend's heading difference is no scale
        return None
    x, y, d = (both[c].to_numpy(float) for c in ("x_m", "y_m", "dir_rad"))
    u = np.array([np.cos(d[-1]) + np.cos(d[-2]), np.sin(d[-1]) + np.sin(d[-2])])
    u /= np.linalg.norm(u)
    reach = 0.5 * ((x[-1] + x[-2]) * u[0] + (y[-1] + y[-2]) * u[1])
    if not abs(reach) >= CLOSURE_MIN_M:
        return None
    offset = length[-1] if steps["side"].iloc[-1] == "left" else -length[-1]  # (left - right) . u
    return float(offset / reach)


def rescaled(both: pd.DataFrame, e: float) -> pd.DataFrame:
    """Decision L310: ``both``'s positions with the relative scale error ``e`` (:func:`closure_scale`) split between
    the feet (left x (1 - e / 2), right x (1 + e / 2), about the shared origin)."""
    f = np.where(both["side"].to_numpy() == "left", 1.0 - 0.5 * e, 1.0 + 0.5 * e)
    return both.assign(x_m=both["x_m"] * f, y_m=both["y_m"] * f)


def merged_contacts(left: pd.DataFrame, right: pd.DataFrame) -> pd.DataFrame:
    """Both feet's :func:`foot_events` in time order with ``side``, ``bout`` (1, 2 ...: decision L261, the
    merged contacts split at L104's pauses) and ``partial`` (decision L317: the bout's first and last contact, whose
    strides start from / end at rest with the feet side by side - half strides - and count in no stride length)."""
    both = pd.concat([left.assign(side="left"), right.assign(side="right")], ignore_index=True)
    both = both.sort_values("ic_s", kind="stable").reset_index(drop=True)
    bout = np.zeros(len(both), int)
    partial = np.zeros(len(both), bool)
    for k, (a, b) in enumerate(bout_rows(both.rename(columns={"ic_s": "start_s"})), start=1):
        bout[a:b] = k
        partial[[a, b - 1]] = True  # decision L317: gait initiation's and termination's half strides
    return both.assign(bout=bout, partial=partial)


#: decision L538: the kinds of a step (gait_steps.csv ``kind``) and of a gait cycle (gait_cycles.csv ``kind``): on
#: level ground and straight; on a stair going up or down (the stride's L179 rule, |dz| >= 0.10 m); in a turn (the
#: stride turns L79's 15 deg or more); a walking bout's first or last step (L317's half strides: gait initiation and
#: the closing step); decision L746: travelling backward (L203). The walk's headline measures are its level steps'
#: (:func:`headline_masks`)
STEP_KINDS = ("level", "stairs_up", "stairs_down", "turn", "start_stop", "backward", "ramp")  # L775: a ramp's
#: decision L538: which kind a step (or cycle) takes when its two contacts' strides differ: the lower rank; on a tie
#: the landing contact's. Decision L746: backward under a start / stop (a backward bout's ends are its start_stop, as
#: a level bout's) and over level (a step from a forward into a backward stride is no level step). Decision L775: ramp
#: under a start / stop, over backward and level
_KIND_RANK = {"stairs_up": 0, "stairs_down": 0, "turn": 1, "start_stop": 2, "ramp": 3, "backward": 4, "level": 5}


def contact_kinds(both: pd.DataFrame) -> np.ndarray:
    """Decision L538: each merged contact's kind (:data:`STEP_KINDS`) from the stride into it: ``stairs_up`` /
    ``stairs_down`` by its ``terrain``, else ``turn`` when it turns at least L79's ``STRAIGHT_MAX_RAD`` (a missing
    turn is straight, as L79's), else ``start_stop`` for a bout's first or last contact (``partial``, L317) or a
    closing step inside a bout (a level stride under L310's :data:`CLOSING_STRIDE_SHARE` of the foot's median level
    stride: the feet brought side by side, e.g. before a stair), else (decision L746) ``backward`` for a stride
    travelling backward (``backward``, :func:`stride_backward`; neither a closing-step candidate nor in the foot's
    median: a backward stride is short), else ``level``; decision L775: ``ramp`` (over backward) for a stride of a
    ramp (``ramp``, :func:`stride_ramp`; likewise outside the closing-step rule)."""
    kind = np.full(len(both), "level", dtype=object)
    if "partial" in both:
        kind[both["partial"].to_numpy(bool)] = "start_stop"
    back = both["backward"].to_numpy(bool) if "backward" in both else np.zeros(len(both), bool)  # decision L746
    kind[back & (kind == "level")] = "backward"
    ramp = both["ramp"].to_numpy(bool) if "ramp" in both else np.zeros(len(both), bool)  # decision L775
    kind[ramp & np.isin(kind, ("level", "backward"))] = "ramp"
    if "length_m" in both:  # L310's closing-step rule on the foot's own strides, inside a bout
        length, side = np.abs(both["length_m"].to_numpy(float)), both["side"].to_numpy()
        plain = kind == "level"
        if "terrain" in both:
            plain &= both["terrain"].to_numpy() == "flat"
        for s in SIDES:
            own = plain & (side == s) & np.isfinite(length)
            if own.sum() >= 3:
                kind[own & (length < CLOSING_STRIDE_SHARE * np.median(length[own]))] = "start_stop"
    if "turn_deg" in both:
        turn = np.nan_to_num(both["turn_deg"].to_numpy(float), nan=0.0)
        kind[turn >= math.degrees(STRAIGHT_MAX_RAD)] = "turn"  # decision L79's straight stride
    if "terrain" in both:
        terrain = both["terrain"].to_numpy()
        kind[terrain == "up"] = "stairs_up"
        kind[terrain == "down"] = "stairs_down"
    return kind


def joined_kind(landing: np.ndarray, other: np.ndarray) -> np.ndarray:
    """Decision L538: the kind of a step or cycle from its landing contact's and its other contact's kinds
    (:data:`_KIND_RANK`: a stair over a turn over a start / stop over level; on a tie the landing contact's)."""
    if not len(landing):
        return np.asarray(landing, dtype=object)
    rank = np.vectorize(_KIND_RANK.__getitem__, otypes=[int])
    return np.where(rank(landing) <= rank(other), landing, other).astype(object)


def step_contacts(both: pd.DataFrame) -> np.ndarray:
    """Decision L259: the merged contacts (rows of ``both``) that end a step: the other foot's contact before, in
    one bout."""
    side, bout = both["side"].to_numpy(), both["bout"].to_numpy(int)
    return np.flatnonzero((side[1:] != side[:-1]) & (bout[1:] == bout[:-1])) + 1


def step_table(both: pd.DataFrame) -> pd.DataFrame:
    """Decision L259: one row per step of :func:`merged_contacts` - ``side`` (the foot it lands on), ``bout``,
    ``start_s`` (the other foot's IC), ``ic_s``, ``step_time_s``, (decision L284) ``swing_time_s``: the landing
    foot's toe-off before this IC (its row's ``tc_s``) to the IC, one unit's clock, so no clock offset moves it (NaN
    without that toe-off), (decision L310) ``step_length_m`` (:func:`step_lengths`) and (decision L538) ``kind``
    (:func:`joined_kind` of the two contacts)."""
    t, side, bout = both["ic_s"].to_numpy(float), both["side"].to_numpy(), both["bout"].to_numpy(int)
    tc = both["tc_s"].to_numpy(float)
    k = step_contacts(both)
    swing = np.where(tc[k] < t[k], t[k] - tc[k], np.nan)  # L284: one unit's toe-off to its IC (any clock offset)
    length = step_lengths(both, k) if "x_m" in both else np.full(len(k), np.nan)  # decision L310
    kinds = contact_kinds(both)  # decision L538
    return pd.DataFrame({"side": side[k], "bout": bout[k], "start_s": t[k - 1], "ic_s": t[k],
                         "step_time_s": t[k] - t[k - 1], "swing_time_s": swing, "step_length_m": length,
                         "kind": joined_kind(kinds[k], kinds[k - 1])})


def cycle_table(both: pd.DataFrame) -> pd.DataFrame:
    """Decision L262: one row per gait cycle of either foot (one IC of it to its next, in one bout, with exactly one
    IC of the other foot between them - a stride either track or label table lacks makes no cycle): ``side``,
    ``bout``, ``start_s``, ``end_s``, ``stride_time_s``, ``stance_time_s`` (decision L327: the foot's IC to its
    toe-off inside the cycle, NaN without one), ``double_support_pct`` and ``single_support_pct`` (module
    docstring; NaN where a toe-off is missing or the cycle has a flight; decision L736: a hand-over within
    ``TOUCH_S`` is 0 % double support), (decision L729) ``flight_time_s``
    (:func:`pdrlearn.kernels.gait_values.cycle_flights`: the time with neither foot on the ground after a toe-off
    that came before the other foot's contact, 0 in walking order, NaN without both toe-offs in their strides) and
    ``flight_after`` (the foot whose toe-off started it, "both", or None) and (decision L538) ``kind``
    (:func:`joined_kind` of the foot's next contact and the other foot's contact inside the cycle)."""
    rows = []
    kinds = contact_kinds(both)  # decision L538
    t, tc, side, bout = (both["ic_s"].to_numpy(float), both["tc_s"].to_numpy(float), both["side"].to_numpy(),
                         both["bout"].to_numpy(int))
    for s in SIDES:
        own = np.flatnonzero(side == s)
        for a, b in zip(own[:-1], own[1:], strict=True):
            if bout[a] != bout[b] or b - a != 2:  # L262: exactly one IC of the other foot inside: it alternated
                continue
            T = t[b] - t[a]
            # decisions L327, L729, L736: the shared per-cycle kernel (E327: the lean summary's too)
            stance, ds, ss, fl = cycle_support(t[a], tc[a + 1], t[a + 1], tc[b], t[b])
            after = flight_after(s, side[a + 1], *fl) if math.isfinite(fl[0]) else None
            kind = joined_kind(kinds[[b]], kinds[[a + 1]])[0]  # decision L538
            rows.append((s, int(bout[a]), t[a], t[b], T, stance, ds, ss, fl[0] + fl[1], after, kind))
    cols = ["side", "bout", "start_s", "end_s", "stride_time_s", "stance_time_s", "double_support_pct",
            "single_support_pct", "flight_time_s", "flight_after", "kind"]
    return pd.DataFrame(rows, columns=cols).sort_values("start_s", kind="stable").reset_index(drop=True)


#: decision L461: a symmetry index or ratio of the walk needs at least this many steps on each side. No source gives a
#: minimum for the SI; the project's minimum for a stride-time CV (L113, :data:`CV_MIN_STRIDES`) is reused: an index
#: compares two means, each as noisy as a CV's mean from the same number of steps
SI_MIN_STEPS = CV_MIN_STRIDES


def withhold_indices(walk: dict, *, min_steps: int = SI_MIN_STEPS) -> str | None:
    """Decision L461: with fewer than ``min_steps`` steps on a side, every ``*_si_pct`` and ``*_ratio`` of ``walk``
    is set to None (in place) and the reason returned; None when there are enough."""
    n = min(walk["n_steps_left"], walk["n_steps_right"])
    if n >= min_steps:
        return None
    for k in [k for k in walk if k.endswith(("_si_pct", "_ratio"))]:
        walk[k] = None
    side = "left" if walk["n_steps_left"] <= walk["n_steps_right"] else "right"
    return (f"symmetry indices and ratios withheld: {n} steps on the {side} side, {min_steps} needed on each side "
            "(decision L461; the stride-time CV's minimum, L113) - walk longer, or pool visits")


def withhold_all(res: dict) -> None:
    """Decision L461 on a :func:`bilateral_gait` result ``res`` (in place): its walk, each bout (L461 amended:
    gait-all's only SI table is its bouts') and each kind (L538) get ``si_withheld``, their indices withheld by
    :func:`withhold_indices`. ``pair_sessions`` runs it on the tracked result and on the labels' reference alike
    (decision L551: a 2-step index is noise whichever contacts it comes from)."""
    if not res:
        return
    res["walk"]["si_withheld"] = withhold_indices(res["walk"])
    for m in [*res.get("bouts", []), *res.get("by_kind", {}).values()]:
        m["si_withheld"] = withhold_indices(m)


def gait_measures(both: pd.DataFrame, steps: pd.DataFrame, cycles: pd.DataFrame) -> dict:
    """Decisions L259, L262: the walk's (or one bout's) bilateral measures from its tables (module docstring)."""
    def sides(name: str, table: pd.DataFrame, col: str | None = None, mask=True) -> dict:  # E320: side_pair's means
        return side_pair(name, *(mean_finite(table.loc[mask & (table["side"] == s), col or name]) for s in SIDES))

    out = {"n_steps_left": int((steps["side"] == "left").sum()), "n_steps_right": int((steps["side"] == "right").sum())}
    out.update(sides("step_time_s", steps))
    out.update(sides("stride_time_s", cycles))
    full = ~both["partial"] if "partial" in both else True  # decision L317: no initiation / termination half stride
    # decision L746: the stride's length whichever way it travels (L654's sign is the travel; the kind says which)
    out.update(side_pair("stride_length_m", *(mean_finite(both.loc[full & (both["side"] == s), "length_m"].abs())
                                              for s in SIDES)))
    out.update(sides("swing_time_s", steps))
    out.update(sides("stance_time_s", cycles))
    if "step_length_m" in steps:  # decision L310
        out.update(sides("step_length_m", steps))
        out["n_step_lengths"] = int(steps["step_length_m"].notna().sum())
    out["clock_offset_s"] = clock_offset_s(steps)
    ok = cycles["double_support_pct"].notna()
    out["n_support_cycles"] = int(ok.sum())
    fl = cycles["flight_time_s"].to_numpy(float) > 0 if "flight_time_s" in cycles else np.zeros(len(cycles), bool)
    out["n_flight_cycles"] = int(fl.sum())  # decision L729: cycles with a toe-off before the other foot's contact
    out["flight_time_s"] = mean_finite(cycles.loc[fl, "flight_time_s"]) if fl.any() else None  # per cycle (C268)
    # decision C268: per step - a gait cycle holds two steps, and its flight_time_s sums the flights of both
    out["step_flight_time_s"] = None if out["flight_time_s"] is None else out["flight_time_s"] / 2.0
    out["double_support_pct"] = mean_finite(cycles.loc[ok, "double_support_pct"])
    out.update(sides("single_support_pct", cycles, mask=ok))
    return out


def clock_offset_s(steps: pd.DataFrame) -> float | None:
    """Decision L284: the left clock's offset (s, > 0 = the left unit's times late against the right's) that the
    steps imply when the walker's two double-support periods are equal: half the difference of the left and right
    steps' mean (step time - swing time), i.e. of the double support before each foot's swing. A walker's own
    double-support imbalance adds half of itself. None without swing times of both feet."""
    ok = steps["swing_time_s"].notna()
    d = [mean_finite((steps["step_time_s"] - steps["swing_time_s"])[ok & (steps["side"] == s)]) for s in SIDES]
    return None if None in d else 0.5 * (d[0] - d[1])


def clock_offset_pattern(walk: dict) -> bool:
    """Decision L284: the step times are asymmetric (symmetry index at least :data:`OFFSET_CHECK_SI_MIN`) but the
    swing times are not (their index under :data:`OFFSET_SWING_SHARE_MAX` of it) - what a clock offset between the
    two units gives (or one foot's late contacts, L318), not a walker's asymmetry; False without swing times."""
    si, swing_si, off = walk.get("step_time_s_si_pct"), walk.get("swing_time_s_si_pct"), walk.get("clock_offset_s")
    return not (si is None or swing_si is None or off is None or si < OFFSET_CHECK_SI_MIN
                or swing_si >= OFFSET_SWING_SHARE_MAX * si)


def clock_offset_warning(walk: dict) -> str | None:
    """Decision L284: one warning line when the step times are asymmetric (symmetry index at least
    :data:`OFFSET_CHECK_SI_MIN`) but the swing times are not (their index under :data:`OFFSET_SWING_SHARE_MAX` of
    it): the pattern a clock offset between the two units gives, not a walker's asymmetry; the line names the
    offset (:func:`clock_offset_s`). None otherwise or without swing times."""
    if not clock_offset_pattern(walk):
        return None
    si, swing_si, off = walk["step_time_s_si_pct"], walk["swing_time_s_si_pct"], walk["clock_offset_s"]
    late, early = ("left", "right") if off > 0 else ("right", "left")
    stride = mean_finite([v for v in (walk.get("stride_time_s_left"), walk.get("stride_time_s_right"))
                          if v is not None])
    period = ("" if stride is None else f" (an offset is only known modulo the stride time, {stride:.3f} s: the "
              "clocks may differ by this plus or minus whole strides; decision L537)")
    return (f"bilateral gait: step-time symmetry index {si:.1f} % but swing-time {swing_si:.1f} % (single support "
            f"{_fmt_pct(walk.get('single_support_pct_left'))} / {_fmt_pct(walk.get('single_support_pct_right'))} "
            f"%): a walker's step-time asymmetry comes with swing asymmetry, a clock offset does not (decision "
            f"L284). The {late} unit's times look ~{abs(off) * 1000:.0f} ms late against the {early} one's{period}: "
            f"are the two clocks synchronised, or do the {late} foot's contacts read late (a soft impact, decision "
            "L318)? The step times, their asymmetry and the double support are not trustworthy if either")


def stance_warning(walk: dict) -> str | None:
    """Decision L285: one warning line when a foot's tracked stance (100 - the other foot's single support, %
    of the cycle) is under :data:`STANCE_MIN_PCT`: implausible for walking, the toe-off likely early."""
    st = {s: None if walk.get(f"single_support_pct_{o}") is None else 100.0 - walk[f"single_support_pct_{o}"]
          for s, o in zip(SIDES, SIDES[::-1], strict=True)}
    low = [s for s in SIDES if st[s] is not None and st[s] < STANCE_MIN_PCT]
    if not low:
        return None
    feet = " and the ".join(low)  # decision L763: the foot (or feet) it fires on, by name
    return (f"bilateral gait: tracked stance left/right {_fmt_pct(st['left'])} / {_fmt_pct(st['right'])} % of the "
            f"gait cycle, the {feet} foot's under {STANCE_MIN_PCT:.0f} % (walking: ~60 %, more when slower; decision "
            f"L285): the {feet} foot's toe-off reads early or its contact late (a soft impact of that foot, decision "
            "L318), so the double support ("
            f"{_fmt_pct(walk.get('double_support_pct'))} %) is too low and the step times may be off too; do not "
            "report them as measured")


#: decision L311: the line saying why a tracked pair has no step length (measured, experiments/step_length_l310.py)
UNANCHORED_NOTE = ("bilateral gait: no step length: the walk is not anchored at both ends (a standing start with "
                   "the feet side by side - the first foot's first stride a half stride - and a closing step that "
                   "brings them side by side again at least 5 m further on; decision L311). Without both, the two "
                   "foot tracks' relative drift is unknown: simulated return walks read the step-length symmetry "
                   "index up to 23 points off, the real 4 x 10 m walk 110 %. Walk one straight length from standing "
                   "to standing for a step-length asymmetry")


def unanchored_warning(walk: dict, steps: pd.DataFrame, reach: float = 0.0) -> str | None:
    """Decision L311: :data:`UNANCHORED_NOTE` for a pair of tracks (rows with positions) whose walk was not anchored
    (:func:`closure_scale` None), so L310 gives no step length; None otherwise. Decision C208: with ``reach``
    (:func:`lateral_reach`, m; given when the reach alone refused the walk's anchors) over
    :data:`CLOSURE_LATERAL_MAX_M` the line says the walk left its axis by that much."""
    if walk.get("step_length_scale_pct") is not None or walk.get("step_length_passes") or not len(steps):
        return None
    if reach > CLOSURE_LATERAL_MAX_M:
        return (f"{UNANCHORED_NOTE}. This walk left its axis (the line from its start to its end) by {reach:.1f} m "
                f"(a bend or a corner; the closing step anchors only a walk within {CLOSURE_LATERAL_MAX_M:g} m of "
                "it: the two foot tracks' heading difference after a bend moves their positions along the walk, a "
                "400 m track's bend read a 9 % step-length asymmetry as 173 %; "
                f"{decision_ref('C208', topic='cohort')})")
    return UNANCHORED_NOTE


def lost_steps_warning(at: np.ndarray, lost: np.ndarray) -> str | None:
    """Decision L783: one line when L760's passes left steps with a measured length without one (``lost``, rows of
    the step table, :func:`pdrlearn.track.step_anchors.lost_rows`; ``at`` the steps' landing times, s): how many,
    when, and why; None when none were."""
    lost = np.asarray(lost, int)
    if not len(lost):
        return None
    runs = np.split(lost, np.flatnonzero(np.diff(lost) > 1) + 1)
    spans = ", ".join(f"{at[r[0]]:.1f}-{at[r[-1]]:.1f} s" for r in runs)
    return (f"bilateral gait: {len(lost)} of the walk's {len(at)} steps have no step length (at {spans}): the two foot "
            "tracks' relative drift is known only on a pass with the feet side by side at both of its ends - a "
            "standing start, a stop or a turn on the spot that ends with the feet together, and a closing step "
            f"before the next turn or stop or at the end ({decision_ref('L783', topic='localization')}); the "
            "step-length measures are of the other steps only")


def drift_warning(walk: dict, *, max_pct: float = 2.0) -> str | None:
    """Decision L761: one line when the walk's step-length symmetry index is given and the tracks' drift bound
    (``step_length_si_drift_pct``, :func:`pdrlearn.track.step_anchors.drift_bound_pct`) exceeds ``max_pct`` points
    (the 2 points a prosthetics lab asked for, trial s50t2); None otherwise."""
    b, si = walk.get("step_length_si_drift_pct"), walk.get("step_length_m_si_pct")
    if b is None or si is None or not b > max_pct:
        return None
    mean = 0.5 * (walk["step_length_m_left"] + walk["step_length_m_right"])
    return (f"bilateral gait: the step-length symmetry index ({si:.1f} %) may be off by about {b:.0f} points: the two "
            f"foot tracks drifted {b * mean:.0f}"  # b % of the mean step (m) in cm
            " cm apart along the walk between the standing start and the first closing step, and drift of that size "
            f"inside a pass is not seen ({decision_ref('L761', topic='localization')}); the step time, stride length "
            "and stance symmetry are not affected - report the step-length index as a range, not a measured value")


def _fmt_pct(v) -> str:
    return "-" if v is None else f"{v:.1f}"


#: decision L538: ``walk["headline_steps"]``: the walk's measures are of its level straight steps (``"level"``; with
#: fewer than L461's :data:`SI_MIN_STEPS` of them on a side their indices are withheld, never taken from the other
#: kinds), or, with under :data:`HEADLINE_MIN_LEVEL_STEPS` level straight steps on a side, of all its steps (``"all"``)
HEADLINE_BASES = ("level", "all")
#: decision L608 (no document gives it): the level headline needs this many level straight steps on each side; a
#: mean of one or two steps is that step (one re-labelled stride is the whole headline, L603's stairs-down pair)
HEADLINE_MIN_LEVEL_STEPS = 3


def headline_masks(both: pd.DataFrame, steps: pd.DataFrame,
                   cycles: pd.DataFrame) -> tuple[str, np.ndarray, np.ndarray, np.ndarray]:
    """Decision L538: which rows of the merged contacts, the step table and the cycle table the walk's headline
    measures take: the ``level`` kind's (:data:`STEP_KINDS`: no stair, turn, gait initiation or closing step) when
    each side has at least :data:`HEADLINE_MIN_LEVEL_STEPS` level steps (decision L608), else every row (a walk of
    stairs or turns with a stray level step or none); ``(basis, contacts, steps, cycles)``, basis in
    :data:`HEADLINE_BASES`."""
    level = steps["kind"].to_numpy() == "level"
    n = [int((level & (steps["side"].to_numpy() == s)).sum()) for s in SIDES]
    if min(n) < HEADLINE_MIN_LEVEL_STEPS:  # decision L608
        return "all", np.ones(len(both), bool), np.ones(len(steps), bool), np.ones(len(cycles), bool)
    return ("level", contact_kinds(both) == "level", level,
            cycles["kind"].to_numpy() == "level" if len(cycles) else np.zeros(0, bool))


def walk_pace(both: pd.DataFrame, steps: pd.DataFrame) -> dict:
    """Decision L539: the walk's (or one bout's, one kind's) ``distance_m`` - the mean of the two feet's summed
    stride lengths (``length_m``; an ``impossible`` stride counts 0 m) -, ``walking_time_s`` - the mean of the two
    feet's summed stride times rest to rest (``end_s - start_s``, so a pause between strides is not walking) -,
    ``gait_speed_mps`` = distance / time (track's rest-to-rest definition, L250) and ``cadence_spm`` = 60 x steps /
    their summed step times (both feet's steps: :func:`step_table`); None where the tables cannot give them (a
    table without stride lengths or rest times)."""
    dist, time = [], []
    for s in SIDES:
        own = both[both["side"] == s]
        length = own["length_m"].to_numpy(float) if "length_m" in own else np.zeros(0)
        span = own["stride_s"].to_numpy(float) if "stride_s" in own else np.zeros(0)
        dist.append(float(np.nansum(np.abs(length))) if np.isfinite(length).any() else None)
        time.append(float(np.nansum(span)) if np.isfinite(span).any() else None)
    d = None if None in dist else 0.5 * (dist[0] + dist[1])
    t = None if None in time else 0.5 * (time[0] + time[1])
    st = steps["step_time_s"].to_numpy(float) if len(steps) else np.zeros(0)
    st = st[np.isfinite(st)]
    return {"distance_m": d, "walking_time_s": t,
            "gait_speed_mps": d / t if d is not None and t else None,
            "cadence_spm": 60.0 * len(st) / float(st.sum()) if len(st) and st.sum() > 0 else None}


def known_step_lengths(steps: pd.DataFrame, ics: pd.DataFrame | None, *, tol_s: float = 0.01) -> pd.DataFrame:
    """Decision L540: ``steps`` with ``step_length_m`` taken from a label table of both feet's contacts that gives
    each step's length (the simulator's ics.csv ``ic_s``, ``foot``, ``step_length_m``, S42), matched on the landing
    foot and its contact within ``tol_s``; ``steps`` unchanged without such a table."""
    if ics is None or not {"ic_s", "foot", "step_length_m"} <= set(ics) or not len(steps):
        return steps
    out = steps.copy()
    length = np.full(len(out), np.nan)
    for s in SIDES:
        own = ics[ics["foot"].astype(str).str.lower() == s]
        t, v = own["ic_s"].to_numpy(float), pd.to_numeric(own["step_length_m"], errors="coerce").to_numpy(float)
        rows = np.flatnonzero(out["side"].to_numpy() == s)
        if not len(t) or not len(rows):
            continue
        ic = out["ic_s"].to_numpy(float)[rows]
        j = nearest_index(ic, t)  # decision L555: no steps x contacts matrix (L546's search; a tie to the first)
        with np.errstate(invalid="ignore"):
            ok = np.abs(ic - t[j]) <= tol_s
        length[rows[ok]] = v[j[ok]]
    out["step_length_m"] = length
    return out


def measures_of(both: pd.DataFrame, steps: pd.DataFrame, cycles: pd.DataFrame, masks=None) -> dict:
    """:func:`gait_measures` of the rows ``masks`` (contacts, steps, cycles; default all) plus :func:`walk_pace` of
    every row (decision L539: the pace is the whole walk's, never the headline's subset)."""
    if masks is None:
        m = gait_measures(both, steps, cycles)
    else:
        m = gait_measures(both[masks[0]], steps[masks[1]], cycles[masks[2]])
    return {**m, **walk_pace(both, steps)}


def kind_measures(both: pd.DataFrame, steps: pd.DataFrame, cycles: pd.DataFrame) -> dict:
    """Decision L538: ``{kind: measures}`` (:func:`measures_of`) of each :data:`STEP_KINDS` kind the walk has a step
    of: its steps, its cycles and the contacts of its kind."""
    ck = contact_kinds(both)
    out = {}
    for kind in STEP_KINDS:
        if not (steps["kind"] == kind).any():
            continue
        c = both[ck == kind]
        s = steps[steps["kind"] == kind]
        y = cycles[cycles["kind"] == kind] if len(cycles) else cycles
        out[kind] = {**gait_measures(c, s, y), **walk_pace(c, s)}
    return out


def bilateral_gait(left_steps: pd.DataFrame, right_steps: pd.DataFrame, *,
                   step_lengths: pd.DataFrame | None = None, contact_source=None,
                   rate_hz: float | None = None, reanchor: bool = True, si_drift: bool = False,
                   ramps: bool = False, per_segment: bool = False) -> dict:
    """Decisions L259-L262 (Python API): bilateral gait of one walk from the left and the right foot's step
    tables (a foot track's ``steps.csv`` or a label table, :func:`foot_events`) on one clock.

    Returns ``{"walk": measures, "bouts": [measures + bout, start_s, end_s], "by_kind": {kind: measures}, "steps":
    step table, "cycles": cycle table, "toe_off": bool, "reason": str | None, "warnings": [lines], "stairs":
    [flights, decision L561's :func:`pdrlearn.track.stair_lead.stair_flights`]}``; measures are
    :func:`gait_measures`' (None where the tables cannot give them) of the walk's level straight steps when it has
    enough (decision L538, :func:`headline_masks`; ``walk["headline_steps"]`` says which) and :func:`walk_pace`'s
    of all its steps (L539); ``warnings`` holds B245's, L284's and L285's lines (each logged). ``step_lengths``
    (decision L540): a label table of both feet's contacts with each step's length (ics.csv), whose lengths the steps
    take (:func:`known_step_lengths`). ``contact_source`` (decision L703: "force" / "imu", or a per-foot dict; None:
    unknown) picks the set-up whose known support bias ``reason`` states, in this walk's gait cycle, at the foot
    units' ``rate_hz`` (decision L737; None: unknown). ``reanchor`` (decision L760): a walk with closing steps
    inside it (before its turns) has each pass re-anchored at its own closing step
    (:func:`pdrlearn.track.step_anchors.pass_corrected`) instead of L310's one scale; False: L310's scale only.
    ``si_drift`` (decision L761, not adopted: the bound flagged 35 of 40 simulated pairs and missed 3 of 5 unflagged
    ones over 2 points): the walk's ``step_length_si_drift_pct`` and :func:`drift_warning`'s line, for measuring
    only. ``ramps`` (decision L775, not adopted; default off): ramp strides (:func:`stride_ramp`) their own
    kind ``ramp``, out of the level headline. ``per_segment`` (decision L791, not adopted: fresh 6MWT-like pairs'
    median |SI err| 4.15 -> 4.44 points; default off, for measuring only): with ``reanchor``, the re-anchored
    passes' step lengths and anchors along each straight segment's own axis, a pass never across a turn
    (:func:`pdrlearn.track.step_anchors.segment_axes`). Refuses
    (:class:`DataError`, one line) two tables whose contacts do not overlap in time (L260: not one walk on one
    clock)."""
    left, right = foot_events(left_steps, ramps=ramps), foot_events(right_steps, ramps=ramps)  # decision L775
    for s, ev in zip(SIDES, (left, right), strict=True):
        if len(ev) < 2:
            raise DataError(f"bilateral gait: the {s} foot has {len(ev)} initial contact(s); give a walk of at least "
                            "two strides of each foot")
    lo, hi = max(left["ic_s"].iloc[0], right["ic_s"].iloc[0]), min(left["ic_s"].iloc[-1], right["ic_s"].iloc[-1])
    if not lo < hi:  # decision L260
        raise DataError(f"bilateral gait: the clocks do not overlap (left contacts {left['ic_s'].iloc[0]:.1f}-"
                        f"{left['ic_s'].iloc[-1]:.1f} s, right {right['ic_s'].iloc[0]:.1f}-"
                        f"{right['ic_s'].iloc[-1]:.1f} s); give the two feet of one walk, recorded on one clock")
    both = merged_contacts(common_frame(left, right), right)  # decision L310: one frame for the step lengths
    warnings = [alternation_warning(both)]
    steps, cycles = step_table(both), cycle_table(both)
    k = step_contacts(both)
    raw = steps["step_length_m"].to_numpy(float)
    ck = contact_kinds(both)
    anchors = anchor_rows(ck, both["bout"].to_numpy(), k, raw)  # decision L760
    passes, first = None, None
    cols = [both[c].to_numpy(float) for c in ("x_m", "y_m", "dir_rad")]
    whole = False
    if reanchor and per_segment:  # decision L791 (not adopted, opt-in): segment axes, two anchors or more
        axes = segment_axes(ck, both["bout"].to_numpy(), cols[2])
        seg = axis_lengths(*cols, k, axes, turn_max_deg=STEP_TURN_MAX_DEG, axis_max_deg=STEP_AXIS_MAX_DEG)
        seg_anchors = anchor_rows(ck, both["bout"].to_numpy(), k, seg)
        if len(seg_anchors) >= 2:
            raw, anchors, cols, whole = seg, seg_anchors, [cols[0], cols[1], axes], True
    if len(anchors) >= 2 and reanchor:  # decision L760: closing steps inside the walk: each pass re-anchored
        scale, bend, passes = None, 0.0, len(anchors)
        side = both["side"].to_numpy()
        short = short_strides(side, both["length_m"].to_numpy(float), share=CLOSING_STRIDE_SHARE)
        starts = pass_starts(ck, side, both["ic_s"].to_numpy(float), *cols, short, k, raw, anchors,
                             bout=both["bout"].to_numpy(), whole_pass=whole)  # decisions L782, L791
        steps["step_length_m"] = pass_corrected(steps["side"].to_numpy(), raw, steps["ic_s"].to_numpy(float),
                                                anchors, starts, opened=opening_step(both),
                                                start=float(both["ic_s"].iloc[0]))
    else:
        scale = closure_scale(both, steps)  # decision L310: the closing step anchors the two tracks' relative scale
        # decision C208: the line names the walk's reach only when the reach alone refused the anchors
        bend = (lateral_reach(both) if scale is None and closure_scale(both, steps, max_reach=math.inf) is not None
                else 0.0)
    if scale is not None:
        first = float(raw[-1] if steps["side"].iloc[-1] == "left" else -raw[-1])  # decision L761: (left - right) . u
        both = rescaled(both, scale)
        steps = step_table(both)
    if scale is None and passes is None:  # decision L311: not anchored at both ends - no step length
        steps["step_length_m"] = np.nan
    elif scale is not None:  # decision L310: the closing step brought the feet side by side: the anchor, no length
        steps.loc[steps.index[-1], "step_length_m"] = np.nan
    steps = known_step_lengths(steps, step_lengths)  # decision L540: the labels' own step lengths
    lost = (lost_rows(raw, steps["step_length_m"].to_numpy(float), anchors) if passes is not None
            else np.zeros(0, int))  # decision L783: steps L760 left without a length
    toe_off = bool(np.isfinite(both["tc_s"]).any())
    basis, *masks = headline_masks(both, steps, cycles)  # decision L538
    bouts = []
    for k in sorted(set(both["bout"])):
        inb = [both["bout"].to_numpy() == k, steps["bout"].to_numpy() == k, cycles["bout"].to_numpy() == k]
        b = both[inb[0]]
        m = measures_of(b, steps[inb[1]], cycles[inb[2]], [mk[ib] for mk, ib in zip(masks, inb, strict=True)])
        bouts.append({"bout": int(k), "start_s": float(b["ic_s"].iloc[0]), "end_s": float(b["ic_s"].iloc[-1]), **m})
    if not toe_off:
        reason = ("no toe-off in the foot tables: double and single support need each foot's terminal contact "
                  "(pdrlearn track --toe-off, decision L73); the step times are given")
    walk = measures_of(both, steps, cycles, masks)
    if toe_off:  # decision L262: a foot track's (event_s) support times carry L73's biases; a label table's do not
        reason = support_note(setup_of(contact_source), _cycle_s(walk), rate_hz) if "event_s" in left_steps else None
    walk["headline_steps"] = basis  # decision L538
    walk.update(foot_angles(both[masks[0]]))  # cohort C244: the headline strides' sole angles per side
    walk["toe_clearance_lower"] = lower_clearance_side(walk)  # decision L795
    walk.update({f"n_steps_all_{s}": int((steps["side"] == s).sum()) for s in SIDES})
    walk["step_length_scale_pct"] = None if scale is None else 100.0 * scale  # decision L310
    walk["step_length_passes"] = passes  # decision L760
    mean_step = [walk.get(f"step_length_m_{s}") for s in SIDES]
    if si_drift and passes is not None:  # decision L761 (not adopted, opt-in): the passes' spread
        level = masks[1] & np.isfinite(steps["step_length_m"].to_numpy(float))
        walk["step_length_si_drift_pct"] = pass_bound_pct(steps["side"].to_numpy(),
                                                          np.where(level, steps["step_length_m"], np.nan), anchors)
    elif si_drift:  # decision L761 (not adopted, opt-in): one pass: its closing step's offset
        walk["step_length_si_drift_pct"] = (drift_bound_pct(first, 0.5 * (mean_step[0] + mean_step[1]))
                                            if None not in mean_step else None)
    log = logging.getLogger(__name__)
    for line in (clock_offset_warning(walk), flight_warning(walk, cycles[masks[2]]),  # L729: the headline's
                 stance_warning(walk) if "event_s" in left_steps else None,
                 unanchored_warning(walk, steps, bend) if np.isfinite(both["x_m"]).any() else None,
                 lost_steps_warning(steps["ic_s"].to_numpy(float), lost),  # decision L783
                 drift_warning(walk)):  # decision L761
        if line is not None:  # L285 judges a track's toe-off, not a label table's
            log.warning(line)
            warnings.append(line)
    from pdrlearn.track.stair_lead import stair_flights

    return {"walk": walk, "bouts": bouts, "by_kind": kind_measures(both, steps, cycles), "steps": steps,
            "cycles": cycles, "toe_off": toe_off, "reason": reason, "warnings": [w for w in warnings if w is not None],
            "stairs": stair_flights(both, contact_kinds(both))}  # decision L561


#: cohort C244: a foot track's sole angles (steps.csv, decision L421) that :func:`foot_events` carries and
#: :func:`foot_angles` gives per side: at the initial contact and at the toe-off (--toe-off); decision L795: and the
#: stride's minimum toe clearance
FOOT_ANGLES = ("ic_angle_deg", "tc_angle_deg", "min_toe_clearance_m")


def foot_angles(contacts: pd.DataFrame) -> dict:
    """Cohort C244: ``{angle}_left`` / ``{angle}_right`` of :data:`FOOT_ANGLES` - the median over each foot's
    ``contacts`` (:func:`merged_contacts` rows; the walk's headline contacts) of its track's sole angle at the
    contact and at the toe-off before it (the same stride's, L421: + toes up); None where a side has none (a label
    table, a track without --toe-off)."""
    out = {}
    for name in FOOT_ANGLES:
        for s in SIDES:
            v = contacts.loc[contacts["side"] == s, name].to_numpy(float) if name in contacts else np.zeros(0)
            v = v[np.isfinite(v)]
            out[f"{name}_{s}"] = float(np.median(v)) if len(v) else None
    return out


def lower_clearance_side(walk: dict, *, min_diff_m: float = 0.005) -> str | None:
    """Decision L795: ``"left"`` / ``"right"``, the side whose median minimum toe clearance (``walk``'s
    ``min_toe_clearance_m_left`` / ``_right``, :func:`foot_angles`) is clearly the lower - at least ``min_diff_m``
    below the other's (a foot drop; a symmetric walker's sides differ by the stride noise); None otherwise or
    without both."""
    v = {s: walk.get(f"min_toe_clearance_m_{s}") for s in SIDES}
    if any(x is None or not np.isfinite(x) for x in v.values()):
        return None
    low, high = sorted(SIDES, key=lambda s: v[s])
    return low if v[high] - v[low] >= min_diff_m else None


def _cycle_s(walk: dict) -> float | None:
    """Decision L703: the walk's gait cycle (s), the mean of the two feet's mean stride times (None without)."""
    t = [walk.get(f"stride_time_s_{s}") for s in SIDES]
    t = [v for v in t if v is not None and np.isfinite(v)]
    return float(np.mean(t)) if t else None


def alternating_share(both: pd.DataFrame) -> tuple[int, int]:
    """Decision B245: of the merged contacts (:func:`merged_contacts`), how many follow a contact of the other
    foot, and how many follow one at all."""
    side = both["side"].to_numpy()
    return int((side[1:] != side[:-1]).sum()), max(len(side) - 1, 0)


def alternation_warning(both: pd.DataFrame) -> str | None:
    """Decision B245: one warning line (logged, and returned) when under :data:`ALTERNATION_MIN` of the merged
    contacts alternate feet: two walks whose clocks overlap, not one walk on one clock."""
    alt, n = alternating_share(both)
    if n == 0 or alt >= ALTERNATION_MIN * n:
        return None
    line = (f"bilateral gait: only {alt} of {n} contacts follow the other foot's "
            f"(one walk alternates feet; under {ALTERNATION_MIN:.0%}, decision B245): are these the two feet of one "
            "walk on one clock? The step times and asymmetry below are not trustworthy if not")
    logging.getLogger(__name__).warning(line)
    return line


def session_foot(meta: dict) -> str | None:
    """Decision L260: ``"left"`` / ``"right"`` from a session's ``meta.json`` (:data:`FOOT_META_KEYS`), else None."""
    for k in FOOT_META_KEYS:
        v = str(meta.get(k, "")).strip().lower()
        if v in SIDES:
            return v
    return None


def check_pair(left_dir: Path, right_dir: Path, left_meta: dict, right_meta: dict,
               left_id: str | None = None, right_id: str | None = None) -> None:
    """Decision L260: refuse (one line) the same folder or recording twice, or two sessions whose ``meta.json``
    puts them on the same foot or on the other foot than given."""
    if Path(left_dir).resolve() == Path(right_dir).resolve() or (left_id is not None and left_id == right_id):
        raise DataError(f"gait: {left_dir} and {right_dir} hold the same recording; give the left foot's session "
                        "and then the right foot's")
    feet = session_foot(left_meta), session_foot(right_meta)
    if feet[0] is not None and feet[0] == feet[1]:
        raise DataError(f"gait: {left_dir} and {right_dir} are both the {feet[0]} foot (meta.json); give one "
                        "session of each foot")
    for d, want, got in ((left_dir, "left", feet[0]), (right_dir, "right", feet[1])):
        if got is not None and got != want:
            raise DataError(f"gait: {d}/meta.json says the {got} foot, given as the {want}; give the left foot's "
                            "session first, then the right foot's")
    check_clock(left_dir, right_dir, left_meta, right_meta)


#: decision S54: the simulator's meta.json keys that fix one simulated walk's events (its ``knobs`` but
#: ``instrumented_foot`` too): the left and the right foot's sessions of one walk give the same values
SIM_WALK_KEYS = ("scenario", "speed", "seed", "user_seed", "user", "n_steps", "clock_offset_s", "clock_drift_ppm")


#: decision L307: the simulator knobs ``paretic_side`` acts through (S35, S42, S55): with both zero it changes nothing
SIM_ASYMMETRY_KNOBS = ("step_time_asymmetry", "step_length_asymmetry")


def sim_walk(meta: dict) -> str | None:
    """Decision S54: a simulated session's walk (``source_project`` "pdrlearn.sim") as a text of
    :data:`SIM_WALK_KEYS` and its knobs without ``instrumented_foot``, and without ``paretic_side`` when every one
    of :data:`SIM_ASYMMETRY_KNOBS` is zero or absent (decision L307: it then has no effect); None for any other
    session."""
    if meta.get("source_project") != "pdrlearn.sim":
        return None
    knobs = {k: v for k, v in (meta.get("knobs") or {}).items() if k != "instrumented_foot"}
    if not any(knobs.get(k) for k in SIM_ASYMMETRY_KNOBS):  # decision L307
        knobs.pop("paretic_side", None)
    return "pdrlearn.sim walk " + json.dumps({**{k: meta.get(k) for k in SIM_WALK_KEYS}, "knobs": knobs},
                                              sort_keys=True, default=str)


def _wall_origin(meta: dict) -> float | None:
    """Decision L537: a session's 0 s on an absolute clock (s since the epoch): ``pdrlearn import``'s
    ``imported.time.origin_s`` (:func:`pdrlearn.track.clock.export_origin_s`) when it is in B39's epoch range (an
    epoch-seconds or epoch-ms column, a date-time text with a date); None otherwise (a device's own counter, a time
    of day without a date, a session not imported - the simulator's, gaitmap's)."""
    from pdrlearn.io.validate import EPOCH_END, EPOCH_START
    from pdrlearn.track.clock import export_origin_s

    o = export_origin_s(meta)
    return o if o is not None and EPOCH_START <= o < EPOCH_END else None


def clock_alignment(left_dir: Path, right_dir: Path, left_meta: dict, right_meta: dict) -> dict:
    """Decision L537: how the two sessions' times are put on one clock. When both were imported from an absolute
    clock (:func:`_wall_origin`), the later one's times are moved by the difference of the two origins, so both are
    on the earlier unit's clock (``basis`` ``"absolute clock"``, ``right_minus_left_s`` = right origin - left
    origin, ``shift_left_s`` / ``shift_right_s`` the s added to each side's times); otherwise both keep their own
    t = 0 (``basis`` ``"shared t = 0"``, as before session 40), with ``note`` saying why when only one side has an
    absolute start."""
    o = _wall_origin(left_meta), _wall_origin(right_meta)
    if None not in o:
        d = o[1] - o[0]
        return {"basis": "absolute clock", "right_minus_left_s": d, "origin_s_left": o[0], "origin_s_right": o[1],
                "shift_left_s": max(-d, 0.0), "shift_right_s": max(d, 0.0), "note": None}
    note = None
    if o != (None, None):
        has, lacks = (left_dir, right_dir) if o[0] is not None else (right_dir, left_dir)
        note = (f"gait: {has} was imported from an absolute clock (meta.json imported.time.origin_s) and {lacks} "
                "was not: the two are paired on their own t = 0 (decision L537), which is one clock only if both "
                "recordings started together; import both feet from exports of one synchronised clock")
    return {"basis": "shared t = 0", "right_minus_left_s": None, "origin_s_left": o[0], "origin_s_right": o[1],
            "shift_left_s": 0.0, "shift_right_s": 0.0, "note": note}


def alignment_line(alignment: dict) -> str | None:
    """Decision L537: the printed line of an absolute-clock alignment (:func:`clock_alignment`); None without one."""
    if alignment["basis"] != "absolute clock":
        return None
    d = alignment["right_minus_left_s"]
    later, earlier = ("right", "left") if d >= 0 else ("left", "right")
    return (f"aligned on the units' absolute clock (meta.json imported.time.origin_s): the {later} unit starts "
            f"{abs(d):.3f} s after the {earlier} one (decision L537)")


def check_clock(left_dir: Path, right_dir: Path, left_meta: dict, right_meta: dict) -> None:
    """Decision L283 (B248): refuse (one line) two sessions whose ``meta.json`` both give :data:`CLOCK_META_KEY`
    with different values: their timestamps do not share t = 0, so no step time between them means anything. Two
    simulated sessions without it are compared by :func:`sim_walk` (S54). Any other session without the key is
    trusted (folders written before L283)."""
    a, b = left_meta.get(CLOCK_META_KEY), right_meta.get(CLOCK_META_KEY)
    fix = ("a step time needs both feet on one clock: synchronise the two recordings and give both meta.json the "
           f"same {CLOCK_META_KEY}, or track each foot alone (pdrlearn track)")
    if a is not None and b is not None and str(a).strip() != str(b).strip():
        raise DataError(f"gait: {left_dir} and {right_dir} are not on one clock (meta.json {CLOCK_META_KEY}: {a!r} / "
                        f"{b!r}); {fix}")
    sa, sb = sim_walk(left_meta), sim_walk(right_meta)
    if (a is None or b is None) and sa is not None and sb is not None and sa != sb:  # decision S54
        raise DataError(f"gait: {left_dir} and {right_dir} are two different simulated walks (meta.json scenario, "
                        "seed, user, steps or knobs differ); simulate the left foot with the right foot's arguments "
                        "and --foot left (decision S54)")


def check_one_walk(left_dir: Path, right_dir: Path, left_meta: dict, right_meta: dict) -> None:
    """Decision B245: refuse (one line) two sessions whose ``meta.json`` names different activities
    (:data:`WALK_META_KEYS`, both given): not the two feet of one walk."""
    for k in WALK_META_KEYS:
        a, b = left_meta.get(k), right_meta.get(k)
        if a is not None and b is not None and str(a).strip().lower() != str(b).strip().lower():
            raise DataError(f"gait: {left_dir} and {right_dir} are different recordings (meta.json {k}: {a!r} / "
                            f"{b!r}); give the two feet of one walk")


#: decision B322: the largest relative difference of the two feet's sample rates for one walk. Two units of one walk
#: are set up together; their rates differ by crystal tolerance (~0.01 %) and by D7's quantised-timestamp reading
#: (integer-ms 204.8 Hz reads as 200 Hz: 2.4 %); the nearest distinct common settings are 100 / 128 / 200 / 204.8 Hz
#: families (100 vs 128: 28 %), so 10 % passes every same-setting pair and refuses different devices or settings
PAIR_RATE_TOLERANCE = 0.10
#: decision B322: the least share of the shorter recording's span that the other recording's span must cover
PAIR_MIN_OVERLAP = 0.5


def check_pair_streams(left_dir: Path, right_dir: Path, sessions: list, shifts: tuple[float, float] = (0.0, 0.0)) \
        -> None:
    """Decision B322 (session 34, trial T5 finding 2): refuse (one line naming both folders) a pair whose foot
    accelerometers' sample rates differ by more than :data:`PAIR_RATE_TOLERANCE` or whose time spans overlap by less
    than :data:`PAIR_MIN_OVERLAP` of the shorter one: not the two feet of one walk on one clock. ``shifts``: each
    session's times moved onto the pair's clock (decision L537, :func:`clock_alignment`)."""
    acc = [s["fAccelerometer"] for s in sessions]
    rates = [a.rate_hz for a in acc]
    if abs(rates[0] - rates[1]) > PAIR_RATE_TOLERANCE * max(rates):
        raise DataError(f"gait: {left_dir} ({rates[0]:.4g} Hz) and {right_dir} ({rates[1]:.4g} Hz) differ in "
                        f"sample rate by over {100 * PAIR_RATE_TOLERANCE:.0f} % (decision B322): not the two units of "
                        "one walk; give the left and the right foot's sessions of the same walk")
    spans = [(float(a.t[0]) + sh, float(a.t[-1]) + sh) for a, sh in zip(acc, shifts, strict=True)]  # L537
    overlap = min(spans[0][1], spans[1][1]) - max(spans[0][0], spans[1][0])
    shorter = min(b - a for a, b in spans)
    if shorter > 0 and overlap < PAIR_MIN_OVERLAP * shorter:
        raise DataError(f"gait: {left_dir} ({spans[0][0]:.1f}-{spans[0][1]:.1f} s) and {right_dir} "
                        f"({spans[1][0]:.1f}-{spans[1][1]:.1f} s) overlap for {max(overlap, 0.0):.1f} s, under "
                        f"{100 * PAIR_MIN_OVERLAP:.0f} % of the shorter recording (decision B322): not one walk on one "
                        "clock; give the two feet's sessions of the same walk")


def side_warning(left_dir: Path, right_dir: Path, metas: list[dict]) -> str | None:
    """Decision B322: one line when a session's ``meta.json`` names no foot (:data:`FOOT_META_KEYS`): its side is
    taken from the argument order, which nothing checks (``pdrlearn import --foot`` records it, B321)."""
    missing = [str(d) for d, m in zip((left_dir, right_dir), metas, strict=True) if session_foot(m) is None]
    if not missing:
        return None
    return (f"gait: {' and '.join(missing)} name no foot in meta.json; the side is taken from the argument order "
            "(left first, then right), which nothing checks (decision B322): record it with `pdrlearn import --foot "
            "left|right` or a meta.json \"foot\"")


#: decision L284: the tracked and the labelled step-time symmetry index differ by more than this (percentage points):
#: on the real level pair they differ by 1.3 pp (L263); a clock moved against its labels shows here
REFERENCE_SI_GAP_MAX = 20.0


def reference_warning(walk: dict, reference: dict | None) -> str | None:
    """Decision L284: one warning line when the tracked step-time symmetry index and the labels' differ by more than
    :data:`REFERENCE_SI_GAP_MAX` percentage points (the sensor files and their labels no longer on one clock, or the
    tracks wrong)."""
    if reference is None:
        return None
    a, b = walk.get("step_time_s_si_pct"), reference["walk"].get("step_time_s_si_pct")
    if a is None or b is None or abs(a - b) <= REFERENCE_SI_GAP_MAX:
        return None
    return (f"bilateral gait: the tracked step-time symmetry index {a:.1f} % and the labelled contacts' {b:.1f} % "
            f"differ by more than {REFERENCE_SI_GAP_MAX:.0f} points (decision L284): the sensor files and their "
            "labels are not on one clock, or the tracks are wrong; trust neither before checking")


#: Decision L600 (session 42, trial T2 finding F7): the share of the pair's strides (both feet's rows together) that
#: must travel backward (L203) before ``gait`` calls the walk backward (L329): more than half - most strides. Not
#: from a document: a walk is "backward" when that is what it mostly does; a few stray strides (a short backward
#: chord at a slow initiation) stay in each track's own n_backward_strides
BACKWARD_WALK_MIN_FRAC = 0.5


def backward_note(tracks: list[pd.DataFrame]) -> str | None:
    """Decision L329 (treadmill trial finding 8): one line when the pair's strides travel backward
    (:func:`pdrlearn.track.evaluate.backward_strides`, L203): the pair's timing is of backward walking, whose contact
    and toe-off detection no measurement validated; None otherwise. Decision L600: only when more than
    :data:`BACKWARD_WALK_MIN_FRAC` of the pair's strides do (was: any one stride)."""
    from pdrlearn.track.evaluate import backward_strides

    n = [backward_strides(t) for t in tracks]
    # decision L600: the walk is backward when more than BACKWARD_WALK_MIN_FRAC of the pair's strides are (one
    # stray backward stride of 31 called a hemiparetic forward walk backward, trial T2 finding F7)
    if sum(k or 0 for k in n) <= BACKWARD_WALK_MIN_FRAC * sum(len(t) for t in tracks):
        return None
    counts = " / ".join(f"{k or 0} of {len(t)}" for k, t in zip(n, tracks, strict=True))
    return (f"bilateral gait: the walk is backward ({counts} strides left / right travel backward, L203; decision "
            "L329): its swing, stance and double support are of backward walking (the toe lands first), which no "
            "measurement of the contact and toe-off detection covers - a symmetric simulated backward walk read "
            "its swing 0.06-0.08 s long and a 3.5 % swing-time asymmetry its labels do not have")


def label_steps(session) -> pd.DataFrame | None:
    """A session's labelled strides with IC / TC times (``ic_s`` and ``tc_s``, e.g. gaitmap's mocap events; the
    simulator's ``steps.csv``) as a :func:`foot_events` table, or None without labelled ICs."""
    st = session.steps
    if st is None or "ic_s" not in st or not np.isfinite(st["ic_s"].to_numpy(float)).any():
        return None
    return st


#: decision E153: what `gait` says once (INFO) instead of each foot track's "no model" warning
GAIT_NO_MODEL_INFO = ("gait: both feet tracked with the M3 engine without the step-class rules (gait takes no model; "
                      "its step and stride lengths are the ZUPT strides, unclamped by length classes)")


@contextmanager
def no_model_as_info(line: str):
    """Decision E153: inside the body, the plasys "no model" warning (:data:`pdrlearn.track.plasys.NO_MODEL_WARNING`)
    is not logged; on leaving, ``line`` is logged once at INFO if it was raised. Every other record passes."""
    from pdrlearn.track.plasys import NO_MODEL_WARNING

    seen: list[bool] = []

    def keep(record: logging.LogRecord) -> bool:
        if record.levelno >= logging.WARNING and NO_MODEL_WARNING in record.getMessage():
            seen.append(True)
            return False
        return True

    plasys_log = logging.getLogger("pdrlearn.track.plasys")
    plasys_log.addFilter(keep)
    try:
        yield
    finally:
        plasys_log.removeFilter(keep)
    if seen:
        logging.getLogger(__name__).info(line)


def foot_warnings(session, result) -> tuple[list[str], list[str]]:
    """Decision L461: one foot track's lines: its result's kept warnings (without E153's "no model" line: gait takes
    no model; they were logged while tracking) and its summary's own trust lines (L95's slower-than-validated walk,
    L113's withheld CV, ...), which ``track`` prints and ``gait`` did not."""
    from pdrlearn.track.evaluate import summary_warnings

    summary = result.summary(session)  # logs the summary's own lines (as track's summary does)
    kept = [str(x) for x in summary["info"].get("warnings", []) if not str(x).startswith("no model:")]  # E153
    own = [str(x) for x in summary_warnings(summary)]
    return kept, own


def foot_rate_hz(sessions) -> float | None:
    """Decision L737: the slowest foot unit's native rate (Hz) of a walk's sessions (None without one)."""
    from pdrlearn.io.plasys import unit_rates

    rates = [r for r in (unit_rates(s)["foot"] for s in sessions) if math.isfinite(r)]
    return min(rates) if rates else None


def offline_foot_track(session, ignore_force: bool):
    """Decision L259: how ``gait`` tracks one foot session: offline plasys with L73's toe-off, no model (E153), no
    TUG transfer read (W439). The default ``track_foot`` of :func:`pair_sessions`."""
    from pdrlearn.track.plasys import track_plasys

    return track_plasys(session, toe_off=True, ignore_force=ignore_force, transfers=False)


def read_pair(left_dir: Path, right_dir: Path, *, streamed: bool = False) -> tuple[list, dict, str | None]:
    """Decisions L260, L283, L537, B321, B322: read the left and the right foot's session folders (``streamed``: as
    ``run`` reads them, E311) and refuse, in one line each, a pair that is not two foot units of one walk on one
    clock. Returns ``(sessions, clock alignment, side warning or None)``; nothing is logged."""
    from pdrlearn.io import read_session

    sessions = [read_session(d, streamed=streamed) for d in (left_dir, right_dir)]
    check_pair(left_dir, right_dir, sessions[0].meta, sessions[1].meta, *(s.content_id() for s in sessions))
    for d, s in zip((left_dir, right_dir), sessions, strict=True):
        if not s.has("fAccelerometer", "fGyroscope"):
            raise DataError(f"gait: {d} has no foot unit (fAccelerometer.csv, fGyroscope.csv); give a foot session")
    check_one_walk(left_dir, right_dir, sessions[0].meta, sessions[1].meta)
    alignment = clock_alignment(left_dir, right_dir, sessions[0].meta, sessions[1].meta)  # decision L537
    check_pair_streams(left_dir, right_dir, sessions,
                       (alignment["shift_left_s"], alignment["shift_right_s"]))  # decision B322
    return sessions, alignment, side_warning(left_dir, right_dir, [s.meta for s in sessions])


def pair_sessions(left_dir: Path, right_dir: Path, *, ignore_force: bool = False, track_foot=None,
                  streamed: bool = False, read: tuple | None = None, ramps: bool = False) -> dict:
    """Decisions L259-L263: read and track (offline plasys with ``toe_off=True``, L73) the left and the right foot's
    session folders of one walk and give :func:`bilateral_gait` of their tracks, plus ``"reference"``: the same
    measures of their labelled events when both sessions have them (L263), and ``"sessions"``: each track's
    summary line data (``n_strides``, ``distance_m``). Steps decision 72: both feet are timed by one detector - the
    IMU's when only one foot has force sensors or the two tracks' contacts came from different detectors (one
    warning line), or always with ``ignore_force`` (L366, ``gait --ignore-force``); ``"contact_source"`` gives each
    foot's. ``track_foot(session, ignore_force)`` tracks one foot (a :class:`~pdrlearn.track.base.TrackResult` whose
    steps have ``event_s`` and ``tc_s``; default :func:`offline_foot_track`; decision E311: ``pdrlearn run --gait``
    passes the runtime's streamed replay, with ``streamed`` = the sessions read as ``run`` reads them; ``read``: the
    pair :func:`read_pair` read and checked already)."""
    from pdrlearn.track.gait_tables import pair_ids

    track_foot = offline_foot_track if track_foot is None else track_foot
    sessions, alignment, side = read_pair(left_dir, right_dir, streamed=streamed) if read is None else read
    shifts = (alignment["shift_left_s"], alignment["shift_right_s"])
    if side is not None:
        logging.getLogger(__name__).warning(side)
    from pdrlearn.track.gait_contacts import contact_source, has_force, mixed_line

    mixed = []  # steps decision 72: one detector times both feet
    forced = {side: "force" if has_force(s) else "none" for side, s in zip(SIDES, sessions, strict=True)}
    if not ignore_force and len(set(forced.values())) > 1:
        ignore_force = True
        mixed.append(mixed_line(forced, before=True))
    with no_model_as_info(GAIT_NO_MODEL_INFO):  # decision E153: gait takes no model; one info line, no warning
        tracks = [track_foot(s, ignore_force) for s in sessions]  # decision E311: offline or streamed
        sources = dict(zip(SIDES, map(contact_source, tracks), strict=True))
        if len(set(sources.values())) > 1:  # steps decision 72: e.g. one foot's insole check fell back (L365)
            mixed.append(mixed_line(sources, before=False))
            tracks = [t if sources[side] == "imu" else track_foot(s, True)
                      for side, s, t in zip(SIDES, sessions, tracks, strict=True)]
            sources = dict(zip(SIDES, map(contact_source, tracks), strict=True))
    for line in mixed:
        logging.getLogger(__name__).warning(line)
    from pdrlearn.track.clock import on_export_clock

    out = bilateral_gait(*(on_export_clock(t.steps, sh) for t, sh in zip(tracks, shifts, strict=True)),  # L537
                         contact_source=sources, rate_hz=foot_rate_hz(sessions), ramps=ramps)  # L703, L737, L775
    out["clock_alignment"] = alignment
    if alignment["note"] is not None:
        logging.getLogger(__name__).warning(alignment["note"])
        out["warnings"].append(alignment["note"])
    out["contact_source"] = sources  # steps decision 72: gait_summary.json's and gait_steps.csv's detector per foot
    out["steps"]["contact_source"] = out["steps"]["side"].map(sources)
    out["warnings"] += mixed
    labels = [label_steps(s) for s in sessions]
    ics = sessions[0].extras.get("ics")  # decision L540: the simulator's both-feet contacts with step lengths
    ics = None if ics is None else on_export_clock(ics, shifts[0])
    out["reference"] = (bilateral_gait(*(on_export_clock(x, sh) for x, sh in zip(labels, shifts, strict=True)),
                                       step_lengths=ics, ramps=ramps) if all(x is not None for x in labels) else None)
    sharp = [impact_sharpness(s["fAccelerometer"].t, s["fAccelerometer"].values, t.steps["event_s"])
             for s, t in zip(sessions, tracks, strict=True)]  # decision L318
    out["walk"]["impact_sharpness_left"], out["walk"]["impact_sharpness_right"] = sharp
    if side is not None:
        out["warnings"].append(side)
    for line in (reference_warning(out["walk"], out["reference"]), comparability_warning(*sharp),
                 backward_note([t.steps for t in tracks]),
                 height_warning(tracks[0].steps, tracks[1].steps)):  # decisions L436, L437
        if line is not None:
            logging.getLogger(__name__).warning(line)
            out["warnings"].append(line)
    feet = [foot_warnings(s, t) for s, t in zip(sessions, tracks, strict=True)]  # decision L461
    out["warnings"] += [f"{side} foot: {line}" for side, (_, own) in zip(SIDES, feet, strict=True) for line in own]
    for res in (out, out["reference"] or {}):  # decision L551: the labels' reference by the same rule as the track
        withhold_all(res)
    if out["walk"]["si_withheld"] is not None:
        logging.getLogger(__name__).warning(out["walk"]["si_withheld"])
        out["warnings"].append(out["walk"]["si_withheld"])
    out["sessions"] = {side: {"session": str(d), "n_strides": int(len(t.steps)), "warnings": [*kept, *own]}
                       for side, d, t, (kept, own) in zip(SIDES, (left_dir, right_dir), tracks, feet, strict=True)}
    out["ids"] = pair_ids(*sessions)  # decision C109: the tables' id columns
    return out
