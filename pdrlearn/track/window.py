"""A time window of a track (decision L105, ``pdrlearn track --window START,END``): the 2-minute-walk distance at
120 s, the speed over the middle of a 10 m walk.

The whole session is tracked (the trackers keep their start-up: the foot's first rest, the lower back's heading)
and the track is then cut: a step (a stride of the tracked foot, a step on the lower back) belongs to the
window when its midpoint lies inside (the accounting rule of the lower-back evaluation and calibration, W21:
strides across either edge count once, on the side of their larger part). The session's references are cut by
the same rule (labelled strides by their midpoint, initial contacts by their time, reference bouts and turns
only when wholly inside), so the summary's errors compare the window with the window. A lower-back track's yaw-rate
turns (``info["yaw_turns"]``, L210) are cut by the steps' rule, their midpoint (decision W329), so turns.csv and the
turn summary keys hold the window's turns only.
"""

from __future__ import annotations

import dataclasses
import logging
import math

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError
from pdrlearn.io.session import Session
from pdrlearn.track.base import TrackResult

WINDOW_USAGE = ("give --window START,END in seconds from the session start, e.g. --window 0,120 or 5,15 (or clock "
                "times, 02:10,02:20, when the session gives its start)")


def parse_window(text: str | None):
    """``"START,END"`` (s) -> ``(start, end)``; None for None. One :class:`DataError` line for a text that is not
    two finite numbers with 0 <= START < END. Clock times (``02:10,02:20`` or two ISO 8601 date-times, decision
    L299) -> a :class:`pdrlearn.track.clock.ClockWindow`, resolved per session by :func:`check_window`."""
    if text is None:
        return None
    from pdrlearn.track.clock import parse_clock_window

    clock = parse_clock_window(text)
    if clock is not None:
        return clock
    parts = [p.strip() for p in str(text).split(",")]
    try:
        if len(parts) != 2:
            raise ValueError
        start, end = float(parts[0]), float(parts[1])
    except ValueError:
        raise DataError(f"--window {text!r}: expected two numbers START,END; {WINDOW_USAGE}") from None
    if not (math.isfinite(start) and math.isfinite(end)):
        raise DataError(f"--window {text!r}: START and END must be finite numbers; {WINDOW_USAGE}")
    if start < 0:
        raise DataError(f"--window {text!r}: START {start:g} s is before the session start (0); {WINDOW_USAGE}")
    if end <= start:
        raise DataError(f"--window {text!r}: END {end:g} s must be later than START {start:g} s; {WINDOW_USAGE}")
    return start, end


def check_window(window: tuple[float, float], session: Session, unit: str | None = None) -> tuple[float, float]:
    """The window in the session's own clock (the recording's start + START, + END; a ``--common-span`` cut,
    decision B81, does not move that start); one :class:`DataError` line
    when it starts at or after the end of the recording of the tracked ``unit`` (foot / waist; None: any stream's;
    decision B126: a foot unit that stopped at 180 s beside a waist recording to 385 s passed ``--window 5,365``).
    Decision B242: a window that starts inside the recording and ends after it is clipped to the recording's end,
    with one warning line saying so (per-hour bins, ``--window 1200,1800`` of a 1614 s recording, are the
    recording's last part; ``track-all --window`` cuts sessions of different lengths alike)."""
    from pdrlearn.track.clock import ClockWindow, require_start, window_seconds
    from pdrlearn.track.units import unit_span

    t0 = session.t_recording_start  # B81: a --common-span cut does not move the session start (its seconds)
    span = unit_span(session, unit) if unit is not None else None
    dur = (span[1] if span is not None else session.t_end) - t0
    if isinstance(window, ClockWindow):  # decision L299: clock times, the session's own start (B254 without one)
        from pdrlearn.track.clock import no_start_window_line, recording_start

        line = no_start_window_line(window, session.where) if recording_start(session.meta, session.where) is None \
            else None
        if line:  # decision B291: 0:00,6:00 on a session without a clock - the seconds meant
            raise DataError(line)
        window = window_seconds(window, require_start(session.meta, session.where, f"--window {window.text}"),
                                dur, t0, session.where)
    start, end = window
    whose = f" (the tracked {unit} unit's, decision B126)" if span is not None else ""
    if start >= dur:
        raise DataError(f"{session.where}: --window {start:g},{end:g} lies outside the recording, which lasts "
                        f"{dur:.2f} s{whose}; give START < {dur:.2f}")
    if end > dur + 1e-6:  # decision B242: the recording's last part, said in one line
        logging.getLogger(__name__).warning(
            "%s: --window %g,%g ends after the recording, which lasts %.2f s%s: the window is clipped to %g,%.2f "
            "(%.2f s, not %g s)", session.where, start, end, dur, whose, start, dur, dur - start, end - start)
        end = dur
    return t0 + start, t0 + end


