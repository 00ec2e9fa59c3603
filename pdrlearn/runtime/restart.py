"""Restarting a live tracker where another stood (decision L134, docs/decisions/localization.md).

A new :class:`~pdrlearn.runtime.tracker.Tracker` made with only the old one's position and heading loses the
stride in progress: its samples since the last emitted stride are not in the new tracker, which opens its
first stride at the next stance, so that stride's turn is never added (a trial: -0.72 rad on every later stride,
6.45 m off after a 90 m walk). :func:`restart_state` is what a new tracker needs instead: the position and
heading after the last measured stride, that stride's end, and the samples the old tracker still buffers
(from its last stride boundary less 1 s on, the stance detector's look-back). ``Tracker(bundle,
resume=state)`` (:func:`resume`) takes the position and heading, re-pushes those samples, and drops the strides
it finds again that end at or before the old tracker's last one: the stride in progress is measured whole,
with the pivot before it (L31). The state is plain numbers and lists (``json.dumps`` writes it), so an app can
save it after each step and restart after a crash.
"""

from __future__ import annotations

import math

import numpy as np

from pdrlearn.errors import DataError

#: the restart state's format (decision E237: 2 adds the clock offsets; a version-1 state is read as before, its
#: samples taken as on the tracker's clock and the constructor's offsets kept; decision E281: 3 adds E272's stop bias,
#: a version-1 or -2 state starts it at 0 as before; any other version is refused in one line)
STATE_VERSION = 3
_KEYS = ("version", "position", "heading_rad", "last_end_s", "last_step", "n_steps", "samples")
_CLOCKS = ("waist_clock_offset_s", "foot_clock_offset_s")  # decision E237: version 2 on
_STOP = ("stop_bias", "pedal_history")  # decisions E281, E280: version 3 on
#: decision E356 (as E338's ``cycle_phase``, still version 3): E354's held waist gap (``bridge_cycle``) and the contacts
#: it reads the stride before from (``contacts``), E46's gap row not emitted yet (``gap_row``, ``row_gaps``) and E339's
#: fused altitude (``altitude``, ``fused``); a state without them
#: (saved before E356) starts them empty, as before (one warning line for ``altitude="fused"``)
_HELD = ("bridge_cycle", "gap_row", "row_gaps", "contacts", "altitude", "fused")


