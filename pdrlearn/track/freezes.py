"""Freezing-of-gait episodes of a track: ``freezes.csv`` and ``n_freezes`` / ``freeze_time_s`` (decision W213).

The freeze index (:mod:`pdrlearn.kernels.freeze`: Moore et al. 2008's bands, Baechlin et al. 2010's 4 s windows every
0.5 s and band-power threshold) of the tracked unit's vertical acceleration: the lower back's for the waist
pipelines, the foot's for the foot pipelines. Orientation-free, the vertical acceleration is read as the
accelerometer's norm (gravity dominates it: for a small oscillation the norm's change is the component along
gravity; each window's mean, gravity, is removed by the index).

W213's threshold: the published global FI threshold of 1.5 (Baechlin et al. 2010, for the shank and thigh; as
published, not verified against the paper text here) flags the foot and the lower back of simulated shuffling walks
(0.2 m steps, FI 1.5-4) as freezing; here an episode needs an FI above :data:`UNIT_FI_THRESHOLD` (twice the
published value), band power of at least :data:`pdrlearn.kernels.freeze.FI_POWER_MIN` and 1 s.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.decision_refs import decision_ref
from pdrlearn.kernels.freeze import FI_STEP_S, FI_WINDOW_S, FREEZE_MIN_S, freeze_episodes, inside_episodes
from pdrlearn.track.bouts import contact_times

#: decision W213: the freeze-index threshold of a foot or lower-back unit (2 x Baechlin et al. 2010's 1.5)
UNIT_FI_THRESHOLD = 3.0
#: freezes.csv's columns (decision W213), in order
FREEZE_COLUMNS = ("freeze", "start_s", "end_s", "duration_s", "peak_fi")
#: decision W213: the summary keys of :func:`freeze_summary`
FREEZE_SUMMARY_KEYS = ("n_freezes", "freeze_time_s")


def unit_stream(pipeline: str | None) -> str:
    """The accelerometer a pipeline tracks: the lower back's for the waist pipelines (and `run`'s waist bundles),
    else the foot's."""
    return "wAccelerometer" if "waist" in str(pipeline) else "fAccelerometer"  # runtime-waist too


def freezes_of(t: np.ndarray, acc: np.ndarray) -> list[dict]:
    """Freeze episodes (freezes.csv's rows) of an accelerometer's samples ``acc`` (n, 3) m/s^2 at times ``t`` (s):
    its norm interpolated onto a uniform grid at the median sampling interval, then
    :func:`pdrlearn.kernels.freeze.freeze_episodes` with :data:`UNIT_FI_THRESHOLD` (decision W213)."""
    t = np.asarray(t, dtype=float)
    if t.size < 2:
        return []
    dt = float(np.median(np.diff(t)))
    if not (np.isfinite(dt) and dt > 0):
        return []
    grid = t[0] + dt * np.arange(int(np.floor((t[-1] - t[0]) / dt)) + 1)
    x = np.interp(grid, t, np.linalg.norm(np.asarray(acc, dtype=float), axis=1))
    eps = freeze_episodes(grid, x, 1.0 / dt, threshold=UNIT_FI_THRESHOLD, min_s=FREEZE_MIN_S)
    return [{"freeze": k + 1, "start_s": round(a, 3), "end_s": round(b, 3), "duration_s": round(b - a, 3),
             "peak_fi": round(fi, 3) if np.isfinite(fi) else None} for k, (a, b, fi) in enumerate(eps)]


def session_freezes(session, pipeline: str | None) -> list[dict] | None:
    """:func:`freezes_of` the tracked unit's accelerometer of ``session`` (None when the session has none)."""
    acc = session.streams.get(unit_stream(pipeline))
    if acc is None:
        return None
    return freezes_of(acc.t, acc.values)


#: decision L413: an episode at least this share of whose time the foot track's side-stepping strides (L228) cover is
#: a side shuffle, not a freeze (more than half: the strides, not the trembling, fill it; a rule, not fitted)
SIDE_SHARE_MIN = 0.5


