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

import logging
import math
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError
from pdrlearn.track.clinical import bout_rows, symmetry_index_pct
from pdrlearn.track.flags import flag_values

#: the columns :func:`foot_events` gives: one row per initial contact of one foot
EVENT_COLUMNS = ("ic_s", "tc_s", "length_m")
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
#: decision L262: what the tracked double support is known to read (measured, experiments/bilateral_gait.py): L73's
#: toe-off is ~21 ms early and the IC ~15 ms late against motion capture, so each double-support period is short
SUPPORT_NOTE = ("double support reads low and single support high from foot units: the gyroscope's toe-off is "
                "~21 ms early and the initial contact ~15 ms late against motion capture (decision L73); on "
                "gaitmap's level walk -7.2 / +3.6 percentage points per cycle (decision L262)")


def foot_events(steps: pd.DataFrame) -> pd.DataFrame:
    """Decision L259: the IC events of one foot track's ``steps.csv`` (offline plasys: ``event_s``; ``tc_s`` with
    ``--toe-off``, else NaN; ``length_m``, NaN on an ``impossible`` stride) in time order; gap rows (``gap_s`` > 0,
    L67) and rows without an IC left out. A label table (``ic_s`` / ``tc_s`` in s, e.g. a mocap ``steps.csv`` read
    by :func:`pdrlearn.io.read_session`) is taken as it is."""
    ic_col = "event_s" if "event_s" in steps else "ic_s"
    if ic_col not in steps:
        raise DataError("bilateral gait: the foot table has no initial contacts (event_s / ic_s); track the foot "
                        "session offline (pdrlearn track, not --streaming)")
    ok = np.isfinite(steps[ic_col].to_numpy(float))
    if "gap_s" in steps:
        ok &= steps["gap_s"].to_numpy(float) == 0
    st = steps[ok]
    length = st["length_m"].to_numpy(float) if "length_m" in st else np.full(len(st), np.nan)
    if "impossible" in st:
        length = np.where(flag_values(st["impossible"]), np.nan, length)
    out = pd.DataFrame({"ic_s": st[ic_col].to_numpy(float),
                        "tc_s": st["tc_s"].to_numpy(float) if "tc_s" in st else np.full(len(st), np.nan),
                        "length_m": length})
    return out.sort_values("ic_s", kind="stable").reset_index(drop=True)


def merged_contacts(left: pd.DataFrame, right: pd.DataFrame) -> pd.DataFrame:
    """Both feet's :func:`foot_events` in time order with ``side`` and ``bout`` (1, 2 ...: decision L261, the
    merged contacts split at L104's pauses)."""
    both = pd.concat([left.assign(side="left"), right.assign(side="right")], ignore_index=True)
    both = both.sort_values("ic_s", kind="stable").reset_index(drop=True)
    bout = np.zeros(len(both), int)
    for k, (a, b) in enumerate(bout_rows(both.rename(columns={"ic_s": "start_s"})), start=1):
        bout[a:b] = k
    return both.assign(bout=bout)


def step_table(both: pd.DataFrame) -> pd.DataFrame:
    """Decision L259: one row per step of :func:`merged_contacts` - ``side`` (the foot it lands on), ``bout``,
    ``start_s`` (the other foot's IC), ``ic_s`` and ``step_time_s``."""
    t, side, bout = both["ic_s"].to_numpy(float), both["side"].to_numpy(), both["bout"].to_numpy(int)
    k = np.flatnonzero((side[1:] != side[:-1]) & (bout[1:] == bout[:-1])) + 1
    return pd.DataFrame({"side": side[k], "bout": bout[k], "start_s": t[k - 1], "ic_s": t[k],
                         "step_time_s": t[k] - t[k - 1]})


