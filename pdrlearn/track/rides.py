"""A lower-back track's rides (decisions L375-L377 in docs/decisions/localization.md): the standstill changes of
the barometric altitude of half a storey or more (W158's ``pause_dz_m``, W231's ``RIDE_MIN_M``), each told a lift,
an escalator or other by its vertical rate and duration, the ``ride`` column of steps.csv, ``rides.csv`` and their
warning lines."""

from __future__ import annotations

import numpy as np
import pandas as pd

#: decision L377: rides.csv's columns (docs/columns.md: pdrlearn.columns.RIDES)
RIDE_COLUMNS = ("ride", "start_s", "end_s", "kind", "dz_m", "duration_s", "vertical_rate_mps", "vibration_mps2",
                "horizontal_est_m")

#: decision L402: the accelerometers a ride's vibration is read from, the first one the session has (the waist unit
#: stands on the legs, the foot unit on the vehicle's floor: both feel it, S71)
VIBRATION_STREAMS = ("wAccelerometer", "fAccelerometer")
#: decision L615: a foot track reads the foot unit first (a standing foot rests flat on the vehicle's floor while the
#: trunk fidgets, which L403 found reads as vibration on real lower-back recordings)
FOOT_VIBRATION_STREAMS = ("fAccelerometer", "wAccelerometer")


def ride_accelerometer(session, streams: tuple[str, ...] = VIBRATION_STREAMS) -> tuple[np.ndarray, np.ndarray,
                                                                                        str] | None:
    """Decision L402: ``(t, acc, name)`` of the first of ``streams`` (:data:`VIBRATION_STREAMS`; a foot track's
    :data:`FOOT_VIBRATION_STREAMS`, L615) in ``session`` with samples; None."""
    for name in streams:
        if name in session and len(session[name].t):
            return session[name].t, session[name].values, name
    return None


def ride_rows(t: np.ndarray, p_hpa: np.ndarray, steps: pd.DataFrame, t0: float, z: np.ndarray,
              z_start: np.ndarray, t_end: float | None = None, acc=None,
              vibration_kind: bool = False, walked_kind: bool = False) -> tuple[np.ndarray, list[dict]]:
    """Decisions L375, L376: per step the kind of the ride in the pause before it (``""``: none) and one record per
    ride (rides.csv's :data:`RIDE_COLUMNS` and ``row``, the step it precedes). ``(t, p_hpa)``: the barometer (s,
    hPa); ``z`` (n+1,) the track's altitude at ``t0`` and each step's end, ``z_start`` (n,) at each step's start
    (W158: ``pause_dz_m = z_start - z[:-1]``). Decision L394: with ``t_end`` (the recording's end) also the ride in
    the standstill after the last step (``row`` n, no step). Decision L402: ``acc`` (:func:`ride_accelerometer`'s)
    gives each ride's ``vibration_mps2``; with ``vibration_kind`` (L403: opt-in, the ``ride_vibration`` option) a
    vibrating ride is a vehicle's, kind other. Decision W609 (not adopted: the ``walked_ride`` option):
    ``walked_kind`` makes a ride that shakes like walking (:func:`pdrlearn.kernels.pause_ride.walked_ride`) kind
    ``"stairs"``."""
    pause = np.asarray(z_start, dtype=float) - np.asarray(z, dtype=float)[:-1]
    kinds, records = _rides(t, p_hpa, _pause_ends(steps, t0), steps["start_s"].to_numpy(float), pause, acc,
                            vibration_kind, walked_kind)
    return kinds, _after_last(t, p_hpa, steps, records, t_end, acc, vibration_kind, walked_kind)


def _pause_dz(t, p_hpa, ends, starts) -> np.ndarray:
    """The barometric altitude change (m) of each standstill from ``ends`` to ``starts`` (W158: the whole change; a
    pause over W231's ``RIDE_WINDOW_S`` only its ride, ``pause_ride_dz``), 0 where under ``RIDE_MIN_M``."""
    from pdrlearn.kernels.barometer import relative_altitude
    from pdrlearn.kernels.pause_ride import RIDE_MIN_M, RIDE_WINDOW_S, pause_ride_dz

    ends, starts = np.asarray(ends, dtype=float), np.asarray(starts, dtype=float)
    h = relative_altitude(t, p_hpa, np.concatenate([ends, starts]))  # one read for the short pauses (W158: whole)
    pause = h[len(ends):] - h[:len(ends)]
    for j in np.flatnonzero(starts - ends > RIDE_WINDOW_S):  # W231: a long pause's ride only
        pause[j] = pause_ride_dz(t, p_hpa, float(ends[j]), float(starts[j]))[0]
    return np.where(np.abs(pause) >= RIDE_MIN_M, pause, 0.0)


