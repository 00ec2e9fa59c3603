"""Decisions L760, L761 (docs/decisions/localization.md): the two foot tracks' relative offset along the walk,
re-anchored at every closing step, and the drift bound a step-length symmetry index carries.

Two foot tracks are two dead-reckoned paths joined only at the standing start (decision L310): where the walker
brings the feet side by side again - a closing step before a turn or a stop - the measured step length of that
closing step is the left track's offset against the right one along the walk (truth: 0). L310 read the walk's last
closing step as a relative scale; a walk of several passes (a corridor's 180 deg turns) moves that offset at each
turn, which no scale describes (trial s50t2: 0.2 m jumps, a 14 % asymmetry read 40 %). Pure functions on the
merged contacts' arrays (:func:`pdrlearn.track.bilateral.merged_contacts`). Decision L782: a pass after a stop
starts where the feet stood side by side (:func:`pass_starts`); L783: :func:`lost_rows`, the steps left without a
length."""
from __future__ import annotations

import numpy as np


def anchor_rows(kinds: np.ndarray, bout: np.ndarray, k: np.ndarray, length: np.ndarray) -> np.ndarray:
    """Decision L760: the rows of a step table (landing contacts ``k`` of the merged contacts, step lengths
    ``length``) that are closing steps: the landing contact is a ``start_stop`` (L538: a bout's end or a stride under
    L310's closing share of the foot's median) followed by a turn (L538's ``turn`` contact), by the bout's end or by
    nothing, with a measured length (the feet side by side: the length is the tracks' offset)."""
    kinds, bout, k = np.asarray(kinds, dtype=object), np.asarray(bout), np.asarray(k, int)
    if not len(k):
        return np.zeros(0, int)
    n = len(kinds)
    nxt = np.minimum(k + 1, n - 1)
    end = (k + 1 >= n) | (bout[nxt] != bout[k])
    turn_next = ~end & (kinds[nxt] == "turn")
    return np.flatnonzero((kinds[k] == "start_stop") & (end | turn_next) & np.isfinite(np.asarray(length, float)))


def anchor_offsets(side: np.ndarray, length: np.ndarray, anchors: np.ndarray) -> np.ndarray:
    """Decision L760: each anchor's offset (m) of the left track against the right along the walk: the closing
    step's length when it lands on the left foot, minus it on the right (L310's ``(left - right) . u``)."""
    side, length = np.asarray(side), np.asarray(length, float)
    return np.where(side[anchors] == "left", length[anchors], -length[anchors])


def short_strides(side: np.ndarray, stride: np.ndarray, *, share: float = 0.75) -> np.ndarray:
    """Decision L760: the merged contacts whose stride (``stride``, m) is under ``share`` (L310's closing share,
    0.75) of the foot's median stride: a stride from or to the feet side by side covers one step."""
    side, stride = np.asarray(side), np.abs(np.asarray(stride, float))
    out = np.zeros(len(side), bool)
    for s in ("left", "right"):
        own = (side == s) & np.isfinite(stride)
        if own.sum() >= 3:
            out |= own & (stride < share * np.median(stride[own]))
    return out