def check_margin(margin_s: float | None, window) -> float | None:
    """Decision L792: ``--window-margin`` in seconds (None: not given); one :class:`DataError` line for a value that
    is not a finite number > 0, or that is given without ``--window``."""
    if margin_s is None:
        return None
    if window is None:
        raise DataError(f"--window-margin {margin_s:g}: the margin is of a --window; add --window START,END or drop "
                        "--window-margin")
    if not math.isfinite(margin_s) or margin_s <= 0:
        from pdrlearn.decision_refs import decision_ref

        raise DataError(f"--window-margin {margin_s:g}: give the seconds tracked before and after the window, a "
                        f"number > 0 (e.g. 60, {decision_ref('L792', topic='localization')})")
    return float(margin_s)


def margin_session(session: Session, t0: float, t1: float, margin_s: float) -> Session:
    """Decision L792: ``session`` with its sensor streams (and the streams ``--units`` left out, W253) cut to
    ``[t0 - margin_s, t1 + margin_s]`` (the session's clock), what a pipeline tracks for ``--window --window-margin``:
    the window with the margin its state needs (a fused heading's +-60 s, a standstill's gyroscope bias, a filter's
    warm-up), not the whole recording. The labels, references and meta are the session's (L105's cut takes the
    window's); the recording's start (:attr:`Session.t_recording_start`) stays the recording's, so the window's
    seconds keep their meaning."""
    a, b = t0 - margin_s, t1 + margin_s

    def cut(stream):
        m = (stream.t >= a) & (stream.t <= b)
        return stream if m.all() else type(stream)(stream.name, stream.t[m], stream.values[m])

    return dataclasses.replace(
        session, streams={k: cut(v) for k, v in session.streams.items()},
        _left_out={k: cut(v) for k, v in session._left_out.items()}, _t_start_uncut=session.t_recording_start,
        _inferred=dict(session._inferred), _checked={}, _handed={}, _valid=None,
        _read_warnings=list(session._read_warnings))


def _mid_inside_rows(df: pd.DataFrame | None, t0: float, t1: float) -> np.ndarray | None:
    """The rows (from 0) of ``df`` whose middle lies in ``[t0, t1]``; None when ``df`` has no start/end."""
    if df is None or not {"start_s", "end_s"} <= set(df):
        return None
    mid = 0.5 * (df["start_s"].to_numpy(float) + df["end_s"].to_numpy(float))
    return np.flatnonzero((mid >= t0) & (mid <= t1))


def _mid_inside(df: pd.DataFrame | None, t0: float, t1: float) -> pd.DataFrame | None:
    rows = _mid_inside_rows(df, t0, t1)
    return df if rows is None else df.iloc[rows].reset_index(drop=True)


def steps_row(session: Session, j: int) -> int:
    """Decision E138: the session's steps.csv row (from 0) of row ``j`` of ``session.steps`` (a ``--window``'s cut
    numbers its rows from 0; this undoes it)."""
    rows = session._steps_rows
    return int(j) if rows is None else int(rows[j])