def side_step_freezes(rows: list[dict] | None, steps) -> tuple[list[dict] | None, list[str]]:
    """Decision L413: ``(kept, lines)`` - the freeze episodes ``rows`` (freezes.csv's) without those that the foot
    track's side-stepping strides (steps.csv's ``sideways`` rows, L228: measured strides of over 0.15 m travelling
    60-120 deg from the foot's facing) cover for at least :data:`SIDE_SHARE_MIN` of their time, renumbered; one
    line naming each one left out. A side step lifts the foot little and lands it sharply, so its vertical
    acceleration has more power above 3 Hz than in the 0.5-3 Hz locomotor band (the trial's rightward shuffle: freeze
    index 3.8 against forward walking's 1.9, W213's threshold 3), which the index reads as trembling in place."""
    if not rows or steps is None or not len(steps) or "sideways" not in steps:
        return rows, []
    from pdrlearn.track.gait import sideways_rows

    is_side = sideways_rows(steps)
    a, b = steps["start_s"].to_numpy(float)[is_side], steps["end_s"].to_numpy(float)[is_side]
    oa, ob = steps["start_s"].to_numpy(float)[~is_side], steps["end_s"].to_numpy(float)[~is_side]
    kept, lines = [], []
    for r in rows:
        s0, s1 = float(r["start_s"]), float(r["end_s"])
        covered = float(np.sum(np.clip(np.minimum(b, s1) - np.maximum(a, s0), 0.0, None)))
        if s1 > s0 and covered >= SIDE_SHARE_MIN * (s1 - s0):
            why = "decision L413"
        elif side_echo(s0, s1, a, b, oa, ob):
            why = f"its index windows reach back {SIDE_REACH_S:g} s to them, decision L693"
        else:
            kept.append({**r, "freeze": len(kept) + 1})
            continue
        lines.append(f"the freeze index's episode at {s0:.1f}-{s1:.1f} s (peak {r.get('peak_fi')}) is left out of "
                     f"freezes.csv: the foot track's strides there are a side-stepping run ({covered:.1f} s of "
                     f"sideways strides, steps.csv sideways), which the index reads as freezing ({why})")
    return kept, lines


#: decision L693: how far (s) a centred freeze-index window at an episode's edge reaches beyond it (half of Baechlin
#: et al. 2010's 4 s window less half the 0.5 s step each window stands for)
SIDE_REACH_S = FI_WINDOW_S / 2 - FI_STEP_S / 2


def side_echo(s0: float, s1: float, side_a, side_b, other_a, other_b) -> bool:
    """Decision L693: whether the episode ``[s0, s1]`` s is read from side steps only - the side-stepping strides
    (``side_a`` / ``side_b``, their start / end s), each widened by :data:`SIDE_REACH_S` either side, cover it whole
    (every index window of it holds part of a side stride), and no other stride (``other_a`` / ``other_b``)
    overlaps it."""
    if np.any((np.asarray(other_b, float) > s0) & (np.asarray(other_a, float) < s1)):
        return False
    reach = sorted(zip(np.asarray(side_a, float) - SIDE_REACH_S, np.asarray(side_b, float) + SIDE_REACH_S,
                       strict=True))
    at = s0
    for lo, hi in reach:  # the widened side strides, in order, must leave no hole in [s0, s1]
        if lo > at:
            break
        at = max(at, hi)
    return bool(reach) and at >= s1


#: decision L617: a foot freeze-index episode is kept only with a stride within this many seconds of it (one index
#: window, Baechlin et al. 2010's 4 s: the episode's edges smear by up to a window)
FREEZE_WALK_GAP_S = FI_WINDOW_S