def pass_starts(kinds: np.ndarray, both_side: np.ndarray, ic: np.ndarray, x: np.ndarray, y: np.ndarray,
                d: np.ndarray, short: np.ndarray, k: np.ndarray, length: np.ndarray,
                anchors: np.ndarray, *, bout: np.ndarray | None = None,
                whole_pass: bool = False) -> list[tuple[int, float, float] | None]:
    """Decision L760: for each pass after the first (the steps after anchor p - 1), where the feet stood side by
    side before it: a turn on the spot (the simulator's ``turn:180``) ends with the feet together, so the last
    contact j of L538's ``turn`` kind before the pass's first step with a length and the other foot's contact
    before it (j - 1) are the pair, when the other foot's next stride (j + 1) opens from standing (``short``,
    :func:`short_strides`). Returns per pass ``(row of the pass's first step with a length, offset m of the left
    track against the right along the opening stride's direction, the pair's time ic[j])`` or None (no such pair:
    that pass has no step length). Decision L782: with ``bout`` (the merged contacts' bout numbers), a pass with no
    turn contact before it whose first step lies in a later bout than the anchor (the walker stopped with the feet
    side by side and went on) takes the anchor's landing contact as j, and the time of the new bout's first contact
    ic[j + 1] (a foot track does not drift while it stands, as the first pass starts at the walk's first contact).
    Decision L791 (iii), ``whole_pass``: the pair is the last turn before the pass's own closing step (anchor p), and
    the pass's first step is the first with a length after it, so a pass whose walk lost a closing step never spans
    a turn (L760 interpolated across it); ``d`` may be :func:`segment_axes` (L791 (i): the offset along the axis
    of the segment after the turn)."""
    n = len(kinds)
    out: list[tuple[int, float, float] | None] = []
    for a, b in zip(anchors[:-1], anchors[1:], strict=True):
        rows = np.flatnonzero(np.isfinite(length[a + 1:b])) + a + 1
        if whole_pass:  # decision L791 (iii): the last turn before the pass's own closing step; steps before it none
            turns = np.flatnonzero(kinds[k[a] + 1:k[b]] == "turn") + k[a] + 1
            rows = rows[k[rows] > turns[-1]] if len(turns) else rows
        else:
            turns = [] if not len(rows) else np.flatnonzero(kinds[k[a] + 1:k[rows[0]] + 1] == "turn") + k[a] + 1
        stop = bool(bout is not None and len(rows) and not len(turns) and k[a] + 1 < n
                and bout[k[rows[0]]] != bout[k[a]])  # decision L782: a stop, not a turn, before the pass
        if stop:
            turns = [k[a]]
        if not len(turns) or not 1 <= turns[-1] < n - 1:
            out.append(None)
            continue
        j = turns[-1]
        if both_side[j - 1] == both_side[j] or both_side[j + 1] == both_side[j] or not short[j + 1]:
            out.append(None)
            continue
        nxt = [i for i in (j + 1, j + 2) if i < n and np.isfinite(d[i])]
        u = np.array([np.cos(d[nxt]).sum(), np.sin(d[nxt]).sum()])
        if not nxt or not np.linalg.norm(u) > 0:
            out.append(None)
            continue
        u /= np.linalg.norm(u)
        gap = (x[j - 1] - x[j]) * u[0] + (y[j - 1] - y[j]) * u[1]  # foot at j - 1 minus the foot at j
        out.append((int(rows[0]), float(gap if both_side[j - 1] == "left" else -gap), float(ic[j + 1 if stop else j])))
    return out


def pass_corrected(side: np.ndarray, length: np.ndarray, at: np.ndarray, anchors: np.ndarray,
                   starts: list, *, opened: bool, start: float | None = None) -> np.ndarray:
    """Decision L760: step lengths with the tracks' relative offset taken out, pass by pass. Pass p ends at anchor
    p (:func:`anchor_offsets`, its offset known there) and starts where the offset was last known: 0 at ``start``
    (the walk's first contact) for the first pass of a walk that ``opened`` from standing (L310's opening step),
    else ``starts[p - 1]`` (:func:`pass_starts`: the row of the pass's first step, the offset of the feet side by
    side before it and its time). Inside the pass the offset is interpolated linearly in ``at`` (each step's landing
    contact, s: drift that accumulates with the walking, a Brownian bridge's mean; across a turn it jumps, so never
    across one),
    the left steps minus it, the right steps plus it. Steps of a pass without a known start, after the last anchor,
    in a turn before a pass's first step, and the anchors themselves (the feet side by side) get NaN."""
    side, length, at = np.asarray(side), np.asarray(length, float), np.asarray(at, float)
    out = np.full(len(length), np.nan)
    off = anchor_offsets(side, length, anchors)
    for p, a in enumerate(anchors):
        if p == 0:
            if not opened or start is None:
                continue
            lo, t0, o0 = 0, start, 0.0
        else:
            if starts[p - 1] is None:
                continue
            lo, o0, t0 = starts[p - 1]
        rows = np.arange(lo, a)
        o = np.interp(at[rows], [t0, at[a]], [o0, off[p]])
        out[rows] = np.where(side[rows] == "left", length[rows] - o, length[rows] + o)
    return out