def _after_last(t, p_hpa, steps: pd.DataFrame, records: list[dict], t_end: float | None, acc=None,
                vibration_kind: bool = False, walked_kind: bool = False) -> list[dict]:
    """Decision L394: ``records`` and the ride in the standstill from the last step's end to ``t_end`` (the
    recording's end, at most the barometer's last time), ``row`` the number of steps (it precedes none)."""
    if t_end is None or not len(steps) or not len(t):
        return records
    a, b = float(steps["end_s"].iloc[-1]), min(float(t_end), float(t[-1]))
    if not b > a:
        return records
    _, extra = _rides(t, p_hpa, np.array([a]), np.array([b]), _pause_dz(t, p_hpa, [a], [b]), acc, vibration_kind,
                      walked_kind)
    return records + [{**r, "ride": len(records) + 1, "row": len(steps)} for r in extra]


def _pause_ends(steps: pd.DataFrame, t0: float) -> np.ndarray:
    """Where the standstill before each row starts: the previous row's end, the first row's at ``t0`` (W158)."""
    return np.concatenate([[t0], steps["end_s"].to_numpy(float)[:-1]])


def _rides(t, p_hpa, ends, starts, pause, acc=None, vibration_kind: bool = False,
           walked_kind: bool = False) -> tuple[np.ndarray, list[dict]]:
    """:func:`ride_rows` on the pauses from ``ends`` to ``starts`` (s) whose altitude changed by ``pause`` (m);
    ``acc`` ``(t, (n, 3))`` or None: decision L402's vibration (NaN without), which tells the kind only with
    ``vibration_kind`` (L403)."""
    from pdrlearn.kernels.pause_ride import (
        RIDE_MIN_M,
        escalator_travel_m,
        ride_kind,
        ride_vibration,
        ride_window,
        vibrating_span,
        walked_ride,
    )

    kinds = np.full(len(starts), "", dtype=object)
    records = []
    for j in range(len(starts)):
        if not abs(float(np.nan_to_num(pause[j]))) >= RIDE_MIN_M:
            vehicle = _vehicle(t, p_hpa, float(ends[j]), float(starts[j]), acc) if vibration_kind else None
            if vehicle is not None:  # decision L616: a long vibrating standstill, level or not
                kinds[j] = "vehicle"
                records.append({**vehicle, "ride": len(records) + 1, "row": int(j)})
            continue
        a, b, duration = ride_window(t, p_hpa, float(ends[j]), float(starts[j]))
        dz = float(pause[j])
        vib = ride_vibration(acc[0], acc[1], a, b) if acc is not None else float("nan")  # decision L402
        kinds[j] = kind = ("stairs" if walked_kind and walked_ride(vib)  # decision W609 (opt-in): missed steps, no ride
                           else ride_kind(dz, duration, vib if vibration_kind else None))
        unread = (acc[2] if acc is not None else "the accelerometer") if vibration_kind and np.isnan(vib) else None
        rate = abs(dz) / duration  # the climb's (W89)
        span = vibrating_span(acc[0], acc[1], float(ends[j]), float(starts[j])) if kind == "vehicle" else None
        if span is not None:  # decision L620: a climbing vehicle's ride is its motion, as L616's level one
            a, b, vib = span
            duration = b - a
        records.append({"ride": len(records) + 1, "start_s": a, "end_s": b, "kind": kind, "dz_m": dz,
                        "duration_s": duration, "vertical_rate_mps": rate, "vibration_mps2": vib,
                        "horizontal_est_m": escalator_travel_m(dz) if kind == "escalator" else None, "row": int(j),
                        "gap_s": _gap_in(t, a, b),  # decision B298
                        "vibration_unread": unread})  # decision B301
    return kinds, records


#: decision L616 amended: a vibrating span at least this share of which the freeze index's episodes cover is a freeze
#: of gait (the foot trembling at 3-8 Hz in place), not a vehicle (a rule, not fitted: most of it)
VEHICLE_FREEZE_SHARE = 0.5