def cycle_table(both: pd.DataFrame) -> pd.DataFrame:
    """Decision L262: one row per gait cycle of either foot (one IC of it to its next, in one bout, with exactly one
    IC of the other foot between them - a stride either track or label table lacks makes no cycle): ``side``,
    ``bout``, ``start_s``, ``end_s``, ``stride_time_s``, ``double_support_pct`` and ``single_support_pct`` (module
    docstring; NaN where a toe-off is missing or the events are out of order)."""
    rows = []
    t, tc, side, bout = (both["ic_s"].to_numpy(float), both["tc_s"].to_numpy(float), both["side"].to_numpy(),
                         both["bout"].to_numpy(int))
    for s in SIDES:
        own = np.flatnonzero(side == s)
        for a, b in zip(own[:-1], own[1:], strict=True):
            if bout[a] != bout[b] or b - a != 2:  # L262: exactly one IC of the other foot inside: it alternated
                continue
            T = t[b] - t[a]
            ds = ss = math.nan
            ic_f, tc_o, ic_o, tc_f, ic_next = t[a], tc[a + 1], t[a + 1], tc[b], t[b]
            if ic_f < tc_o < ic_o < tc_f < ic_next:  # Perry & Burnfield 2010: the cycle's event order
                ds = 100.0 * ((tc_o - ic_f) + (tc_f - ic_o)) / T
                ss = 100.0 * (ic_o - tc_o) / T
            rows.append((s, int(bout[a]), t[a], t[b], T, ds, ss))
    cols = ["side", "bout", "start_s", "end_s", "stride_time_s", "double_support_pct", "single_support_pct"]
    return pd.DataFrame(rows, columns=cols).sort_values("start_s", kind="stable").reset_index(drop=True)


def _mean(x) -> float | None:
    x = np.asarray(x, dtype=float)
    x = x[np.isfinite(x)]
    return float(x.mean()) if len(x) else None


def _pair(name: str, left: float | None, right: float | None) -> dict:
    """``{name}_left``, ``_right``, ``_si_pct`` (Robinson 1987) and ``_ratio`` (L / R, Patterson et al. 2010)."""
    both = left is not None and right is not None and left + right > 0 and right > 0
    return {f"{name}_left": left, f"{name}_right": right,
            f"{name}_si_pct": symmetry_index_pct(left, right) if both else None,
            f"{name}_ratio": float(left / right) if both else None}


def gait_measures(both: pd.DataFrame, steps: pd.DataFrame, cycles: pd.DataFrame) -> dict:
    """Decisions L259, L262: the walk's (or one bout's) bilateral measures from its tables (module docstring)."""
    out = {"n_steps_left": int((steps["side"] == "left").sum()), "n_steps_right": int((steps["side"] == "right").sum())}
    out.update(_pair("step_time_s", *(_mean(steps.loc[steps["side"] == s, "step_time_s"]) for s in SIDES)))
    out.update(_pair("stride_time_s", *(_mean(cycles.loc[cycles["side"] == s, "stride_time_s"]) for s in SIDES)))
    out.update(_pair("stride_length_m", *(_mean(both.loc[both["side"] == s, "length_m"]) for s in SIDES)))
    ok = cycles["double_support_pct"].notna()
    out["n_support_cycles"] = int(ok.sum())
    out["double_support_pct"] = _mean(cycles.loc[ok, "double_support_pct"])
    out.update(_pair("single_support_pct", *(_mean(cycles.loc[ok & (cycles["side"] == s), "single_support_pct"])
                                             for s in SIDES)))
    return out