def restart_state(tracker) -> dict:
    """Decision L134: ``{"version", "position" [x, y, z] m, "heading_rad", "last_end_s" (the last measured
    stride's end, s, or None), "last_step" (the last emitted row's end, heading, position and stride times, for
    E46's gap row and E51's stride time; or None), "n_steps", "samples": {sensor: {"t": [...] s, "values":
    [[...], ...]}}, "waist_clock_offset_s", "foot_clock_offset_s", "stop_bias"}`` with the samples the tracker buffers
    (on its clock: already moved by the offsets), the offsets it applies now (a ``rebase_clock`` included; E237) and
    E272's waist gyroscope bias read at the last stop (``{"rps", "n_stops"}``, None without the waist unit; E281) and
    the last L611 rows judged (``pedal_history``, E280) and L621's live foot rest reading (``foot_rest``: ``{"readings",
    "n_still"}``, review R1 F3) and E338's held end-phase yaw (``cycle_phase``, rad, or None). Decision E356: and
    E354's held waist gap (``bridge_cycle``: ``{"gap_s", "before", "last"}``, E365: the last stride's rate), the last
    strides' contacts (``contacts``), E46's gap row not emitted yet (``gap_row``, ``row_gaps``), the ``altitude``
    tracked and E339's fused altitude (``fused``: the barometer held, L154's filter, the rows waiting for the
    barometer; None for ``"foot"``). Strides held for their L611 verdict (E280) are not in it:
    ``last_end_s`` and the bias are those before the first held one, which the new tracker measures again. A
    tracker that resamples (``resample=True``, E22) is refused in one line (decision L140): its buffer holds
    resampled samples, and its low-pass filter holds the last raw ones (its delay, 0.84 s from 50 to 20 Hz), which
    no state carries; a new tracker fed the resampled samples resampled them again and lost a stride (0.20-0.28 m
    off at the end of a 40-stride walk)."""
    if tracker.inputs.resamplers:
        names = ", ".join(sorted(tracker.inputs.resamplers))
        raise DataError(f"restart_state(): this tracker resamples {names} to {tracker.rate_hz:g} Hz (resample=True, "
                        "E22), and its filter's last samples cannot be handed on; restart it with Tracker(bundle, "
                        "start=tuple(old.position), heading_rad=old.heading) (the stride in progress is lost), or "
                        "track at the data's own rate (resample='native', the default) to restart whole "
                        "(decision L140)")
    kept = tracker._kept
    # decision E280: strides held for L611's verdict are measured again (E356: E354's held gap as before the first)
    prev_end, stop, rest, cycle, compass = tracker._restart_from
    fused = tracker._fused
    phase = None if tracker._cycle_phase is None else tracker._cycle_phase.psi  # E338: set by placed strides only
    return {
        "version": STATE_VERSION,
        "position": [float(v) for v in tracker.position],
        "heading_rad": float(tracker.heading),
        "last_end_s": None if prev_end is None else float(prev_end),
        "last_step": None if kept is None else [kept[0], kept[1], list(kept[2]), list(kept[3])],
        "n_steps": int(tracker.n_steps),
        "samples": {name: {"t": t.tolist(), "values": v.tolist()}
                    for name, (t, v) in ((n, r.view()) for n, r in tracker._buf.items())},
        **{k: float(getattr(tracker, k)) for k in _CLOCKS},  # decision E237
        "stop_bias": None if stop is None else {"rps": float(stop[0]), "n_stops": int(stop[1])},  # decision E281
        "pedal_history": [list(r) for r in tracker._loops.history],  # decision E280: the verdicts' neighbours
        "foot_rest": {"readings": [float(v) for v in rest[0]], "n_still": int(rest[1])},  # review R1 F3 (L621)
        "cycle_phase": None if phase is None else float(phase),  # decision E338: the held end-phase yaw (rad)
        # decision E356: E354's held waist gap, E46's pending gap row and E339's fused altitude
        "bridge_cycle": {"gap_s": float(cycle[0]), "before": None if cycle[1] is None else float(cycle[1]),
                         "last": None if cycle[2] is None else float(cycle[2])},  # decision E365: the last rate
        "gap_row": None if tracker._gap_row is None else [float(v) for v in tracker._gap_row],
        "row_gaps": [[float(a), float(b)] for a, b in tracker._row_gaps],
        # the last strides' (start, contact) (steps decision 87): E354's stride before a bridged span is read from them
        "contacts": [[float(a), float(c)] for a, c in tracker._contacts],
        "altitude": "foot" if fused is None else "fused",
        "fused": None if fused is None else fused.state(step_record),
        "gap_compass": compass,  # decision E370: E361's re-anchoring compass (None without it)
    }


def step_record(step) -> dict:
    """Decision E356: a :class:`~pdrlearn.runtime.tracker.Step` as plain numbers, lists and dicts (JSON)."""
    from dataclasses import asdict

    return {**asdict(step), "flags": list(step.flags)}


def step_from_record(record: dict):
    """Decision E356: the :class:`~pdrlearn.runtime.tracker.Step` of :func:`step_record`."""
    from pdrlearn.runtime.tracker import Step

    return Step(**{**record, "flags": tuple(record["flags"])})