def freeze_share(acc, a: float, b: float) -> float:
    """Decision L616 amended: the share of ``[a, b]`` (s) that W213's freeze-index episodes of ``acc`` (``(t, (n, 3),
    name)``) read inside it cover (:func:`pdrlearn.track.freezes.freezes_of`: 3-8 Hz power over 0.5-3 Hz above 3)."""
    from pdrlearn.track.freezes import freezes_of

    t = np.asarray(acc[0], dtype=float)
    inside = (t >= a) & (t <= b)
    eps = freezes_of(t[inside], np.asarray(acc[1], dtype=float)[inside]) if b > a else []
    return float(sum(r["duration_s"] for r in eps)) / (b - a) if b > a else 0.0


def _vehicle(t, p_hpa, a: float, b: float, acc) -> dict | None:
    """Decision L616: the record (rides.csv's columns, ``gap_s``) of the vehicle ride in the standstill from ``a``
    to ``b`` (s) when it lasts ``VEHICLE_STILL_MIN_S`` or more and vibrates like a vehicle
    (:func:`pdrlearn.kernels.pause_ride.vibrating_span` of ``acc``) and is no freeze of gait (:func:`freeze_share`
    under :data:`VEHICLE_FREEZE_SHARE`, L616 amended); its ``dz_m`` the barometric change over the vibrating span
    (W89); None otherwise."""
    from pdrlearn.kernels.barometer import relative_altitude
    from pdrlearn.kernels.pause_ride import VEHICLE_STILL_MIN_S, vibrating_span

    if acc is None or not b - a >= VEHICLE_STILL_MIN_S:
        return None
    span = vibrating_span(acc[0], acc[1], a, b)
    if span is None:
        return None
    s0, s1, vib = span
    if freeze_share(acc, s0, s1) >= VEHICLE_FREEZE_SHARE:  # decision L616 amended: a freeze of gait trembles too
        return None
    # decision L624: no barometer (t None), no altitude change
    dz = float(np.diff(relative_altitude(t, p_hpa, np.array([s0, s1])))[0]) if t is not None else float("nan")
    duration = s1 - s0
    return {"start_s": s0, "end_s": s1, "kind": "vehicle", "dz_m": dz, "duration_s": duration,
            "vertical_rate_mps": abs(dz) / max(duration, 1e-9), "vibration_mps2": vib, "horizontal_est_m": None,
            "gap_s": _gap_in(t, s0, s1), "vibration_unread": None}


#: decision B298: a barometer gap longer than this (s) inside a ride is said (its duration and kind are interpolated)
RIDE_GAP_S = 2.0


def _gap_in(t, a: float, b: float) -> float:
    """Decision B298: the longest interval between two barometer samples ``t`` that overlaps the ride ``[a, b]``."""
    if t is None or len(t) < 2:  # decision L624: no barometer, no gap of it
        return 0.0
    t = np.asarray(t, dtype=float)
    overlap = (t[1:] > a) & (t[:-1] < b)
    return float(np.diff(t)[overlap].max()) if overlap.any() else 0.0