def _inside(df: pd.DataFrame, t0: float, t1: float) -> pd.DataFrame:
    if "ic_s" in df:
        t = df["ic_s"].to_numpy(float)
        return df[(t >= t0) & (t <= t1)].reset_index(drop=True)
    if {"after_s", "before_s"} <= set(df):
        return df[(df["after_s"] >= t0) & (df["before_s"] <= t1)].reset_index(drop=True)
    if {"start_s", "end_s"} <= set(df):
        return df[(df["start_s"] >= t0) & (df["end_s"] <= t1)].reset_index(drop=True)
    return df


def window_episodes(rows: list[dict] | None, t0: float, t1: float, *, clip: bool) -> list[dict] | None:
    """The episode rows (``start_s`` / ``end_s`` on the session's clock) of a window ``[t0, t1]``: with ``clip``
    those overlapping it, cut at its edges (``duration_s`` recomputed; the other columns, e.g. the number and
    ``peak_fi``, are the whole episode's), else those wholly inside it (decision L272). None stays None."""
    if rows is None:
        return None
    if not clip:
        return [r for r in rows if r["start_s"] >= t0 and r["end_s"] <= t1]
    out = []
    for r in rows:
        a, b = max(float(r["start_s"]), t0), min(float(r["end_s"]), t1)
        if b > a:
            out.append({**r, "start_s": round(a, 3), "end_s": round(b, 3), "duration_s": round(b - a, 3)}
                       if (a, b) != (r["start_s"], r["end_s"]) else r)
    return out


def window_cut_wbs(session: Session, t0: float, t1: float) -> list[dict]:
    """Decision W499: the reference walking bouts (W493's, on the tracked clock) that overlap the window ``[t0, t1]``
    but do not lie wholly inside it - the cut session drops them (L272's "only when wholly inside") - as
    ``{"start_s", "end_s"}`` rows; W493's scores leave out the detected bouts that overlap them."""
    from pdrlearn.steps.reference_clock import waist_clock_labels
    from pdrlearn.waist.evaluate import reference_wbs

    ref = reference_wbs(waist_clock_labels(session)) if session.extras.get("bouts") is not None else None
    if ref is None:
        return []
    a, b = ref["start_s"].to_numpy(float), ref["end_s"].to_numpy(float)
    cut = (b > t0) & (a < t1) & ~((a >= t0) & (b <= t1))
    return [{"start_s": float(x), "end_s": float(y)} for x, y in zip(a[cut], b[cut], strict=True)]