def resume(tracker, state: dict) -> list:
    """Decision L134: set a new ``tracker`` (no sample pushed yet) to ``state`` (:func:`restart_state`) and push
    the state's samples; returns the steps they complete (strides the old tracker had not emitted yet).

    Decision E237: the samples are on the old tracker's clock already, so they are pushed with every clock offset
    (and the waist's drift) at 0; then the state's offsets are set (a version-2 state: they win over the
    constructor's, one warning line when they differ; version 1: the constructor's kept).

    Decision E281: a version-3 state's ``stop_bias`` (E272's bias read at the old tracker's last stop) is the new
    tracker's, so its waist-headed strides lose it as the old tracker's would; a version-1 or -2 state starts it at 0
    (nothing known until the next stop, as before)."""
    where = "Tracker(resume=state)"
    version = state.get("version") if isinstance(state, dict) else None
    keys = _KEYS + (_CLOCKS if version in (2, STATE_VERSION) else ()) + (_STOP if version == STATE_VERSION else ())
    if version not in (1, 2, STATE_VERSION) or not set(keys) <= set(state):
        got = version if isinstance(state, dict) else type(state).__name__
        raise DataError(f"{where}: not a restart state of version {STATE_VERSION} (got {got!r}); give what "
                        "Tracker.restart_state() returned (decision L134)")
    try:
        position = np.asarray(state["position"], dtype=float).reshape(3)
        heading = float(state["heading_rad"])
        last_end = None if state["last_end_s"] is None else float(state["last_end_s"])
        samples = {str(n): (np.asarray(s["t"], dtype=float), np.asarray(s["values"], dtype=float))
                   for n, s in state["samples"].items()}
        clocks = {k: float(state[k]) for k in keys if k in _CLOCKS}
        stop = state.get("stop_bias") if version == STATE_VERSION else None  # decision E281
        stop = None if stop is None else (float(stop["rps"]), float(stop["n_stops"]))
        history = [(float(a), float(b), float(dz), bool(u), float(d), bool(j))  # decision E280
                   for a, b, dz, u, d, j in (state["pedal_history"] if version == STATE_VERSION else [])]
        rest = state.get("foot_rest") if version == STATE_VERSION else None  # review R1 F3: absent = not read yet
        rest = None if rest is None else ([float(v) for v in rest["readings"]], float(rest["n_still"]))
        phase = state.get("cycle_phase")  # decision E338: absent (an older state) or None = no straight stride yet
        phase = None if phase is None else float(phase)
        cycle = state.get("bridge_cycle")  # decision E356: absent (a state saved before E356) = no gap held
        cycle = (0.0, None, None) if cycle is None else (  # decision E365: "last" absent (before E365) = none
            float(cycle["gap_s"]), *(None if cycle.get(k) is None else float(cycle[k]) for k in ("before", "last")))
        gap_row = state.get("gap_row")  # decision E356 (E46): absent or None = no gap row pending
        gap_row = None if gap_row is None else [float(gap_row[0]), float(gap_row[1])]
        row_gaps = [(float(a), float(b)) for a, b in state.get("row_gaps") or []]
        contacts = [(float(a), float(c)) for a, c in state.get("contacts") or []]  # E356: absent = none (as before)
    except (TypeError, ValueError, KeyError, IndexError) as exc:
        raise DataError(f"{where}: the state's position, heading_rad, last_end_s, samples, clock offsets, foot_rest, "
                        f"bridge_cycle, gap_row, contacts, stop_bias or pedal_history are malformed ({exc}); give what "
                        "Tracker.restart_state() returned (decision L134)") from None
    if not (np.isfinite(position).all() and math.isfinite(heading) and all(map(math.isfinite, clocks.values()))
            and (stop is None or (math.isfinite(stop[0]) and _count(stop[1])))
            and all(math.isfinite(v) for r in history for v in (r[0], r[1], r[2], r[4]))
            and (rest is None or (all(math.isfinite(v) and v > 0 for v in rest[0]) and _count(rest[1])))
            and (phase is None or math.isfinite(phase))
            and all(v is None or math.isfinite(v) for v in (*cycle, *(gap_row or ())))):
        raise DataError(f"{where}: the state's position {position.tolist()}, heading {heading}, clock offsets "
                        f"{clocks}, stop_bias {stop}, pedal_history or foot_rest are not finite (or a count is not a "
                        "whole number >= 0); give what Tracker.restart_state() returned (decision L134, review R1 F5)")
    tracker.position = position
    tracker._init_fixes(position[:2])
    tracker.heading = heading
    if tracker._first_walk is not None:  # decision E215: a resumed tracker goes on in its old frame
        tracker._first_walk.stop()
    tracker._prev_end = last_end
    tracker._resume_end = last_end
    if last_end is not None:  # decisions L505, E318: past the stream's first measured stride, the next one is judged
        from pdrlearn.kernels import sideways as _sideways

        tracker._side_rows = _sideways.SideRun()
        tracker._side_rows.started = True
    ls = state["last_step"]
    tracker._kept = None if ls is None else (float(ls[0]), float(ls[1]), tuple(map(float, ls[2])),
                                             tuple(map(float, ls[3])))
    tracker.n_steps = int(state["n_steps"])
    if stop is not None and tracker._stop_bias is not None:  # decision E281: the bias read at the old one's last stop
        tracker._stop_bias.rps, tracker._stop_bias.n_stops = stop[0], int(stop[1])
    if tracker._cycle_phase is not None:  # decision E338: the old tracker's held end-phase yaw
        tracker._cycle_phase.psi = phase
    if rest is not None:  # review R1 F3: L621's reading before the first held stride, which is measured again
        tracker._foot_rest.readings, tracker._foot_rest.n_still = rest[0], int(rest[1])
    tracker._loops.history, tracker._loops.seen = history, len(history)  # decision E280
    tracker._cycle.gap_s, tracker._cycle.before, tracker._cycle.last = cycle  # decisions E356, E365: E354's gap turn
    compass = state.get("gap_compass")  # decision E370: absent (a state saved before E370) or None = starts afresh
    if compass is not None and tracker._compass is not None:
        try:
            tracker._compass.restore(compass)
        except (TypeError, ValueError, KeyError) as exc:
            raise DataError(f"{where}: the state's gap_compass is malformed ({exc}); give what "
                            "Tracker.restart_state() returned (decision E370)") from None
    tracker._gap_row, tracker._row_gaps = gap_row, row_gaps  # decision E356: E46's gap row, emitted before it
    tracker._contacts = contacts  # decision E356: steps decision 87's contacts (E354's stride before a gap)
    _resume_fused(tracker, state, where)  # decision E356: E339's barometer, filter and rows not returned yet
    for k, v in clocks.items():  # decision E237: the state's clock wins; a different given value is said
        if v != getattr(tracker, k):
            tracker._warn(f"{where}: the state's {k} = {v:g} s replaces the {getattr(tracker, k):g} s given (the "
                          "offset the saved tracker applied last, a rebase_clock included; decision E237)")
    kept = {k: getattr(tracker, k) for k in (*_CLOCKS, "waist_clock_drift_ppm")}
    for k in kept:  # decision E237: the saved samples are on the tracker's clock already: not moved again
        setattr(tracker, k, 0.0)
    try:
        return tracker.push({n: tv for n, tv in samples.items() if len(tv[0])}) if samples else []
    finally:
        for k, v in {**kept, **clocks}.items():
            setattr(tracker, k, v)