def foot_rides(result, session, vibration_kind: bool = True) -> None:
    """Decision L378: a foot track's rides from the session's waist barometer (B188's usable one; none: nothing
    changes). Each standstill between two strides (from the previous stride's end, the first's from the barometer's
    first time, decision L393, and the one after the last stride to the barometer's last time, L394) changes the
    barometric altitude by W231's ride (``pause_ride_dz``: over 30 s only what moved 1.5 m within
    30 s); where that is ``RIDE_MIN_M`` or more it is the stride's ``pause_dz_m`` (0 elsewhere), its ``ride`` kind
    (L376), a record of ``info["rides"]`` (rides.csv, L377) and L376's / L377's lines. The strides' ``dz_m`` and the
    trajectory's z are not changed. ``vibration_kind``: decision L402's vehicle test on the foot unit's vibration
    (:data:`FOOT_VIBRATION_STREAMS`; decision L615: on by default, the ``ride_vibration`` option) and L616's level
    vehicle rides."""
    import logging

    from pdrlearn.track.barometer import FOOT_EFFECT, usable_barometer

    steps = result.steps
    b = usable_barometer(session, [], FOOT_EFFECT)  # B188's line is the foot's barometer check's (L145)
    if not len(steps) or not len(result.trajectory):
        return
    if b is None:  # decision L624: no barometer, no climb; a vehicle is read from the foot's vibration alone
        if vibration_kind:
            _vibration_rides(result, session)
        return
    p = b.values[:, 0]
    # decision L393: the first standstill from the barometer's first time (the first stride's start hid a ride
    # before it)
    ends = _pause_ends(steps, min(float(b.t[0]), float(result.trajectory["t"].iloc[0])))
    starts = steps["start_s"].to_numpy(float)
    pause = _pause_dz(b.t, p, ends, starts)
    acc = ride_accelerometer(session, FOOT_VIBRATION_STREAMS)  # decisions L402, L615
    kinds, records = _rides(b.t, p, ends, starts, pause, acc, vibration_kind)
    records = _after_last(b.t, p, steps, records, float(b.t[-1]), acc, vibration_kind)  # decision L394
    # before the columns every track ends its steps.csv with (L97's stride_time_s ... grade_pct, E51's order)
    at = list(steps.columns).index("stride_time_s") if "stride_time_s" in steps else len(steps.columns)
    steps = steps.copy()
    steps.insert(at, "pause_dz_m", pause)
    steps.insert(at + 1, "ride", kinds)
    result.steps = steps
    result.info["rides"] = records
    lines = ride_lines(records)
    result.info.setdefault("warnings", []).extend(lines)
    for line in lines:
        logging.getLogger("pdrlearn.track").warning("%s: %s", session.where, line)


def _vibration_rides(result, session) -> None:
    """Decision L624: a foot track without a usable barometer: L616's vehicle rows from the foot unit's vibration
    (:data:`FOOT_VIBRATION_STREAMS`), each standstill between two strides (the first from the accelerometer's first
    time, L393; the one after the last stride to its last time, L394) of ``VEHICLE_STILL_MIN_S`` or more whose
    vibration is a vehicle's and no freeze (:func:`_vehicle`); ``dz_m`` and ``vertical_rate_mps`` empty (no
    barometer), no ``pause_dz_m`` (no altitude read). Sets steps.csv's ``ride``, ``info["rides"]`` (rides.csv) and
    the vehicle line, as :func:`foot_rides`."""
    import logging

    acc = ride_accelerometer(session, FOOT_VIBRATION_STREAMS)
    if acc is None or not len(acc[0]):
        return
    steps = result.steps
    ends = _pause_ends(steps, min(float(acc[0][0]), float(result.trajectory["t"].iloc[0])))
    starts = steps["start_s"].to_numpy(float)
    kinds, records = _rides(None, None, ends, starts, np.zeros(len(starts)), acc, True)
    last = _vehicle(None, None, float(steps["end_s"].iloc[-1]), float(acc[0][-1]), acc)  # decision L394
    if last is not None:
        records.append({**last, "ride": len(records) + 1, "row": len(steps)})
    at = list(steps.columns).index("stride_time_s") if "stride_time_s" in steps else len(steps.columns)
    steps = steps.copy()
    steps.insert(at, "ride", kinds)
    result.steps = steps
    result.info["rides"] = records
    lines = ride_lines(records)
    result.info.setdefault("warnings", []).extend(lines)
    for line in lines:
        logging.getLogger("pdrlearn.track").warning("%s: %s", session.where, line)


def window_rides(steps: pd.DataFrame, records: list[dict] | None, t0: float, t1: float):
    """Decision L395: a window's ``(steps, records)``: the rides whose standstill (``start_s`` to ``end_s``) lies
    inside ``[t0, t1]``, renumbered, each ``row`` the first kept step after it (the number of kept steps: none);
    a kept step's ride that is not one of them (a ride before the window) is no ride of the window (``pause_dz_m`` 0,
    ``ride`` "")."""
    if records is None:
        return steps, None
    starts = steps["start_s"].to_numpy(float) if len(steps) else np.zeros(0)
    kept = [r for r in records if t0 <= float(r["start_s"]) and float(r["end_s"]) <= t1]
    out = [{**r, "ride": k + 1, "row": int(np.searchsorted(starts, float(r["end_s"])))} for k, r in enumerate(kept)]
    if "pause_dz_m" in steps and len(steps):
        from pdrlearn.kernels.pause_ride import RIDE_MIN_M

        gone = np.abs(np.nan_to_num(steps["pause_dz_m"].to_numpy(float))) >= RIDE_MIN_M
        gone[[r["row"] for r in out if r["row"] < len(steps)]] = False
        steps = steps.assign(pause_dz_m=np.where(gone, 0.0, steps["pause_dz_m"].to_numpy(float)))
        if "ride" in steps:
            steps = steps.assign(ride=np.where(gone, "", steps["ride"].to_numpy(object)))
    return steps, out


