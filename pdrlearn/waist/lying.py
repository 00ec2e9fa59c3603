"""Lying transfers of the lower-back unit: each sit-to-lie, lie-to-sit, stand-to-lie and lie-to-stand, written to
transfers.csv with W182's chair transfers (decisions W245, W246, docs/decisions/waist.md).

A lying transfer is an edge of W222's lying (:mod:`pdrlearn.waist.posture_time`: the trunk's tilt from the session's
walking upright, averaged over +-1 s, at :data:`~pdrlearn.waist.posture_time.LYING_TILT_DEG` = 60 deg or more) - no
second posture detector:

* **where**: the instant the per-sample tilt passes 60 deg (toward lying at a lying run's start, away from it at its
  end) nearest the averaged tilt's edge, within +-:data:`~pdrlearn.waist.posture_time.POSTURE_HALF_WINDOW_S` (else
  the averaged edge itself); a lying run at the recording's start or end has no transfer there (not seen), and a
  lying run shorter than :data:`MIN_LYING_S` (10 s, W247) has none at all;
* **bounds**: from that instant, backward and forward for as long as the tilt moves toward (away from) lying at
  W182's :data:`~pdrlearn.waist.transfers.MOVING_DPS` or more (its rate over W182's ``RATE_WINDOW_S``): the
  mechanism of W182's :func:`~pdrlearn.waist.transfers.movement_bounds`, along one direction;
* **kind**: the posture on the other side, W222's label (chair transfers and tilt) of the non-lying piece next to
  the lying run, from :data:`SIDE_GAP_S` before the movement's start (after its end) - where the averaged tilt no
  longer sees the movement - or the piece's farthest sample if it is shorter: the posture (standing or sitting) with
  most samples over the :data:`SIDE_WINDOW_S` (10 s, W249) beyond it, inside the piece and not across a W182 chair
  row (W259, adopted: a seen sit on the bed's edge makes the side sitting; a tie: the one sample's);
  sitting gives ``sit-to-lie`` / ``lie-to-sit``, standing ``stand-to-lie`` / ``lie-to-stand``; an unknown side
  (W234) gives no row.

The row's ``peak_s`` is the instant the trunk passes 60 deg, ``peak_tilt_deg`` the largest tilt in the movement,
``height_change_m`` W182's double integral over the movement. Not from a seed: no threshold is new (W222's 60 deg and
1 s, W182's 10 deg/s and 0.25 s) but W247's 10 s and W249's 10 s, each chosen on HAPT users 1-10 and measured on
users 11-30.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.signal import runs
from pdrlearn.waist.ahrs import WaistIMU
from pdrlearn.waist.posture import sample_tilt_deg
from pdrlearn.waist.posture_time import (
    _CODE,
    LYING,
    LYING_TILT_DEG,
    POSTURE_HALF_WINDOW_S,
    SITTING,
    STANDING,
    posture_runs,
    session_labels,
)
from pdrlearn.waist.transfers import (  # decision W245's kinds, defined beside W182's (W258's counts read them)
    LIE_TO_SIT,
    LIE_TO_STAND,
    MOVING_DPS,
    SIT_TO_LIE,
    STAND_TO_LIE,
    TRANSFER_COLUMNS,
    flag_texts,
    height_change_m,
    tilt_rate_dps,
)

LYING_KINDS = (SIT_TO_LIE, LIE_TO_SIT, STAND_TO_LIE, LIE_TO_STAND)
#: decision W245: the other side's posture is read this far (s) outside the movement: W222's averaging half window,
#: so that the averaged tilt there does not see the movement itself
SIDE_GAP_S = POSTURE_HALF_WINDOW_S
#: decision W247 (adopted by its rule; the value chosen on HAPT users 1-10 from {2, 5, 10} s, measured on users
#: 11-30): a run of W222's lying shorter than this (s) gives no transfer - a phone handled while it is put on or taken
#: off reads a few seconds of lying; None = every run gives its edges
MIN_LYING_S: float | None = 10.0
#: decision W249 (adopted by its rule; chosen on HAPT users 1-10 from {3, 5, 10} s, measured on users 11-30): the
#: other side's posture is the one W222 gives most samples (standing or sitting) over this many seconds beyond
#: :data:`SIDE_GAP_S`, inside the non-lying piece - a lying down from standing often sits on the bed first; None = the
#: one sample at :data:`SIDE_GAP_S`
SIDE_WINDOW_S: float | None = 10.0
_KIND = {(+1, _CODE[SITTING]): SIT_TO_LIE, (+1, _CODE[STANDING]): STAND_TO_LIE,
         (-1, _CODE[SITTING]): LIE_TO_SIT, (-1, _CODE[STANDING]): LIE_TO_STAND}


def _crossing(tilt: np.ndarray, i: int, sign: int, half: int) -> int:
    """The sample nearest ``i`` (within +-``half``) where ``tilt`` passes :data:`LYING_TILT_DEG` toward lying
    (``sign`` +1) or away from it (-1); ``i`` when there is none."""
    lo, hi = max(i - half, 1), min(i + half, tilt.size - 1)
    j = np.arange(lo, hi + 1)
    if sign > 0:
        hit = j[(tilt[j - 1] < LYING_TILT_DEG) & (tilt[j] >= LYING_TILT_DEG)]
    else:
        hit = j[(tilt[j - 1] >= LYING_TILT_DEG) & (tilt[j] < LYING_TILT_DEG)]
    return int(hit[np.argmin(np.abs(hit - i))]) if hit.size else i


def _along(rate: np.ndarray, j: int, sign: int) -> tuple[int, int]:
    """W182's bounds along one direction: the samples around ``j`` where ``sign * rate >= MOVING_DPS``."""
    a = b = j
    while a > 0 and sign * rate[a - 1] >= MOVING_DPS:
        a -= 1
    while b < rate.size - 1 and sign * rate[b + 1] >= MOVING_DPS:
        b += 1
    return a, b


