"""The phases of a lower-back Timed-Up-and-Go (decision W293, docs/decisions/waist.md): sit-to-stand, walk out, turn,
walk back, turn-to-sit and stand-to-sit, cut from the rows a track already has - transfers.csv (W182), turns.csv
(L200 / L210) and the walking contacts (steps.csv ``start_s``) - never from a second detector.

The names follow the instrumented TUG's segmentation (Salarian et al. 2010, IEEE TNSRE 18:303-310; Weiss et al.
2011; both as recalled, not from a seed); the boundaries are this module's choice (W293):

* ``sit_to_stand`` / ``stand_to_sit``: the TUG's rise and sit rows (W183's ``tug_time_s`` runs from one to the other);
* ``turn``: the first turn whose midpoint lies between the rise's end and the sit's start; ``turn_to_sit``: the last
  one when there are two or more;
* ``walk_out``: the first walking contact after the rise's end to the turn's start;
* ``walk_back``: the turn's end to the turn-to-sit's start, or without one to the last walking contact before the
  sit's start.

Decision W307: when turns.csv has no second turn, the turn-to-sit may come from the track's yaw-rate turns
(``info["yaw_turns"]``, El-Gohary's, L210) - the last one of at least turns.csv's 80 deg (L200) that starts at or
after the turn's end with its midpoint before the sit's start (:func:`yaw_turn_to_sit`; W308: adopted).
turns.csv itself is unchanged (L233/L234).

A phase that cannot be placed (no turn, an end not after its start) is None. Standing still before the first step
or before the sit is in no phase.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

#: decision W293: the phases, in time order
TUG_PHASES = ("sit_to_stand", "walk_out", "turn", "walk_back", "turn_to_sit", "stand_to_sit")
#: decision W293: tug_phases.csv's columns, in order
TUG_PHASE_COLUMNS = ("phase", "start_s", "end_s", "duration_s")
#: decision W293: the summary's flat duration keys (sessions.csv keeps scalars only, C12), one per phase
TUG_PHASE_KEYS = tuple(f"tug_{p}_s" for p in TUG_PHASES)
#: decision W325: tug_trials.csv's columns, in order
TUG_TRIAL_COLUMNS = ("trial", "start_s", "end_s", "tug_time_s", *TUG_PHASE_KEYS, "n_steps", "n_turns",
                     "steps_source", "turns_source")  # W419: the unit each count comes from
#: the phases as the console line names them
PHASE_LABELS = {"sit_to_stand": "sit-to-stand", "walk_out": "walk out", "turn": "turn", "walk_back": "walk back",
                "turn_to_sit": "turn-to-sit", "stand_to_sit": "stand-to-sit"}


def phase_span(start: float | None, end: float | None) -> dict | None:
    """Decision W293: a phase's ``{start_s, end_s, duration_s}``; None when either time is missing or the end is not
    after the start."""
    if start is None or end is None or not np.isfinite(start) or not np.isfinite(end) or end <= start:
        return None
    return {"start_s": float(start), "end_s": float(end), "duration_s": float(end - start)}


def yaw_turn_to_sit(yaw_turns, after_s: float, before_s: float, min_deg: float | None = None) -> dict | None:
    """Decision W307: the turn-to-sit among a track's yaw-rate turns (``info["yaw_turns"]`` records, L210): the last
    one of |angle| >= ``min_deg`` (None: turns.csv's :data:`~pdrlearn.track.clinical.TURN_COUNT_MIN_DEG`, 80 deg,
    L200) that starts at or after ``after_s`` (the first turn's end) and whose midpoint lies before ``before_s``
    (the sit's start); ``{start_s, end_s}`` (El-Gohary's times, as turns.csv's, L210) or None."""
    from pdrlearn.track.clinical import TURN_COUNT_MIN_DEG

    lim = TURN_COUNT_MIN_DEG if min_deg is None else float(min_deg)
    found = None
    for y in sorted(yaw_turns or [], key=lambda r: float(r["start_s"])):
        a, b = float(y["start_s"]), float(y["end_s"])
        if abs(float(y["angle_deg"])) >= lim and a >= after_s and 0.5 * (a + b) < before_s:
            found = {"start_s": a, "end_s": b}
    return found


def tug_phases(transfers, turns: pd.DataFrame | None, steps: pd.DataFrame | None, yaw_turns=None,
               yaw_to_sit: bool = True, *, walk: pd.DataFrame | None = None) -> dict | None:
    """Decision W293: ``{phase: {start_s, end_s, duration_s} or None}`` for each of :data:`TUG_PHASES` of a track's
    transfers (a transfers.csv table or its records), ``turns`` (turns.csv) and ``steps`` (the walking contacts,
    ``start_s``); None when the track has no TUG time (W183's :func:`~pdrlearn.waist.transfers.transfer_summary`).
    Decision W307: with ``yaw_to_sit`` (True: W308 adopted it; decision W467) and one turns.csv turn in the TUG, the
    turn-to-sit is :func:`yaw_turn_to_sit` of ``yaw_turns`` (a lower-back track's ``info["yaw_turns"]``).
    Decisions W490 / L614: the TUG time is judged with ``turns`` and ``walk`` (a two-unit foot track's strides) as
    :func:`~pdrlearn.waist.transfers.transfer_summary` judges it (W498: with the waist's ``yaw_turns``)."""
    from pdrlearn.waist.transfers import SIT_TO_STAND, STAND_TO_SIT, transfer_summary

    if transfers is None or transfer_summary(transfers, steps, turns=turns, walk=walk,
                                             yaw_turns=yaw_turns)["tug_time_s"] is None:  # W498
        return None
    tr = _table(transfers)
    rise = tr[tr["kind"] == SIT_TO_STAND].iloc[0]  # W183: exactly one rise, then one sit
    sit = tr[tr["kind"] == STAND_TO_SIT].iloc[-1]
    return segment_phases(rise, sit, turns, steps, yaw_turns, yaw_to_sit)


def _table(transfers) -> pd.DataFrame:
    """A transfers.csv table of ``transfers`` (a table or its records)."""
    from pdrlearn.waist.transfers import TRANSFER_COLUMNS

    return pd.DataFrame(list(transfers) if not isinstance(transfers, pd.DataFrame) else transfers,
                        columns=list(TRANSFER_COLUMNS))


def _turns_inside(turns: pd.DataFrame | None, up: float, down: float) -> pd.DataFrame:
    """Decision W293: the turns.csv rows whose midpoint lies between ``up`` (the rise's end) and ``down`` (the sit's
    start), by start time."""
    from pdrlearn.waist.transfers import turns_inside

    return turns_inside(turns, up, down)


def segment_phases(rise, sit, turns: pd.DataFrame | None, steps: pd.DataFrame | None, yaw_turns=None,
                   yaw_to_sit: bool = True) -> dict:
    """Decision W293: the phases of one seat-to-seat segment, from its ``rise`` and ``sit`` transfers.csv rows (W183's
    TUG, or one of W325's trials), ``turns`` (turns.csv), ``steps`` (the walking contacts) and W307's ``yaw_turns``
    / ``yaw_to_sit`` (:func:`tug_phases`)."""
    up, down = float(rise["end_s"]), float(sit["start_s"])
    contacts = np.zeros(0) if steps is None or not len(steps) else np.sort(steps["start_s"].to_numpy(float))
    contacts = contacts[(contacts > up) & (contacts < down)]
    inside = _turns_inside(turns, up, down)
    turn = inside.iloc[0] if len(inside) else None
    to_sit = inside.iloc[-1] if len(inside) >= 2 else None
    if to_sit is None and turn is not None and yaw_to_sit:
        to_sit = yaw_turn_to_sit(yaw_turns, float(turn["end_s"]), down)  # decision W307
    first = float(contacts[0]) if contacts.size else None
    last = float(contacts[-1]) if contacts.size else None
    out = {"sit_to_stand": phase_span(float(rise["start_s"]), up),
           "walk_out": phase_span(first, None if turn is None else float(turn["start_s"])),
           "turn": None if turn is None else phase_span(float(turn["start_s"]), float(turn["end_s"])),
           "walk_back": (None if turn is None else
                         phase_span(float(turn["end_s"]), float(to_sit["start_s"]) if to_sit is not None else last)),
           "turn_to_sit": None if to_sit is None else phase_span(float(to_sit["start_s"]), float(to_sit["end_s"])),
           "stand_to_sit": phase_span(down, float(sit["end_s"]))}
    return out


def tug_trial_table(transfers, turns: pd.DataFrame | None, steps: pd.DataFrame | None, yaw_turns=None,
                    yaw_to_sit: bool = True, foot: pd.DataFrame | None = None) -> pd.DataFrame:
    """Decision W325: tug_trials.csv's rows (:data:`TUG_TRIAL_COLUMNS`), one per TUG trial
    (:func:`~pdrlearn.waist.transfers.tug_trial_pairs`) of a track's transfers, with each trial's W293 phases
    (:func:`segment_phases`), its walking contacts from the rise's start to the sit's end and its turns.csv turns.
    Decision W419: ``foot`` (a two-unit track's foot strides, ``turns`` then the foot's turns.csv) counts the steps
    (:func:`~pdrlearn.track.trunk_tug.foot_step_count`); ``steps_source`` / ``turns_source`` name the unit."""
    from pdrlearn.track.trunk_tug import FOOT, WAIST, foot_step_count
    from pdrlearn.waist.transfers import contact_path, flag_texts, shape_turns, tug_trial_pairs

    rows = []
    if transfers is not None:
        tr = _table(transfers)
        contacts = np.zeros(0) if steps is None or not len(steps) else steps["start_s"].to_numpy(float)
        for k, (i, j) in enumerate(tug_trial_pairs(tr["kind"], tr["start_s"], tr["end_s"], flag_texts(tr["flag"]),
                                                   contacts, **contact_path(steps, foot),
                                                   turns=shape_turns(turns, foot, yaw_turns))):  # W490, W498
            rise, sit = tr.iloc[i], tr.iloc[j]
            t0, t1 = float(rise["start_s"]), float(sit["end_s"])
            phases = tug_phase_summary(segment_phases(rise, sit, turns, steps, yaw_turns, yaw_to_sit))
            rows.append({"trial": k + 1, "start_s": t0, "end_s": t1, "tug_time_s": t1 - t0,
                         **{key: phases[key] for key in TUG_PHASE_KEYS},
                         "n_steps": (int(((contacts >= t0) & (contacts <= t1)).sum()) if foot is None
                                     else foot_step_count(foot, t0, t1)),  # W419
                         "n_turns": len(_turns_inside(turns, float(rise["end_s"]), float(sit["start_s"]))),
                         "steps_source": WAIST if foot is None else FOOT,
                         "turns_source": WAIST if foot is None else FOOT})
    return pd.DataFrame(rows, columns=list(TUG_TRIAL_COLUMNS))


def tug_trials_line(summary: dict, table: pd.DataFrame | None = None) -> str | None:
    """Decision W325: ``track``'s line of the TUG trials when there is no single ``tug_time_s``; None otherwise.
    ``table``: tug_trials.csv's rows (the times listed); without it only the count and the median."""
    n = summary.get("n_tug_trials")
    if not n or summary.get("tug_time_s") is not None:
        return None
    times = "" if table is None or not len(table) else ", ".join(f"{t:.2f}" for t in table["tug_time_s"]) + " s "
    walks = summary.get("n_chair_walks")
    return (f"{n} TUG trial(s): {times}(median {summary['tug_trials_median_s']:.2f} s; tug_trials.csv, "
            "decision W325)" + (f"; {walks} chair-to-chair walk(s) not timed (W445)" if walks else ""))


def tug_phase_summary(phases: dict | None) -> dict:
    """Decision W293: the summary's ``tug_phases`` (the object, None without a TUG) and :data:`TUG_PHASE_KEYS`
    (each phase's duration, None when the phase is)."""
    out = {"tug_phases": phases}
    for phase, key in zip(TUG_PHASES, TUG_PHASE_KEYS, strict=True):
        span = (phases or {}).get(phase)
        out[key] = None if span is None else span["duration_s"]
    return out


def tug_phase_table(phases: dict | None) -> pd.DataFrame:
    """Decision W293: tug_phases.csv's rows (:data:`TUG_PHASE_COLUMNS`), one per phase placed, in time order."""
    rows = [{"phase": p, **phases[p]} for p in TUG_PHASES if phases and phases.get(p) is not None]
    return pd.DataFrame(rows, columns=list(TUG_PHASE_COLUMNS))


def tug_phase_line(summary: dict) -> str | None:
    """Decision W293: ``track``'s one line of the TUG phases' durations; None without them."""
    phases = summary.get("tug_phases")
    if not phases:
        return None
    parts = [f"{PHASE_LABELS[p]} {phases[p]['duration_s']:.2f} s" if phases.get(p) else f"{PHASE_LABELS[p]} -"
             for p in TUG_PHASES]
    return "TUG phases: " + ", ".join(parts) + " (tug_phases.csv, decision W293)"