def pauses_in_z(steps: pd.DataFrame) -> bool:
    """Whether a track's z carries its standstills' change ``pause_dz_m``: a lower-back track's does (W158: ``dz_m +
    pause_dz_m`` sum to ``z``), a foot track's does not (its altitude is its strides' own, L378)."""
    return bool(len(steps)) and not ("unit" in steps and bool((steps["unit"].astype(str) == "foot").all()))


def window_first_z(traj: pd.DataFrame, whole: pd.DataFrame, kept: pd.DataFrame) -> pd.DataFrame:
    """Decision L401: a window's trajectory (its first row the last one at or before the first kept step's start)
    with that row's z moved by the ride :func:`window_rides` left out of the first kept step (``whole``: the kept
    steps before it, ``kept`` after it), so ``altitude_change_m`` (last z minus first), ``ascent_m`` and
    trajectory.csv hold the window's own change: its steps' ``dz_m`` and the ``pause_dz_m`` steps.csv keeps. Only
    where z carries the standstills' change (:func:`pauses_in_z`); unchanged when no ride was left out."""
    if not len(traj) or not len(kept) or "z" not in traj or "pause_dz_m" not in kept or not pauses_in_z(kept):
        return traj
    dropped = float(np.nan_to_num(whole["pause_dz_m"].iloc[0]) - np.nan_to_num(kept["pause_dz_m"].iloc[0]))
    if dropped == 0.0 or float(traj["t"].iloc[0]) > float(kept["start_s"].iloc[0]) + 1e-9:
        return traj  # no ride left out, or no row before the step (its rows already hold the ride)
    traj = traj.copy()
    traj.loc[0, "z"] = float(traj["z"].iloc[0]) + dropped
    return traj


def ride_lines(records: list[dict]) -> list[str]:
    """Decisions L376, L377: one line for the rides that are neither a lift nor an escalator (not counted as floors),
    one per ride with a barometer gap over :data:`RIDE_GAP_S` (B298) and one for the escalator rides' horizontal
    travel the track leaves out."""
    lines = []
    other = [r for r in records if r["kind"] == "other"]
    if other:
        shown = ", ".join(f"{r['dz_m']:+.1f} m over {r['duration_s']:.0f} s at {r['start_s']:.0f} s" for r in other[:3])
        lines.append(f"{len(other)} barometric climb(s) while standing ({shown}{', ...' if len(other) > 3 else ''}) "
                     "are neither a lift (0.5 m/s or more vertically) nor an escalator (0.15-0.5 m/s for at most 45 "
                     "s): a vehicle on a hill or a ride of another kind, so they count no floors; their "
                     "height stays in the altitude (rides.csv kind other; decision L376)")
    lines.extend(vehicle_lines(records))
    walked = [r for r in records if r["kind"] == "stairs"]
    if walked:  # decision W609
        shown = ", ".join(f"{r['dz_m']:+.1f} m at {r['start_s']:.0f}-{r['end_s']:.0f} s ({r['vibration_mps2']:.2f} "
                          "m/s^2)" for r in walked[:3])
        more = ", ..." if len(walked) > 3 else ""
        lines.append(f"{len(walked)} barometric climb(s) between detected steps ({shown}{more}) "
                     "shook the unit like walking (1.2 m/s^2 or more; a rider stands still): stairs walked whose steps "
                     "the lower back missed, not a lift or an escalator (rides.csv kind stairs; their floors counted, "
                     "no ride travel added); n_steps and the distance lack those steps (decision W609)")
    for r in records:
        if r.get("gap_s", 0.0) > RIDE_GAP_S:  # decision B298
            lines.append(f"wBarometer.csv has a gap of {r['gap_s']:.1f} s inside ride {r['ride']} "
                         f"({r['start_s']:.0f}-{r['end_s']:.0f} s): its duration ({r['duration_s']:.1f} s), rate and "
                         f"kind ({r['kind']}) are interpolated across it; check the barometer's recording (decision "
                         "B298)")
    for r in records:
        if r.get("vibration_unread"):  # decision B301: the ride_vibration option could not read this ride
            lines.append(f"{r['vibration_unread']}.csv has no usable samples during ride {r['ride']} "
                         f"({r['start_s']:.0f}-{r['end_s']:.0f} s): the ride_vibration option cannot tell a vehicle "
                         f"there, so its kind ({r['kind']}) is its vertical rate's alone; check that unit's recording "
                         "(decision B301)")
    esc = [r for r in records if r["kind"] == "escalator"]
    if esc:
        travel = sum(r["horizontal_est_m"] for r in esc)
        lines.append(f"{len(esc)} escalator ride(s) (rides.csv) carried the walker an estimated {travel:.1f} m "
                     "horizontally (their height / tan 30 deg) that the track leaves out: dead reckoning counts steps, "
                     "and a ride has none, so positions after a ride are off by its travel (decision L377)")
    return lines