def _edge_movement(tilt: np.ndarray, rate: np.ndarray, edge: int, sign: int, half: int) -> tuple[int, int, int]:
    """Decision W245: ``(j, s, e)`` of a lying run's edge at sample ``edge`` (its first sample toward lying, ``sign``
    +1; one past its last away from it, -1): the 60 deg crossing ``j`` nearest it and the movement's bounds around it
    (shared by W269's lying episodes)."""
    j = _crossing(tilt, edge if sign > 0 else edge - 1, sign, half)
    s, e = _along(rate, j, sign)
    return j, s, e


def _side(code: np.ndarray, i: int, lo: int, hi: int, step: int, fs: float) -> int:
    """The other side's posture code: W222's at sample ``i``, or (decision W249's candidate, :data:`SIDE_WINDOW_S`)
    the standing / sitting code with the most samples from ``i`` over the window away from the movement (``step``
    -1: backward), inside ``[lo, hi)``; a tie, or neither in the window, gives the code at ``i``."""
    if SIDE_WINDOW_S is None:
        return int(code[i])
    w = int(round(SIDE_WINDOW_S * fs))
    seg = code[max(i - w, lo):i + 1] if step < 0 else code[i:min(i + w + 1, hi)]
    n_stand, n_sit = int((seg == _CODE[STANDING]).sum()), int((seg == _CODE[SITTING]).sum())
    if n_stand == n_sit:
        return int(code[i])
    return _CODE[STANDING] if n_stand > n_sit else _CODE[SITTING]


def _chair_bound(t: np.ndarray, chair: np.ndarray | None, lo: int, hi: int, sign: int) -> int | None:
    """Decision W259 (adopted): into lying (``sign`` +1), the sample after the last chair row's end inside
    ``[lo, hi)``; out of lying (-1), the sample of the first chair row's start inside ``(lo, hi]``; None when
    none. ``chair``: the chair rows' (start_s, end_s) (k, 2)."""
    if chair is None or not len(chair):
        return None
    idx = np.searchsorted(t, chair[:, 1 if sign > 0 else 0])
    inside = idx[(idx >= lo) & (idx < hi)] if sign > 0 else idx[(idx > lo) & (idx <= hi)]
    if not inside.size:
        return None
    return int(inside.max()) + 1 if sign > 0 else int(inside.min())


def lying_transfer_rows(t: np.ndarray, tilt: np.ndarray, code: np.ndarray, fs: float,
                        acc_v: np.ndarray, chair: np.ndarray | None = None) -> list[dict]:
    """Decision W245 (module docstring; a pure kernel): the lying transfers of a recording as transfers.csv rows
    without their ``transfer`` number. ``tilt``: the per-sample tilt from the walking upright (deg), ``code``: W222's
    :func:`~pdrlearn.waist.posture_time.label_postures` (3 = lying), ``acc_v``: the vertical acceleration (m/s^2),
    ``chair``: W182's rows' (start_s, end_s) (k, 2), read by W259's rule only."""
    t, tilt, code = np.asarray(t, float), np.asarray(tilt, float), np.asarray(code)
    n = t.size
    if n < 3:
        return []
    rate = tilt_rate_dps(t, tilt, fs)
    half, gap = max(int(round(POSTURE_HALF_WINDOW_S * fs)), 1), max(int(round(SIDE_GAP_S * fs)), 1)
    spans = runs(code == _CODE[LYING])
    rows: list[dict] = []
    for k, (a, b) in enumerate(spans):
        lo = spans[k - 1][1] if k else 0  # the non-lying piece before this run: [lo, a); after it: [b, hi)
        hi = spans[k + 1][0] if k + 1 < len(spans) else n
        if MIN_LYING_S is not None and t[b - 1] - t[a] < MIN_LYING_S:  # decision W247's candidate
            continue
        for edge, sign in ((a, +1), (b, -1)):
            if edge in (0, n):  # the recording starts or ends lying: that transfer was not recorded
                continue
            j, s, e = _edge_movement(tilt, rate, edge, sign, half)
            if sign > 0:  # the posture it came from
                if s <= lo:
                    continue
                b0 = _chair_bound(t, chair, lo, s, +1)  # W259: not back across a chair row
                lo2 = b0 if b0 is not None and b0 < s else lo
                side = _side(code, max(s - gap, lo2), lo2, s, -1, fs)
            else:  # the posture it went to
                if e >= hi - 1:
                    continue
                b1 = _chair_bound(t, chair, e, hi - 1, -1)  # W259: not on across a chair row
                hi2 = b1 if b1 is not None and b1 > e + 1 else hi
                side = _side(code, min(e + gap, hi2 - 1), e + 1, hi2, +1, fs)
            kind = _KIND.get((sign, side))
            if kind is None:  # W234: an unknown side names no posture
                continue
            t0, t1 = float(t[s]), float(t[e])
            rows.append({"kind": kind, "start_s": t0, "end_s": t1, "duration_s": t1 - t0, "peak_s": float(t[j]),
                         "peak_tilt_deg": float(np.nanmax(tilt[s:e + 1])),
                         "height_change_m": height_change_m(t, acc_v, s, e)})
    return rows