def _resume_fused(tracker, state: dict, where: str) -> None:
    """Decision E356: the saved ``Tracker(altitude="fused")``'s holder (the barometer held, L154's filter, the rows
    waiting for the barometer) is the new tracker's; a state saved with the other ``altitude`` is refused in one line
    (the rows it holds would be lost, or the altitude would change its origin); a state saved before E356 (no
    ``altitude``) restarts the fusion at the next row, with one line."""
    mine = "foot" if tracker._fused is None else "fused"
    saved = state.get("altitude")
    if saved is None:
        if mine == "fused":
            tracker._warn(f"{where}: the state was saved before decision E356 and holds no fused altitude: L154's "
                          "filter starts again at the next row (from the state's z), and rows the saved tracker held "
                          "for the barometer are lost")
        return
    if saved != mine:
        raise DataError(f"{where}: the state was saved by a Tracker(altitude={saved!r}) and this one tracks "
                        f"altitude={mine!r}; resume with altitude={saved!r} (decision E356)")
    if mine == "fused":
        try:
            tracker._fused.restore(state["fused"], step_from_record)
        except (TypeError, ValueError, KeyError, IndexError) as exc:
            raise DataError(f"{where}: the state's fused altitude is malformed ({exc}); give what "
                            "Tracker.restart_state() returned (decisions L134, E356)") from None


def _count(v: float) -> bool:
    """Review R1 F5: a state's count (``n_stops``, ``n_still``) is a finite whole number >= 0."""
    return math.isfinite(v) and v >= 0 and v == int(v)


def drop_measured(pending: list, last_end: float | None) -> list:
    """The detected strides ``(t0, t1)`` a resumed tracker measures: those ending after ``last_end`` (s), the old
    tracker's last measured stride (the re-pushed samples show it, and the one before, again)."""
    if last_end is None:
        return pending
    return [p for p in pending if p[1] > last_end + 1e-9]