def bilateral_gait(left_steps: pd.DataFrame, right_steps: pd.DataFrame) -> dict:
    """Decisions L259-L262 (Python API): bilateral gait of one walk from the left and the right foot's step
    tables (a foot track's ``steps.csv`` or a label table, :func:`foot_events`) on one clock.

    Returns ``{"walk": measures, "bouts": [measures + bout, start_s, end_s], "steps": step table, "cycles":
    cycle table, "toe_off": bool, "reason": str | None}``; measures are :func:`gait_measures`' (None where the
    tables cannot give them). Refuses (:class:`DataError`, one line) two tables whose contacts do not overlap in
    time (L260: not one walk on one clock)."""
    left, right = foot_events(left_steps), foot_events(right_steps)
    for s, ev in zip(SIDES, (left, right), strict=True):
        if len(ev) < 2:
            raise DataError(f"bilateral gait: the {s} foot has {len(ev)} initial contact(s); give a walk of at least "
                            "two strides of each foot")
    lo, hi = max(left["ic_s"].iloc[0], right["ic_s"].iloc[0]), min(left["ic_s"].iloc[-1], right["ic_s"].iloc[-1])
    if not lo < hi:  # decision L260
        raise DataError(f"bilateral gait: the clocks do not overlap (left contacts {left['ic_s'].iloc[0]:.1f}-"
                        f"{left['ic_s'].iloc[-1]:.1f} s, right {right['ic_s'].iloc[0]:.1f}-"
                        f"{right['ic_s'].iloc[-1]:.1f} s); give the two feet of one walk, recorded on one clock")
    both = merged_contacts(left, right)
    alternation_warning(both)
    steps, cycles = step_table(both), cycle_table(both)
    toe_off = bool(np.isfinite(both["tc_s"]).any())
    bouts = []
    for k in sorted(set(both["bout"])):
        b = both[both["bout"] == k]
        m = gait_measures(b, steps[steps["bout"] == k], cycles[cycles["bout"] == k])
        bouts.append({"bout": int(k), "start_s": float(b["ic_s"].iloc[0]), "end_s": float(b["ic_s"].iloc[-1]), **m})
    if not toe_off:
        reason = ("no toe-off in the foot tables: double and single support need each foot's terminal contact "
                  "(pdrlearn track --toe-off, decision L73); the step times are given")
    else:  # decision L262: a foot track's (event_s) support times carry L73's biases; a label table's do not
        reason = SUPPORT_NOTE if "event_s" in left_steps else None
    return {"walk": gait_measures(both, steps, cycles), "bouts": bouts, "steps": steps, "cycles": cycles,
            "toe_off": toe_off, "reason": reason}


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


def check_one_walk(left_dir: Path, right_dir: Path, left_meta: dict, right_meta: dict) -> None:
    """Decision B245: refuse (one line) two sessions whose ``meta.json`` names different activities
    (:data:`WALK_META_KEYS`, both given): not the two feet of one walk."""
    for k in WALK_META_KEYS:
        a, b = left_meta.get(k), right_meta.get(k)
        if a is not None and b is not None and str(a).strip().lower() != str(b).strip().lower():
            raise DataError(f"gait: {left_dir} and {right_dir} are different recordings (meta.json {k}: {a!r} / "
                            f"{b!r}); give the two feet of one walk")


def label_steps(session) -> pd.DataFrame | None:
    """A session's labelled strides with IC / TC times (``ic_s`` and ``tc_s``, e.g. gaitmap's mocap events; the
    simulator's ``steps.csv``) as a :func:`foot_events` table, or None without labelled ICs."""
    st = session.steps
    if st is None or "ic_s" not in st or not np.isfinite(st["ic_s"].to_numpy(float)).any():
        return None
    return st


def pair_sessions(left_dir: Path, right_dir: Path) -> dict:
    """Decisions L259-L263: read and track (offline plasys with ``toe_off=True``, L73) the left and the right foot's
    session folders of one walk and give :func:`bilateral_gait` of their tracks, plus ``"reference"``: the same
    measures of their labelled events when both sessions have them (L263), and ``"sessions"``: each track's
    summary line data (``n_strides``, ``distance_m``)."""
    from pdrlearn.io import read_session
    from pdrlearn.track.plasys import track_plasys

    sessions = [read_session(d) for d in (left_dir, right_dir)]
    check_pair(left_dir, right_dir, sessions[0].meta, sessions[1].meta, *(s.content_id() for s in sessions))
    for d, s in zip((left_dir, right_dir), sessions, strict=True):
        if not s.has("fAccelerometer", "fGyroscope"):
            raise DataError(f"gait: {d} has no foot unit (fAccelerometer.csv, fGyroscope.csv); give a foot session")
    check_one_walk(left_dir, right_dir, sessions[0].meta, sessions[1].meta)
    tracks = [track_plasys(s, toe_off=True) for s in sessions]
    out = bilateral_gait(tracks[0].steps, tracks[1].steps)
    labels = [label_steps(s) for s in sessions]
    out["reference"] = (bilateral_gait(labels[0], labels[1]) if all(x is not None for x in labels) else None)
    out["sessions"] = {side: {"session": str(d), "n_strides": int(len(t.steps))}
                       for side, d, t in zip(SIDES, (left_dir, right_dir), tracks, strict=True)}
    return out