def walkless_freezes(rows: list[dict] | None, steps) -> tuple[list[dict] | None, list[str]]:
    """Decision L617: ``(kept, lines)`` - the freeze episodes ``rows`` without those that no stride of ``steps``
    (``start_s`` / ``end_s``) reaches within :data:`FREEZE_WALK_GAP_S` of (before its start, inside it or after its
    end), renumbered, and one line naming those left out. A freeze interrupts walking (Moore et al. 2008: on starting,
    turning or while walking); an episode with no walking next to it is the foot trembling on a vehicle's floor or a
    bike's pedal (trial T3: a cycling coast, a seated bus)."""
    if not rows or steps is None:
        return rows, []
    a = steps["start_s"].to_numpy(float) if len(steps) else np.zeros(0)
    b = steps["end_s"].to_numpy(float) if len(steps) else np.zeros(0)
    kept, gone = [], []
    for r in rows:
        s0, s1 = float(r["start_s"]) - FREEZE_WALK_GAP_S, float(r["end_s"]) + FREEZE_WALK_GAP_S
        if bool(np.any((b >= s0) & (a <= s1))):
            kept.append({**r, "freeze": len(kept) + 1})
        else:
            gone.append(r)
    if not gone:
        return kept, []
    spans = ", ".join(f"{r['start_s']:.1f}-{r['end_s']:.1f} s (peak {r.get('peak_fi')})" for r in gone[:5])
    return kept, [f"{len(gone)} freeze-index episode(s) ({spans}{', ...' if len(gone) > 5 else ''}) are left out of "
                  f"freezes.csv: no stride of the track lies within {FREEZE_WALK_GAP_S:g} s of them, and a freeze "
                  "interrupts walking; the foot trembled without walking (a vehicle's floor, a bike, a seat; "
                  "decision L617) - or it moved in strides the stride detectors could not cut: a contact too short "
                  "for their 0.1 s rest of the foot, as in running, whose strides are then lost from the track and "
                  f"the distance ({decision_ref('L800')})"]


def walked_freezes(rows: list[dict] | None, steps, *, min_length_m: float = 0.15, max_stride_s: float = 3.0,
                   min_s: float = FREEZE_MIN_S) -> tuple[list[dict] | None, list[str]]:
    """Decision L765: ``(kept, lines)`` - the freeze episodes ``rows`` with the time that walking strides of ``steps``
    cover cut out of them: each stride-free remainder of at least ``min_s`` (W213's shortest episode) stays an
    episode (the episode's ``peak_fi``), the rest are left out; renumbered, and one line naming the episodes left out
    or shortened. A walking stride travels at least ``min_length_m`` (L228 / L413's travel bound) within at most
    ``max_stride_s`` (Mobilise-D's 3 s break, L163: a longer stride holds a pause). A slow shuffler's foot (strides
    of 1.2-2 s, a 6 cm swing) has little power in the 0.5-3 Hz locomotor band and its heel strikes reach 3-8 Hz, so
    the index reads its steady walking as freezing (trial s50t3 F2); a freeze is trembling in place, with no stride,
    and an episode the shuffling ran into keeps it."""
    if not rows or steps is None or not len(steps) or "length_m" not in steps:
        return rows, []
    a, b = steps["start_s"].to_numpy(float), steps["end_s"].to_numpy(float)
    walk = (steps["length_m"].to_numpy(float) >= min_length_m) & (b - a <= max_stride_s)
    spans = sorted(zip(a[walk].tolist(), b[walk].tolist(), strict=True))
    kept, changed = [], []
    for r in rows:
        s0, s1 = float(r["start_s"]), float(r["end_s"])
        pieces, at = [], s0
        for lo, hi in spans:  # the episode's stride-free remainders, in order
            if hi <= at or lo >= s1:
                continue
            if lo > at:
                pieces.append((at, lo))
            at = max(at, hi)
        if at < s1:
            pieces.append((at, s1))
        pieces = [(x, y) for x, y in pieces if y - x >= min_s]
        if pieces != [(s0, s1)]:
            changed.append(r)
        kept += [{**r, "start_s": round(x, 3), "end_s": round(y, 3), "duration_s": round(y - x, 3)} for x, y in pieces]
    kept = [{**r, "freeze": k + 1} for k, r in enumerate(kept)]
    if not changed:
        return kept, []
    named = ", ".join(f"{r['start_s']:.1f}-{r['end_s']:.1f} s" for r in changed[:5])
    return kept, [f"{len(changed)} freeze-index episode(s) ({named}{', ...' if len(changed) > 5 else ''}) are left "
                  f"out of freezes.csv or shortened: the foot's strides of {min_length_m:g} m or more cover them, so "
                  "the foot walked there; slow or shuffling strides read as 3-8 Hz power (decision L765)"]