def window_track(result: TrackResult, session: Session, t0: float, t1: float) -> tuple[TrackResult, Session]:
    """The track and the session cut to ``[t0, t1]`` (the session's clock; module docstring). The trajectory keeps
    the position at the first kept step's start (the last row at or before it; decision L401: its altitude without
    a ride that L395 leaves out of the window) and the rows after it up to the last kept step's end.
    ``info["window"]`` records the window."""
    steps = result.steps
    t_rec = session.t_recording_start  # the seconds of check_window (B81's cut does not move them)
    warnings, notes = [], []
    if len(steps):
        mid = 0.5 * (steps["start_s"].to_numpy(float) + steps["end_s"].to_numpy(float))
        kept = steps[(mid >= t0) & (mid <= t1)].reset_index(drop=True)
        if not len(kept):  # decision L276 (was L107's warning): 0 m walked is an answer - one note, the steps' span
            notes.append(f"--window {t0 - t_rec:g},{t1 - t_rec:g} holds no step: walking 0 s, 0 m (the "
                         f"session's steps lie between {float(steps['start_s'].min()) - t_rec:.1f} and "
                         f"{float(steps['end_s'].max()) - t_rec:.1f} s)")
        steps = kept
    else:
        warnings.append(f"--window {t0 - t_rec:g},{t1 - t_rec:g} holds no step: the track of the "
                        "whole session has none")
    for line in warnings:  # one "warning:" line each on the command line (decision B13)
        logging.getLogger(__name__).warning("%s: %s", session.where, line)
    traj = result.trajectory
    if len(steps) and len(traj):
        a, b = float(steps["start_s"].min()), float(steps["end_s"].max())
        t = traj["t"].to_numpy(float)
        first = int(np.searchsorted(t, a + 1e-9, side="right")) - 1
        keep = (np.arange(len(t)) >= max(first, 0)) & (t <= b + 1e-9)
        traj = traj[keep].reset_index(drop=True)
    else:  # no step inside: the position where the window starts, as one row
        t = traj["t"].to_numpy(float)
        traj = traj.iloc[[max(int(np.searchsorted(t, t0, side="right")) - 1, 0)]].reset_index(drop=True) \
            if len(traj) else traj
    info = {**result.info, "window": {"start_s": t0 - t_rec, "end_s": t1 - t_rec}}
    if result.info.get("rides") is not None:  # decision L395: the rides whose standstill lies inside the window
        from pdrlearn.track.rides import window_first_z, window_rides

        whole_steps = steps
        steps, info["rides"] = window_rides(steps, result.info["rides"], t0, t1)
        traj = window_first_z(traj, whole_steps, steps)  # decision L401: nor the altitude of the window
    if "freezes" not in info:  # decision L272: a foot track's episodes, of the whole session, then cut below
        from pdrlearn.track.freezes import foot_freezes

        info["freezes"], lines = foot_freezes(session, info.get("pipeline"), result.steps)  # L413: no side shuffle
        for line in lines:  # one "warning:" line each (decision B13)
            logging.getLogger(__name__).warning("%s: %s", session.where, line)
        warnings = [*warnings, *lines]
    # decision W182: the chair transfers wholly inside; decision L272: the freezes clipped to the window
    info["transfers"] = window_episodes(info.get("transfers"), t0, t1, clip=False)
    info["freezes"] = window_episodes(info["freezes"], t0, t1, clip=True)
    if info.get("yaw_turns") is not None:  # decision W329: a yaw-rate turn counts on the side of its larger part
        info["yaw_turns"] = [r for r in info["yaw_turns"] if t0 <= 0.5 * (r["start_s"] + r["end_s"]) <= t1]
    if info.get("trunk_yaw_turns") is not None:  # decision W418: the waist unit's turns, as W329's
        info["trunk_yaw_turns"] = [r for r in info["trunk_yaw_turns"] if t0 <= 0.5 * (r["start_s"] + r["end_s"]) <= t1]
    if info.get("waist_gap_turns"):  # decisions L701 / L702: a rest gap's turn, as W329's (turns.csv's rows)
        info["waist_gap_turns"] = [r for r in info["waist_gap_turns"] if t0 <= 0.5 * (r["start_s"] + r["end_s"]) <= t1]
    if info.get("trunk_contacts") is not None:  # decision W418: the waist unit's contacts inside the window
        info["trunk_contacts"] = [r for r in info["trunk_contacts"] if t0 <= r["start_s"] <= t1]
    cut_wbs = window_cut_wbs(session, t0, t1)
    if cut_wbs:  # decision W499: the reference WBs the window cuts, and so drops (wb_scores.csv leaves them out)
        info["window_cut_wbs"] = cut_wbs
    if info["transfers"] is None and "transfers" not in result.info:
        del info["transfers"]
    if warnings:
        info["warnings"] = [*result.info.get("warnings", []), *warnings]
    if notes:  # decision L276: printed as a "note:" line by the command line
        info["notes"] = [*result.info.get("notes", []), *notes]
    gt = session.trajectory
    if gt is not None and len(gt) and len(traj):
        tt = gt["t"].to_numpy(float)
        gt = gt[(tt >= float(traj["t"].iloc[0]) - 1e-9) & (tt <= float(traj["t"].iloc[-1]) + 1e-9)]
        gt = gt.reset_index(drop=True) if len(gt) > 1 else None
    cut = dataclasses.replace(session, steps=_mid_inside(session.steps, t0, t1), trajectory=gt,
                              _steps_rows=_mid_inside_rows(session.steps, t0, t1),
                              extras={k: (_inside(v, t0, t1) if isinstance(v, pd.DataFrame) else v)
                                      for k, v in session.extras.items()})
    return TrackResult(steps=steps, trajectory=traj, info=info), cut
