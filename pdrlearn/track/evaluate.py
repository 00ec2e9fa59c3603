"""Metrics of a :class:`~pdrlearn.track.base.TrackResult` against a session's ground truth.

:func:`evaluate_track` is shared by every pipeline; each metric group is a small helper that adds keys
to the result dictionary (add new ones, e.g. step F1 or bout distance, the same way).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.io.session import Session
from pdrlearn.kernels.backward import BACKWARD_MAX_TURN_DEG, backward_mask  # noqa: F401  decision L203
from pdrlearn.track.base import TrackResult
from pdrlearn.track.flags import flag_values


def match_by_overlap(est: pd.DataFrame, ref: pd.DataFrame, *, min_iou: float = 0.5) -> list[tuple[int, int]]:
    """Pairs (est row, ref row) whose ``[start_s, end_s]`` windows overlap best (IoU >= ``min_iou``);
    each reference row is used at most once."""
    if len(est) == 0 or len(ref) == 0:
        return []
    es, ee = est["start_s"].to_numpy(float), est["end_s"].to_numpy(float)
    order = np.argsort(ref["start_s"].to_numpy(float), kind="stable")
    rs, re = ref["start_s"].to_numpy(float)[order], ref["end_s"].to_numpy(float)[order]
    cands = []
    max_len = float(np.max(re - rs)) if len(rs) else 0.0
    for i in range(len(es)):
        lo = int(np.searchsorted(rs, es[i] - max_len, side="left"))
        hi = int(np.searchsorted(rs, ee[i], side="right"))
        for j in range(lo, hi):
            inter = min(ee[i], re[j]) - max(es[i], rs[j])
            if inter <= 0:
                continue
            iou = inter / (max(ee[i], re[j]) - min(es[i], rs[j]))
            if iou >= min_iou:
                cands.append((iou, i, j))
    pairs, used_e, used_r = [], set(), set()
    for _, i, j in sorted(cands, reverse=True):
        if i not in used_e and j not in used_r:
            pairs.append((i, int(order[j])))
            used_e.add(i)
            used_r.add(j)
    return sorted(pairs)


def contact_windows(ref: pd.DataFrame, *, tol_s: float = 1e-3) -> np.ndarray:
    """Steps decision 99: which labelled strides of ``ref`` are windows from contact to contact - ``end_s`` their own
    ``ic_s`` within ``tol_s``, and ``start_s`` their ``pre_ic_s`` within ``tol_s`` or, without ``pre_ic_s``, another
    labelled stride's ``ic_s`` (a chain; ``import --steps``' footfall strides, B338). Native labels (gaitmap's and
    the simulator's mid-stance windows) end after their contact: False."""
    n = len(ref)
    if not n or "ic_s" not in ref:
        return np.zeros(n, dtype=bool)
    ic = pd.to_numeric(ref["ic_s"], errors="coerce").to_numpy(float)
    s, e = ref["start_s"].to_numpy(float), ref["end_s"].to_numpy(float)
    pre = (pd.to_numeric(ref["pre_ic_s"], errors="coerce").to_numpy(float) if "pre_ic_s" in ref
           else np.full(n, np.nan))
    with np.errstate(invalid="ignore"):
        ends = np.abs(e - ic) <= tol_s
        opens = np.where(np.isfinite(pre), np.abs(s - pre) <= tol_s, False)
    chained = np.array([bool(np.any(np.abs(ic[np.isfinite(ic)] - x) <= tol_s)) for x in s], dtype=bool)
    return ends & (opens | (~np.isfinite(pre) & chained))


def match_strides(est: pd.DataFrame, ref: pd.DataFrame, *, min_iou: float = 0.5,
                  by_contact: bool = True) -> list[tuple[int, int]]:
    """Pairs (est row, ref row) of tracked and labelled strides: steps decision 99 - a contact-to-contact labelled
    stride (:func:`contact_windows`) pairs with the tracked row whose initial contact ``event_s`` is its ``ic_s``,
    one-to-one, closest first, within the event tolerance of ``pdrlearn steps`` (steps decision 36's
    ``match_events``, ``DEFAULT_TOLERANCE_S``); every other one by window overlap (:func:`match_by_overlap`, IoU >=
    ``min_iou``) among the tracked rows left. ``by_contact=False``: the overlap alone (before decision 99)."""
    if len(est) == 0 or len(ref) == 0:
        return []
    est, ref = est.reset_index(drop=True), ref.reset_index(drop=True)
    cw = contact_windows(ref) if by_contact and "event_s" in est else np.zeros(len(ref), dtype=bool)
    if not cw.any():
        return match_by_overlap(est, ref, min_iou=min_iou)
    from pdrlearn.steps.evaluate import DEFAULT_TOLERANCE_S, match_events

    ev = pd.to_numeric(est["event_s"], errors="coerce").to_numpy(float)
    ok, rows = np.flatnonzero(np.isfinite(ev)), np.flatnonzero(cw)
    i_d, i_r = match_events(ev[ok], ref["ic_s"].to_numpy(float)[rows], DEFAULT_TOLERANCE_S)  # steps decision 99
    pairs = [(int(ok[i]), int(rows[j])) for i, j in zip(i_d, i_r, strict=True)]
    left_e = np.setdiff1d(np.arange(len(est)), [i for i, _ in pairs])
    left_r = np.flatnonzero(~cw)
    pairs += [(int(left_e[i]), int(left_r[j])) for i, j in
              match_by_overlap(est.iloc[left_e], ref.iloc[left_r], min_iou=min_iou)]
    return sorted(pairs)


def straight_legs(heading_deg: np.ndarray, *, max_change_deg: float = 20.0, min_strides: int = 4) -> list[list[int]]:
    """Runs of consecutive strides whose heading changes by less than ``max_change_deg`` from one stride to
    the next (the straight legs of a walk), keeping runs of at least ``min_strides``: stride indices."""
    legs, cur = [], [0]
    for i in range(1, len(heading_deg)):
        if abs(heading_deg[i] - heading_deg[i - 1]) < max_change_deg:
            cur.append(i)
        else:
            legs.append(cur)
            cur = [i]
    return [g for g in legs + [cur] if len(g) >= min_strides]


def path_length(traj: pd.DataFrame, *, min_spacing_s: float = 0.5) -> float:
    """Horizontal length (m) of a trajectory sampled every ``min_spacing_s`` s (smooths body sway)."""
    t = traj["t"].to_numpy(float)
    if len(t) < 2:
        return 0.0
    grid = np.arange(t[0], t[-1], min_spacing_s)
    grid = np.append(grid, t[-1])
    x = np.interp(grid, t, traj["x"].to_numpy(float))
    y = np.interp(grid, t, traj["y"].to_numpy(float))
    return float(np.hypot(np.diff(x), np.diff(y)).sum())


def heading_change(heading_rad, before, after) -> float:
    """Change (rad) of a heading sequence from the entries ``before`` to the entries ``after`` (index arrays,
    slices or masks): the circular mean of each group, placed on the unwrapped sequence, so a turn beyond
    180 deg keeps its size and sign; NaN when either group is empty. One mechanism for the reference-turn
    metric of :func:`evaluate_track` and the whole-walk turn error of ``experiments/waist.py``."""
    h = np.unwrap(np.asarray(heading_rad, dtype=np.float64))
    means = []
    for sel in (before, after):
        g = h[sel]
        if not g.size:
            return float("nan")
        means.append(g[0] + np.angle(np.mean(np.exp(1j * (g - g[0])))))
    return float(means[1] - means[0])


#: turns smaller than this (deg) do not count in ``turn_sign_agreement`` (a small turn's sign is noise)
TURN_SIGN_MIN_DEG = 45.0
#: the mirrored-turns warning needs at least this many such turns with at most this agreement (decision L42:
#: truthful lower-back sessions gave 0.57 (7 turns), 0.33 / 0.0 (3 turns), 0.91 (11 turns))
TURN_WARN_MIN_TURNS, TURN_WARN_MAX_AGREEMENT = 4, 0.25
#: a turn is compared only when steps lie within this many seconds before its start and after its end
TURN_MAX_REACH_S = 3.0


def _turns(result: TrackResult, session: Session, out: dict) -> None:
    """Sessions with reference turns (``turns.csv``: ``start_s``, ``end_s``, ``angle_deg``, left = positive,
    Mobilise-D/INDIP): per turn the tracked heading change from the last step ending by the turn's start to
    the first step starting from its end (ENU: counter-clockwise = left = positive, the same sign), and
    ``turn_angle_mae_deg``, ``turn_sign_agreement`` (fraction of the turns of at least 45 deg whose tracked
    change has their sign) and ``n_turns`` (turns compared; decision L42)."""
    turns = session.extras.get("turns")
    st = result.steps
    if turns is None or not {"start_s", "end_s", "angle_deg"} <= set(turns) or not len(turns) or len(st) < 2:
        return
    order = np.argsort(st["start_s"].to_numpy(float), kind="stable")
    s0, s1 = st["start_s"].to_numpy(float)[order], st["end_s"].to_numpy(float)[order]
    head = st["heading_rad"].to_numpy(float)[order]
    ref, est = [], []
    for t0, t1, ang in turns[["start_s", "end_s", "angle_deg"]].to_numpy(float):
        if not np.isfinite(ang):
            continue
        before = np.flatnonzero((s1 <= t0) & (s1 >= t0 - TURN_MAX_REACH_S))[-1:]
        after = np.flatnonzero((s0 >= t1) & (s0 <= t1 + TURN_MAX_REACH_S))[:1]
        if not (before.size and after.size):
            continue
        d = heading_change(head[before[0]:after[0] + 1], [0], [-1])  # unwrapped over the steps in between
        ref.append(ang)
        est.append(np.degrees(d))
    out["n_turns"] = len(ref)
    if not ref:
        return
    r, e = np.array(ref), np.array(est)
    out["turn_angle_mae_deg"] = float(np.mean(np.abs(e - r)))
    big = np.abs(r) >= TURN_SIGN_MIN_DEG
    out["n_turns_signed"] = int(big.sum())
    out["turn_sign_agreement"] = float(np.mean(np.sign(e[big]) == np.sign(r[big]))) if big.any() else None


def turn_warning(summary: dict) -> str | None:
    """One warning line when the tracked turns come out mirrored against the reference turns (decision
    L42): at least :data:`TURN_WARN_MIN_TURNS` turns of >= 45 deg, at most :data:`TURN_WARN_MAX_AGREEMENT`
    of them with the reference's sign."""
    n, agree = summary.get("n_turns_signed", 0), summary.get("turn_sign_agreement")
    if agree is None or n < TURN_WARN_MIN_TURNS or agree > TURN_WARN_MAX_AGREEMENT:
        return None
    return (f"{n - round(agree * n)} of {n} reference turns (turns.csv) come out the other way round: the track "
            "is mirrored (left turns go right); check the axis signs - a gyroscope axis negated, or an "
            "accelerometer sign convention such as iOS reporting gravity as -1 g (multiply the accelerometer by "
            "-1 rather than declaring flipped axes in meta.json \"frames\")")


#: decision L64: the storey height (m) the floor count assumes, between the thesis' 2.5 m storeys (ch.4, the
#: barometer test of Figure 44: "the height difference between floors is 2.5 meters") and its 3.8 m scenario D
#: climb (ch.7.3.2.1); the simulator's stairwell storey is 18 stairs x 0.17 m = 3.06 m
STOREY_HEIGHT_M = 3.0
#: decision L64: floor k (k storeys above the start) is reached when the altitude comes within this fraction of
#: a storey of k * STOREY_HEIGHT_M; between the bands (0.4-0.6 of a storey: a half-storey landing) the floor
#: stays the last one reached, so sway and landings do not count
STOREY_BAND = 0.4


def count_floors(z, storey_height_m: float = STOREY_HEIGHT_M, band: float = STOREY_BAND) -> tuple[int, int, int]:
    """Storeys climbed and descended along an altitude track ``z`` (m, in walking order) and the floor it ends
    on, relative to its first value: ``(floors_up, floors_down, storeys_changed)`` (decision L64). A floor k is
    reached when ``|z - z[0] - k h| <= band h`` (h = ``storey_height_m``); each change of the floor reached adds
    its storeys to the up or down count. Non-finite values are skipped."""
    z = np.asarray(z, dtype=float).ravel()
    levels = floor_levels(z[np.isfinite(z)], storey_height_m, band)
    steps = np.diff(np.concatenate([[0], levels]))
    return int(steps[steps > 0].sum()), int(-steps[steps < 0].sum()), int(levels[-1]) if len(levels) else 0


def floor_levels(z, storey_height_m: float = STOREY_HEIGHT_M, band: float = STOREY_BAND) -> np.ndarray:
    """Decision L64's floor per sample of an altitude track ``z`` (m, relative to its first finite value): floor k
    once ``|z - z[0] - k h| <= band h``, else the last floor reached (0 before any; NaN samples keep it) - the rule
    :func:`count_floors` counts on, and trajectory.csv's ``floor`` where no climbs are counted (decision L631)."""
    z = np.asarray(z, dtype=float).ravel()
    out = np.zeros(len(z), dtype=int)
    ok = np.flatnonzero(np.isfinite(z))
    if not len(ok):
        return out
    rel = (z - z[ok[0]]) / storey_height_m
    level = 0
    for i in range(len(z)):
        if np.isfinite(rel[i]) and abs(rel[i] - np.rint(rel[i])) <= band:  # inside a floor's band
            level = int(np.rint(rel[i]))
        out[i] = level
    return out


#: decision L127: at most this many level strides between two stair strides of one climb (a landing and its U-turn)
CLIMB_BRIDGE_STRIDES = 4


#: decision L337: the centred window (strides; x STEPS_PER_STRIDE on the lower back) whose grade (summed dz over summed
#: horizontal length) makes a row a climb row when it reaches L301's RAMP_MIN_GRADE_PCT: ~10 m, longer than a 1:12
#: ramp run between landings (ADA 2010 sec. 405.6: 30 in of rise = 9.1 m), so a landing does not break the climb
CLIMB_SLOPE_WINDOW_STRIDES = 7


def count_floors_by_climb(dz, storey_height_m: float = STOREY_HEIGHT_M, band: float = STOREY_BAND,
                          bridge: int = CLIMB_BRIDGE_STRIDES, slope: bool | None = None,
                          slope_rows=None, parts=None) -> tuple[int, int, int]:
    """Storeys climbed and descended counted per climb from the strides' height changes ``dz`` (m, one per
    stride in walking order): ``(floors_up, floors_down, storeys_changed)`` (decision L127). A climb up (down)
    is a run of up (down) stair strides, dz >= ``LEVEL_DZ_M`` (<= -``LEVEL_DZ_M``, L39), with at most
    ``bridge`` other strides between two of them; its height H (the sum of dz from its first to its last stair
    stride) counts floor(|H| / h + band) storeys, the storeys of L64's band rule, so a slow altitude drift
    between climbs moves no count. Non-finite dz count as 0. ``slope`` (default ``SUSTAINED_SLOPE``, decision
    L144): the strides of a sustained slope (``kernels.distance.sustained_slope``) count as stair strides too.
    ``slope_rows`` (decision L337, :func:`climb_slope_rows`; None: none): per row +1 / -1 where a sustained grade up /
    down makes it a climb row of that sign. ``parts`` (decisions L374-L376, :func:`_climb_parts`): the rows' rides and
    W108's climb rows."""
    climbs = [n for _, n in floor_climbs(dz, storey_height_m, band, bridge, slope, slope_rows, parts)]
    up, down = sum(n for n in climbs if n > 0), -sum(n for n in climbs if n < 0)
    return up, down, up - down


def floor_climbs(dz, storey_height_m: float = STOREY_HEIGHT_M, band: float = STOREY_BAND,
                 bridge: int = CLIMB_BRIDGE_STRIDES, slope: bool | None = None,
                 slope_rows=None, parts=None) -> list[tuple[int, int]]:
    """:func:`count_floors_by_climb`'s climbs that count a storey (decision L127), as ``(last, storeys)``: the index
    of the climb's last stair stride and its storeys, + up / - down (decision L277: periods.csv places each climb's
    storeys in the period of its last stair stride, so the periods' floors add up to the summary's)."""

    return [(int(r[-1]), n) for r, n in _climb_runs(dz, storey_height_m, band, bridge, slope,
                                                    slope_rows=slope_rows, parts=parts)]


def _climb_runs(dz, storey_height_m: float, band: float, bridge: int, slope: bool | None, every: bool = False,
                slope_rows=None, parts=None):
    """:func:`floor_climbs`' climbs as ``(stair rows, storeys)`` (decision L127; L302 reads their rows); ``every``:
    also the climbs under a storey (storeys 0, sign lost; decision L303 reads their rows); ``slope_rows`` (L337):
    +1 / -1 rows that are climb rows of that sign whatever their own dz. ``parts`` (:func:`_climb_parts`, decisions
    L374, L375): the rows' rides and W108's signed climb rows; None: none of either."""
    return [(r, n) for r, n, _ in _climbs(dz, storey_height_m, band, bridge, slope, every, slope_rows, parts)]


def _climbs(dz, storey_height_m: float, band: float, bridge: int, slope: bool | None, every: bool = False,
            slope_rows=None, parts=None):
    """:func:`_climb_runs`' climbs as ``(rows, storeys, ride)``: ``ride`` the kind of a ride's climb (decisions L375,
    L376: the one row whose standstill carried it, ``"lift"`` / ``"escalator"`` / ``"other"``, or ``"ride"`` without
    L376's kinds), ``""`` for a walking climb. A walking climb is a run of stair rows (L127: |dz| >= ``LEVEL_DZ_M``;
    decision L374: W108's climb rows where ``parts`` has them) bridged over at most ``bridge`` rows and never across a
    ride; its height leaves the rides out and its storeys carry its height's sign (L374: a run whose height is of the
    other sign counts none). An "other" or a "vehicle" ride counts no storey (L376, L615)."""
    from pdrlearn.kernels import distance
    from pdrlearn.kernels.pause_ride import NO_STOREY_KINDS  # decision L615: a vehicle's climb counts none either

    dz = np.nan_to_num(np.asarray(dz, dtype=float).ravel(), nan=0.0, posinf=0.0, neginf=0.0)
    ride, ride_kind, climb_sign = (np.zeros(len(dz)), None, None) if parts is None else parts
    walk = dz - ride
    sloped = (distance.sustained_slope(walk) if (distance.SUSTAINED_SLOPE if slope is None else slope)
              else np.zeros(len(dz), dtype=bool))
    grade = np.zeros(len(dz), dtype=int) if slope_rows is None else np.asarray(slope_rows, dtype=int).ravel()
    rides = np.flatnonzero(ride != 0)
    out = []
    for sign in (1, -1):
        base = sign * walk >= distance.LEVEL_DZ_M if climb_sign is None else climb_sign == sign  # decision L374
        stair = np.flatnonzero(base | (sloped & (sign * walk > 0)) | (sign * grade > 0))
        if not len(stair):
            continue
        cut = (np.diff(stair) > bridge + 1) | (np.searchsorted(rides, stair[1:], side="right")
                                               > np.searchsorted(rides, stair[:-1], side="right"))  # L375
        for r in np.split(stair, np.flatnonzero(cut) + 1):
            height = sign * float(walk[r[0]:r[-1] + 1].sum())
            n = int(np.floor(max(height, 0.0) / storey_height_m + band))  # decision L374: the height's sign
            if n or every:
                out.append((r, sign * n, ""))
    for k in rides:  # decision L375: each ride a climb of its own
        kind = "ride" if ride_kind is None else str(ride_kind[k])
        n = 0 if kind in NO_STOREY_KINDS else int(np.floor(abs(float(ride[k])) / storey_height_m + band))  # L376
        if n or every:
            out.append((np.array([k]), int(np.sign(ride[k])) * n, kind))
    return sorted(out, key=lambda c: (int(c[0][-1]), c[2] == ""))


def _climb_parts(steps: pd.DataFrame):
    """Decisions L374, L375: ``(ride, kind, climb_sign)`` per row of the steps: ``ride`` the standstill change
    (W158's ``pause_dz_m``) where it is W231's ``RIDE_MIN_M`` or more (a ride), else 0; ``kind`` steps.csv's ``ride``
    column (L376; None without it); ``climb_sign`` +1 / -1 on a lower-back track's W108 climb rows (steps.csv
    ``climb``; each run of them signed by its walking height), 0 elsewhere, None without the column or on a foot."""
    from pdrlearn.kernels.barometer import climb_turn_pieces
    from pdrlearn.kernels.pause_ride import RIDE_MIN_M

    pause = np.nan_to_num(steps["pause_dz_m"].to_numpy(float)) if "pause_dz_m" in steps else np.zeros(len(steps))
    ride = np.where(np.abs(pause) >= RIDE_MIN_M, pause, 0.0)
    kind = np.array([v if isinstance(v, str) else "" for v in steps["ride"]], dtype=object) if "ride" in steps else None
    units = set(steps["unit"].astype(str)) if "unit" in steps else {"foot"}
    if "climb" not in steps or units != {"waist"}:
        return ride, kind, None
    on = flag_values(steps["climb"])
    walk = np.nan_to_num(steps["dz_m"].to_numpy(float)) if "dz_m" in steps else np.zeros(len(steps))
    sign = np.zeros(len(steps), dtype=int)
    edges = np.flatnonzero(np.diff(np.concatenate([[0], on.astype(int), [0]])))
    for a, b in zip(edges[::2], edges[1::2], strict=True):
        for p, q in climb_turn_pieces(walk[a:b]):  # decision W526: an up and a down flight, adjacent, are two climbs
            sign[a + p:a + q] = int(np.sign(walk[a + p:a + q].sum()))
    return ride, kind, sign


def climb_inputs(result) -> tuple:
    """``(dz, bridge, parts, slope_rows)`` that L127's per-climb floor count reads from a track ``result``'s steps
    (:func:`_climb_dz`; decisions L374-L376's parts, L394's rides after the last step, L337's slope rows); ``dz``
    None where the floors are counted on the altitude instead. One reading for the summary's floors and
    trajectory.csv's ``floor`` (decision L631)."""
    dz, bridge = _climb_dz(result.steps)
    parts = _climb_parts(result.steps) if dz is not None else None  # decisions L374-L376
    dz, parts, slope_rows = _with_after(result.steps, result.info, dz, parts,  # decision L394
                                        climb_slope_rows(result.steps, result.info))  # decision L337
    return dz, bridge, parts, slope_rows


def _with_after(steps: pd.DataFrame, info: dict | None, dz, parts, slope_rows):
    """Decision L394: ``(dz, parts, slope_rows)`` with one row more per ride after the last step (``info["rides"]``'s
    ``row`` n: a standstill that precedes no step), so its storeys count as a ride's (L375, L376)."""
    after = [r for r in (info or {}).get("rides") or [] if int(r.get("row", -1)) >= len(steps)]
    if dz is None or not after:
        return dz, parts, slope_rows
    m = len(after)
    extra = np.array([float(r["dz_m"]) for r in after])
    ride, kind, sign = parts
    kinds = None if kind is None else np.concatenate([kind, np.array([r["kind"] for r in after], dtype=object)])
    return (np.concatenate([np.asarray(dz, dtype=float), extra]),
            (np.concatenate([ride, extra]), kinds, None if sign is None else np.concatenate([sign, np.zeros(m, int)])),
            None if slope_rows is None else np.concatenate([np.asarray(slope_rows, dtype=int), np.zeros(m, int)]))


#: decision L302: what a climb's storeys climbed, the keys floors_up_<kind> / floors_down_<kind> split L127's count by
CLIMB_KINDS = ("stairs", "ramps", "rides")


def climb_kind(dz, pause_dz, length, rows, on_stairs=None, stair_grade_pct: float | None = None,
               long_slopes: bool = False) -> str:
    """Decision L302: what climbed one climb of :func:`floor_climbs` (its ``rows``, first to last stair row, of the
    rows' walking height change ``dz``, standstill change ``pause_dz`` (W158) and horizontal ``length``): ``"rides"``
    when the standstills from its first to its last stair row carry more than half its height (a lift or escalator
    ride), ``"ramps"`` when its stair rows' rise over their horizontal run is under
    :data:`pdrlearn.track.grade.STAIR_MIN_GRADE_PCT` (a ramp or a hill, not a stair), else ``"stairs"`` - the stair
    rows alone, as a landing's and a U-turn's bridged rows would flatten a stairwell (L302's measurement).
    Decision L314: a climb of which more than half the stair rows are ``on_stairs`` (a lower-back track's W108 climbs,
    :func:`pdrlearn.track.grade.climb_rows`) is "stairs" (or "rides"), whatever its grade. Decision L463:
    ``stair_grade_pct`` (None: L301's 20 %) is the unit's stair grade,
    :func:`pdrlearn.track.grade.stair_min_grade_pct`. Decision L788 (``long_slopes``, a foot track's): a climb of
    which at least half the height is walked in :func:`pdrlearn.track.grade.long_slope_rows` (a run of stair strides
    far longer than a building's flight, at a slope's grade) is "ramps"."""
    from pdrlearn.track.grade import STAIR_MIN_GRADE_PCT

    stair_grade = STAIR_MIN_GRADE_PCT if stair_grade_pct is None else stair_grade_pct

    rows = np.asarray(rows, dtype=int)
    span = slice(int(rows[0]), int(rows[-1]) + 1)
    walked, ride = float(np.sum(dz[span])), float(np.sum(pause_dz[span]))
    if abs(ride) > abs(walked + ride) / 2:
        return "rides"
    if on_stairs is not None and 2 * int(np.count_nonzero(np.asarray(on_stairs, bool)[rows])) > len(rows):
        return "stairs"  # decision L314
    if long_slopes and _long_slope_share(dz, length, rows) >= 0.5:  # decision L788
        return "ramps"
    run = float(np.sum(np.abs(length[rows])))
    return "ramps" if run > 0 and 100.0 * abs(float(np.sum(dz[rows]))) / run < stair_grade else "stairs"


def _long_slope_share(dz, length, rows) -> float:
    """Decision L788: the share of the ``rows``' |height change| walked in
    :func:`pdrlearn.track.grade.long_slope_rows` of their L179 stair rows (|dz| >= ``LEVEL_DZ_M``); 0 without height."""
    from pdrlearn.kernels.distance import LEVEL_DZ_M
    from pdrlearn.track.grade import long_slope_rows

    stair = np.zeros(len(dz), bool)
    stair[rows] = np.abs(np.asarray(dz, dtype=float)[rows]) >= LEVEL_DZ_M
    slope = long_slope_rows(dz, length, stair)
    total = float(np.sum(np.abs(dz[rows])))
    return float(np.sum(np.abs(dz[rows][slope[rows]]))) / total if total > 0 else 0.0


def _foot_rows(steps: pd.DataFrame) -> bool:
    """Decision L788: a foot track's rows (a table without ``unit``: a foot track)."""
    return "unit" not in steps or set(steps["unit"].astype(str)) == {"foot"}


def _climb_inputs(steps: pd.DataFrame):
    """:func:`climb_kind`'s per-row inputs from the steps, NaN read as 0: the walking height change ``dz_m``, the
    standstill change ``pause_dz_m`` (W158) and the horizontal ``length_m``, zeros for a missing column - one reading
    for decisions L302 (:func:`floors_by_kind`) and L303 (:func:`ramp_climb_rows`)."""
    def column(name):
        return np.nan_to_num(steps[name].to_numpy(float)) if name in steps else np.zeros(len(steps))
    return column("dz_m"), column("pause_dz_m"), column("length_m")


def climb_slope_rows(steps: pd.DataFrame, info: dict | None = None) -> np.ndarray | None:
    """Decision L337 (adopted by L338's rule: L339; decision L595: the rule, no module switch): where the altitude
    measures a slope a row inside a sustained grade is a climb row too, so a ramp's or hill's floors come from its
    whole rise - per row +1 / -1 where the grade of the centred window of :data:`CLIMB_SLOPE_WINDOW_STRIDES`
    strides (x :data:`STEPS_PER_STRIDE`) around it is at least L301's ``RAMP_MIN_GRADE_PCT`` up / down, else 0 - only
    where the altitude measures a slope (L300's :func:`pdrlearn.track.grade.grade_source`); None elsewhere and for a
    table not counted per climb."""
    from pdrlearn.track.grade import RAMP_MIN_GRADE_PCT, grade_source, window_grades_pct

    if _climb_dz(steps)[0] is None or grade_source(steps, info) is None:
        return None
    walked, _, length = _climb_inputs(steps)
    g = window_grades_pct(length, walked, CLIMB_SLOPE_WINDOW_STRIDES * STEPS_PER_STRIDE[str(steps["unit"].iloc[0])]
                          if "unit" in steps else CLIMB_SLOPE_WINDOW_STRIDES)
    return np.where(np.abs(g) >= RAMP_MIN_GRADE_PCT, np.sign(g), 0).astype(int)


def _kind_rows(rows, dz, slope_rows) -> np.ndarray:
    """Decision L337: the rows :func:`climb_kind` judges a climb on - its rows (L127's stair rows) without
    ``slope_rows``; with them, its L127 stair rows (|dz| >= ``LEVEL_DZ_M``) when they carry at least half its height
    (a stair flight), else all its rows (a ramp, whose few noisy 0.10 m rows would read as stair steps)."""
    from pdrlearn.kernels.distance import LEVEL_DZ_M

    rows = np.asarray(rows, dtype=int)
    if slope_rows is None:
        return rows
    stair = rows[np.abs(dz[rows]) >= LEVEL_DZ_M]
    height = abs(float(np.sum(dz[int(rows[0]):int(rows[-1]) + 1])))
    return stair if len(stair) and abs(float(np.sum(dz[stair]))) >= height / 2 else rows


def ramp_climb_rows(steps: pd.DataFrame, info: dict | None = None) -> np.ndarray:
    """Decision L303: the rows of the climbs (L127's runs of stair rows and the rows bridged between them, any height,
    :func:`_climb_runs` with ``every``) that :func:`climb_kind` calls ``"ramps"``: walked under
    :data:`pdrlearn.track.grade.STAIR_MIN_GRADE_PCT` of rise over horizontal run. All False where floors are not
    counted per climb."""
    out = np.zeros(len(steps), bool)
    dz, bridge = _climb_dz(steps)
    if dz is None:
        return out
    walked, pause, length = _climb_inputs(steps)
    from pdrlearn.track.grade import climb_rows, stair_min_grade_pct

    on_stairs = climb_rows(steps, info)  # decisions L314, L330
    stair_grade = stair_min_grade_pct(steps)  # decision L463
    foot = _foot_rows(steps)  # decision L788
    slope_rows = climb_slope_rows(steps, info)  # decision L337
    parts = _climb_parts(steps)  # decisions L374, L375
    for rows, _, ride in _climbs(dz, STOREY_HEIGHT_M, STOREY_BAND, bridge, None, every=True, slope_rows=slope_rows,
                                 parts=parts):
        if not ride and climb_kind(walked, pause - parts[0], length, _kind_rows(rows, dz, slope_rows),
                                   on_stairs, stair_grade, long_slopes=foot) == "ramps":
            out[int(rows[0]):int(rows[-1]) + 1] = True
    return out


def floors_by_kind(steps: pd.DataFrame, storey_height_m: float = STOREY_HEIGHT_M, info: dict | None = None) -> dict:
    """Decision L302: ``floors_up_<kind>`` / ``floors_down_<kind>`` for each of :data:`CLIMB_KINDS`, the storeys of
    L127's climbs (:func:`floor_climbs` on :func:`_climb_dz`) by :func:`climb_kind`, so each direction's sum is
    ``floors_up`` / ``floors_down``; None for every key where the floors are not counted per climb."""
    dz, bridge = _climb_dz(steps)
    out = {f"floors_{d}_{k}": None for d in ("up", "down") for k in CLIMB_KINDS}
    if dz is None:
        return out
    out.update({k: 0 for k in out})
    walked, pause, length = _climb_inputs(steps)
    from pdrlearn.track.grade import climb_rows, stair_min_grade_pct

    on_stairs = climb_rows(steps, info)  # decisions L314, L330
    stair_grade = stair_min_grade_pct(steps)  # decision L463
    foot = _foot_rows(steps)  # decision L788
    slope_rows = climb_slope_rows(steps, info)  # decision L337
    parts = _climb_parts(steps)  # decisions L374-L376: a ride is a climb of its own, "rides"
    dz, parts, slope_rows = _with_after(steps, info, dz, parts, slope_rows)  # decision L394
    for rows, n, ride in _climbs(dz, storey_height_m, STOREY_BAND, bridge, None, slope_rows=slope_rows, parts=parts):
        # decision W610: parts carry L394's rides after the last step, rows the steps never reach
        kind = "rides" if ride else climb_kind(walked, pause - parts[0][:len(pause)], length,
                                               _kind_rows(rows, dz, slope_rows), on_stairs, stair_grade,
                                               long_slopes=foot)  # decision L788
        key = f"floors_{'up' if n > 0 else 'down'}_{kind}"
        out[key] += abs(n)
    return out


#: decision L127: how the tracked storeys are counted on foot strides - "climb" (per climb, from the strides' dz,
#: :func:`count_floors_by_climb`) or "altitude" (L64's bands on the absolute z, :func:`count_floors`)
FLOOR_COUNT = "climb"


def _floors(z, out: dict, suffix: str = "", dz=None, bridge: int = CLIMB_BRIDGE_STRIDES, slope_rows=None,
            parts=None) -> None:
    """The floor keys (decisions L64, L127) in storeys of ``out["storey_height_m"]``: per climb from the steps'
    ``dz`` when given (FLOOR_COUNT "climb"; ``bridge`` steps between two stair steps of a climb; ``slope_rows``:
    L337's), else from the altitude ``z``."""
    h = out.get("storey_height_m", STOREY_HEIGHT_M)
    up, down, net = (count_floors_by_climb(dz, h, bridge=bridge, slope_rows=slope_rows, parts=parts) if dz is not None
                     else count_floors(z, h))
    out[f"floors_up{suffix}"], out[f"floors_down{suffix}"], out[f"storeys_changed{suffix}"] = up, down, net


#: decision L172: a lower-back step is half a stride, so a climb bridges twice L127's strides in steps
STEPS_PER_STRIDE = {"foot": 1, "waist": 2}


def _climb_dz(steps: pd.DataFrame):
    """The steps' height changes and the bridge (in steps) a floor count per climb reads (decisions L127, L172):
    a foot track's strides' ``dz_m`` and a lower-back track's steps' (their barometric change, W89), so a slow
    drift of the barometer joins no climb; None for steps of mixed units or FLOOR_COUNT "altitude"."""
    if FLOOR_COUNT != "climb" or not len(steps) or "dz_m" not in steps:
        return None, CLIMB_BRIDGE_STRIDES
    units = set(steps["unit"].astype(str)) if "unit" in steps else {"foot"}
    if len(units) != 1 or next(iter(units)) not in STEPS_PER_STRIDE:
        return None, CLIMB_BRIDGE_STRIDES
    dz = steps["dz_m"].to_numpy(float)
    if "pause_dz_m" in steps:  # W158: a ride during a standstill (a lift) is a change of floor as a climb is
        dz = dz + np.nan_to_num(steps["pause_dz_m"].to_numpy(float))
    return dz, CLIMB_BRIDGE_STRIDES * STEPS_PER_STRIDE[next(iter(units))]


#: decision L743: a distance error against a reference shorter than this (m) is printed in metres, not in percent
#: (under about one and a half adult strides of 1.3-1.4 m: one stride more or less is 50-100 % of it)
DISTANCE_PCT_MIN_REF_M = 2.0


def distance_error_text(err_pct: float, ref_m: float | None) -> str:
    """Decision L743: the summary line's distance error, "+1.23 %", or in metres (the compared distance minus the
    reference, ``err_pct`` x ``ref_m`` / 100) when the reference ``ref_m`` is under :data:`DISTANCE_PCT_MIN_REF_M`."""
    if ref_m is None or not ref_m < DISTANCE_PCT_MIN_REF_M:
        return f"{err_pct:+.2f} %"
    return (f"{err_pct * ref_m / 100:+.2f} m (reference {ref_m:.2f} m: under {DISTANCE_PCT_MIN_REF_M:g} m, no "
            "percent, L743)")


def floors_phrase(summary: dict) -> str:
    """The one-line summaries' floor part (``track`` and ``run``, decisions L64, L127): ", floors up U / down D"
    when the track changed floors, and once whether a barometer file lay unused (``barometer_unused``); then (decision
    L473) the storey the walk ended on, ``storeys_changed`` from the start: ", end floor +N"."""
    if not (summary.get("floors_up") or summary.get("floors_down") or summary.get("barometer_unused")):
        return ""
    part = f", floors up {summary.get('floors_up', 0)} / down {summary.get('floors_down', 0)}"
    if summary.get("barometer_unused"):  # a recorded barometer the foot track does not read: say it
        part += (f" (foot altitude, storeys of {summary.get('storey_height_m', STOREY_HEIGHT_M):g} m; "
                 + ("wBarometer.csv read for rides only, L378)" if summary.get("n_rides") is not None
                    else "wBarometer.csv not used)"))
    if summary.get("storeys_changed") is not None:  # decision L473: the net storey, a responder's key number
        part += f", end floor {int(summary['storeys_changed']):+d}"
    return part


#: decision L103: the value of ``n_steps_counts`` per unit of the step table
STEP_COUNT_KINDS = {"foot": "strides of the tracked foot", "waist": "steps of both feet"}


def step_counts(steps: pd.DataFrame) -> dict:
    """Decision L103: ``n_steps`` (the rows of steps.csv, the JSON contract's key) counts strides of the tracked
    foot for a foot track and steps of either foot for a lower-back track; say which and give both counts.
    ``n_steps_counts``: :data:`STEP_COUNT_KINDS`' text (None for an empty table); ``n_strides_one_foot``: foot,
    the rows that are strides (a gap row, ``gap_s`` > 0, is none, L67); None on the lower back, which does not
    tell the feet apart; ``n_steps_both_feet``: lower back, its detected steps (= ``n_steps``); foot, 2 per
    stride of the tracked foot - an estimate, the other foot is not measured (each walking bout can end with
    one step more or less: the closing step)."""
    units = set(steps["unit"].astype(str)) if len(steps) and "unit" in steps else set()
    if units == {"foot"}:
        n = int((steps["gap_s"].to_numpy(float) == 0).sum()) if "gap_s" in steps else int(len(steps))
        return {"n_steps_counts": STEP_COUNT_KINDS["foot"], "n_strides_one_foot": n, "n_steps_both_feet": 2 * n}
    if units == {"waist"}:
        return {"n_steps_counts": STEP_COUNT_KINDS["waist"], "n_strides_one_foot": None,
                "n_steps_both_feet": int(len(steps))}
    return {"n_steps_counts": None, "n_strides_one_foot": None if len(steps) else 0,
            "n_steps_both_feet": None if len(steps) else 0}


def median_stride_length(steps: pd.DataFrame) -> float | None:
    """``median_stride_length_m`` (decisions C12, C19): the median |length_m| of a foot track's strides, without
    the 0 m rows that stand for a foot gap (``gap_s`` > 0, L67: no stride) or a stride the last-line guard moved
    0 m (``impossible``, L97); decision W537: on a lower-back track (its rows are steps of either foot) the median
    of :func:`waist_stride_lengths`; None without strides."""
    length = stride_lengths(steps)
    if length is None:
        length = waist_stride_lengths(steps)  # decision W537
    return float(pd.Series(length).median()) if length is not None and len(length) else None


def waist_stride_lengths(steps: pd.DataFrame) -> np.ndarray | None:
    """Decision W537: a lower-back track's stride lengths (m), each two consecutive steps' |length_m| summed - the
    stride from contact k to contact k + 2 as bouts.csv counts its ``n_strides`` (mobgap's, ``n_steps`` - 2) and
    forms its ``stride_length_m`` (L166: 2 x its steps' mean length), one step of each foot so a left / right
    asymmetry does not bias it. Both steps must continue their walking sequence (``has_next``: a row without a next
    contact is the 0 m closing one, W70) and neither may be a row ``--steady-trim`` cuts (L415). None for a table
    that is not a lower-back one (or lacks ``has_next`` / ``length_m``)."""
    from pdrlearn.track.clinical import _is_lower_back

    if not _is_lower_back(steps) or not {"has_next", "length_m", "start_s"} <= set(steps):
        return None
    from pdrlearn.track.steady import trimmed_rows

    order = steps["start_s"].reset_index(drop=True).sort_values(kind="stable").index.to_numpy()
    length = np.abs(pd.to_numeric(steps["length_m"], errors="coerce").to_numpy(float))[order]
    ok = (flag_values(steps["has_next"]) & ~trimmed_rows(steps))[order] & np.isfinite(length)
    pair = ok[:-1] & ok[1:]
    return (length[:-1] + length[1:])[pair]


def stride_lengths(steps: pd.DataFrame) -> np.ndarray | None:
    """The |length_m| (m) :func:`median_stride_length` takes the median of: a foot track's strides, without a gap
    row (L67), a stride L97's guard zeroed or one ``--steady-trim`` cut (L415); None for a lower-back track.
    Decision C146: subjects.csv's pooled median stride length pools these over a subject's sessions."""
    units = set(steps["unit"].astype(str)) if len(steps) and "unit" in steps else set()
    if units != {"foot"} or "length_m" not in steps:
        return None
    length = steps["length_m"].abs()
    drop = steps["gap_s"].to_numpy(float) > 0 if "gap_s" in steps else np.zeros(len(steps), bool)
    if "impossible" in steps:
        drop = drop | steps["impossible"].eq(True).to_numpy(bool)
    from pdrlearn.track.steady import trimmed_rows

    return length[~(drop | trimmed_rows(steps))].to_numpy(float)  # decision L415: --steady-trim


def backward_travel(steps: pd.DataFrame) -> np.ndarray | None:
    """Decision L203: (rows,) bool, the foot track's strides that travel backward - ``raw_length_m`` negative (the
    stride's displacement points backward along the foot's forward axis), with or without a model (a model-free
    track leaves ``direction`` empty and its ``length_m`` positive, L65); the 0 m rows of a foot gap (``gap_s`` > 0,
    L67) and ``impossible`` strides (L97) are not, as :func:`median_stride_length`; amended in the same session (a
    feature-tour trial): a stride turning :data:`BACKWARD_MAX_TURN_DEG` or more is a turn on the spot, whose short
    chord can point anywhere (user 5's ``straight:10, turn:180, straight:10``: two turn strides of 120 and 60 deg
    with -0.25 / -0.15 m), not backward travel - decision L692: when its chord is under
    :data:`pdrlearn.kernels.backward.SPOT_MAX_CHORD_M` (a longer one's sign is judged against the mid-stride facing,
    :func:`pdrlearn.kernels.backward.signed_chord`). None for a lower-back track (no raw length per step) or a table
    without ``raw_length_m`` / ``length_m``. Decision L270: a stride of a side-stepping run (``sideways``, L228 /
    L243) is no backward travel either."""
    from pdrlearn.track.gait import sideways_rows

    units = set(steps["unit"].astype(str)) if len(steps) and "unit" in steps else set()
    # L203 amended: a replayed table (`pdrlearn run`) has no raw length; its signed ``length_m`` (the measured travel's
    # sign, decision L654) counts instead
    column = "raw_length_m" if "raw_length_m" in steps else "length_m"
    if units != {"foot"} or column not in steps:
        return None
    return backward_mask(steps[column].to_numpy(float),
                         steps["gap_s"].to_numpy(float) if "gap_s" in steps else None,
                         steps["impossible"].eq(True).to_numpy(bool) if "impossible" in steps else None,
                         # L203 amended, L692: a turning stride on a short chord is no backward travel
                         steps["turn_angle_rad"].to_numpy(float) if "turn_angle_rad" in steps else None,
                         sideways_rows(steps),  # decision L270: nor is a side step (L228's runs; L243 streamed)
                         streamed="pivot_rad" in steps)  # decision L505: nor a stream's first stride


def add_backward_travel(steps: pd.DataFrame) -> None:
    """Decision L224: a foot table gets steps.csv's ``backward_travel`` (bool, :func:`backward_travel`, placed right
    after ``direction``, else before ``impossible`` / ``gap_s`` / ``unit``): the rows ``n_backward_strides`` counts,
    so a reader of ``direction`` (the model's class, which a pivot stride of a turn can take) sees which of its
    ``backward`` rows are counted as backward travel. In place; nothing for a lower-back table."""
    flag = backward_travel(steps)
    if flag is None:
        return
    from pdrlearn.track.table_columns import place_column

    place_column(steps, "backward_travel", flag, after=("direction",), before=("impossible", "gap_s", "unit"))


def backward_strides(steps: pd.DataFrame) -> int | None:
    """Decision L203: ``n_backward_strides``, the number of :func:`backward_travel` strides (None where it has
    none: a lower-back track)."""
    flag = backward_travel(steps)
    return None if flag is None else int(flag.sum())


def backward_gait(steps: pd.DataFrame) -> dict:
    """Decision L326 (trial 31 finding 9): ``median_backward_stride_length_m`` (median |``length_m``| of the
    :func:`backward_travel` strides) and ``median_backward_speed_mps`` (median ``speed_mps`` of those with one, L66);
    None without backward strides, on a lower-back track, or without the column. ``median_stride_length_m`` and
    ``gait_speed_mps`` keep pooling both ways."""
    flag = backward_travel(steps)
    out: dict = {"median_backward_stride_length_m": None, "median_backward_speed_mps": None}
    if flag is None or not flag.any():
        return out
    back = steps[flag]
    length = np.abs(back["length_m"].to_numpy(float)) if "length_m" in back else np.array([])
    speed = back["speed_mps"].to_numpy(float) if "speed_mps" in back else np.array([])
    if np.isfinite(length).any():
        out["median_backward_stride_length_m"] = float(np.nanmedian(length))
    if np.isfinite(speed).any():
        out["median_backward_speed_mps"] = float(np.nanmedian(speed))
    return out


def side_strides(steps: pd.DataFrame) -> int | None:
    """Decision L270: ``n_side_strides``, the foot track's strides of side-stepping runs (L219 / L228's
    ``sideways``, a streamed table's runs whole, L243), which ``n_backward_strides`` leaves out; None where
    :func:`backward_travel` is None (a lower-back track)."""
    from pdrlearn.track.gait import sideways_rows

    return None if backward_travel(steps) is None else int(sideways_rows(steps).sum())


#: decision L484: the summary's distance split by travel direction (sums to ``distance_m``)
TRAVEL_DISTANCE_KEYS = ("forward_distance_m", "backward_distance_m", "side_distance_m")


def travel_masks(steps: pd.DataFrame) -> tuple[np.ndarray, np.ndarray] | None:
    """Decision L484: (backward, side) row masks of a foot table, the rows ``n_backward_strides`` (L203) and
    ``n_side_strides`` (L270) count; None for a lower-back table (no facing per step)."""
    from pdrlearn.track.gait import sideways_rows

    back = backward_travel(steps)
    if back is None:
        return None
    back = np.asarray(back, bool)
    return back, np.asarray(sideways_rows(steps), bool) & ~back


def travel_distances(steps: pd.DataFrame) -> dict:
    """Decision L484: :data:`TRAVEL_DISTANCE_KEYS`: the summed |``length_m``| (m) of the backward and side strides
    (:func:`travel_masks`) and the rest of the distance (forward strides, turns on the spot, shuffles), so the three
    sum to ``distance_m``; None each on a lower-back table."""
    masks = travel_masks(steps)
    if masks is None:
        return dict.fromkeys(TRAVEL_DISTANCE_KEYS)
    length = np.abs(np.nan_to_num(steps["length_m"].to_numpy(float))) if len(steps) else np.zeros(0)
    back, side = float(length[masks[0]].sum()), float(length[masks[1]].sum())
    return {"forward_distance_m": float(length.sum()) - back - side, "backward_distance_m": back,
            "side_distance_m": side}


def tracked_rate_hz(session: Session, pipeline: str | None) -> float | None:
    """Decision C19: the sampling rate (Hz) of the tracked unit's accelerometer (the lower back's for the waist
    pipelines, else the foot's): contact times, and so stride times and cadence, are resolved to one sample."""
    name = "wAccelerometer" if str(pipeline).startswith("waist") else "fAccelerometer"
    acc = session.streams.get(name)
    if acc is None or len(acc) < 2 or not np.isfinite(acc.rate_hz):
        return None
    return round(float(acc.rate_hz), 4)


def _basic(result: TrackResult, out: dict) -> None:
    tr = result.trajectory
    out["distance_m"] = result.distance_m
    out["n_steps"] = int(len(result.steps))
    out.update(step_counts(result.steps))  # decision L103: what n_steps counts, and the steps of both feet
    out["median_stride_length_m"] = median_stride_length(result.steps)  # decision C19: as in sessions.csv
    add_backward_travel(result.steps)  # decision L224: steps.csv's per-row form of the count below
    out["n_backward_strides"] = backward_strides(result.steps)  # decision L203: model-free backward travel
    out["n_side_strides"] = side_strides(result.steps)  # decision L270: side steps, no backward travel
    out.update(travel_distances(result.steps))  # decision L484: the distance by travel direction
    from pdrlearn.track.travel import add_travel, direction_change_table

    add_travel(result.steps)  # decision L412: each stride's travel direction (steps.csv travel)
    changes = direction_change_table(result.steps)
    out["direction_changes"] = None if changes is None else len(changes)  # L412: changes of travel direction
    out.update(backward_gait(result.steps))  # decision L326: the backward strides' own length and speed
    last = tr.iloc[-1] if len(tr) else None
    out["final_position"] = {k: (float(last[k]) if last is not None else 0.0) for k in ("x", "y", "z")}
    if last is not None and "lat" in tr:
        out["final_position"].update(lat=float(last["lat"]), lon=float(last["lon"]))
    from pdrlearn.kernels.travel import loop_closure

    # decision L771: the end's distance from the start, m and % of the walked distance (meaningful on a loop)
    out["loop_closure_m"], out["loop_closure_pct"] = loop_closure(tr["x"], tr["y"], out["distance_m"]) \
        if len(tr) else (None, None)
    # the tracked altitude change, with or without ground truth (session 14 trial finding 2)
    out["altitude_change_m"] = float(tr["z"].iloc[-1] - tr["z"].iloc[0]) if len(tr) and "z" in tr else 0.0
    from pdrlearn.track.floor_column import ride_change

    # decision L630: with the rides a foot track's z leaves out (rides.csv: a lift while the feet stand)
    out["altitude_change_rides_m"] = out["altitude_change_m"] + (
        ride_change(result, float(tr["t"].iloc[0]), float(tr["t"].iloc[-1])) if len(tr) else 0.0)
    # decision L66: median stride time, cadence and speed of a table with the gait columns (foot pipeline)
    from pdrlearn.track.gait import gait_summary

    out.update(gait_summary(result.steps))
    from pdrlearn.track.clinical import clinical_summary, leg_summary, turn_summary, turn_table, walked_turns
    from pdrlearn.waist.transfers import transfer_summary

    # decision L104: pauses, walking bouts, turns, stride-time CV; C248: the pauses standing (the posture runs known)
    out.update(clinical_summary(result.steps, postures=result.info.get("postures")))
    from pdrlearn.track.contact_summary import contact_summary

    out.update(contact_summary(result.steps))  # decision L756: the steady strides' toe-contact share
    out.update(leg_summary(result.steps))  # decision W228: steps per leg, the lower back's step-time asymmetry
    # decision L200: each turn's duration, angle, peak rate (L210: a lower-back track's yaw-rate turns)
    table = turn_table(result.steps, yaw_turns=result.info.get("yaw_turns"),
                       gap_turns=result.info.get("waist_gap_turns"))  # decision L701
    out.update(turn_summary(walked_turns(table)))  # decision L622: not the turns made seated or riding (W488)
    # decisions L231 / L233: turns.csv's turns are turn_count's; L701: with a foot rest gap's lower-back turn
    if result.info.get("yaw_turns") is not None or result.info.get("waist_gap_turns"):
        out["turn_count"] = len(walked_turns(table))  # L622: less those marked carried
    from pdrlearn.track.trunk_tug import foot_strides, trunk_note, tug_contacts, tug_source_summary, tug_yaw_turns

    # decision W183: chair transfers, TUG (W418: a foot track's from the waist unit's transfers and contacts; W490 /
    # L614: a TUG's shape from these turns and, on a foot track, the foot's strides)
    out.update(transfer_summary(result.info.get("transfers"), tug_contacts(result), turns=table,
                                walk=foot_strides(result), yaw_turns=tug_yaw_turns(result)))  # W498
    if out.get("tug_time_note") is None:
        out["tug_time_note"] = trunk_note(result)  # W418: why a two-unit track has no transfers
    from pdrlearn.waist.tug_phases import tug_phase_summary, tug_phases

    # decision W293: the TUG's phases, from the transfers, these turns and the walking contacts
    out.update(tug_phase_summary(tug_phases(result.info.get("transfers"), table, tug_contacts(result),
                                            yaw_turns=tug_yaw_turns(result), walk=foot_strides(result))))  # W307
    out.update(tug_source_summary(result, out))  # decision W419; W427: None without a TUG
    from pdrlearn.waist.turn_steps import stepless_summary

    # decision W331: a lower-back track's turns on the spot that hold no step, and the steps they imply
    out.update(stepless_summary(result.steps["event_s"] if "event_s" in result.steps else [],
                                result.info.get("yaw_turns")))
    from pdrlearn.waist.turn_steps import steps_with_turns

    # decision W603: the steps with W331's turning steps on the spot, beside n_steps (which stays the detected ones)
    out["n_steps_with_turns"] = steps_with_turns(out.get("n_steps"), out.get("turn_steps_missed"),
                                                 bool(result.info.get("step_count_unusable")))
    from pdrlearn.track.grade import add_grade, grade_summary, info_stair_grade, track_ramps
    from pdrlearn.track.walk_test import ramp_numbers, t25fw, ten_metre_walk

    add_grade(result.steps, result.info)  # decision L300: steps.csv's grade_pct
    with info_stair_grade(result.info):  # session 42: the ramps found once for both (L469's grade, as ramps.csv's)
        found = track_ramps(result.steps, result.info)
    ramps = ramp_numbers(result.steps, found)  # decision L679: no walk test on a ramp
    from pdrlearn.track.gait import stair_ramp_split

    out.update(stair_ramp_split(result.steps, found[0]))  # decision L705: a ramp's strides are no stair strides
    # decisions L312, L313: the 10 m walk test's middle 10 m; L522: --ten-m-walk's walkway; L524: every trial
    calibrated = result.info.get("params_source") == "calibrated"  # decision L649
    out.update(ten_metre_walk(result.steps, result.info.get("ten_m_walk_m"), calibrated, ramps=ramps))
    # decision L387: the timed 25-foot walk from standing; L552: a long bout only on a declared walkway
    out.update(t25fw(result.steps, walkway=result.info.get("ten_m_walk_m") is not None, calibrated=calibrated,
                     ramps=ramps))
    from pdrlearn.track.stair_flights import flight_summary

    out.update(flight_summary(result.steps))  # decision L432: stairs.csv's flights up and down
    # decisions L64, L127: the storeys the track climbed and descended (storeys of storey_height_m, set by
    # evaluate_track)
    dz, bridge, parts, slope_rows = climb_inputs(result)
    _floors(tr["z"].to_numpy(float) if len(tr) and "z" in tr else [], out, dz=dz, bridge=bridge,
            slope_rows=slope_rows, parts=parts)
    out["n_rides"] = len(result.info["rides"]) if result.info.get("rides") is not None else None  # decision L377
    out.update(floors_by_kind(result.steps, out.get("storey_height_m", STOREY_HEIGHT_M),
                             result.info))  # decision L302
    from pdrlearn.track.belt import belt_floors

    belt_floors(out)  # decision L442: a declared inclined belt climbs no storeys
    _ascent(result, out)
    out.update(grade_summary(result.steps, result.info, found=found))  # decisions L300, L301
    out.update(identified_climbs(result, found=found))  # decision L566: what ramps.csv / stairs.csv rise and drop


def _altitude_kind(result: TrackResult) -> tuple[bool, bool]:
    """Decision L146: (a foot track, its z barometric: a lower-back track or a fused foot track, L154)."""
    steps = result.steps
    foot = bool(len(steps)) and "unit" in steps and bool((steps["unit"].astype(str) == "foot").all())
    return foot, bool(len(steps)) and (not foot or (result.info or {}).get("altitude_source") == "fused")


def no_altitude(result: TrackResult) -> bool:
    """Decision L575: a lower-back track without a barometric altitude (W90: no usable wBarometer.csv, its steps'
    ``dz_m`` and trajectory z all 0, as L300's :func:`pdrlearn.track.grade.grade_source` reads it): its ascent and
    descent are not measured (None), not 0."""
    steps, tr = result.steps, result.trajectory
    if not len(steps) or "unit" not in steps or not bool((steps["unit"].astype(str) == "waist").all()):
        return False
    dz = np.nan_to_num(pd.to_numeric(steps["dz_m"], errors="coerce").to_numpy(float)) if "dz_m" in steps else [0.0]
    z = np.nan_to_num(tr["z"].to_numpy(float)) if len(tr) and "z" in tr else [0.0]
    return not (np.any(dz != 0) or np.any(z != 0))


def interval_ascent(result: TrackResult, a: float, b: float) -> tuple[float | None, float | None]:
    """Decision L467: the ascent and descent (m) of the trajectory's z from ``a`` to ``b`` (s) by the summary's
    rule (:func:`_ascent`: a barometric z L146's band crossed within L172's window, a foot track's strides as they
    are); (None, None) without a trajectory z and time."""
    from pdrlearn.kernels.altitude_check import ASCENT_BAND_BARO_M, CLIMB_WINDOW_S, ascent_descent

    tr = result.trajectory
    if not len(tr) or "z" not in tr or "t" not in tr or no_altitude(result):  # decision L575
        return None, None
    t = tr["t"].to_numpy(float)
    m = (t >= a) & (t <= b)
    z, t = tr["z"].to_numpy(float)[m], t[m]
    foot, barometric = _altitude_kind(result)
    if barometric:
        return ascent_descent(z, ASCENT_BAND_BARO_M, t, CLIMB_WINDOW_S)
    return ascent_descent(z, 0.0 if foot or not len(result.steps) else ASCENT_BAND_BARO_M)


def _ascent(result: TrackResult, out: dict) -> None:
    """Decision L146: ``ascent_m`` / ``descent_m``, the cumulative climb and descent of the track's z (a hill
    walked up and down has both, its ``altitude_change_m`` ~0); a foot track's strides as they are, a barometric z
    (a lower-back track, or a foot track with ``altitude="fused"``, L154) within the hysteresis band
    ``ASCENT_BAND_BARO_M`` crossed within ``CLIMB_WINDOW_S`` (decision L172: the weather's slow drift is dropped),
    and ``altitude_drift_m``, the barometric change so dropped (altitude_change_m minus ascent plus descent); decision
    W370: only a drift the weather can make in the track's span (else climbs counted turning point to turning point).
    Decision L575: all None on a lower-back track without a barometric altitude (:func:`no_altitude`)."""
    from pdrlearn.kernels.altitude_check import (
        ASCENT_BAND_BARO_M,
        CLIMB_WINDOW_S,
        WEATHER_RATE_MAX_M_PER_S,
        ascent_descent,
        climbs_within_weather,
    )

    tr, steps = result.trajectory, result.steps
    if no_altitude(result):  # decision L575: not measured, not 0
        out.update(dict.fromkeys(("ascent_m", "descent_m", "altitude_drift_m", "altitude_drift_limit_m")))
        return
    z = tr["z"].to_numpy(float) if len(tr) and "z" in tr else np.zeros(0)
    foot, barometric = _altitude_kind(result)
    if not barometric or "t" not in tr:
        out["ascent_m"], out["descent_m"] = ascent_descent(z, 0.0 if foot or not len(steps) else ASCENT_BAND_BARO_M)
        return
    # decision W370: L172's count unless the drift it drops is more than the weather can make in the track's span
    out["ascent_m"], out["descent_m"] = climbs_within_weather(z, tr["t"].to_numpy(float), ASCENT_BAND_BARO_M,
                                                              CLIMB_WINDOW_S)
    out["altitude_drift_m"] = float(out.get("altitude_change_m", 0.0) - out["ascent_m"] + out["descent_m"])
    t = tr["t"].to_numpy(float)
    t = t[np.isfinite(t)]
    # decision W371: the most the fastest weather changes z in the track's span (W370's rate)
    out["altitude_drift_limit_m"] = float(WEATHER_RATE_MAX_M_PER_S * (t[-1] - t[0])) if len(t) > 1 else 0.0


def identified_climbs(result: TrackResult, *, found=None) -> dict:
    """Decision L566: ``ramps_stairs_ascent_m`` / ``ramps_stairs_descent_m``, the summed rise of the ramps
    (ramps.csv ``rise_m``, L301) and stair flights (stairs.csv ``height_m``, L432) up and down of a track whose z is
    barometric (a lower-back track, ``--altitude fused``): the climbs the track identified whole, against which
    :func:`climb_total_warning` checks L172's ``ascent_m`` / ``descent_m``. None on other tracks. ``found``:
    :func:`pdrlearn.track.grade.track_ramps` of the track's rows, when the caller has it (session 42)."""
    from pdrlearn.track.clinical import _is_lower_back
    from pdrlearn.track.grade import info_stair_grade, ramp_table
    from pdrlearn.track.stair_flights import flight_table

    if not _altitude_kind(result)[1]:
        return {"ramps_stairs_ascent_m": None, "ramps_stairs_descent_m": None}
    with info_stair_grade(result.info):  # as track/folder.py writes ramps.csv and stairs.csv (L469, L440, L442)
        rise = pd.to_numeric(ramp_table(result.steps, result.info, found=found)["rise_m"],
                             errors="coerce").to_numpy(float)
        if not _is_lower_back(result.steps) and result.info.get("belt_incline_pct") is None:
            rise = np.concatenate([rise, pd.to_numeric(flight_table(result.steps)["height_m"],
                                                       errors="coerce").to_numpy(float)])
    rise = rise[np.isfinite(rise)]
    return {"ramps_stairs_ascent_m": float(rise[rise > 0].sum()),
            "ramps_stairs_descent_m": float(-rise[rise < 0].sum()) + 0.0}


def _walked_heights(session: Session) -> pd.DataFrame | None:
    """The labelled strides when their ``height_m`` is the whole height change: every row has one and the session
    has no ride (decision S47: a lift or escalator's height is in ``rides.csv`` and the trajectory, not the strides)."""
    st = session.steps
    rides = session.extras.get("rides")
    if rides is not None and len(rides):
        return None
    if st is not None and len(st) and "height_m" in st and st["height_m"].notna().all():
        return st
    return None


def reference_altitude_change(session: Session, t0: float, t1: float) -> tuple[float | None, str]:
    """The reference altitude change (m) of a walk and its source. A ``steps.csv`` whose rows all have a
    ``height_m`` gives their sum (the floor-level change of the labelled strides, as ``distance_ref_m`` sums
    their ``length_m``; strides of two feet: the mean of the feet's sums, each foot's strides tile the walk),
    the same for every tracker of the session; else the ground-truth trajectory's z from ``t0`` to ``t1``
    (the track's first and last time). Before, the trajectory was always read at the track's own times, so
    ``track`` and ``run`` (whose first stride starts 0.02 s apart) differed by the body's sway (3.0514 vs
    3.0494 m on one walk). Decision S47: a session with rides (``rides.csv``: a lift or an escalator carried the
    walker, whose strides' ``height_m`` are the walked ones) takes the trajectory."""
    st = _walked_heights(session)
    if st is not None:
        h = st["height_m"].astype(float)
        if "foot" in st and st["foot"].nunique() >= 2:
            return float(h.groupby(st["foot"]).sum().mean()), "steps.csv height_m (mean of the feet's sums)"
        return float(h.sum()), "steps.csv height_m"
    walked = _walking_reference(session)  # decision L357: z at standing moments, not seated vs standing
    if walked is not None:
        from pdrlearn.track.pelvis_reference import STRIDE_AVERAGED_ALTITUDE_SOURCE

        return float(walked["z"].iloc[-1] - walked["z"].iloc[0]), STRIDE_AVERAGED_ALTITUDE_SOURCE
    gt = session.trajectory
    if gt is not None and len(gt) > 1 and "z" in gt:
        t, z = gt["t"].to_numpy(float), gt["z"].to_numpy(float)
        return float(np.interp(t1, t, z) - np.interp(t0, t, z)), "trajectory.csv z at the track's first and last time"
    return None, ""


def _walking_reference(session: Session) -> pd.DataFrame | None:
    """Decision L357: a pelvis trajectory with labelled contacts (ics.csv) is read stride-averaged over the walking
    span - :func:`pdrlearn.track.pelvis_reference.walking_reference` of the session's trajectory and labelled
    contacts, for a pelvis-only reference (decision L595: the rule, no module switch): None when the session lacks
    either, has a steps.csv (its strides are the reference, or S47 chose the trajectory for its rides) or a ride
    (rides.csv: a lift before the first or after the last contact is outside the walking span)."""
    rides = session.extras.get("rides")
    if (session.steps is not None and len(session.steps)) or (rides is not None and len(rides)):
        return None
    from pdrlearn.track.pelvis_reference import walking_reference

    return walking_reference(session.trajectory, session.extras.get("ics"))


def reference_altitude_track(session: Session, t0: float, t1: float) -> np.ndarray | None:
    """The reference altitudes of a walk in walking order (decision L64), from the source of
    :func:`reference_altitude_change`: the running sum of one foot's labelled ``height_m`` (the first foot
    named) or the ground-truth trajectory's z from ``t0`` to ``t1``; None without either."""
    st = _walked_heights(session)
    if st is not None:
        if "foot" in st and st["foot"].nunique() >= 2:
            st = st[st["foot"] == st["foot"].iloc[0]]
        if "start_s" in st:
            st = st.sort_values("start_s", kind="stable")
        return np.concatenate([[0.0], np.cumsum(st["height_m"].to_numpy(float))])
    walked = _walking_reference(session)  # decision L357
    if walked is not None:
        return walked["z"].to_numpy(float)
    gt = session.trajectory
    if gt is not None and len(gt) > 1 and "z" in gt:
        t, z = gt["t"].to_numpy(float), gt["z"].to_numpy(float)
        inside = (t >= t0) & (t <= t1)
        return np.concatenate([[np.interp(t0, t, z)], z[inside], [np.interp(t1, t, z)]])
    return None


def _reference_distance(session: Session, *, waist: bool = False) -> tuple[float | None, str]:
    """The reference distance and its source. For a waist track (``waist``) a ``steps.csv`` of strides of
    both feet (a ``foot`` column with two values) gives the larger of the two feet's sums: each foot's
    strides tile the walked path once, so the sum over both feet counts it twice (decision W38)."""
    st = session.steps
    if st is not None and "length_m" in st and len(st) and st["length_m"].notna().all():
        if waist and "foot" in st and st["foot"].nunique() >= 2:
            per_foot = st["length_m"].abs().groupby(st["foot"]).sum()
            return float(per_foot.max()), "steps.csv length_m (strides of both feet: the longer foot's sum, W38)"
        return float(st["length_m"].abs().sum()), "steps.csv length_m"
    walked = _walking_reference(session)  # decision L357: no sway, no chair transfers' pelvis travel
    if walked is not None:
        from pdrlearn.track.pelvis_reference import STRIDE_AVERAGED_SOURCE, walked_length

        return walked_length(walked), STRIDE_AVERAGED_SOURCE
    if session.trajectory is not None and len(session.trajectory) > 1:
        return path_length(session.trajectory), "trajectory.csv path"
    return None, ""


#: decision L319: a reference trajectory that travels less than this fraction of the track's own largest distance
#: from its start (a lab-frame motion capture on a treadmill: the pelvis wobbles in place) is no reference for the
#: distance or the final position; judged only when the track goes at least STATIONARY_REF_MIN_TRACK_M from its start
STATIONARY_REF_FRAC = 0.1
STATIONARY_REF_MIN_TRACK_M = 5.0
#: decision L727: a reference that goes this far (m) or farther from its start travels, whatever the track did (a 400 m
#: athletics oval goes ~128 m from its start; a lab-frame pelvis on a belt under 1 m)
STATIONARY_REF_MAX_M = 5.0


def stationary_reference(ref_m: float, track_m: float) -> bool:
    """Decisions L319, L727: whether a reference that goes ``ref_m`` from its start while the track goes ``track_m``
    from its own is a treadmill's lab frame (it walked in place) rather than a travelled path."""
    return track_m >= STATIONARY_REF_MIN_TRACK_M and ref_m < min(STATIONARY_REF_FRAC * track_m, STATIONARY_REF_MAX_M)


def reference_travel(gt: pd.DataFrame, tr: pd.DataFrame) -> tuple[float, float]:
    """Decision L319: (the reference trajectory ``gt``'s largest horizontal distance from its position at the
    track's first time, over the track's span; the track ``tr``'s largest horizontal distance from its start), m."""
    t0, t1 = float(tr["t"].iloc[0]), float(tr["t"].iloc[-1])
    t = gt["t"].to_numpy(float)
    inside = (t >= t0) & (t <= t1)
    xy = np.column_stack([np.r_[np.interp(t0, t, gt[c].to_numpy(float)), gt[c].to_numpy(float)[inside],
                                np.interp(t1, t, gt[c].to_numpy(float))] for c in ("x", "y")])
    est = tr[["x", "y"]].to_numpy(float)
    return (float(np.nanmax(np.hypot(*(xy - xy[0]).T))), float(np.nanmax(np.hypot(*(est - est[0]).T))))


def _ground_truth(result: TrackResult, session: Session, out: dict) -> None:
    waist = bool(len(result.steps)) and "unit" in result.steps and bool((result.steps["unit"] == "waist").all())
    ref, source = _reference_distance(session, waist=waist)
    if ref is None or ref <= 0:
        return
    gt = session.trajectory
    tr = result.trajectory
    still = False  # decision L319: a reference that does not travel while the track does (a treadmill's lab frame)
    if gt is not None and len(gt) > 1 and len(tr):
        ref_m, track_m = reference_travel(gt, tr)
        still = stationary_reference(ref_m, track_m)
        if still:
            out["reference_travel_m"] = ref_m
    if still and source.startswith("trajectory.csv path"):  # its wobble's path is no distance walked (L357 too)
        return
    out["distance_ref_m"] = ref
    out["distance_ref_source"] = source
    out["distance_error_pct"] = 100.0 * (out["distance_m"] - ref) / ref
    out["distance_error_scope"] = "whole track"  # decision W71: what distance_error_pct compares
    out["distance_compared_m"] = out["distance_m"]  # decision W459: the tracked distance the error compares
    if gt is not None and len(gt) > 1 and len(tr) and not still:
        t0, t1 = float(tr["t"].iloc[0]), float(tr["t"].iloc[-1])
        g = {c: gt[c].to_numpy(float) for c in ("t", "x", "y", "z")}
        p0 = np.array([np.interp(t0, g["t"], g[c]) for c in ("x", "y", "z")])
        p1 = np.array([np.interp(t1, g["t"], g[c]) for c in ("x", "y", "z")])
        est = tr[["x", "y", "z"]].to_numpy(float)
        d_true = p1 - p0
        d_est = est[-1] - est[0]
        out["final_position_error_m"] = float(np.hypot(*(d_est[:2] - d_true[:2])))  # horizontal


def stationary_reference_warning(summary: dict) -> str | None:
    """Decision L319: one line when the reference trajectory did not travel (``reference_travel_m``) while the
    track walked: what was and was not compared."""
    ref_m = summary.get("reference_travel_m")
    if ref_m is None:
        return None
    kept = ("the distance error compares " + str(summary["distance_ref_source"])
            if summary.get("distance_error_pct") is not None else "no distance error from its path")
    return (f"the reference trajectory (trajectory.csv) goes at most {float(ref_m):.2f} m from its start while the "
            f"track walks {float(summary.get('distance_m', 0.0)):.2f} m: a treadmill, or a walk captured in the lab "
            "frame? On a belt the foot measures belt distance, not travel (docs/frames.md, L147); "
            f"{kept}, and no final position error against it (decision L319)")


def _altitude(result: TrackResult, session: Session, out: dict) -> None:
    """``altitude_change_ref_m`` (:func:`reference_altitude_change`), ``final_altitude_error_m`` (|tracked -
    reference altitude change|), ``final_position_error_3d_m`` (with the horizontal ``final_position_error_m``)
    and ``altitude_error_pct`` (a reference change over 0.5 m)."""
    tr = result.trajectory
    if not len(tr):
        return
    ref, source = reference_altitude_change(session, float(tr["t"].iloc[0]), float(tr["t"].iloc[-1]))
    if ref is None:
        return
    rides = result.info.get("rides") or []  # decisions L393, L394: the floors' span holds the rides at its edges
    z_ref = reference_altitude_track(session, min([float(tr["t"].iloc[0])] + [float(r["start_s"]) for r in rides]),
                                     max([float(tr["t"].iloc[-1])] + [float(r["end_s"]) for r in rides]))
    if z_ref is not None:  # decision L64: the reference's storeys, counted by the same rule
        _floors(z_ref, out, "_ref")  # L64's count on the reference altitude
    est = out["altitude_change_rides_m"]  # decision L630: a foot track's rides are the walker's height too
    out["altitude_change_ref_m"] = ref
    out["altitude_ref_source"] = source
    out["final_altitude_error_m"] = abs(est - ref)
    if "final_position_error_m" in out:
        out["final_position_error_3d_m"] = float(np.hypot(out["final_position_error_m"], est - ref))
    if abs(ref) > 0.5:
        out["altitude_error_pct"] = 100.0 * abs(est - ref) / abs(ref)


def _composed_strides(est: pd.DataFrame, ref: pd.DataFrame, used_est: set, used_ref: set, *,
                      tol_s: float = 0.15, min_cover: float = 0.8) -> list[tuple[int, float, list[int]]]:
    """Reference strides left unmatched that two or more estimated strides tile (e.g. a turn on the spot
    split at an intermediate rest): (ref row, horizontal length of the vector sum of those strides, their rows)."""
    out = []
    es, ee = est["start_s"].to_numpy(float), est["end_s"].to_numpy(float)
    vec = est["length_m"].to_numpy(float)[:, None] * np.column_stack(
        [np.cos(est["heading_rad"].to_numpy(float)), np.sin(est["heading_rad"].to_numpy(float))])
    for j in range(len(ref)):
        if j in used_ref:
            continue
        rs, re = float(ref["start_s"].iloc[j]), float(ref["end_s"].iloc[j])
        inside = [i for i in np.flatnonzero((es >= rs - tol_s) & (ee <= re + tol_s)) if i not in used_est]
        if len(inside) >= 2 and (ee[inside].max() - es[inside].min()) >= min_cover * (re - rs):
            out.append((j, float(np.hypot(*vec[inside].sum(axis=0))), [int(i) for i in inside]))
            used_est.update(int(i) for i in inside)
    return out


def reference_stride_times(st: pd.DataFrame) -> np.ndarray:
    """Decision E135: each labelled stride's time (s), initial contact to the same foot's previous one: ``ic_s -
    pre_ic_s`` where the labels give both (motion capture), else ``ic_s`` less the ``ic_s`` of the labelled stride
    that ends where this one starts (within 1 ms: a chain of strides, as a simulated walk's); NaN otherwise."""
    n = len(st)
    ic = st["ic_s"].to_numpy(float) if "ic_s" in st else np.full(n, np.nan)
    t = ic - st["pre_ic_s"].to_numpy(float) if "pre_ic_s" in st else np.full(n, np.nan)
    s, e = st["start_s"].to_numpy(float), st["end_s"].to_numpy(float)
    for k in np.flatnonzero(~np.isfinite(t)):
        prev = np.flatnonzero(np.abs(e - s[k]) <= 1e-3)
        if prev.size:
            t[k] = ic[k] - ic[prev[0]]
    return t


def stride_pairs(result: TrackResult, session: Session, *,
                 by_contact: bool = True) -> list[tuple[list[int], int, float]] | None:
    """Decision E135: the (tracked rows, labelled stride, estimated length) pairs the stride-length metrics score:
    one tracked row matched to one labelled stride with a length (IoU >= 0.5, :func:`match_strides`: a
    contact-to-contact label by its initial contact, steps decision 99; a gap or
    impossible row left out, decisions E30 / L67 / L97), then the unmatched labelled strides two or more tracked rows
    tile (:func:`_composed_strides`, the vector sum of the rows). The labelled stride is its row in ``session.steps``
    (0 = steps.csv's first row). None without labelled stride lengths."""
    st = session.steps
    if st is None or "length_m" not in st or not st["length_m"].notna().any() or not len(result.steps):
        return None
    keep = np.flatnonzero(st["length_m"].notna().to_numpy())
    ref = st.iloc[keep].reset_index(drop=True)
    pairs = match_strides(result.steps, ref, by_contact=by_contact)  # steps decision 99
    # decisions E30 / L67: a row across a foot-stream gap (gap_s > 0) is 0 m by rule, no estimate of the
    # labelled stride it overlaps: that stride is not scored (nor composed of its neighbours)
    gap = (result.steps["gap_s"].to_numpy(float) > 0 if "gap_s" in result.steps
           else np.zeros(len(result.steps), dtype=bool))
    if "impossible" in result.steps:  # decision L97: nor is a stride the last-line guard (L94) moved 0 m
        gap = gap | result.steps["impossible"].eq(True).to_numpy(bool)
    used_est, used_ref = {i for i, _ in pairs} | set(np.flatnonzero(gap).tolist()), {j for _, j in pairs}
    length = result.steps["length_m"].to_numpy(float)
    out = [([i], int(keep[j]), float(length[i])) for i, j in pairs if not gap[i]]
    out += [(rows, int(keep[j]), est) for j, est, rows in _composed_strides(result.steps, ref, used_est, used_ref)]
    return out


#: decision E135: the columns a foot track's steps.csv gets where the session labels stride lengths
REFERENCE_COLUMNS = ("ref_match", "ref_length_m", "ref_stride_time_s", "ref_composed", "pair_length_m")
#: decision D52: after them, on a ``--toe-off`` track whose labels give the toe-off (``tc_ms``): the labelled
#: stride's toe-off and its stance / swing split, the reference of the row's tc_s, stance_time_s, swing_time_s,
#: stance_pct (the labelled stride runs pre_ic -> tc -> ic, the row's cycle_start_s -> tc_s -> event_s, L672)
TIMING_REFERENCE_COLUMNS = ("ref_tc_s", "ref_stance_time_s", "ref_swing_time_s", "ref_stance_pct")


def reference_timings(st: pd.DataFrame) -> tuple[np.ndarray, ...]:
    """Decision D52: per labelled stride (a steps.csv, seconds), ``(tc, stance, swing, stance_pct)``: ``tc_s`` where
    it lies inside the stride's cycle (its opening IC ``ic - stride time``, :func:`reference_stride_times`, to its
    ``ic_s``), stance = tc - that opening IC, swing = ic - tc, stance_pct = 100 x stance / stride time; NaN
    otherwise (no toe-off, no stride time)."""
    n = len(st)
    ic = st["ic_s"].to_numpy(float) if "ic_s" in st else np.full(n, np.nan)
    tc = st["tc_s"].to_numpy(float) if "tc_s" in st else np.full(n, np.nan)
    stride = reference_stride_times(st)
    start = ic - stride
    with np.errstate(invalid="ignore"):
        tc = np.where((tc > start) & (tc < ic), tc, np.nan)
        return tc, tc - start, ic - tc, 100.0 * (tc - start) / stride


def _timing_pairs(result: TrackResult, session: Session) -> list[tuple[int, int]]:
    """Decision D52: (tracked row, labelled stride) pairs for the timing reference: one tracked stride matched to one
    labelled stride with a toe-off (:func:`match_strides`, as the stride lengths), on a track with
    toe-offs (``--toe-off``); a gap or impossible row left out (no stance of its own, L67 / L97)."""
    st, steps = session.steps, result.steps
    if st is None or "tc_s" not in st or "tc_s" not in steps:
        return []
    keep = np.flatnonzero(np.isfinite(reference_timings(st)[0]))
    if not len(keep):
        return []
    from pdrlearn.track.gait import stride_rows

    valid = stride_rows(steps)
    return [(i, int(keep[j])) for i, j in match_strides(steps, st.iloc[keep].reset_index(drop=True)) if valid[i]]


def with_reference_columns(result: TrackResult, session: Session | None) -> pd.DataFrame:
    """Decision E135: ``result.steps`` with :data:`REFERENCE_COLUMNS` appended on a foot track whose session labels
    stride lengths (else unchanged): per tracked row of a :func:`stride_pairs` pair, the labelled stride's row in the
    session's steps.csv (``ref_match``, from 0), its ``length_m`` and stride time (:func:`reference_stride_times`),
    whether the pair is two or more tracked rows tiling one labelled stride (``ref_composed``) and the pair's
    estimated length (``pair_length_m``: the row's |length|, or the tiles' vector sum on each of them). The summary's
    ``stride_length_mae_m`` / ``_pct`` / ``stride_length_matched`` are these pairs, one per ``ref_match``.
    Decision D52: on a ``--toe-off`` track whose labels give toe-offs, :data:`TIMING_REFERENCE_COLUMNS` too (the
    :func:`_timing_pairs`, :func:`reference_timings`); without labelled lengths ``ref_match`` and
    ``ref_stride_time_s`` then come from those pairs and the length columns are left out. Steps decision 98: on a
    composed pair's rows the temporal columns (``ref_stride_time_s`` and :data:`TIMING_REFERENCE_COLUMNS`) stay
    empty: the labelled stride spans both tiles, so no row's own time has a reference."""
    steps = result.steps
    if session is None or not len(steps) or "unit" not in steps or not (steps["unit"] == "foot").all():
        return steps
    from pdrlearn.track.window import steps_row

    pairs = stride_pairs(result, session)
    timing = _timing_pairs(result, session)
    if pairs is None and not timing:
        return steps
    st = session.steps
    n = len(steps)
    match = pd.array([pd.NA] * n, dtype="Int64")
    ref_len, ref_t, pair_len = np.full(n, np.nan), np.full(n, np.nan), np.full(n, np.nan)
    composed = np.zeros(n, dtype=bool)
    times = reference_stride_times(st)
    for rows, j, est in pairs or []:
        for i in rows:
            match[i] = steps_row(session, j)  # decision E138: steps.csv's row, also under --window
            composed[i] = len(rows) > 1
            # steps decision 98: a tile of a composed pair is no labelled stride in time (two tracked strides carry
            # one labelled stride): its temporal reference stays empty, its length pairs by pair_length_m
            ref_len[i], ref_t[i], pair_len[i] = (float(st["length_m"].iloc[j]), np.nan if composed[i] else times[j],
                                                 abs(est))
    cols = {}
    if pairs is not None:
        cols = dict(ref_match=match, ref_length_m=ref_len, ref_stride_time_s=ref_t, ref_composed=composed,
                    pair_length_m=pair_len)
    if timing:  # decision D52
        ref = reference_timings(st)
        vals = [np.full(n, np.nan) for _ in TIMING_REFERENCE_COLUMNS]
        for i, j in timing:
            if composed[i]:  # steps decision 98: no temporal reference on a composed pair's tile
                continue
            if pairs is None:
                match[i], ref_t[i] = steps_row(session, j), times[j]
            for v, r in zip(vals, ref, strict=True):
                v[i] = r[j]
        if pairs is None:
            cols = dict(ref_match=match, ref_stride_time_s=ref_t)
        cols.update(zip(TIMING_REFERENCE_COLUMNS, vals, strict=True))
    return steps.assign(**cols)


def _stride_lengths(result: TrackResult, session: Session, out: dict) -> None:
    pairs = stride_pairs(result, session)  # decision E135: the pairs steps.csv's reference columns give
    if not pairs:
        return
    e = np.array([est for _, _, est in pairs])
    r = session.steps["length_m"].to_numpy(float)[[j for _, j, _ in pairs]]
    err = np.abs(np.abs(e) - np.abs(r))
    ri = np.array([j for _, j, _ in pairs])
    out["stride_length_composed"] = int(sum(len(rows) > 1 for rows, _, _ in pairs))
    out["stride_length_matched"] = int(len(pairs))
    out["stride_length_mae_m"] = float(err.mean())
    out["stride_length_mae_pct"] = float(100.0 * np.mean(err / np.abs(r)))
    # the distance over the labelled strides only: a reference that labels part of the walk (gaitmap's
    # mocap volume: 28 of 32 strides) makes distance_error_pct compare the whole track with part of it
    out["distance_matched_error_pct"] = float(100.0 * (np.abs(e).sum() / np.abs(r).sum() - 1.0))
    # decision L419: the two sums that error compares (the matched tracked strides, their labelled strides), so the
    # printed headline can say which span each number covers
    out["distance_matched_m"] = float(np.abs(e).sum())
    out["distance_matched_ref_m"] = float(np.abs(r).sum())
    if "turn" in session.steps:
        turn = flag_values(session.steps["turn"])[ri]
        if (~turn).any():
            out["stride_length_mae_pct_straight"] = float(100.0 * np.mean((err / np.abs(r))[~turn]))
        if turn.any():
            out["stride_length_mae_pct_turns"] = float(100.0 * np.mean((err / np.abs(r))[turn]))
    if "steady" in session.steps:  # decision L252: a walkway reference's strides (no initiation / termination / turn)
        steady = flag_values(session.steps["steady"])[ri]
        if steady.any():
            out["stride_length_mae_pct_steady"] = float(100.0 * np.mean((err / np.abs(r))[steady]))


#: the class columns of a tracked step table compared with the labels (steps.csv), decision L53
CLASS_TASKS = ("terrain", "direction", "length_class")


def _class_agreement(result: TrackResult, session: Session, out: dict) -> None:
    """Foot tracks on sessions with class labels (decision L53): per task, the fraction of tracked strides
    matched to a labelled stride (time overlap, IoU >= 0.5) whose class is the label, ``<task>_agreement``,
    and the strides compared, ``class_agreement_strides``. This scores the classes of the tracker's own
    stride windows (what the rules used), not the labelled windows ``pdrlearn evaluate`` scores."""
    st, lab = result.steps, session.steps
    if lab is None or not len(lab) or not len(st) or "unit" not in st or not (st["unit"] == "foot").all():
        return
    tasks = [c for c in CLASS_TASKS if c in st and c in lab and st[c].notna().any() and lab[c].notna().any()]
    if not tasks:
        return
    lab = lab.reset_index(drop=True)
    pairs = match_strides(st, lab)  # steps decision 99
    n = 0
    for c in tasks:
        both = [(st[c].iloc[i], lab[c].iloc[j]) for i, j in pairs
                if pd.notna(st[c].iloc[i]) and pd.notna(lab[c].iloc[j])]
        if both:
            out[f"{c}_agreement"] = float(np.mean([str(a) == str(b) for a, b in both]))
            n = max(n, len(both))
    if n:
        out["class_agreement_strides"] = n


def _foot_stride_f1(result: TrackResult, session: Session, out: dict) -> None:
    """Foot tracks on sessions with ground-truth strides: ``step_f1`` (with ``step_precision`` /
    ``step_recall``) of the tracked strides against the labelled ones, matched by time overlap (IoU >= 0.5,
    as the stride lengths). A tracked stride matched to a labelled one is always scored; an unmatched one only
    when its middle lies in a labelled interval (the intervals of :func:`pdrlearn.steps.evaluate.reference_events`:
    a reference that labels part of a walk leaves the rest unscored; decision L249). A labelled stride that two or
    more tracked strides tile (a turn split at an intermediate rest) counts once, and its pieces are not false
    positives; a rest-based segmentation
    (``source=detected``) is not ground truth and gives no F1 (decision L36)."""
    st = session.steps
    if st is None or not len(st) or not len(result.steps) or "unit" not in result.steps:
        return
    if not (result.steps["unit"] == "foot").all():
        return
    from pdrlearn.steps.evaluate import in_intervals, reference_events

    ref = reference_events(session, "foot")
    if ref is None or not ref.ground_truth:
        return
    est = result.steps.reset_index(drop=True)
    pairs = match_strides(est, st)  # steps decision 99
    used_est, used_ref = {i for i, _ in pairs}, {j for _, j in pairs}
    tp = len(pairs) + len(_composed_strides(est, st, used_est, used_ref))  # adds the tiles to used_est
    # decision L249: a tracked stride matched to (or tiling) a labelled stride is always scored, as every labelled
    # stride is in the recall's denominator; only an unmatched one is scored by its middle (L36's intervals). The
    # first stride from standing starts a stance early, so its middle fell before the first IC's interval
    mid = est[["start_s", "end_s"]].to_numpy(float).mean(axis=1)
    scored = in_intervals(mid, ref.intervals)
    # steps decision 86: a tracked stride whose initial contact (event_s) `pdrlearn steps`' own matching pairs with a
    # reference contact (match_events, the reference's tolerance) is a hit there, so it is no false positive here
    # (the stride onto a chain's first labelled contact, pre_ic_s, has no labelled stride of its own)
    correct = used_est | _event_hits(est, ref)
    scored[list(correct)] = True
    precision = len(correct) / int(scored.sum()) if scored.any() else 0.0
    recall = tp / len(st)
    out["step_precision"], out["step_recall"] = float(precision), float(recall)
    out["step_f1"] = float(2 * precision * recall / (precision + recall)) if tp else 0.0


def _event_hits(est: pd.DataFrame, ref) -> set[int]:
    """Steps decision 86: the rows of the tracked strides ``est`` whose ``event_s`` :func:`pdrlearn.steps.evaluate.
    match_events` pairs one-to-one with a contact of the reference ``ref`` (``reference_events``): the detections
    `pdrlearn steps` counts as true positives. Empty without ``event_s``."""
    from pdrlearn.steps.evaluate import match_events

    if "event_s" not in est:
        return set()
    ev = pd.to_numeric(est["event_s"], errors="coerce").to_numpy(float)
    ok = np.flatnonzero(np.isfinite(ev))
    i_det, _ = match_events(ev[ok], ref.times, ref.tolerance_s)
    return {int(i) for i in ok[i_det]}


def _waist_references(result: TrackResult, session: Session, out: dict) -> None:
    """Waist tracks on sessions with Mobilise-D style references (``ics.csv``, ``bouts.csv``): ``step_f1``
    vs every initial contact, ``distance_error_pct`` over the reference walking bouts and
    ``stride_length_mae_m`` from the steps inside each reference stride (see pdrlearn.waist.evaluate).
    Without ``ics.csv`` and ``bouts.csv`` a ``steps.csv`` of strides still gives that stride metric, never
    :func:`_stride_lengths`' overlap match of one waist step with one stride (decision W49)."""
    if not len(result.steps) or "unit" not in result.steps or not (result.steps["unit"] == "waist").all():
        return
    from pdrlearn.steps.reference_clock import waist_clock_labels
    from pdrlearn.waist.evaluate import stride_metrics, waist_metrics

    session = waist_clock_labels(session)  # decision W380: the labels on the simulated waist clock
    refs = "ics" in session.extras or "bouts" in session.extras
    m = waist_metrics(result.steps, session) if refs else stride_metrics(result.steps, session)
    if "distance_error_pct" in m:  # the bouts, not the sum of overlapping stride lengths, are the reference
        out["distance_ref_m"] = m["bout_reference_m"]
        out["distance_ref_source"] = "bouts.csv length_m (distance tracked inside the bouts)"
        # decision W71: the error compares the distance tracked inside the reference bouts (not distance_m)
        # with distance_ref_m; say so next to the number
        out["distance_error_scope"] = "reference bouts"
        out["distance_in_ref_bouts_m"] = m["bout_distance_m"]
        out["distance_compared_m"] = m["bout_distance_m"]  # decision W459: the error's numerator, in every scope
    for k in ("stride_length_matched", "stride_length_composed", "stride_length_mae_pct",
              "stride_length_mae_pct_straight", "stride_length_mae_pct_turns", "stride_length_mae_pct_steady",
              "distance_matched_error_pct", "distance_matched_m", "distance_matched_ref_m"):
        out.pop(k, None)  # step rows are not strides: the stride metric of waist_metrics replaces these
    if "n_strides" in m:  # decision C19: the reference strides scored, not strides tracked (sessions.csv's
        m["n_reference_strides"] = m.pop("n_strides")  # n_strides column was 7 on the lower back, empty on the foot)
    out.update(m)


def _barometer(result: TrackResult, session: Session, out: dict) -> None:
    """Decision L127: ``barometer_unused`` - the session has a waist barometer (wBarometer.csv with samples) and
    the track is of foot strides, whose altitude is the foot's own (lower-back tracks read the barometer, and so
    does a foot track with ``altitude="fused"``, decision L154)."""
    steps = result.steps
    foot = bool(len(steps)) and "unit" in steps and bool((steps["unit"].astype(str) == "foot").all())
    baro = bool(foot and session.has("wBarometer") and len(session["wBarometer"]))
    out["barometer_unused"] = baro and (result.info or {}).get("altitude_source") != "fused"
    if baro:  # decision L145: the barometer's altitude change over the track, to compare
        from pdrlearn.kernels.barometer import relative_altitude
        from pdrlearn.track.barometer import FOOT_EFFECT, usable_barometer

        lines: list[str] = []
        b = usable_barometer(session, lines, FOOT_EFFECT)  # decision B188: an impossible pressure is not compared
        if b is None:  # one line per track: L154's fusion may have said it already
            if not any("decision B188" in w for w in (result.info or {}).get("warnings", [])):
                out["barometer_implausible"] = lines[0]
            return
        span = [float(steps["start_s"].min()), float(steps["end_s"].max())]
        at = np.unique(np.concatenate([span[:1], steps["end_s"].to_numpy(float)]))  # the strides' ends, in order
        # decision E232: the keys from the altitude at the strides' ends, one function with the live Tracker's
        out.update(barometer_keys(at, relative_altitude(b.t, b.values[:, 0], at),
                                  float(relative_altitude(b.t, b.values[:, 0], span)[1])))
        _weather_drift(b, steps, span, out)  # decision L464


def _weather_drift(b, steps: pd.DataFrame, span: list[float], out: dict) -> None:
    """Decision L464: ``weather_drift_rate_m_per_h`` (the barometric altitude's slope over the standstills of at
    least :data:`pdrlearn.kernels.weather_drift.STANDSTILL_MIN_S`, the weather's), ``weather_drift_standstill_s``
    (the seconds it was read on) and ``weather_drift_m`` (that rate over the strides' span: what the weather added
    to the barometer's net change and its climbs); None without such a standstill."""
    from pdrlearn.kernels.barometer import altitude_m
    from pdrlearn.kernels.weather_drift import drift_rate, standstills

    t = np.asarray(b.t, dtype=float)
    spans = standstills(steps["start_s"], steps["end_s"], float(np.nanmin(t)), float(np.nanmax(t)))
    rate, seconds = drift_rate(t, altitude_m(b.values[:, 0]), spans)
    out["weather_drift_standstill_s"] = seconds if rate is not None else None
    out["weather_drift_rate_m_per_h"] = None if rate is None else 3600.0 * rate
    out["weather_drift_m"] = None if rate is None else rate * (span[1] - span[0])


from pdrlearn.kernels.barometer_check import (  # noqa: E402, F401 (decision E232: numpy only, shared with the runtime)
    _FOOT_BLIND,
    BAROMETER_DISAGREE_M,
    BAROMETER_DRIFT_M_PER_H,
    _climb_miss,
    _closed_by_floors,
    barometer_keys,
    barometer_warning,
    ridden_climbs,
)

#: decision L172: a barometric track's altitude change that its climbs do not explain by more than this (m; twice
#: L146's band, so more than the band's uncounted remainder at the end) is named as the weather's slow drift
ALTITUDE_DRIFT_WARN_M = 1.0


#: decision W371: a drift under this (m) is not warned about as more than the weather's: the BMP280's per-sample
#: altitude noise (thesis Table 18: 0.0157 hPa = 0.13 m; W89)
DRIFT_BEYOND_WEATHER_FLOOR_M = 0.13


def drift_warning(summary: dict) -> str | None:
    """Decision L172: one line when a barometric altitude (a lower-back track, or ``altitude="fused"``) changed by
    more than :data:`ALTITUDE_DRIFT_WARN_M` slowly (``altitude_drift_m``): ``altitude_change_m`` includes it, the
    floors and ``ascent_m`` / ``descent_m`` do not. Decision W371: when the drift is more than the fastest weather
    makes in the track's span (``altitude_drift_limit_m``, and over :data:`DRIFT_BEYOND_WEATHER_FLOOR_M`), the line
    says it is not the weather's: climbs' remainders L172 did not count, or the barometer's own error (only where
    climbs were counted: ascent_m + descent_m at least L146's band)."""
    from pdrlearn.kernels.altitude_check import ASCENT_BAND_BARO_M

    drift = summary.get("altitude_drift_m")
    limit = summary.get("altitude_drift_limit_m")
    if drift is None:
        return None
    climbed = float(summary.get("ascent_m") or 0.0) + float(summary.get("descent_m") or 0.0)
    if (limit is not None and abs(float(drift)) > max(float(limit), DRIFT_BEYOND_WEATHER_FLOOR_M)
            and climbed >= ASCENT_BAND_BARO_M):  # decision W371: only where climbs were counted (their remainders)
        return (f"the barometric altitude's climbs leave {float(drift):+.2f} m uncounted as slow drift "
                f"(altitude_drift_m), more than the fastest weather (2 hPa/h) changes it in this track's span "
                f"({float(limit):.2f} m; decision W371): it is the part of climbs under L172's 0.5 m band (the end of "
                "a flight down, the top of a flight) or the barometer's own error, so ascent_m / descent_m may each be "
                f"short by up to {abs(float(drift)):.2f} m (pdrlearn.kernels.altitude_check.CLIMBS_WITHIN_WEATHER = "
                "True counts such climbs whole, W370, not adopted)")
    if not abs(float(drift)) > ALTITUDE_DRIFT_WARN_M:
        return None
    return (f"the barometric altitude drifted {float(drift):+.2f} m slowly (less than "
            f"0.5 m per minute: the weather's pressure trend, L172): altitude_change_m "
            f"{float(summary.get('altitude_change_m', 0.0)):+.2f} m includes it; the floors and ascent_m / descent_m "
            "count only climbs")


def climb_total_warning(summary: dict) -> str | None:
    """Decision L566: one line when a barometric track's ``ascent_m`` (``descent_m``) is more than
    :data:`DRIFT_BEYOND_WEATHER_FLOOR_M` (the BMP280's 0.13 m) below what its ramps and stair flights rise (drop)
    (``ramps_stairs_ascent_m`` / ``_descent_m``): L172's band-within-a-minute count lost part of climbs the track
    identified whole, so the route's height gained / lost is to be read from ramps.csv / stairs.csv. Decision W539:
    only when that whole reaches L172's band (``ASCENT_BAND_BARO_M``, 0.5 m; under it the band counts nothing by
    definition), and "counts none of" when ``ascent_m`` (``descent_m``) is 0."""
    from pdrlearn.kernels.altitude_check import ASCENT_BAND_BARO_M

    parts = []
    for key, word in (("ascent", "rise"), ("descent", "drop")):
        counted, whole = summary.get(f"{key}_m"), summary.get(f"ramps_stairs_{key}_m")
        if (counted is None or whole is None or not float(whole) - float(counted) > DRIFT_BEYOND_WEATHER_FLOOR_M
                or float(whole) < ASCENT_BAND_BARO_M):  # decision W539: a whole under the band is never counted
            continue
        short = ("counts none of" if round(float(counted), 2) == 0.0
                 else f"is {float(whole) - float(counted):.2f} m below")
        parts.append(f"{key}_m {float(counted):.2f} m {short} the {float(whole):.2f} m its ramps and stair flights "
                     f"{word} (ramps_stairs_{key}_m)")
    if not parts:
        return None
    return ("; ".join(parts) + ": the barometric count (L172: 0.5 m crossed within 60 s) drops the part of a climb "
            "under that band, so the height gained / lost of ramps and stairs is in ramps.csv rise_m / stairs.csv "
            "height_m (decision L566)")


def weather_drift_warning(summary: dict) -> str | None:
    """Decision L464: one line when a barometric track (a foot track fused with the barometer, L154: its
    ``altitude_drift_m`` is set) read more than :data:`ALTITUDE_DRIFT_WARN_M` of weather drift over its span from
    its standstills (``weather_drift_m``): the net change and the climbs include it, ``altitude_drift_m`` does not
    measure it."""
    drift, rate = summary.get("weather_drift_m"), summary.get("weather_drift_rate_m_per_h")
    if summary.get("altitude_drift_m") is None or drift is None or not abs(float(drift)) > ALTITUDE_DRIFT_WARN_M:
        return None
    standing = float(summary["weather_drift_standstill_s"])
    return (f"the barometer drifted {float(rate):+.2f} m/h while standing ({standing:.0f} s of standstill; the "
            f"weather, decision L464): over the track that is {float(drift):+.2f} m, which "
            f"altitude_change_m ({float(summary.get('altitude_change_m', 0.0)):+.2f} m) and the climbs while it "
            f"drifted (ascent_m / descent_m) include; altitude_drift_m ({float(summary['altitude_drift_m']):+.2f} m) "
            "is only the slow change L172 left out of the climbs, not this drift")


def _leg_length(result: TrackResult, session: Session, out: dict) -> None:
    """Decision L148: the walker's leg length from meta.json (``leg_length_m``, ``leg_length_source``), by which
    L95's walking range is scaled."""
    from pdrlearn.track.gait import leg_length

    out.update(leg_length(session.meta))


#: metric helpers run in order by :func:`evaluate_track`; append to extend.
METRICS = [_basic, _ground_truth, _altitude, _stride_lengths, _foot_stride_f1, _waist_references, _turns,
           _class_agreement, _barometer, _leg_length]


def add_gait_range_flag(summary: dict) -> dict:
    """Decision L195: ``gait_out_of_range`` (bool) - L95's session line fires (:func:`pdrlearn.track.gait.
    session_range_side`: above or below the walking range) or some bout lies above it (``n_bouts_out_of_range``);
    the machine-readable form of those warnings (sessions.csv, bouts.csv per bout). Set in place; returned.
    Decision L222: None (unknown, empty in sessions.csv) when L95 had no figure to judge (no cadence and no judged
    speed) and no bout is flagged - not False, which says "inside the range"."""
    from pdrlearn.track.gait import _judged, session_range_side

    if (summary.get("n_bouts_out_of_range") or 0) > 0 or session_range_side(summary) is not None:
        summary["gait_out_of_range"] = True
    else:
        cad, speed, _ = _judged(summary)
        summary["gait_out_of_range"] = False if cad is not None or speed is not None else None  # L222: unknown
    return summary


# decisions L321, L441: a declared treadmill (pdrlearn.track.belt; the names kept here for their callers)
from pdrlearn.track.belt import BELT_KEY, belt_line, belt_summary  # noqa: E402, F401

#: decision L680: L602's band in each direction grows to this fraction of the stair flights' height that way (ours:
#: the flights' summed height and the barometer's counted climbs each err in proportion to the climb)
FLIGHT_BAND_FRACTION = 0.10


def ramps_need_fused_warning(summary: dict) -> str | None:
    """Decision L574 (trial T3 finding F8): one line when a foot track did not read the session's waist barometer
    (``barometer_unused``) and the barometer counted a climb (``barometer_ascent_m`` / ``barometer_descent_m`` over
    0: L146's 0.5 m within L172's minute): its ramps.csv is the header alone and steps.csv's ``grade_pct`` empty
    (L300), which says nothing about the route's slopes. Decision L602 (session 42 trial T3 finding F1): only what
    the track's stair flights do not explain - the barometer's ascent less their rise (``flights_rise_m``), its
    descent less their drop (``flights_drop_m``) - counts, and only over L146's band
    (:data:`pdrlearn.kernels.altitude_check.ASCENT_BAND_BARO_M`, 0.5 m: the least climb the barometer counts), so a
    stair walk whose flights the track lists stays quiet (``--altitude fused`` would add no ramp to it).
    Decision L680: each direction's band is the larger of that and :data:`FLIGHT_BAND_FRACTION` of the flights'
    height that way (their disagreement with the barometer grows with the climb: a 17 m stair loop's flights missed
    0.58 m of the barometer's descent, streamed). Decision L717: a foot track's own ramps (``ramp_source`` "foot",
    ramps.csv from its L39 heights) explain their rise too (``ramps_rise_m`` / ``ramps_drop_m``), and the line then
    says ramps.csv holds only the ramps of strides rising 0.10 m or more."""
    from pdrlearn.kernels.altitude_check import ASCENT_BAND_BARO_M

    up = float(summary.get("barometer_ascent_m") or 0.0)
    down = float(summary.get("barometer_descent_m") or 0.0)
    ridden = ridden_climbs(summary) or {"ascent": 0.0, "descent": 0.0}  # decision L632: rides.csv's lifts
    rise, drop = float(summary.get("flights_rise_m") or 0.0), float(summary.get("flights_drop_m") or 0.0)
    ramp_up, ramp_down = float(summary.get("ramps_rise_m") or 0.0), float(summary.get("ramps_drop_m") or 0.0)
    left_up = up - ridden["ascent"] - rise - ramp_up  # decisions L602, L717
    left_down = down - ridden["descent"] - drop - ramp_down
    band_up, band_down = (max(ASCENT_BAND_BARO_M, FLIGHT_BAND_FRACTION * h) for h in (rise, drop))  # decision L680
    if (not summary.get("barometer_unused") or summary.get("grade_source") is not None
            or not (left_up > band_up or left_down > band_down)
            or barometer_warning(summary) is not None):  # decision L632: one line, L145's, names ramps too
        return None
    what = " and ".join(w for w, on in (("stairs.csv's flights", rise or drop),
                                        ("ramps.csv's ramps", ramp_up or ramp_down),  # decision L717
                                        ("rides.csv's rides", ridden["ascent"] or ridden["descent"])) if on)
    band = max(band_up if left_up > band_up else 0.0, band_down if left_down > band_down else 0.0)
    bands = ("" if band <= ASCENT_BAND_BARO_M else
             f", over {band:.2f} m: {100 * FLIGHT_BAND_FRACTION:g} % of the flights' climb, L680")
    codes = "L602, L632" + (", L717" if ramp_up or ramp_down else "")
    flights = ("" if not what else f" ({max(left_up, 0.0):.2f} m / {max(left_down, 0.0):.2f} m more than {what}, "
               f"{codes}{bands})")
    n = int(summary.get("n_ramps") or 0)
    held = ("ramps.csv is empty" if not n else  # decision L717: the foot's own ramps
            f"ramps.csv holds only the {n} ramp(s) of strides rising 0.10 m or more (the foot's own heights, L717)")
    return (f"the waist barometer climbed {up:.2f} m and descended {down:.2f} m{flights}, but {held} and "
            f"steps.csv has no grade_pct: {'other ' if n else ''}ramps / grades need --altitude fused (L300) - a foot "
            "track's own height levels every stride under 0.10 m (L39), a 1:12 ramp's at strides under 1.2 m "
            "(decision L574)")


def lower_back_grade_warning(summary: dict) -> str | None:
    """Decision W463 (trial T3 finding F9): one line when a lower-back track's ramps.csv has ramps (its grades the
    barometer's rise over the pendulum's step lengths, L300): a grade scales with the step-length calibration, so an
    uncalibrated track's (``info["params_source"]`` not ``"calibrated"``) reads high by about its distance shortfall."""
    if summary.get("grade_source") != "barometer" or not summary.get("n_ramps"):
        return None
    calibrated = ((summary.get("info") or {}).get("params_source") == "calibrated")
    return (f"ramps.csv's {int(summary['n_ramps'])} lower-back ramp(s): a grade is the barometer's rise over the "
            "pendulum's step lengths, so it scales with the step-length calibration - "
            + ("this track's calibration sets it; check it on a walk of known length before a 1:12 / 1:20 decision"
               if calibrated else
               "uncalibrated, 14 simulated 4-12 % ramps read +0.97 points high on average and up to +2.44 (their "
               "steps short by 5-24 %): run `pdrlearn calibrate` first, or track the foot with --altitude fused")
            + "; a ramp may also be split across a level stretch (decision W463)")


def summary_warnings(summary: dict, *, foot_clip_g: float | None = None) -> list[str]:
    """The warning lines a track's summary itself gives (``track`` and ``run``): decision L95's gait range,
    L353's reported gait speed below it while L95's judged figures are inside, and L195's bouts above it, decision
    L113's withheld stride-time CV, decision L196's CV pooled over bouts of different rhythm (L380: the stride-length
    CV over straight stretches of different length), decision L116's
    whole-sample rounding of the CV, decision L145's foot altitude against the unused barometer, decision B188's
    implausible barometer, decision L175's position uncertainty against the distance walked (and L341's radius
    beyond its calibration routes), decision L319's reference trajectory that does not travel, decision L414's
    --toe-off stance times below the contacts they were checked on, decision L574's empty ramps table of a foot
    track that left a climbing barometer unread, and decision W463's lower-back grades. Decision L688:
    ``foot_clip_g`` (:func:`pdrlearn.io.validate.foot_accel_clip_g`) names a clipped foot accelerometer in L145's
    line."""
    from pdrlearn.track.clinical import (
        pooled_cv_warning,
        pooled_length_cv_warning,
        resolution_warning,
        stride_cv_warning,
    )
    from pdrlearn.track.gait import (
        bout_range_warning,
        contact_cadence_warning,
        gait_range_warning,
        gait_speed_warning,
    )
    from pdrlearn.track.position_sigma import position_sigma_range_warning, position_sigma_warning
    from pdrlearn.track.toeoff import contact_rate_warning, stance_range_warning  # decision L414, steps 97

    return [w for w in (gait_range_warning(summary), contact_cadence_warning(summary),  # L431
                        gait_speed_warning(summary),  # L353: adopted by its rule
                        bout_range_warning(summary), stride_cv_warning(summary),
                        pooled_cv_warning(summary), pooled_length_cv_warning(summary),  # L380
                        resolution_warning(summary),
                        barometer_warning(summary, foot_clip_g=foot_clip_g),  # decision L688
                        drift_warning(summary), summary.get("barometer_implausible"),
                        weather_drift_warning(summary),  # decision L464
                        climb_total_warning(summary),  # decision L566
                        ramps_need_fused_warning(summary),  # decision L574
                        lower_back_grade_warning(summary),  # decision W463
                        position_sigma_warning(summary), position_sigma_range_warning(summary),
                        stationary_reference_warning(summary), stance_range_warning(summary),
                        contact_rate_warning(summary)) if w]


def evaluate_track(result: TrackResult, session: Session | None = None, *, bouts=None, bout_table=None,
                   storey_height_m: float = STOREY_HEIGHT_M) -> dict:
    """Summary metrics: ``distance_m``, ``n_steps``, ``final_position``, ``altitude_change_m``, the storeys
    climbed / descended and the floor reached (``floors_up``, ``floors_down``, ``storeys_changed``, storeys of
    ``storey_height_m``; with a reference altitude also ``floors_up_ref`` ..., decision L64) and, with
    ground truth, ``distance_error_pct``, ``final_position_error_m`` (horizontal, start-aligned),
    ``altitude_change_ref_m``, ``final_altitude_error_m``, ``final_position_error_3d_m``, ``altitude_error_pct``,
    per-task class agreement with the labels (``terrain_agreement``, ..., decision L53) and
    ``stride_length_mae_m`` / ``stride_length_mae_pct`` (strides matched by time overlap) and, with
    reference turns, ``n_turns``, ``turn_angle_mae_deg`` and ``turn_sign_agreement`` (decision L42); and
    ``n_bouts``, ``bout_definition`` of the detected walking bouts under ``bouts`` (a
    :class:`pdrlearn.track.bouts.BoutRule`, None = its defaults; decision L124); ``bout_table``: their table
    (:func:`pdrlearn.track.bouts.detected_bouts` under ``bouts``) when the caller has it (decision E73); with the
    trajectory's ``pos_sigma_m`` its last and largest value, ``final_position_sigma_m`` and
    ``max_position_sigma_m`` (m, decision L128). Decision L454: with a ``session`` whose meta.json declares a
    treadmill, the metrics are taken inside its declared incline (:func:`pdrlearn.track.belt.session_incline`: L442's
    storeys, flights and CV strides; it sets ``result.info["belt_incline_pct"]`` on the result it is given, which
    stairs.csv reads: pass a copy to keep yours unchanged, as ``TrackResult.summary`` and ``write_track`` do, L456)
    and the belt's keys follow (:func:`pdrlearn.track.belt.belt_summary`, L321 / L441) - one place for ``track``,
    ``run`` and this function."""
    from pdrlearn.track.belt import INCLINE_KEY, session_incline, session_where
    from pdrlearn.track.grade import info_stair_grade

    with session_incline(session) as incline, info_stair_grade(result.info):  # decision L469: --stair-grade
        if incline is not None:
            result.info[INCLINE_KEY] = incline  # stairs.csv reads it (clinical_tables)
        out = _evaluate_track(result, session, bouts=bouts, bout_table=bout_table, storey_height_m=storey_height_m)
    if session is not None:
        out.update(belt_summary(session.meta, out, session_where(session), result.steps))  # decisions L321, L441
    return out


def _evaluate_track(result: TrackResult, session: Session | None, *, bouts, bout_table, storey_height_m) -> dict:
    """:func:`evaluate_track`'s metrics, taken in the incline scope it opened."""
    from pdrlearn.track.bouts import BoutRule, bouts_summary

    if not (np.isfinite(storey_height_m) and storey_height_m > 0):
        raise ValueError(f"storey height {storey_height_m!r} m: give a positive number of metres (e.g. 3.0)")
    out: dict = {"storey_height_m": float(storey_height_m)}  # decisions L64, L127: the floor counts' storey
    for fn in METRICS:
        if fn is _basic:
            fn(result, out)
        elif session is not None:
            fn(result, session, out)
    if session is not None:
        from pdrlearn.track.belt import belt_walk_tests

        belt_walk_tests(session.meta, out)  # decision L445: no walkway test on a declared treadmill
    from pdrlearn.track.freezes import foot_freezes, freeze_summary

    # decision W213: a foot track's episodes; W216: a lower-back track sets "freezes" itself (None: not measured)
    if "freezes" not in result.info and session is not None:
        # decision L413: a side shuffle the foot tracked is no freeze
        result.info["freezes"], lines = foot_freezes(session, result.info.get("pipeline"), result.steps)
        for line in lines:
            import logging

            logging.getLogger("pdrlearn.track").warning("%s: %s", session.where, line)
        if lines:
            result.info["warnings"] = [*result.info.get("warnings", []), *lines]
    out.update(freeze_summary(result.info.get("freezes")))  # W213: n_freezes, freeze_time_s (None: not computed)
    if session is not None:  # decision W363: flight phases in the foot recording (jumps, running)
        from pdrlearn.track.flight import flight_summary

        win = result.info.get("window")  # decision W425: a --window's flights only (its seconds from the start)
        span = None if not win else (win["start_s"] + session.t_recording_start,
                                     win["end_s"] + session.t_recording_start)
        keys, line = flight_summary(session, result.info.get("pipeline"), span)
        out.update(keys)
        if keys["n_flight_phases"] is not None and "flights" not in result.info:  # decision W417: flights.csv
            from pdrlearn.track.flight import flight_rows

            result.info["flights"] = flight_rows(session, span)
        if line:
            import logging

            logging.getLogger("pdrlearn.track").warning("%s: %s", session.where, line)
            result.info["warnings"] = [*result.info.get("warnings", []), line]
    # decision L124: bouts.csv's rows and their definition; L195: the bouts above the (leg-scaled) walking range
    out.update(bouts_summary(result.steps, bouts, bout_table, leg_m=out.get("leg_length_m"),
                             turn_gaps=(bouts or BoutRule()).turn_gaps(result.info)))  # decisions C180 / C182
    if session is not None:  # decision W493: the detected bouts against the reference WBs (wb_scores.csv)
        _wb_scores(result, session, bouts, bout_table, out)
    if "pos_sigma_m" in result.trajectory and len(result.trajectory):  # decision L128: position uncertainty
        sigma = result.trajectory["pos_sigma_m"].to_numpy(float)
        out["final_position_sigma_m"] = float(sigma[-1])
        out["max_position_sigma_m"] = float(np.nanmax(sigma))
    return out


def _wb_scores(result: TrackResult, session: Session, bouts, bout_table, out: dict) -> None:
    """Decision W493: on a session with reference walking bouts (bouts.csv, level ``wb``), the detected bouts (the
    table bouts.csv holds, under the track's bout rule) matched to them as mobgap's ``categorize_intervals`` does
    (:mod:`pdrlearn.track.wb_scores`): the table in ``info["wb_scores"]`` (wb_scores.csv), the WB precision /
    recall / F1 and the per-WB DMO errors in the summary. Nothing without reference WBs."""
    from pdrlearn.steps.reference_clock import waist_clock_labels
    from pdrlearn.track.bouts import BoutRule, detected_bouts
    from pdrlearn.track.wb_scores import outside_spans, wb_evaluation
    from pdrlearn.waist.evaluate import reference_wbs

    ref = reference_wbs(waist_clock_labels(session))  # decision W380: the labels on the tracked clock
    if ref is None:
        return
    if bout_table is None:
        rule = bouts or BoutRule()
        bout_table = detected_bouts(result.steps, rule, leg_m=out.get("leg_length_m"),
                                    turn_gaps=rule.turn_gaps(result.info))  # decisions C180 / C182, as bouts.csv
    # decision W499: a --window drops the reference WBs it cuts; the detected bouts of those walks are left out too
    table, keys = wb_evaluation(outside_spans(bout_table, result.info.get("window_cut_wbs")), ref)
    result.info["wb_scores"] = table.to_dict("records")
    out.update(keys)


def domain_fraction(result: TrackResult) -> dict:
    """Decision C16: ``{"out_of_domain_fraction": share of the strides outside the model's training range}`` of a
    track whose ``info["out_of_domain"]`` holds a report (``track --model``; ``run``, decision E105), else ``{}``."""
    dom = result.info.get("out_of_domain")
    return {"out_of_domain_fraction": dom.get("out_of_domain_fraction")} if isinstance(dom, dict) else {}


#: decision E141: the entries of a track's ``info`` that summary.json leaves out, each with the file that holds it
#: instead (rows of a table, not summary values). One list for every writer of summary.json (``track``,
#: ``track-all``, ``TrackResult.summary``, ``run`` of a foot or a waist bundle): :func:`summary_info`.
SUMMARY_INFO_LEFT_OUT = {
    "transfers": "transfers.csv (decision W182)",
    "freezes": "freezes.csv (decision W213)",
    "flights": "flights.csv (decision W417)",
    "postures": "the runs behind the posture time keys (decision W222)",
    "yaw_turns": "turns.csv's turn timing (decision L210)",
    "rest_bias_rests": "the position radius's clock (decision L306)",
    "rides": "rides.csv (decision L377)",
    "trunk_contacts": "the lower-back contacts a two-unit TUG is timed on (decision W418)",
    "trunk_postures": "the lower-back posture runs behind a two-unit track's posture time keys (decision W586)",
    "trunk_yaw_turns": "the lower-back turns of a two-unit TUG's turn-to-sit (decisions W307, W418)",
    "waist_gap_turns": "turns.csv's rows of n_rows 0 on a foot track: the lower back's turn in a rest gap (L701)",
    "wb_scores": "wb_scores.csv (decision W493)",
    "window_cut_wbs": "the reference WBs a --window cuts, left out of wb_scores.csv (decision W499)",
}
#: decision E141: the entries of ``info["aid"]`` that summary.json leaves out (every fix's row: aided.png's)
SUMMARY_AID_LEFT_OUT = ("fix_table",)


def summary_info(info: dict) -> dict:
    """Decision E141: a track's ``info`` as summary.json holds it, a new dict: the entries of
    :data:`SUMMARY_INFO_LEFT_OUT` dropped, and ``aid``'s :data:`SUMMARY_AID_LEFT_OUT` (``info`` is not changed)."""
    out = {k: v for k, v in info.items() if k not in SUMMARY_INFO_LEFT_OUT}
    aid = out.get("aid")
    if isinstance(aid, dict) and any(k in aid for k in SUMMARY_AID_LEFT_OUT):
        out["aid"] = {k: v for k, v in aid.items() if k not in SUMMARY_AID_LEFT_OUT}
    return out


def track_summary(result: TrackResult, session: Session, *, pipeline: str | None = None, bouts=None,
                  bout_table=None, storey_height_m: float = STOREY_HEIGHT_M) -> dict:
    """The summary of a track, exactly as ``pdrlearn track`` writes it to ``summary.json`` (strict JSON:
    NaN -> None, numpy scalars -> Python numbers): :func:`evaluate_track`'s metrics (with the session's
    ground truth when it has some, :func:`pdrlearn.track.gait.gait_summary`'s gait speed and cadence
    included), ``session`` (meta.json's name), ``input_dir`` (the session folder, resolved; decision C13),
    ``pipeline``, ``info`` (the pipeline's settings and warnings), and where they apply
    ``out_of_domain_fraction`` (C16) and ``frames_inferred`` (D8). Mirrored turns against turns.csv (L42) and a
    cadence or speed outside the validated walking range (L95) are warned here. Also :meth:`TrackResult.summary`.

    Parameters
    ----------
    result : the pipeline's output (``get_pipeline(name)(session, ...)``).
    session : the session that was tracked (its ground truth, name and folder).
    pipeline : name written as ``pipeline``; default ``result.info["pipeline"]``.
    bouts : the walking-bout definition (:class:`pdrlearn.track.bouts.BoutRule`, decision L124; None = its
        defaults) behind ``n_bouts`` and ``bout_definition``.
    bout_table : :func:`pdrlearn.track.bouts.detected_bouts`'s table under ``bouts``, when the caller has it
        (decision E73: ``track`` detects the bouts once for bouts.csv and the summary); None = detected here.
    """
    import json
    import logging

    from pdrlearn.io.plasys import json_safe
    from pdrlearn.track.clinical import contact_timing

    # decisions L442, L454: the declared incline and the belt's keys (L321, L441) in evaluate_track
    summary = evaluate_track(result, session, bouts=bouts, bout_table=bout_table, storey_height_m=storey_height_m)
    summary.update(contact_timing(session, result.steps))  # decision L116: the contacts' timing resolution
    from pdrlearn.track.periods import time_accounting

    summary.update(time_accounting(result, session))  # decision L275 (track --window sets the window's own)
    if summary.get("tug_time_s") is None and summary.get("tug_time_note") is None and result.info.get(
            "transfers") is not None:  # decision W556: sitting read or a sit found, no rise: why no TUG time
        from pdrlearn.track.trunk_tug import tug_contacts
        from pdrlearn.waist.transfers import no_rise_note

        steps = tug_contacts(result)
        summary["tug_time_note"] = no_rise_note(result.info["transfers"], steps["start_s"] if steps is not None and len(
            steps) else [], summary.get("sitting_time_s"))
    summary["session"] = session.name
    from pdrlearn.track.bouts import session_ids

    summary.update(session_ids(session))  # decision C100: meta.json's subject and visit, as bouts.csv's
    folder = getattr(session, "folder", None)
    summary["input_dir"] = str(Path(folder).resolve()) if folder is not None else None
    summary["pipeline"] = pipeline if pipeline is not None else result.info.get("pipeline")
    summary["rate_hz"] = tracked_rate_hz(session, summary["pipeline"])  # decision C19
    from pdrlearn.track.units import span_cut_s

    unit = "waist" if str(summary["pipeline"]).startswith("waist") else "foot"  # the tracked unit (B126)
    uncut = getattr(session, "_unit_ends_uncut", None)  # decision B267: read_session's ends before a cut
    summary["common_span_cut_s"] = span_cut_s(uncut, session, unit)
    from pdrlearn.track.labelled_asymmetry import track_asymmetry
    from pdrlearn.track.steady import steady_trim

    summary["steady_trim"] = steady_trim()  # decision L415: the bout ends left out of the steady measures
    # decision L416: a foot unit and the lower back together (L447: not on clocks said to be offset)
    summary.update(track_asymmetry(session, result.steps, result.info.get("warnings", ()),
                                   result.info.get("unit_alignment")))
    from pdrlearn import __version__

    summary["pdrlearn_version"] = __version__  # decision C18: which pdrlearn wrote the numbers
    summary["info"] = dict(result.info)
    mirrored = turn_warning(summary)  # decision L42: the turns against turns.csv
    if mirrored:
        logging.getLogger("pdrlearn.track").warning("%s: %s", session.where, mirrored)
        summary["info"]["warnings"] = [*summary["info"].get("warnings", []), mirrored]
    for line in session.frame_warnings:  # decision W334: D10's frame warning, logged by the session, kept too
        if line not in summary["info"].get("warnings", []):
            summary["info"]["warnings"] = [*summary["info"].get("warnings", []), line]
    summary.update(domain_fraction(result))  # decision C16
    placement = scale = None
    if result.info.get("pipeline") == "plasys":  # decision B134: a foot unit that never swings is not on the foot
        from pdrlearn.track.foot_rest import foot_placement_line, foot_rest_stats, foot_scale_warning

        stats = foot_rest_stats(session)
        placement = foot_placement_line(session, stats, "")  # L352: the loop prefixes session.where; W415
        scale = foot_scale_warning(stats, "")  # decision B201: the foot accelerometer's rest |acc| off 1 g
    add_gait_range_flag(summary)  # decision L195
    from pdrlearn.io.validate import foot_accel_clip_g

    lines = summary_warnings(summary, foot_clip_g=foot_accel_clip_g(session))  # decision L688
    if placement:  # its cadence is not a foot's: B134's line replaces L95's "looks like running" guess
        from pdrlearn.track.gait import gait_range_warning

        lines = [ln for ln in lines if ln != gait_range_warning(summary)] + [placement]
    lines += [scale] if scale else []
    for line in lines:  # decisions L95 (running / very slow walking), L113 (CV withheld), B134, B201
        logging.getLogger("pdrlearn.track").warning("%s: %s", session.where, line)
        summary["info"]["warnings"] = [*summary["info"].get("warnings", []), line]
    from pdrlearn.waist.plausibility import withhold_step_count

    withhold_step_count(summary)  # decision W476: W442's contacts give no cadence or step time (after L95's lines)
    summary["info"] = summary_info(summary["info"])  # decision E141: W182's, W213's, L210's rows and aid's fixes
    for p in ("foot", "waist"):  # decision C142: each unit's frame status, a sessions.csv column
        summary[f"frame_{p}"] = session.frame_status(p)
    if session.frames_inferred:  # D8: undeclared frames taken from the data, to paste into meta.json
        summary["frames_inferred"] = session.frames_inferred
    from pdrlearn.warning_lines import machine_summary

    machine_summary(summary, [], session.where)  # decision E155 (C14: the API's summary is summary.json's)
    return json_safe(json.loads(json.dumps(
        summary, default=lambda o: o.item() if hasattr(o, "item") else str(o))))