def foot_freezes(session, pipeline: str | None, steps, *,
                 walked_strides: bool = False) -> tuple[list[dict] | None, list[str]]:
    """Decisions W213, L413, L617: a foot track's freeze episodes (:func:`session_freezes`) without its side shuffles
    (:func:`side_step_freezes` over the track's ``steps``) and without those with no walking next to them
    (:func:`walkless_freezes`), and the lines naming those left out. ``walked_strides`` (decision L765, not adopted:
    off): first cut the walking strides' time out of them (:func:`walked_freezes`)."""
    rows, side = side_step_freezes(session_freezes(session, pipeline), steps)
    rows, walked = walked_freezes(rows, steps) if walked_strides else (rows, [])
    rows, alone = walkless_freezes(rows, steps)
    return rows, side + walked + alone


def freeze_index_on(options: dict | None) -> bool:
    """Decision W216: whether a lower-back track computes its freeze index - the ``freeze_index`` option, or
    ``freeze_veto`` (W214 needs the episodes); off by default (foot tracks always compute theirs)."""
    o = options or {}
    return bool(o.get("freeze_index") or o.get("freeze_veto"))


def lower_back_freezes(session, pipeline: str | None, options: dict | None) -> list[dict] | None:
    """:func:`session_freezes` of a lower-back track when :func:`freeze_index_on` its ``options``, else None (not
    measured: no freezes.csv, ``n_freezes`` / ``freeze_time_s`` null; decision W216)."""
    return session_freezes(session, pipeline) if freeze_index_on(options) else None


def freeze_table(rows: list[dict] | None) -> pd.DataFrame:
    """freezes.csv: one row per episode (:data:`FREEZE_COLUMNS`), empty with the header when none."""
    return pd.DataFrame(rows or [], columns=list(FREEZE_COLUMNS))


def freeze_summary(rows: list[dict] | None) -> dict:
    """``n_freezes`` and ``freeze_time_s`` (s in all) of the episodes; None for both when not computed."""
    if rows is None:
        return dict.fromkeys(FREEZE_SUMMARY_KEYS)
    return {"n_freezes": len(rows), "freeze_time_s": round(float(sum(r["duration_s"] for r in rows)), 3)}


def freeze_caveat_message(n: int, seconds: float, vetoed: bool) -> str:
    """Decision W215: the lower-back track's line when its freeze index found episodes: what else reads as freezing
    there, and whether the contacts inside were counted as steps (``vetoed``: W214's option)."""
    steps = ("their contacts were dropped (freeze_veto, decision W214)" if vetoed else
             "the contacts inside them are still counted as steps and distance (the option freeze_veto drops them, "
             "decision W214; off by default: it also drops slow shuffling steps)")
    return (f"{n} freeze episode(s) of {seconds:.1f} s in all (freezes.csv, the lower back's freeze index, decision "
            f"W213); {steps}. On the lower back the index also reads very slow shuffling (0.2-0.3 m/s), festinating "
            "walks and daily activities as freezing (decision W215): confirm a freeze with a foot unit or video")


def bout_spans(steps) -> list[tuple[float, float]]:
    """The ``(start_s, end_s)`` of each walking bout of ``steps`` (:func:`pdrlearn.track.bouts.bout_ranges`, the
    default rule): its first step's start to its last step's end."""
    from pdrlearn.track.bouts import bout_ranges

    if steps is None or not len(steps):
        return []
    st = steps.sort_values("start_s", kind="stable").reset_index(drop=True)
    s, e = st["start_s"].to_numpy(float), st["end_s"].to_numpy(float)
    return [(float(s[a]), float(np.nanmax(e[a:b]))) for a, b in bout_ranges(st)]