def lying_episodes(t: np.ndarray, tilt: np.ndarray, code: np.ndarray, fs: float) -> list[tuple[float, float, float,
                                                                                               float]]:
    """Decision W269 (a pure kernel): ``(start, lying, rise, end)`` (s) of each run of W222's lying (``code`` 3) that
    lasts :data:`MIN_LYING_S` or more (W247: a shorter one is no lying down): the lying-down movement's start, its end
    (the lying run's first sample if later), the getting-up movement's start (the run's last sample if earlier) and its
    end, the movements W245's (:func:`_edge_movement`); at the recording's start (end) the movement was not recorded:
    its first (last) sample."""
    t, tilt, code = np.asarray(t, float), np.asarray(tilt, float), np.asarray(code)
    n = t.size
    if n < 3:
        return []
    rate = tilt_rate_dps(t, tilt, fs)
    half = max(int(round(POSTURE_HALF_WINDOW_S * fs)), 1)
    out = []
    for a, b in runs(code == _CODE[LYING]):
        if MIN_LYING_S is not None and t[b - 1] - t[a] < MIN_LYING_S:
            continue
        s0, e0 = (a, a) if a == 0 else _edge_movement(tilt, rate, a, +1, half)[1:]
        s1, e1 = (b - 1, b - 1) if b == n else _edge_movement(tilt, rate, b, -1, half)[1:]
        out.append((float(t[min(s0, a)]), float(t[max(e0, a)]), float(t[min(s1, b - 1)]), float(t[max(e1, b - 1)])))
    return out


def session_lying(imu: WaistIMU, steps: pd.DataFrame, chair: pd.DataFrame
                  ) -> tuple[list[tuple[float, float, float, float]], np.ndarray | None]:
    """Decision W269: ``(episodes, upright)`` of a lower-back track - :func:`lying_episodes` of W222's labels (from
    ``steps``' walking contacts and ``chair``, W182's rows) and W102's walking upright (the trunk's long axis in the
    body frame); ``([], None)`` without an upright."""
    lab = session_labels(imu, steps, chair)
    if lab is None:
        return [], None
    upright, code = lab
    return lying_episodes(imu.t, sample_tilt_deg(imu.up_body, upright), code, imu.fs), upright


def postures_and_transfers(imu: WaistIMU, steps: pd.DataFrame, chair: pd.DataFrame,
                           upright: np.ndarray | None = None) -> tuple[list[list], pd.DataFrame]:
    """Decisions W222 and W245: ``(info["postures"], transfers.csv)`` of a lower-back track - W222's posture runs
    from ``chair`` (W182's rows) and ``steps``' walking contacts, and ``chair`` with the lying transfers added, in
    the order of their start, numbered from 1. ``upright``: W277's, as
    :func:`~pdrlearn.waist.posture_time.session_labels` takes it."""
    lab = session_labels(imu, steps, chair, upright)
    if lab is None:
        return [], chair
    upright, code = lab
    rows = lying_transfer_rows(imu.t, sample_tilt_deg(imu.up_body, upright), code, imu.fs, imu.acc_v,
                               chair[["start_s", "end_s"]].to_numpy(float) if len(chair) else None)
    if not rows:
        return posture_runs(imu.t, code), chair
    parts = [chair.drop(columns="transfer")] if len(chair) else []
    both = pd.concat([*parts, pd.DataFrame(rows)], ignore_index=True)
    both = both.sort_values("start_s", kind="stable").reset_index(drop=True)
    both.insert(0, "transfer", np.arange(1, len(both) + 1))
    both = both.reindex(columns=list(TRANSFER_COLUMNS))
    both["flag"] = flag_texts(both["flag"])  # decision W278: filled in by the track (flag_transfers)
    return posture_runs(imu.t, code), both