def vehicle_lines(records: list[dict]) -> list[str]:
    """Decisions L615, L616: the one line for the rides that vibrate like a vehicle (rides.csv kind vehicle): no
    floors counted, and their travel, which no step measures, left out of the track."""
    from pdrlearn.kernels.pause_ride import VEHICLE_VIBRATION_MPS2

    rides = [r for r in records if r["kind"] == "vehicle"]
    if not rides:
        return []
    shown = ", ".join(f"{r['start_s']:.0f}-{r['end_s']:.0f} s ({r['vibration_mps2']:.2f} m/s^2, "
                      + (f"{r['dz_m']:+.1f} m)" if np.isfinite(r["dz_m"]) else "no barometer)")  # decision L624
                      for r in rides[:3])
    minutes = sum(float(r["end_s"]) - float(r["start_s"]) for r in rides) / 60.0
    return [f"{len(rides)} vehicle ride(s) ({shown}{', ...' if len(rides) > 3 else ''}; {minutes:.1f} min in all): "
            f"standstills whose floor vibrated at {VEHICLE_VIBRATION_MPS2:g} m/s^2 or more (rides.csv kind vehicle; "
            "decisions L402, L615, L616); they count no floors, and the vehicle's travel is unknown to a step "
            "counter and left out of the track, so positions after a ride are off by it"]


def trajectory_rides(traj: pd.DataFrame, records: list[dict] | None) -> pd.Series:
    """Decision L623: trajectory.csv's ``ride``: per row, the rides.csv ``ride`` whose span (``start_s`` to
    ``end_s``) the line from the row before to this one overlaps (``t[i - 1] < end_s`` and ``t[i] > start_s``): that
    line was not walked (a foot track's stride after the ride starts where the walker boarded; a lower-back track's
    contacts inside a ride, W486, are its bounce), so a plot does not draw it as a path; empty (<NA>) elsewhere and on
    the first row. The position after a ride misses the vehicle's travel (L616)."""
    out = pd.array([pd.NA] * len(traj), dtype="Int64")
    if not records or len(traj) < 2:
        return pd.Series(out, index=traj.index, name="ride")
    t = traj["t"].to_numpy(float)
    for r in records:
        hit = np.flatnonzero((t[:-1] < float(r["end_s"])) & (t[1:] > float(r["start_s"]))) + 1
        out[hit] = int(r["ride"])
    return pd.Series(out, index=traj.index, name="ride")


def with_ride_column(traj: pd.DataFrame, info: dict) -> pd.DataFrame:
    """Decision L623: ``traj`` with trajectory.csv's ``ride`` column (:func:`trajectory_rides`) when ``info["rides"]``
    holds a ride; unchanged otherwise (no column without a ride). ``track`` and ``run`` (decision E293) write it."""
    if not info.get("rides"):
        return traj
    return traj.assign(ride=trajectory_rides(traj, info["rides"]))


def ride_table(info: dict) -> pd.DataFrame:
    """Decision L377: rides.csv from a track's ``info["rides"]`` (:func:`ride_rows`' records); the header alone
    without rides (a foot track, no barometer)."""
    return pd.DataFrame(info.get("rides") or [], columns=list(RIDE_COLUMNS))