def unreliable_mask(rows: list[dict] | None, steps) -> np.ndarray:
    """Decision W396: for each freeze episode ``rows`` (freezes.csv's), whether the episodes together leave less than
    two of the index's windows (2 x :data:`pdrlearn.kernels.freeze.FI_WINDOW_S`, Baechlin et al. 2010's 4 s) of a
    walking bout of ``steps`` it overlaps uncovered: the index saw no walking around the "freeze", so it reads the
    walking itself (slow or shuffling gait, W215)."""
    rows = rows or []
    eps = [(float(r["start_s"]), float(r["end_s"])) for r in rows]
    out = np.zeros(len(rows), dtype=bool)
    for s, e in bout_spans(steps):
        if e <= s:
            continue
        grid = np.linspace(s, e, max(2, int(np.ceil((e - s) / 0.05)) + 1))  # 50 ms: the union's measure
        covered = inside_episodes(grid, eps)
        if (1.0 - covered.mean()) * (e - s) < 2.0 * FI_WINDOW_S:
            out |= np.array([min(b, e) > max(a, s) for a, b in eps], dtype=bool)
    return out


def unreliable_message(rows: list[dict], vetoed: bool) -> str:
    """Decision W396: the line naming the unreliable freeze episodes (:func:`unreliable_mask`)."""
    spans = ", ".join(f"{r['start_s']:.1f}-{r['end_s']:.1f} s" for r in rows)
    veto = "; freeze_veto (W214) left their contacts in" if vetoed else ""
    return (f"{len(rows)} freeze episode(s) ({spans}) leave under {2 * FI_WINDOW_S:g} s of their walking bout "
            "uncovered: unreliable, read as slow or shuffling walking rather than freezing (freezes.csv still lists "
            "them; decision W396)" + veto)


def freeze_hint(rows: list[dict] | None, steps) -> str | None:
    """Decision W395: with the freeze index off, the one line saying that counted steps lie in episodes of 3-8 Hz
    power (W213's, those :func:`unreliable_mask` does not flag); None when none does. The steps are unchanged."""
    if not rows or steps is None or not len(steps):
        return None
    ok = [r for r, bad in zip(rows, unreliable_mask(rows, steps), strict=True) if not bad]
    ev = contact_times(steps)  # closing re-read: as in_freeze reads it (a NaN contact: the step's start)
    each = [inside_episodes(ev, [(r["start_s"], r["end_s"])]) for r in ok]
    inside = np.logical_or.reduce(each) if each else np.zeros(len(ev), dtype=bool)
    if not inside.any():
        return None
    seconds = sum(r["duration_s"] for r, hit in zip(ok, each, strict=True) if hit.any())
    # decision W444: slow or shuffling walking named first (it fired on 6 of 40 fresh simulated slow walks without a
    # freeze, 0 of 10 normal ones)
    return (f"{int(inside.sum())} counted step(s) lie in {seconds:.1f} s of 3-8 Hz power (the lower back's freeze "
            "index over 3, decision W213): on the lower back most often slow or shuffling walking (the index fired "
            "on 6 of 40 simulated slow walks with no freeze, decision W444), else freezing or a turn on the spot, "
            "whose trembling is then counted as steps and walking; run with --freeze-index for freezes.csv (the "
            "option freeze_veto drops them; decision W395)")


def add_freeze_columns(bouts: pd.DataFrame, steps: pd.DataFrame, rows: list[dict] | None) -> pd.DataFrame:
    """Decision W397: when the freeze index ran (``rows``, freezes.csv's episodes, not None), bouts.csv's
    ``freeze_time_s`` (the seconds of the episodes inside each bout, ``start_s`` to ``end_s``) and, in place,
    steps.csv's ``in_freeze`` (the step's contact, ``event_s`` else ``start_s``, lies inside an episode); nothing
    when the index did not run (not measured). Returns ``bouts``."""
    if rows is None:
        return bouts
    eps = [(float(r["start_s"]), float(r["end_s"])) for r in rows]
    if len(steps):
        steps["in_freeze"] = inside_episodes(contact_times(steps), eps)
    if len(bouts):
        a, b = bouts["start_s"].to_numpy(float), bouts["end_s"].to_numpy(float)
        bouts["freeze_time_s"] = [round(sum(max(0.0, min(e, y) - max(s, x)) for s, e in eps), 3)
                                  for x, y in zip(a, b, strict=True)]
    return bouts