def pass_bound_pct(side: np.ndarray, length: np.ndarray, anchors: np.ndarray, *, min_steps: int = 3) -> float | None:
    """Decision L761: for a walk of several re-anchored passes (L760), 2 x the standard error of the passes'
    signed step-length symmetry indices (100 x (L - R) / (0.5 x (L + R)) of each pass's left and right steps with a
    length, ``min_steps`` a side): a true asymmetry is the same on every pass, each pass's drift its own, so their
    spread shows what the walk's index can be off by. None with under two such passes."""
    side, length = np.asarray(side), np.asarray(length, float)
    p = np.searchsorted(np.asarray(anchors), np.arange(len(length)))
    si = []
    for q in range(len(anchors)):
        lr = [length[(p == q) & (side == s) & np.isfinite(length)] for s in ("left", "right")]
        if min(len(v) for v in lr) >= min_steps:
            a, b = lr[0].mean(), lr[1].mean()
            si.append(100.0 * (a - b) / (0.5 * (a + b)))
    if len(si) < 2:
        return None
    return float(2.0 * np.std(si, ddof=1) / np.sqrt(len(si)))


def drift_bound_pct(first_offset_m: float | None, mean_step_m: float | None) -> float | None:
    """Decision L761: for a walk of one pass (L310's scale), the points of step-length symmetry index the tracks'
    unseen drift can move: 100 x |o| / the mean step length, o the offset the closing step measured (the drift of
    the pass from the standing start); a drift of that size inside the pass, not linear in the distance, reads as
    about that many points. None without an offset or a positive mean step."""
    if first_offset_m is None or mean_step_m is None or not np.isfinite(first_offset_m) or not mean_step_m > 0:
        return None
    return float(100.0 * abs(first_offset_m) / mean_step_m)


def lost_rows(raw: np.ndarray, corrected: np.ndarray, anchors: np.ndarray) -> np.ndarray:
    """Decision L783: the rows of a step table that had a measured length (``raw``) but got none from
    :func:`pass_corrected` (``corrected``): a pass without a known start, steps after the last anchor or in a turn
    before a pass; the anchors themselves (the feet side by side, no step) are not among them."""
    lost = np.isfinite(np.asarray(raw, float)) & ~np.isfinite(np.asarray(corrected, float))
    lost[np.asarray(anchors, int)] = False
    return np.flatnonzero(lost)


def segment_axes(kinds: np.ndarray, bout: np.ndarray, d: np.ndarray) -> np.ndarray:
    """Decision L791 (i): each merged contact's straight-segment axis (rad): the contacts of a bout between two of
    L538's ``turn`` contacts form a segment, its axis the circular mean of its non-turn contacts' stride directions
    ``d`` (both feet); a turn contact's is NaN. Along one axis the two tracks' sideways separation, never re-anchored,
    is a constant inside a pass, which the pass's two anchors take out; each step's own direction reads it into the
    step length by its sine (trial s51t2: 0.26 m wobbles in a 30 m pass)."""
    kinds, bout, d = np.asarray(kinds, dtype=object), np.asarray(bout), np.asarray(d, float)
    turn = kinds == "turn"
    seg = np.cumsum(turn | np.r_[True, bout[1:] != bout[:-1]])
    out = np.full(len(d), np.nan)
    for s in np.unique(seg[~turn]):
        own = (seg == s) & ~turn
        ok = own & np.isfinite(d)
        if ok.any():
            out[own] = np.arctan2(np.sin(d[ok]).sum(), np.cos(d[ok]).sum())
    out[turn] = np.nan
    return out


def axis_lengths(x: np.ndarray, y: np.ndarray, d: np.ndarray, k: np.ndarray, axes: np.ndarray, *,
                 turn_max_deg: float, axis_max_deg: float) -> np.ndarray:
    """Decision L791 (i, ii): the length (m) of the steps ending on the merged contacts ``k`` (from contact k - 1),
    the two feet's rest positions differenced along the landing contact's segment axis (:func:`segment_axes`); NaN
    in a turn (the two strides differ over ``turn_max_deg``, L310's), when the step's own direction (its two strides'
    mean) lies over ``axis_max_deg`` (L310's) off its segment's axis or its opposite, or without positions."""
    x, y, d, axes = (np.asarray(v, float) for v in (x, y, d, axes))
    k = np.asarray(k, int)
    a, b = k, k - 1
    ax = axes[a]
    length = (x[a] - x[b]) * np.cos(ax) + (y[a] - y[b]) * np.sin(ax)
    walk = np.arctan2(np.sin(d[a]) + np.sin(d[b]), np.cos(d[a]) + np.cos(d[b]))
    step = np.angle(np.exp(1j * (d[a] - d[b])))
    with np.errstate(invalid="ignore"):
        bad = (np.abs(step) > np.radians(turn_max_deg)) | (np.abs(np.sin(walk - ax)) > np.sin(np.radians(axis_max_deg)))
    return np.where(bad | ~np.isfinite(length), np.nan, length)
