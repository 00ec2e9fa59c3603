"""Chair transfers of the lower-back unit: each sit-to-stand and stand-to-sit, and a Timed-Up-and-Go time
(decisions W182, W183, docs/decisions/waist.md).

The transfers are W104's trunk-flexion events (:func:`pdrlearn.waist.posture.flexion_events`: a run of samples whose
trunk tilts more than 25 deg from the session's walking upright) - no second detector. Each event is widened to the
whole movement and classed by the pelvis's height change over it:

* **bounds** (W182): from the event's tilt peak, backward and forward for as long as the trunk's tilt still moves
  toward the peak at :data:`MOVING_DPS` deg/s or more (the tilt's rate over :data:`RATE_WINDOW_S`): the trunk is at
  rest, seated or standing, before and after a transfer;
* **kind** (W182): the pelvis's height change from the movement's start to its end, the vertical acceleration
  (gravity removed, the AHRS's) integrated twice with the velocity made zero at both bounds (the trunk rests there;
  a constant acceleration error is removed with it): up by :data:`HEIGHT_MIN_M` or more is a ``sit-to-stand``, down
  by as much a ``stand-to-sit``; less is a bend (picking something up, leaning forward) and no transfer;
* **TUG time** (W183): ``tug_time_s`` is the first sit-to-stand's start to the last stand-to-sit's end, only when
  the session starts and ends seated: no step starts before that sit-to-stand's start or after that stand-to-sit's
  end (a contact inside a transfer may: W146), and no transfer lies between them (else None: the test was not
  recorded from seat to seat); and at least one step lies between the rise and the sit (W340: a TUG walks; a rise
  and a sit with nothing between are a chair stand);
* **TUG trials** (W325): the same rule applied to each sit-to-stand directly followed by a stand-to-sit with walking
  between (:func:`tug_trial_pairs`), so two or three trials in one recording are each timed (tug_trials.csv);
  W445: only when the pair looks like a TUG (:func:`tug_like`), else it is a chair-to-chair walk (``n_chair_walks``);
  W490: with the track's turns, a TUG also turns about once at its far end and walks at most 9 m each way
  (:func:`tug_turn_legs`); L614: a two-unit foot track judges that shape on the foot's turns and strides.

Not from a seed: the clinical TUG runs from rising off the chair to sitting back on it (Podsiadlo & Richardson 1991,
J Am Geriatr Soc 39:142-148, as recalled), and the thresholds are this module's choices (W182), set before
measuring. A foot unit sees no trunk: a foot track has no transfers (the summary keys are None).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.waist.ahrs import WaistIMU
from pdrlearn.waist.posture import contact_directions, flexion_runs, near_flexion, walking_upright
from pdrlearn.waist.upright import (
    CONVERGED_DEG,
    MAX_PASSES,
    flexion_free_walking,
    mean_direction,
    not_lying,
    standing_mask,
    still_mask,
    walking_is_reliable,
)

#: decision W182: the trunk still moves while its tilt changes this fast (deg/s) toward the flexion peak; a
#: transfer's trunk flexes 30-45 deg in about a second (30-45 deg/s on average), standing or seated it rests
MOVING_DPS = 10.0
#: decision W182: the tilt's rate is the mean over this window (s), so that a walking step's rocking of a few degrees
#: does not extend a transfer
RATE_WINDOW_S = 0.25
#: decision W182: a rise or a sit moves the pelvis by this much (m) or more; standing hip height (~0.9 m) less a
#: chair seat (~0.45 m) is ~0.45 m, half of a low 0.40 m is taken; a bend moves it less
HEIGHT_MIN_M = 0.20
#: decision W233's candidate (measured, see its text): the height change over at least this (s) on each side of the tilt
#: peak (W104's TRANSFER_HALF_S); None = over W182's movement bounds only
HEIGHT_HALF_S: float | None = None
#: decision W450's candidate (measured, NOT adopted: see its text), :func:`transfers_from_tilt`'s ``slow_bounds``: a
#: flexion run whose W182 bounds move the pelvis by less than HEIGHT_MIN_M is bounded again with movement_bounds'
#: keywords (a slow transfer's trunk flexes at under MOVING_DPS near its top), kept only with a still trunk within
#: ``seated_rest_s`` on its seated side
W450_CANDIDATE = {"top_s": 1.0, "seated_rest_s": 1.0}
#: decision L648: a slow rise read at the walk's start ends at most this (s) before its first contact, a slow sit at its
#: end starts at most this after its last (a TUG walks off once up and sits once back; HAPT's protocol holds each
#: posture for seconds: candidate 1 without it added a false rise there); W506: or after the turn in front of the chair
SLOW_EDGE_WALK_S = 5.0
SIT_TO_STAND, STAND_TO_SIT = "sit-to-stand", "stand-to-sit"
#: transfers.csv's columns (decision W182), in order
TRANSFER_COLUMNS = ("transfer", "kind", "start_s", "end_s", "duration_s", "peak_s", "peak_tilt_deg",
                    "height_change_m", "flag")
#: decision W183: the summary keys of :func:`transfer_summary`
TRANSFER_SUMMARY_KEYS = ("n_sit_to_stand", "n_stand_to_sit", "median_sit_to_stand_s", "median_stand_to_sit_s",
                         "tug_time_s", "n_lie_down", "n_get_up", "tug_time_note", "sts5_time_s",
                         "n_transfers_flagged", "n_tug_trials", "tug_trials_median_s", "n_chair_walks")
#: decision W445: a TUG trial lasts at most this (s) from the rise's start to the sit's end
TUG_MAX_S = 120.0
#: decision W445: and comes back: the contacts' net displacement at most this fraction of the walked path (0.35:
#: W445 amended by the lead after the final clone run: a waist-pll TUG reads 0.31, a one-way daily walk from 0.37)
TUG_RETURN_MAX = 0.35
#: decision W490: a TUG's first turn (its turn at the 3 m line, Podsiadlo & Richardson 1991, as recalled) turns by
#: 180 deg +- this: 135 deg is halfway between a corner (90 deg) and an about-turn
TUG_TURN_TOL_DEG = 45.0
#: decision W490: its walk out and its walk back are each at most this (m): 3 x the protocol's 3 m, so that an
#: uncalibrated waist-pll reading a short-stepping walker twice as long (MS001 Test11 +103.60 %) keeps a TUG
TUG_LEG_MAX_M = 9.0
#: decision W278: a transfer with walking contacts within this (s) before its start and after its end is flagged
FLAG_WALK_S = 2.0
#: decision W278: transfers.csv's ``flag`` texts ("" = none)
NOT_ALTERNATING, WALKING_BOTH_SIDES = "not alternating", "walking on both sides"
#: decision W451: a sitting posture run at least this long (s) that turns into standing (or standing into it) needs a
#: chair transfer there; a shorter one may be a bend read as sitting from the tilt (W222's 15 deg)
UNMATCHED_SIT_S = 10.0
#: decision W279: the five-times sit-to-stand's number of rises
STS_RISES = 5
#: decision W258: the lying kinds (W245) counted by direction: into lying (``n_lie_down``) and out of it
#: (``n_get_up``); their sit / stand side is W223's split (W257), their direction right on every HAPT label (W246)
#: decision W245: transfers.csv's lying kinds (into lying from / out of lying to: sitting, standing), written by
#: :mod:`pdrlearn.waist.lying`
SIT_TO_LIE, LIE_TO_SIT, STAND_TO_LIE, LIE_TO_STAND = "sit-to-lie", "lie-to-sit", "stand-to-lie", "lie-to-stand"
LIE_DOWN_KINDS, GET_UP_KINDS = (SIT_TO_LIE, STAND_TO_LIE), (LIE_TO_SIT, LIE_TO_STAND)
#: decision W278: each kind's posture before and after it
_FROM_TO = {SIT_TO_STAND: ("sit", "stand"), STAND_TO_SIT: ("stand", "sit"), SIT_TO_LIE: ("sit", "lie"),
            LIE_TO_SIT: ("lie", "sit"), STAND_TO_LIE: ("stand", "lie"), LIE_TO_STAND: ("lie", "stand")}


def _tilt_deg(imu: WaistIMU, up: np.ndarray) -> np.ndarray:
    u = imu.up_body / np.linalg.norm(imu.up_body, axis=1, keepdims=True)
    return np.degrees(np.arccos(np.clip(u @ up, -1.0, 1.0)))


def tilt_rate_dps(t: np.ndarray, tilt: np.ndarray, fs: float, window_s: float = RATE_WINDOW_S) -> np.ndarray:
    """The trunk tilt's rate (deg/s), the mean over ``window_s`` (:data:`RATE_WINDOW_S`, decision W182; shared by
    W245's lying transfers; W450's candidate may pass another)."""
    w = max(int(round(window_s * fs)), 1)
    return np.convolve(np.gradient(tilt, t), np.ones(w) / w, mode="same")


def movement_bounds(t: np.ndarray, tilt: np.ndarray, peak: int, fs: float, *, moving_dps: float = MOVING_DPS,
                    window_s: float = RATE_WINDOW_S, top_s: float = RATE_WINDOW_S) -> tuple[int, int]:
    """Sample indices ``(start, end)`` of the movement around the tilt peak ``peak`` (decision W182): backward from
    the peak past the samples near it where the tilt's rate (mean over ``window_s``) is under ``moving_dps`` (at
    most ``top_s`` of them: the top of the flexion), then past those where the trunk flexes at ``moving_dps`` or
    more; the first sample after them is the start. Forward alike with the trunk straightening (the rate at or
    under -``moving_dps``). The defaults are W182's (:data:`MOVING_DPS`, :data:`RATE_WINDOW_S` for both); W450's
    not adopted candidate passes others (:data:`W450_CANDIDATE`)."""
    w = max(int(round(top_s * fs)), 1)
    rate = tilt_rate_dps(t, tilt, fs, window_s)
    a = peak
    while a > 0 and peak - a < w and rate[a - 1] < moving_dps:  # the top of the flexion
        a -= 1
    while a > 0 and rate[a - 1] >= moving_dps:
        a -= 1
    b = peak
    while b < len(t) - 1 and b - peak < w and rate[b + 1] > -moving_dps:
        b += 1
    while b < len(t) - 1 and rate[b + 1] <= -moving_dps:
        b += 1
    return a, b


def height_change_m(t: np.ndarray, acc_v: np.ndarray, a: int, b: int) -> float:
    """The pelvis's height change (m) from sample ``a`` to ``b``: ``acc_v`` (m/s^2, up +) integrated to a velocity
    (trapezoids), less the line that makes it zero at both ends (the trunk rests there), integrated again
    (decision W182)."""
    if b - a < 2:
        return 0.0
    tt, acc = t[a:b + 1], acc_v[a:b + 1]
    v = np.concatenate([[0.0], np.cumsum(0.5 * (acc[1:] + acc[:-1]) * np.diff(tt))])
    v = v - v[-1] * (tt - tt[0]) / (tt[-1] - tt[0])
    return float(np.sum(0.5 * (v[1:] + v[:-1]) * np.diff(tt)))


def transfers_from_tilt(imu: WaistIMU, tilt: np.ndarray, *, slow_bounds: dict | None = None) -> pd.DataFrame:
    """Decision W182: transfers.csv's rows (:data:`TRANSFER_COLUMNS`) from the trunk's per-sample ``tilt`` (deg)
    from an upright: each W104 flexion run (:func:`~pdrlearn.waist.posture.flexion_runs`) widened to its movement
    (:func:`movement_bounds`) and classed by :func:`height_change_m`; bends (less than :data:`HEIGHT_MIN_M`) are
    left out. ``slow_bounds`` (decision W450, not adopted; e.g. :data:`W450_CANDIDATE`): a run left out is bounded
    again with these :func:`movement_bounds` keywords and, with ``seated_rest_s``, kept only when the trunk is still
    (W277's :func:`~pdrlearn.waist.upright.still_mask`) within that many seconds on its seated side."""
    rows: list[dict] = []
    still = None
    for _, t_peak, _ in flexion_runs(imu.t, tilt):
        peak = int(np.clip(np.searchsorted(imu.t, t_peak), 0, len(imu.t) - 1))
        a, b = movement_bounds(imu.t, tilt, peak, imu.fs)
        ha, hb = a, b
        if HEIGHT_HALF_S is not None:  # decision W233: at least W104's +-1 s around the peak
            ha = min(a, int(np.searchsorted(imu.t, t_peak - HEIGHT_HALF_S)))
            hb = max(b, min(int(np.searchsorted(imu.t, t_peak + HEIGHT_HALF_S)), len(imu.t) - 1))
        dz = height_change_m(imu.t, imu.acc_v, ha, hb)
        if abs(dz) < HEIGHT_MIN_M and slow_bounds is not None:  # decision W450: a slow transfer's wider movement
            a, b = movement_bounds(imu.t, tilt, peak, imu.fs, **{k: v for k, v in slow_bounds.items()
                                                                    if k != "seated_rest_s"})
            dz = height_change_m(imu.t, imu.acc_v, a, b)
            rest_s = slow_bounds.get("seated_rest_s")
            if rest_s is not None and abs(dz) >= HEIGHT_MIN_M:
                still = still_mask(imu.gyr_nav, imu.fs) if still is None else still
                side = ((imu.t >= imu.t[a] - rest_s) & (imu.t <= imu.t[a])) if dz > 0 else (
                    (imu.t >= imu.t[b]) & (imu.t <= imu.t[b] + rest_s))
                if not still[side].any():
                    continue
        if abs(dz) < HEIGHT_MIN_M:
            continue
        t0, t1 = float(imu.t[a]), float(imu.t[b])
        if rows and t0 < rows[-1]["end_s"]:  # one movement seen as two flexion runs: keep the first
            continue
        rows.append({"transfer": len(rows) + 1, "kind": SIT_TO_STAND if dz > 0 else STAND_TO_SIT,
                     "start_s": t0, "end_s": t1, "duration_s": t1 - t0, "peak_s": float(t_peak),
                     "peak_tilt_deg": float(tilt[peak]), "height_change_m": dz, "flag": ""})
    return pd.DataFrame(rows, columns=list(TRANSFER_COLUMNS))


def with_slow_edges(imu: WaistIMU, tilt: np.ndarray, rows: pd.DataFrame, contacts: np.ndarray, *,
                    final_turn: bool = True, standstill: bool = True) -> pd.DataFrame:
    """Decision L648: W182's ``rows`` with the session's first rise and last sit of W450's candidate C reading
    (:data:`W450_CANDIDATE`: a slow 3-6 s transfer's wider bounds, kept only with a still trunk on its seated side)
    where W182 has none: the last sit-to-stand starting before the first of ``contacts`` (s) when no W182 row starts
    before it, the first stand-to-sit ending after the last contact when no W182 row ends after it, each within
    :data:`SLOW_EDGE_WALK_S` of the walk - a TUG's slow
    rise and sit (trial T1: 4 of 6 slow TUGs untimed). Nothing else of that reading is taken (W450's false transfers
    in daily life stay out). Rows renumbered in time order. ``final_turn`` (decision W506, adopted; False: L648
    alone): when no such
    sit starts within :data:`SLOW_EDGE_WALK_S` of the last contact, the window is counted from the end of a pelvis
    yaw-rate turn of at least C180's 90 deg that starts at most :data:`SLOW_EDGE_WALK_S` after the last contact and
    ends after it (the stepless turn in front of the chair, W331). ``standstill`` (decision W555; False: L648 and
    W506 alone): the window does not count the samples where the trunk stands upright (:func:`not_upright_s`): a
    standstill between rising and walking off, or between the turn and sitting."""
    if not len(contacts):
        return rows
    first, last = float(np.min(contacts)), float(np.max(contacts))
    need_rise = not (rows["start_s"].astype(float) < first).any() if len(rows) else True
    need_sit = not (rows["end_s"].astype(float) > last).any() if len(rows) else True
    if not (need_rise or need_sit):
        return rows
    slow = transfers_from_tilt(imu, tilt, slow_bounds=W450_CANDIDATE)
    added = []
    rise = slow[(slow["kind"] == SIT_TO_STAND) & (slow["start_s"] < first)] if need_rise else slow.iloc[:0]
    def gap_s(t0: float, t1: float) -> float:  # decision W555: a standstill upright is not counted
        return not_upright_s(imu.t, tilt, t0, t1) if standstill else t1 - t0

    if len(rise) and gap_s(float(rise["end_s"].iloc[-1]), first) <= SLOW_EDGE_WALK_S:  # a TUG walks off once up
        added.append(rise.iloc[[-1]])
    sit = slow[(slow["kind"] == STAND_TO_SIT) & (slow["end_s"] > last)] if need_sit else slow.iloc[:0]
    if len(sit) and gap_s(last, float(sit["start_s"].iloc[0])) <= SLOW_EDGE_WALK_S:  # ... and sits once back
        added.append(sit.iloc[[0]])
    elif len(sit) and final_turn and float(sit["start_s"].iloc[0]) <= _final_turn_end(imu, last) + SLOW_EDGE_WALK_S:
        added.append(sit.iloc[[0]])  # decision W506: ... once back and turned about in front of the chair
    return _with_added(rows, added)


def seated_side_bounds(t: np.ndarray, tilt: np.ndarray, rows: pd.DataFrame, fs: float, *,
                       onset_dps: float = 1.0, max_s: float = 1.0) -> pd.DataFrame:
    """Decision C277 (a pure kernel): ``rows`` (transfers.csv's) with each chair transfer's seated side dated where
    the trunk starts or stops moving: a sit-to-stand's ``start_s`` moved back over the samples before it where the
    tilt's rate (W182's :func:`tilt_rate_dps`) still flexes toward the peak at ``onset_dps`` (deg/s) or more, a
    stand-to-sit's ``end_s`` forward over those after it where the trunk still straightens as fast; by at most
    ``max_s`` (s: a seated trunk's slow sway does not carry it further) and never past the row before / after.
    W182's :data:`MOVING_DPS` dates a slow (4-6 s) transfer's seated end 0.4-0.6 s inside the movement (a smooth
    onset passes 10 deg/s late): a TUG's timer starts at the first movement to rise and stops when seated
    (Podsiadlo & Richardson 1991, as recalled). ``duration_s`` follows; the kind, peak and height stay."""
    if not len(rows):
        return rows
    rate = tilt_rate_dps(t, tilt, fs)
    out = rows.copy()
    starts, ends = out["start_s"].to_numpy(float).copy(), out["end_s"].to_numpy(float).copy()
    for k, kind in enumerate(out["kind"]):
        if kind == SIT_TO_STAND:
            floor = max(ends[k - 1] if k else -np.inf, starts[k] - max_s)
            a = int(np.clip(np.searchsorted(t, starts[k]), 0, len(t) - 1))
            while a > 0 and t[a - 1] >= floor and rate[a - 1] >= onset_dps:
                a -= 1
            starts[k] = min(starts[k], float(t[a]))
        elif kind == STAND_TO_SIT:
            ceil = min(starts[k + 1] if k + 1 < len(out) else np.inf, ends[k] + max_s)
            b = int(np.clip(np.searchsorted(t, ends[k]), 0, len(t) - 1))
            while b < len(t) - 1 and t[b + 1] <= ceil and rate[b + 1] <= -onset_dps:
                b += 1
            ends[k] = max(ends[k], float(t[b]))
    out["start_s"], out["end_s"], out["duration_s"] = starts, ends, ends - starts
    return out


def not_upright_s(t: np.ndarray, tilt: np.ndarray, t0: float, t1: float) -> float:
    """Decision W555 (a pure kernel): the time (s) from ``t0`` to ``t1`` (0 when ``t1 <= t0``) less that of the
    samples (times ``t``, s) where the trunk's ``tilt`` (deg from the track's upright) is under W222's
    :data:`~pdrlearn.waist.posture_time.SITTING_TILT_DEG`: the time the trunk was not standing upright."""
    if t1 <= t0:
        return 0.0
    from pdrlearn.waist.posture_time import SITTING_TILT_DEG

    t, tilt = np.asarray(t, dtype=float), np.asarray(tilt, dtype=float)
    inside = (t >= t0) & (t <= t1)
    share = float((tilt[inside] < SITTING_TILT_DEG).mean()) if inside.any() else 0.0  # W222's standing tilt
    return (t1 - t0) * (1.0 - share)


def _with_added(rows: pd.DataFrame, added: list) -> pd.DataFrame:
    """``rows`` with the transfer rows of ``added`` (a list of frames), in time order and renumbered (L648, W528)."""
    if not added:
        return rows
    out = pd.concat([rows, *added], ignore_index=True) if len(rows) else pd.concat(added, ignore_index=True)
    out = out.sort_values("start_s", kind="stable").reset_index(drop=True)
    out["transfer"] = np.arange(1, len(out) + 1)
    return out[list(TRANSFER_COLUMNS)]


def with_slow_seats(imu: WaistIMU, tilt: np.ndarray, rows: pd.DataFrame, contacts: np.ndarray) -> pd.DataFrame:
    """Decision W528: ``rows`` with a slow seated period between two walks read again, as L648 reads a TUG's ends:
    in each gap of at least :data:`UNMATCHED_SIT_S` between consecutive ``contacts`` (s) that does not already hold
    a stand-to-sit followed by a sit-to-stand, W450's candidate C reading (:data:`W450_CANDIDATE`) gives the first
    slow stand-to-sit starting at most :data:`SLOW_EDGE_WALK_S` after the gap's first contact and the last slow
    sit-to-stand ending at most that before its last; the kinds the gap lacks are added only when the gap then holds
    exactly one sit and one rise, the sit ending before the rise starts (a one-sided find adds nothing). Rows
    renumbered in time order."""
    c = np.sort(np.asarray(contacts, dtype=float))
    gaps = np.flatnonzero(np.diff(c) >= UNMATCHED_SIT_S) if c.size > 1 else np.zeros(0, int)
    slow, added = None, []
    start, end = rows["start_s"].to_numpy(float), rows["end_s"].to_numpy(float)
    for g in gaps:
        c0, c1 = c[g], c[g + 1]
        mine = rows[(end > c0) & (start < c1)].sort_values("start_s")
        sits, rises = mine[mine["kind"] == STAND_TO_SIT], mine[mine["kind"] == SIT_TO_STAND]
        if len(sits) and len(rises) and float(sits["end_s"].min()) <= float(rises["start_s"].max()):
            continue  # W182's whole seated period (a sit, then a rise)
        if len(mine) > 1 or len(mine) != len(sits) + len(rises):
            continue  # W182 already reads more than one transfer here, or another kind: left as read
        slow = transfers_from_tilt(imu, tilt, slow_bounds=W450_CANDIDATE) if slow is None else slow
        new = []
        if not len(sits):
            sits = slow[(slow["kind"] == STAND_TO_SIT) & (slow["start_s"] <= c0 + SLOW_EDGE_WALK_S)
                        & (slow["end_s"] > c0) & (slow["end_s"] < c1)].iloc[:1]
            new.append(sits)
        if not len(rises):
            rises = slow[(slow["kind"] == SIT_TO_STAND) & (slow["end_s"] >= c1 - SLOW_EDGE_WALK_S)
                         & (slow["start_s"] > c0) & (slow["start_s"] < c1)].iloc[-1:]
            new.append(rises)
        if len(sits) == 1 and len(rises) == 1 and float(sits["end_s"].iloc[0]) <= float(rises["start_s"].iloc[0]):
            added += new  # exactly one sit, then one rise: a whole seated period walked into and out of
    return _with_added(rows, added)


def with_slow_pairs(imu: WaistIMU, tilt: np.ndarray, rows: pd.DataFrame, contacts: np.ndarray) -> pd.DataFrame:
    """Decision W583: ``rows`` with each seated period read by W450's candidate C (:data:`W450_CANDIDATE`) alone, as
    W528 reads one between two walks but with no walk needed (a stand-pivot between two chairs, a rise that leads
    nowhere, a seated start or end): two consecutive rows of that reading, a stand-to-sit then a sit-to-stand, at
    least :data:`UNMATCHED_SIT_S` apart (seated between) and with none of ``contacts`` (s) from the sit's start to
    the rise's end; each of the two is added unless it overlaps a row already read (a pair whose sit or rise overlaps a
    row of another kind adds nothing). Rows renumbered in time order."""
    slow = transfers_from_tilt(imu, tilt, slow_bounds=W450_CANDIDATE)
    c = np.asarray(contacts, dtype=float)
    start, end, kind = rows["start_s"].to_numpy(float), rows["end_s"].to_numpy(float), rows["kind"].to_numpy()
    added = []
    for k in range(len(slow) - 1):
        sit, rise = slow.iloc[k], slow.iloc[k + 1]
        if sit["kind"] != STAND_TO_SIT or rise["kind"] != SIT_TO_STAND:
            continue
        if float(rise["start_s"]) - float(sit["end_s"]) < UNMATCHED_SIT_S:
            continue
        if ((c >= float(sit["start_s"])) & (c <= float(rise["end_s"]))).any():
            continue  # walked while "seated": no seated period
        new, clash = [], False
        for j in (k, k + 1):
            over = (start < float(slow["end_s"].iloc[j])) & (end > float(slow["start_s"].iloc[j]))
            clash |= bool((kind[over] != slow["kind"].iloc[j]).any())
            if not over.any():
                new.append(slow.iloc[[j]])
        if not clash:
            added += new
    return _with_added(rows, added)


def _final_turn_end(imu: WaistIMU, last: float) -> float:
    """Decision W506: the end (s) of the first pelvis yaw-rate turn (L210) of at least C180's
    :data:`~pdrlearn.track.turn_gaps.TURN_GAP_MIN_DEG` that starts at most :data:`SLOW_EDGE_WALK_S` after ``last``
    (the last contact) and ends after it; ``last`` without one."""
    from pdrlearn.track.turn_gaps import TURN_GAP_MIN_DEG
    from pdrlearn.waist.heading import yaw_turns

    ends = [float(y["end_s"]) for y in yaw_turns(imu) if abs(float(y["angle_deg"])) >= TURN_GAP_MIN_DEG
            and float(y["start_s"]) <= last + SLOW_EDGE_WALK_S and float(y["end_s"]) > last]
    return ends[0] if ends else last


def _empty() -> pd.DataFrame:
    return pd.DataFrame([], columns=list(TRANSFER_COLUMNS))


def still_upright_transfers(imu: WaistIMU) -> tuple[pd.DataFrame, np.ndarray | None]:
    """Decision W277: ``(rows, upright)`` without walking - the upright first the median direction of every still
    sample (:func:`~pdrlearn.waist.upright.still_mask`), then, up to :data:`~pdrlearn.waist.upright.MAX_PASSES`
    times, that of the still samples which the transfers read from it call standing
    (:func:`~pdrlearn.waist.upright.standing_mask`), until it moves by less than
    :data:`~pdrlearn.waist.upright.CONVERGED_DEG`. ``(empty, None)`` when no still sample is standing: no
    reliable upright."""
    still = still_mask(imu.gyr_nav, imu.fs) & not_lying(imu.up_body)  # decision W453: not the hours in bed
    up = mean_direction(imu.up_body, still)
    found = False
    rows = _empty()
    for _ in range(MAX_PASSES):
        if up is None:
            break
        rows = transfers_from_tilt(imu, _tilt_deg(imu, up))
        new = mean_direction(imu.up_body, standing_mask(imu.t, still, rows, SIT_TO_STAND, STAND_TO_SIT))
        if new is None:
            break
        found = True
        moved = float(np.degrees(np.arccos(np.clip(new @ up, -1.0, 1.0))))
        up = new
        if moved < CONVERGED_DEG:
            break
    if not found:
        return _empty(), None
    return transfers_from_tilt(imu, _tilt_deg(imu, up)), up


def chair_transfers_upright(imu: WaistIMU, steps: pd.DataFrame, *, slow_pairs: bool = True,
                            seated_onset_dps: float | None = 1.0) -> tuple[pd.DataFrame, np.ndarray | None, str]:
    """Decisions W182, W277: ``(rows, upright, source)`` of a lower-back track. ``source`` ``"walking"``: W102's
    walking upright of ``steps``' contacts (``event_s``, ``has_next``), when they hold a walking sequence
    (:func:`~pdrlearn.waist.upright.walking_is_reliable`); ``"still"``: else the still standing upright
    (:func:`still_upright_transfers`); ``"none"``: neither (no rows, upright None); ``"walking"`` with no rows and
    upright None also when the AHRS gave no up direction or there is no contact at all to go by. ``slow_pairs``
    (decision W583, adopted; False: without it): and :func:`with_slow_pairs`' seated periods.
    ``seated_onset_dps`` (decision C277; None: without it): each transfer's seated side dated by
    :func:`seated_side_bounds` with that ``onset_dps``."""
    rows, up, source = _chair_transfers_upright(imu, steps, slow_pairs=slow_pairs)
    if seated_onset_dps is not None and up is not None and len(rows):
        rows = seated_side_bounds(imu.t, _tilt_deg(imu, up), rows, imu.fs, onset_dps=seated_onset_dps)
    return rows, up, source


def _chair_transfers_upright(imu: WaistIMU, steps: pd.DataFrame, *, slow_pairs: bool
                             ) -> tuple[pd.DataFrame, np.ndarray | None, str]:
    if imu.up_body is None:
        return _empty(), None, "walking"
    ev = steps["event_s"].to_numpy(float) if len(steps) and "event_s" in steps else np.zeros(0)
    walking = (steps["has_next"].to_numpy(bool) if len(ev) and "has_next" in steps else np.ones(len(ev), bool))
    still = None
    if walking_is_reliable(walking):  # decision W309 (W310: adopted)
        still = still_upright_transfers(imu)
        if still[1] is not None:
            flexed = near_flexion(ev, flexion_runs(imu.t, _tilt_deg(imu, still[1])))
            walking = flexion_free_walking(walking, flexed) if flexed.any() else walking
    if walking_is_reliable(walking):
        up = walking_upright(contact_directions(imu.t, imu.up_body, ev), steps["has_next"].to_numpy(bool)
                             if "has_next" in steps else np.ones(len(ev), bool))
        tilt = _tilt_deg(imu, up)
        # decision L648: a slow rise before the first contact / sit after the last one (a TUG's) by W450's bounds;
        # W528: a slow seated period between two walks, as a sit-and-rise pair
        rows = with_slow_seats(imu, tilt, with_slow_edges(imu, tilt, transfers_from_tilt(imu, tilt), ev), ev)
        return (with_slow_pairs(imu, tilt, rows, ev) if slow_pairs else rows), up, "walking"  # decision W583
    rows, up = still if still is not None else still_upright_transfers(imu)
    if up is not None:  # decision L648: W277's upright, the same slow rise / sit at the walk's ends (W528: between)
        tilt = _tilt_deg(imu, up)
        rows = with_slow_seats(imu, tilt, with_slow_edges(imu, tilt, rows, ev), ev)
        rows = with_slow_pairs(imu, tilt, rows, ev) if slow_pairs else rows  # decision W583
    return rows, up, "still" if up is not None else "none"


def chair_transfers(imu: WaistIMU, steps: pd.DataFrame) -> pd.DataFrame:
    """Decision W182: transfers.csv's rows (:data:`TRANSFER_COLUMNS`) of a lower-back track
    (:func:`chair_transfers_upright`'s)."""
    return chair_transfers_upright(imu, steps)[0]


def transfer_summary(transfers, steps: pd.DataFrame | None = None, *, turns: pd.DataFrame | None = None,
                     walk: pd.DataFrame | None = None, yaw_turns=None) -> dict:
    """Decision W183: :data:`TRANSFER_SUMMARY_KEYS` of a transfers table (a DataFrame or its records; None = a
    track without a trunk unit: every key None). ``tug_time_s`` (module docstring) needs ``steps`` (the contacts'
    ``start_s``); without them it is judged on the transfers alone (a sit-to-stand first and a stand-to-sit
    last). Decision W490: ``turns`` (the track's turns.csv) judges a trial's shape (:func:`tug_turn_legs`); L614:
    ``walk`` (a two-unit foot track's strides) carries the step lengths and headings in place of ``steps``; W498:
    there the shape's turns are the waist's ``yaw_turns`` (:func:`shape_turns`)."""
    if transfers is None:
        return dict.fromkeys(TRANSFER_SUMMARY_KEYS)
    tr = pd.DataFrame(list(transfers) if not isinstance(transfers, pd.DataFrame) else transfers,
                      columns=list(TRANSFER_COLUMNS))
    rise, sit = tr[tr["kind"] == SIT_TO_STAND], tr[tr["kind"] == STAND_TO_SIT]
    out = {"n_sit_to_stand": int(len(rise)), "n_stand_to_sit": int(len(sit)),
           "median_sit_to_stand_s": float(rise["duration_s"].median()) if len(rise) else None,
           "median_stand_to_sit_s": float(sit["duration_s"].median()) if len(sit) else None, "tug_time_s": None,
           "n_lie_down": int(tr["kind"].isin(LIE_DOWN_KINDS).sum()),  # decision W258
           "n_get_up": int(tr["kind"].isin(GET_UP_KINDS).sum()),
           "sts5_time_s": sts5_time_s(tr, steps),  # decision W279
           "n_transfers_flagged": int((flag_texts(tr["flag"]) != "").sum())}  # decision W278
    contacts = np.zeros(0) if steps is None or not len(steps) else steps["start_s"].to_numpy(float)
    pairs = seat_to_seat_pairs(tr["kind"], tr["start_s"], tr["end_s"], flag_texts(tr["flag"]), contacts)  # W325
    trials = tug_trial_pairs(tr["kind"], tr["start_s"], tr["end_s"], flag_texts(tr["flag"]), contacts,
                             **contact_path(steps, walk), turns=shape_turns(turns, walk, yaw_turns))  # W445, W490, W498
    if len(tr) >= 2 and tr["kind"].iloc[0] == SIT_TO_STAND and tr["kind"].iloc[-1] == STAND_TO_SIT:
        t0, t1 = float(tr["start_s"].iloc[0]), float(tr["end_s"].iloc[-1])
        # decision W340: and a walking contact between the rise and the sit (a TUG walks; W325's trial test);
        # W445: and the pair is a TUG trial (it looks like one)
        if len(tr) == 2 and not ((contacts < t0).any() or (contacts > t1).any()) and trials == [(0, 1)]:
            out["tug_time_s"] = t1 - t0
    times = [float(tr["end_s"].iloc[j]) - float(tr["start_s"].iloc[i]) for i, j in trials]
    out["n_tug_trials"], out["tug_trials_median_s"] = len(trials), float(np.median(times)) if times else None
    out["n_chair_walks"] = len(pairs) - len(trials)  # decision W445
    # decision W282: why not, when a rise is followed by a sit (a TUG could be timed on them)
    pair = len(rise) and len(sit) and float(rise["start_s"].min()) < float(sit["end_s"].max())
    # decision W279: a five-times sit-to-stand is no TUG to explain: it has its own time
    out["tug_time_note"] = None
    if out["tug_time_s"] is None and pair and out["sts5_time_s"] is None:
        out["tug_time_note"] = (trials_note(tr, trials) if trials else  # W445: seat-to-seat walks, no TUG among them
                                chair_walks_note(tr, pairs) if pairs else tug_note(tr, contacts))
    if out["tug_time_s"] is None and out["tug_time_note"] is None and out["sts5_time_s"] is None:
        out["tug_time_note"] = one_sided_tug_note(tr, contacts)  # decision L648
    return out


def one_sided_tug_note(tr: pd.DataFrame, contacts: np.ndarray) -> str | None:
    """Decision L648: why a walk of at most :data:`TUG_MAX_S` with a rise before its first contact and no sit after
    its last (or a sit after it and no rise before) - a TUG with one transfer missed - has no ``tug_time_s``; None
    otherwise (no walk, a longer one, both ends or neither found)."""
    c = np.asarray(contacts, dtype=float)
    if not c.size or c.max() - c.min() > TUG_MAX_S:
        return None
    rise = tr[(tr["kind"] == SIT_TO_STAND) & (tr["start_s"].astype(float) < c.min())]
    sit = tr[(tr["kind"] == STAND_TO_SIT) & (tr["end_s"].astype(float) > c.max())]
    if bool(len(rise)) == bool(len(sit)):
        return None
    if len(rise):
        found = f"a sit-to-stand at {float(rise['start_s'].iloc[-1]):.1f} s before the walk"
        missing = f"no stand-to-sit after its last step at {c.max():.1f} s"
    else:
        found = f"a stand-to-sit ending at {float(sit['end_s'].iloc[0]):.1f} s after the walk"
        missing = f"no sit-to-stand before its first step at {c.min():.1f} s"
    return (f"no TUG time: {found} but {missing}: a slow (3-6 s) transfer is often missed (W450, L648); if this was "
            "a TUG, time it by hand or from transfers.csv and the steps")


def no_rise_note(transfers, contacts, sitting_s: float | None) -> str | None:
    """Decision W556: ``tug_time_note`` of a lower-back walk of at most :data:`TUG_MAX_S` (``contacts``: its steps'
    start times, s) with no sit-to-stand in ``transfers`` (transfers.csv's rows) but sitting read (``sitting_s``,
    W222's sitting time) or a stand-to-sit found: no TUG time, why, and how to time it; None otherwise (no walk, a
    longer one, a rise found, no sitting at all)."""
    tr = pd.DataFrame(list(transfers) if transfers is not None and not isinstance(transfers, pd.DataFrame)
                      else transfers, columns=list(TRANSFER_COLUMNS)) if transfers is not None else _empty()
    c = np.asarray(contacts, dtype=float)
    if not c.size or c.max() - c.min() > TUG_MAX_S or (tr["kind"] == SIT_TO_STAND).any():
        return None
    n_sit = int((tr["kind"] == STAND_TO_SIT).sum())
    if not n_sit and not (sitting_s or 0.0) > 0.0:
        return None
    found = f"{n_sit} stand-to-sit" if n_sit else "no chair transfer"
    sat = f", sitting {sitting_s:.1f} s read from the trunk's tilt" if sitting_s else ""
    return (f"no TUG time: no sit-to-stand found ({found}{sat}; steps {c.min():.1f}-{c.max():.1f} s): a slow (3-6 s) "
            "or small rise is often missed on the lower back (W450, L648, W555); if this was a TUG, time it by hand "
            "from the rise to the sit (decision W556)")


def walked_between(contacts, t0: float, t1: float) -> bool:
    """Decisions W325, W340: at least one contact (start time, s) strictly between ``t0`` (a rise's end) and ``t1``
    (the next sit's start): the walk a TUG trial needs; without it a rise and a sit are a chair stand."""
    c = np.asarray(contacts, dtype=float)
    return bool(((c > t0) & (c < t1)).any())


def seat_to_seat_pairs(kinds, start_s, end_s, flags, contacts) -> list[tuple[int, int]]:
    """Decision W325: the seat-to-seat walks of a transfers table in time order (``kinds``, ``start_s``, ``end_s``,
    W278's ``flags`` per row) with walking ``contacts`` (start times, s), as ``(rise row, sit row)`` index pairs (a
    pure kernel): W183's seat-to-seat rule applied per pair of consecutive rows - a sit-to-stand directly followed by
    a stand-to-sit, neither flagged, at least one contact between the rise's end and the sit's start, and none
    between the transfer before (or the start) and the rise's start nor between the sit's end and the next transfer
    (or the end). W445: a TUG trial (:func:`tug_trial_pairs`) or a chair-to-chair walk."""
    kinds = list(kinds)
    a, b = np.asarray(start_s, dtype=float), np.asarray(end_s, dtype=float)
    c = np.asarray(contacts, dtype=float)
    out = []
    for i in range(len(kinds) - 1):
        if kinds[i] != SIT_TO_STAND or kinds[i + 1] != STAND_TO_SIT or flags[i] or flags[i + 1]:
            continue
        before = b[i - 1] if i > 0 else -np.inf
        after = a[i + 2] if i + 2 < len(kinds) else np.inf
        seated = not (((c > before) & (c < a[i])).any() or ((c > b[i + 1]) & (c < after)).any())
        if seated and walked_between(c, b[i], a[i + 1]):
            out.append((i, i + 1))
    return out


def tug_like(t0: float, up: float, down: float, t1: float, contacts, length_m=None, heading_rad=None, *,
             path_s=None, turns=None) -> bool:
    """Decision W445: whether a seat-to-seat walk (rise from ``t0`` to ``up``, sit from ``down`` to ``t1``, s; walking
    ``contacts``' start times, s) looks like a TUG (a pure kernel): at most :data:`TUG_MAX_S` long and - with each
    contact's ``length_m`` and ``heading_rad`` - a net displacement of the contacts between ``up`` and ``down`` at
    most :data:`TUG_RETURN_MAX` of their path (it comes back to the chair). Decision L614: ``path_s``, the times the
    lengths and headings belong to when they are not the contacts' (a two-unit foot track's strides). Decision W490:
    with ``turns`` (turns.csv), also :func:`tug_turn_legs`."""
    if t1 - t0 > TUG_MAX_S:
        return False
    c = np.asarray(contacts if path_s is None else path_s, dtype=float)
    inside = (c > up) & (c < down)
    ln = None if length_m is None else np.asarray(length_m, dtype=float)
    if not tug_turn_legs(up, down, turns, c, ln):
        return False
    if ln is None or heading_rad is None:
        return True
    hd = np.asarray(heading_rad, dtype=float)[inside]
    ln = ln[inside]
    ok = np.isfinite(ln) & np.isfinite(hd)
    path = float(ln[ok].sum())
    if path <= 0.0:
        return True
    net = float(np.hypot((ln[ok] * np.cos(hd[ok])).sum(), (ln[ok] * np.sin(hd[ok])).sum()))
    return net <= TUG_RETURN_MAX * path


def turns_inside(turns, up: float, down: float) -> pd.DataFrame:
    """Decision W293: the turns.csv rows (``start_s``, ``end_s``) whose midpoint lies between ``up`` (a rise's end)
    and ``down`` (the next sit's start), by start time."""
    tt = pd.DataFrame(turns) if turns is not None else pd.DataFrame(columns=["start_s", "end_s"])
    mid = 0.5 * (tt["start_s"].to_numpy(float) + tt["end_s"].to_numpy(float))
    return tt[(mid > up) & (mid < down)].sort_values("start_s")


def shape_turns(turns, walk=None, yaw_turns=None):
    """Decision W498 (amends W490 / L614): the turns W490's (d) and (e) judge a TUG's shape on: on a two-unit foot
    track (``walk``, its strides, given) the waist unit's ``yaw_turns`` (W418's ``trunk_yaw_turns``) of at least
    L200's :data:`~pdrlearn.track.clinical.TURN_COUNT_MIN_DEG` - the foot's turns.csv merges a pivot about-turn, the
    walk back and a pivot turn-to-sit into one turn of about 360 deg, the lower back's yaw rate splits them - else
    ``turns`` (turns.csv; None: not judged)."""
    if turns is None or walk is None or yaw_turns is None:
        return turns
    from pdrlearn.track.clinical import TURN_COUNT_MIN_DEG

    yaw = pd.DataFrame(list(yaw_turns), columns=["start_s", "end_s", "angle_deg"])
    return yaw[yaw["angle_deg"].astype(float).abs() >= TURN_COUNT_MIN_DEG]


def tug_turn_legs(up: float, down: float, turns, path_s, length_m=None) -> bool:
    """Decision W490 (a pure kernel): whether the walk between ``up`` (a rise's end) and ``down`` (the sit's start)
    has a TUG's shape: its first turn (:func:`turns_inside` of ``turns``, W293's TUG turn) turns by 180 deg +-
    :data:`TUG_TURN_TOL_DEG`, and - with ``length_m`` per step at ``path_s`` (s) - the steps before that turn's start
    and those after its end each sum to at most :data:`TUG_LEG_MAX_M`. True (not judged) when ``turns`` is None or
    carries no ``angle_deg`` (a table of times only)."""
    if turns is None or "angle_deg" not in pd.DataFrame(turns):
        return True
    inside = turns_inside(turns, up, down)
    if not len(inside):
        return False  # a TUG turns around
    turn = inside.iloc[0]
    if abs(abs(float(turn["angle_deg"])) - 180.0) > TUG_TURN_TOL_DEG:
        return False
    if length_m is None:
        return True
    t = np.asarray(path_s, dtype=float)
    ln = np.nan_to_num(np.abs(np.asarray(length_m, dtype=float)))
    out = ln[(t > up) & (t < float(turn["start_s"]))].sum()
    back = ln[(t > float(turn["end_s"])) & (t < down)].sum()
    return bool(out <= TUG_LEG_MAX_M and back <= TUG_LEG_MAX_M)


def contact_path(steps: pd.DataFrame | None, walk: pd.DataFrame | None = None) -> dict:
    """Decision W445: ``{"length_m", "heading_rad"}`` of the walking contacts (``steps``, a lower-back track's
    steps.csv) for :func:`tug_like`'s return test; empty when they carry none (a two-unit track's trunk contacts).
    Decision L614: ``walk`` (a two-unit foot track's strides) gives them instead, with ``path_s`` their contact times
    (``event_s``, else ``start_s``: W419's step count's)."""
    if walk is not None:
        if not len(walk) or "length_m" not in walk or "heading_rad" not in walk:
            return {}
        col = "event_s" if "event_s" in walk else "start_s"
        return {"path_s": walk[col].to_numpy(float), "length_m": walk["length_m"].to_numpy(float),
                "heading_rad": walk["heading_rad"].to_numpy(float)}
    if steps is None or not len(steps) or "length_m" not in steps or "heading_rad" not in steps:
        return {}
    return {"length_m": steps["length_m"].to_numpy(float), "heading_rad": steps["heading_rad"].to_numpy(float)}


def tug_trial_pairs(kinds, start_s, end_s, flags, contacts, length_m=None, heading_rad=None, *, path_s=None,
                    turns=None) -> list[tuple[int, int]]:
    """Decisions W325, W445: the TUG trials of a transfers table: :func:`seat_to_seat_pairs` that look like a TUG
    (:func:`tug_like`; ``length_m`` / ``heading_rad`` per contact, optional; L614: per ``path_s``; W490: ``turns``)."""
    a, b = np.asarray(start_s, dtype=float), np.asarray(end_s, dtype=float)
    return [(i, j) for i, j in seat_to_seat_pairs(kinds, start_s, end_s, flags, contacts)
            if tug_like(a[i], b[i], a[j], b[j], contacts, length_m, heading_rad, path_s=path_s, turns=turns)]


def chair_walks_note(tr: pd.DataFrame, pairs: list[tuple[int, int]]) -> str:
    """Decision W445: ``tug_time_note`` when every seat-to-seat walk is a chair-to-chair walk (no TUG trial)."""
    rises = ", ".join(f"{float(tr['start_s'].iloc[i]):.1f}" for i, _ in pairs)
    return (f"no TUG time: {len(pairs)} chair-to-chair walk(s) (rises at {rises} s) do not look like a TUG (longer "
            f"than {TUG_MAX_S:g} s, not back to the chair it rose from, no about-turn first, or a walk out or back "
            f"over {TUG_LEG_MAX_M:g} m): daily walks, not timed (W445, W490)")


def trials_note(tr: pd.DataFrame, trials: list[tuple[int, int]]) -> str:
    """Decision W325: ``tug_time_note`` of a recording with TUG ``trials`` (:func:`tug_trial_pairs`) but no single
    ``tug_time_s``: how many, their rises, and where each is timed."""
    rises = ", ".join(f"{float(tr['start_s'].iloc[i]):.1f}" for i, _ in trials)
    return (f"no single TUG time: {len(trials)} TUG trial(s) among {len(tr)} transfers (rises at {rises} s), each "
            "timed in tug_trials.csv; tug_trials_median_s is their median (W183, W325)")


def tug_note(tr: pd.DataFrame, contacts: np.ndarray) -> str:
    """Decision W282: why a transfers table ``tr`` (a sit-to-stand followed by a stand-to-sit) with step ``contacts``
    (start times, s) has no ``tug_time_s`` (W183's rule, module docstring), in one line that points at ``--window``."""
    rise, sit = tr[tr["kind"] == SIT_TO_STAND], tr[tr["kind"] == STAND_TO_SIT]
    first, last = tr.iloc[0], tr.iloc[-1]
    times = (f"the rises start at {', '.join(f'{t:.1f}' for t in rise['start_s'])} s" if len(rise) else "no rise")
    times += f", the sits end at {', '.join(f'{t:.1f}' for t in sit['end_s'])} s" if len(sit) else ", no sit"
    if first["kind"] != SIT_TO_STAND or last["kind"] != STAND_TO_SIT:
        return (f"no TUG time: the recording does not start and end seated (first transfer {first['kind']} at "
                f"{first['start_s']:.1f} s, last {last['kind']} at {last['start_s']:.1f} s; {times}); a TUG is "
                "timed from a rise to the next sit of a session cut with --window START,END around them (W183, W282)")
    if len(tr) > 2:
        return (f"no TUG time: {len(tr)} transfers ({len(rise)} sit-to-stand, {len(sit)} stand-to-sit), not one "
                f"seat-to-seat test ({times}); time each trial with --window START,END around one rise and the "
                "next sit (W183, W282)")
    t0, t1 = float(first["start_s"]), float(last["end_s"])
    if not walked_between(contacts, float(first["end_s"]), float(last["start_s"])):  # decision W340
        return (f"no TUG time: no step between the rise ending at {float(first['end_s']):.1f} s and the sit starting "
                f"at {float(last['start_s']):.1f} s: a chair stand, not a TUG (a TUG walks; if the person walked, the "
                "steps were not detected) (W183, W340)")
    n0, n1 = int((contacts < t0).sum()), int((contacts > t1).sum())
    return (f"no TUG time: {n0} step(s) before the rise at {t0:.1f} s and {n1} after the sit ending at {t1:.1f} s: "
            "not recorded from seat to seat; --window START,END around the rise and the sit times it (W183, W282)")


def upright_message(source: str, n_transfers: int) -> str:
    """Decision W277: the one line of a track whose upright is not the walking one (``source`` ``"still"`` or
    ``"none"``, :func:`chair_transfers_upright`'s)."""
    if source == "still":
        return (f"no walking to take the trunk's upright from: the {n_transfers} chair transfers and the posture times "
                "are read against the trunk's direction while standing still between transfers (decision W277)")
    return ("no walking and no still standing to take the trunk's upright from: the chair transfers and the posture "
            "times cannot be judged and are left empty (unknown; decision W277)")


def unmatched_posture_changes(postures, transfers) -> list[float]:
    """Decision W451: the times (s) where the posture runs (``[start_s, end_s, posture]`` in time order, W222's)
    change between a sitting run of :data:`UNMATCHED_SIT_S` or more and a standing one with no chair transfer
    (``transfers``' sit-to-stand / stand-to-sit rows) whose span widened by :data:`FLAG_WALK_S` holds the change (a
    pure kernel): a rise or a sit that W182 missed, or a posture misread from the tilt."""
    tr = pd.DataFrame(list(transfers) if transfers is not None and not isinstance(transfers, pd.DataFrame)
                      else transfers, columns=list(TRANSFER_COLUMNS)) if transfers is not None else _empty()
    chair = tr[tr["kind"].isin((SIT_TO_STAND, STAND_TO_SIT))]
    a = chair["start_s"].to_numpy(float) - FLAG_WALK_S
    b = chair["end_s"].to_numpy(float) + FLAG_WALK_S
    out = []
    for prev, nxt in zip(postures[:-1], postures[1:], strict=True):
        kinds = {prev[2], nxt[2]}
        if kinds != {"sitting", "standing"}:
            continue
        sit = prev if prev[2] == "sitting" else nxt
        t = float(nxt[0])
        if float(sit[1]) - float(sit[0]) >= UNMATCHED_SIT_S and not ((a <= t) & (t <= b)).any():
            out.append(t)
    return out


def unmatched_message(times: list[float]) -> str | None:
    """Decision W451: one line for :func:`unmatched_posture_changes`' times; None when there is none."""
    if not times:
        return None
    at = ", ".join(f"{t:.1f}" for t in times[:8]) + (", ..." if len(times) > 8 else "")
    return (f"{len(times)} change(s) between sitting and standing (at {at} s) have no chair transfer in "
            "transfers.csv: a slow or small rise or sit was not found (or the posture was misread from the trunk's "
            "tilt), so n_sit_to_stand / n_stand_to_sit may count too few (decision W451)")


def flag_texts(column) -> np.ndarray:
    """Decision W278: a ``flag`` column's texts, ``""`` for a missing one (rows made before W278, lying rows)."""
    return np.array([x if isinstance(x, str) else "" for x in column], dtype=object)


def sequence_flags(kinds, start_s, end_s, walk_s) -> list[str]:
    """Decision W278: per transfer (in time order), ``""`` or why it cannot be taken as read (a pure kernel):
    :data:`NOT_ALTERNATING` when the posture it comes from is not the one the transfer before it went to, or the one
    it goes to not the one the next comes from (two rises in a row: both rows, one is wrong); and
    :data:`WALKING_BOTH_SIDES` when walking contacts (``walk_s``, s) lie within :data:`FLAG_WALK_S` before its start
    and after its end (one does not sit down or rise in mid-walk), joined by ``"; "``."""
    kinds = list(kinds)
    a, b = np.asarray(start_s, dtype=float), np.asarray(end_s, dtype=float)
    w = np.sort(np.asarray(walk_s, dtype=float))
    out = []
    for i, k in enumerate(kinds):
        why = []
        fr, to = _FROM_TO.get(k, (None, None))
        before = _FROM_TO.get(kinds[i - 1], (None, None))[1] if i > 0 else None
        after = _FROM_TO.get(kinds[i + 1], (None, None))[0] if i + 1 < len(kinds) else None
        if (before is not None and fr is not None and before != fr) or (after is not None and to is not None
                                                                          and after != to):
            why.append(NOT_ALTERNATING)
        n_before = np.searchsorted(w, a[i]) - np.searchsorted(w, a[i] - FLAG_WALK_S)
        n_after = np.searchsorted(w, b[i] + FLAG_WALK_S, side="right") - np.searchsorted(w, b[i], side="right")
        if n_before and n_after:
            why.append(WALKING_BOTH_SIDES)
        out.append("; ".join(why))
    return out


def walking_contacts_s(steps: pd.DataFrame) -> np.ndarray:
    """Decision W278: the times (s, ``event_s``) of the contacts of walking sequences: those that start a step
    (``has_next``) and those that end one."""
    if not len(steps) or "event_s" not in steps:
        return np.zeros(0)
    hn = steps["has_next"].to_numpy(bool) if "has_next" in steps else np.ones(len(steps), bool)
    return steps["event_s"].to_numpy(float)[hn | np.r_[False, hn[:-1]]]


def flag_transfers(transfers: pd.DataFrame, steps: pd.DataFrame) -> pd.DataFrame:
    """Decision W278: ``transfers`` (in time order) with the ``flag`` column of :func:`sequence_flags`; only flagged,
    no row dropped."""
    out = transfers.copy()
    out["flag"] = (sequence_flags(out["kind"], out["start_s"], out["end_s"], walking_contacts_s(steps))
                   if len(out) else pd.Series([], dtype=object))
    return out


def flag_message(transfers: pd.DataFrame) -> str | None:
    """Decision W278: one line when transfers are flagged; None when none is."""
    bad = flag_texts(transfers["flag"]) != "" if len(transfers) else np.zeros(0, dtype=bool)
    if not bad.any():
        return None
    rows = ", ".join(f"{int(r.transfer)} ({r.kind} at {r.start_s:.1f} s: {r.flag})"
                     for r in transfers[bad].itertuples())
    return (f"{int(bad.sum())} of the {len(transfers)} transfers cannot be taken as read: {rows}; rises and sits must "
            f"alternate and nobody sits or rises with walking within {FLAG_WALK_S:g} s on both sides (a turn or a "
            "bend can read as one): they are flagged in transfers.csv's flag column and still counted (decision W278)")


def sts5_time_s(transfers: pd.DataFrame, steps: pd.DataFrame | None = None) -> float | None:
    """Decision W279: the five-times sit-to-stand's time, the first sit-to-stand's start to the last stand-to-sit's
    end, when the session's transfers are exactly :data:`STS_RISES` sit-to-stand and as many stand-to-sit,
    alternating from a rise, none flagged (W278), and no walking contact (``steps``' ``has_next``) lies between those
    times outside the transfers; else None."""
    tr = pd.DataFrame(transfers)
    if len(tr) != 2 * STS_RISES:
        return None
    want = [SIT_TO_STAND, STAND_TO_SIT] * STS_RISES
    if tr["kind"].tolist() != want or (flag_texts(tr["flag"]) != "").any():
        return None
    t0, t1 = float(tr["start_s"].iloc[0]), float(tr["end_s"].iloc[-1])
    if steps is not None and len(steps) and "event_s" in steps:
        e = steps["event_s"].to_numpy(float)
        keep = (e > t0) & (e < t1)
        for a, b in zip(tr["start_s"].to_numpy(float), tr["end_s"].to_numpy(float), strict=True):
            keep &= ~((e >= a) & (e <= b))  # a contact inside a transfer (W146) is the rise's bounce
        hn = steps["has_next"].to_numpy(bool) if "has_next" in steps else np.ones(len(e), bool)
        if walking_is_reliable(hn[keep]):  # W277's walking sequence between the rises: not one chair test
            return None
    return t1 - t0


def seated_spans(transfers: pd.DataFrame) -> list[tuple[float, float]]:
    """Decision W487: ``(start_s, end_s)`` from the end of each stand-to-sit transfer (``transfers``: W182's rows,
    ``kind``, ``start_s``, ``end_s``; a W278-flagged row is not read) to the start of the next one when that is a
    sit-to-stand: the span both transfers call seated (W222's votes), where nobody walks."""
    tr = pd.DataFrame(transfers)
    if len(tr) < 2:
        return []
    if "flag" in tr:
        tr = tr[flag_texts(tr["flag"]) == ""]
    tr = tr.sort_values("start_s")
    kind, t0, t1 = tr["kind"].tolist(), tr["start_s"].to_numpy(float), tr["end_s"].to_numpy(float)
    return [(float(t1[k]), float(t0[k + 1])) for k in range(len(tr) - 1)
            if kind[k] == STAND_TO_SIT and kind[k + 1] == SIT_TO_STAND and t0[k + 1] > t1[k]]
