"""The 10-metre walk test's timing from a tracked step table (decisions L312, L313, docs/decisions/localization.md).

The clinical 10MWT times the middle 10 m of a straight walkway, with zones of about 2 m to accelerate and to
decelerate excluded (a 14 m walkway, e.g. Bohannon 1997, Age Ageing 26:15-19; the thesis and seeds give no
protocol). From a track: the walk's positions after each row of ``steps.csv`` (``length_m`` along ``heading_rad``,
reached at the row's contact ``event_s``) are joined by straight lines in time; the times the path passes
:data:`ZONE_M` and :data:`ZONE_M` + :data:`TIMED_M` from the bout's start give ``ten_m_walk_time_s`` and
``ten_m_walk_speed_mps`` = 10 m / that time. Pure functions.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from pdrlearn.kernels.turn_length import STRAIGHT_MAX_RAD
from pdrlearn.track.clinical import TURN_COUNT_MIN_DEG, _is_lower_back, bout_rows
from pdrlearn.track.flags import flag_values
from pdrlearn.track.stair_flights import flight_spans, flight_strides

#: decision L312: the acceleration and the deceleration zone (m) a 10MWT leaves out on each side (Bohannon 1997:
#: a 14 m walkway, the middle 10 m timed; 2 m each side is the common protocol, the seeds give none)
ZONE_M = 2.0
#: decision L312: the timed distance (m)
TIMED_M = 10.0
#: decision L312: the walkway's first ZONE_M + TIMED_M + ZONE_M must be straight: the straight-line distance from the
#: bout's start to where its path reaches 14 m is at least this share of 14 m (a 90 deg turn in the middle: 0.71)
STRAIGHT_MIN = 0.9
#: decision L349: a walk whose longest bout is short of 14 m by less than this (m) is told to walk past the walkway's
#: ends (a run-out; a foot track of a 14 m walkway read 13.84 m in the session 32 trial: 1.1 % short, inside the foot's
#: distance error); the walk is still not timed (L313: no zone shortened, nothing extrapolated)
RUN_OUT_M = 1.0
#: decision C193: a declared walkway's pass (``track --ten-m-walk``) that passed the timed stretch's end mark and
#: tracked short of the walkway's end by at most this share of its length is timed (the foot track's scale error with
#: a margin: L349's 14 m walkway read 1.1 % short, trial T1's 10 m one 0.4 %)
DECLARED_SHORT_SHARE = 0.02
#: decision C205: a calibrated lower back's share instead (its 10 m walks' shortfall, measured on fresh calibrated
#: walkers); None = C193's :data:`DECLARED_SHORT_SHARE`
DECLARED_SHORT_SHARE_LOWER_BACK: float | None = None
#: decision C205 (measured, not adopted): what a calibrated lower back's refused walkway pass adds to its note
LOWER_BACK_SHORT_NOTE = ("; a calibrated lower back tracks a walkway walked end to end up to 5 % short (simulated "
                         "walkers: 0.0-5.0 %, decision C205) and gets no more tolerance than C193's 2 % (its timed "
                         "speed already errs up to 5.45 %): have the walker start and stop 1 m beyond the walkway's "
                         "ends, or time the walk with a foot unit")
#: decision L649: the calibrated lower back's walk from standing, measured and not adopted
#: (experiments/walk_test_calibrated_l649.py, users 12462-12470: the T25FW's speed error median +9.11 %, max 14.13 %)
CALIBRATED_FROM_STANDING = "speed +9.1 % median, up to +14.1 %"


def lower_back_note(accel: float, timed: float, calibrated: bool = False, what: str = "the walk") -> str | None:
    """Decisions L313, L649: why a lower-back track's walk timed over ``timed`` metres after ``accel`` metres is not
    timed, naming the marks asked; None when it is timed - a calibrated lower back (``calibrate``'s parameters) with
    an acceleration zone (L649 measured the 10 m walk's speed within 2.31 %, trial T1's 1,7.62,3.38 within 2.58 %).
    From standing (``accel`` 0) a calibrated one reads fast (:data:`CALIBRATED_FROM_STANDING`): its first contact
    comes after the body begins to move."""
    marks = f"the {accel:g} m and {accel + timed:g} m marks are" if accel > 0 else f"the {timed:g} m mark is"
    if calibrated and accel > 0:
        return None
    if calibrated:
        return (f"not given on the calibrated lower back from standing: its first contact comes after the body "
                f"begins to move, so {what} reads fast (simulated calibrated walkers' timed 25-foot walk from "
                f"standing: {CALIBRATED_FROM_STANDING}, decision L649); " + (
                    "a walkway with an acceleration zone is timed on a calibrated lower back (L649): --ten-m-walk "
                    "1,7.62,3.38 gives a flying 25-foot walk, whose time is ten_m_walk_time_s (changes.csv compares "
                    "its speed as ten_m_walk_speed_mps), not this T25FW from standing, which only a foot unit times "
                    "(decision C206)" if "25-foot" in what else  # decision C206: the T25FW's own note
                    "give the walkway an acceleration zone (--ten-m-walk ACCEL,TIMED,DECEL with ACCEL over 0: timed "
                    "on a calibrated lower back, L649) or time it with a foot unit"))
    return (f"not given on the uncalibrated lower back: its step lengths read slow walkers' short steps long, so "
            f"{marks} passed early (simulated 0.45-1.0 m/s walkers, waist-pendulum without calibration: speed +34 to "
            "+164 %, decision L313); calibrate the wearer (pdrlearn calibrate on a walk of known length, then track "
            "--params: timed with an acceleration zone, L649) or time it with a foot unit")


#: decision L313: why an uncalibrated lower-back track gives no 10 m walk time on L312's walkway (L649: the marks)
LOWER_BACK_NOTE = lower_back_note(2.0, 10.0)
#: decision L552 (our choice, no document gives one): with no walkway declared (no ``track --ten-m-walk``), a walking
#: bout longer than this (m) is not a walkway test - a march or a long walk (trial T3 finding 9: "10 m walk test
#: 5.30 s" on a 9 km march) - and the automatic 10 m walk and T25FW skip it. 100 m: ten 10 m walk tests, as
#: position_sigma's 100 m; a 14 m walkway's bout with run-outs is some 20 m
WALKWAY_BOUT_MAX_M = 100.0
#: decision L673 (our choice, no document gives one): a turn of at least this much (deg) inside a walking bout ends a
#: straight pass, and each pass is a 10 m walk trial (trial T3 finding F6: a walkway's back-and-forth passes with
#: turns on the spot are one bout). 90 deg: a walkway's turnaround is 180 deg; L312's STRAIGHT_MIN already refuses a
#: pass that turns less inside its 14 m; the turn's strides are those over L79's 15 deg (STRAIGHT_MAX_RAD)
PASS_TURN_DEG = 90.0
#: decision L673 (amended, review R2 finding 4): the measured turn that ends a pass - a 90 deg turn measured as L104's
#: TURN_COUNT_MIN_DEG (80 deg: 10 deg for the tracked heading's error), as turns.csv counts it
PASS_TURN_MIN_DEG = TURN_COUNT_MIN_DEG
#: the summary keys :func:`ten_metre_walk` gives (decision L312)
KEYS = ("ten_m_walk_time_s", "ten_m_walk_speed_mps", "ten_m_walk_note")


def walkway_zones(summary: dict) -> tuple[float, float, float]:
    """Decision L531: the walkway (acceleration, timed, deceleration metres) a summary's ``ten_m_walk_*`` keys were
    timed on: ``ten_m_walk_zones_m`` (L522), else L312's 2, 10, 2."""
    accel, timed, decel = summary.get("ten_m_walk_zones_m") or (ZONE_M, TIMED_M, ZONE_M)
    return float(accel), float(timed), float(decel)


def walkway_timed_m(summary: dict) -> float | None:
    """Decision C211: the timed metres a summary's 10 m walk speed is over (:func:`walkway_zones`), None without a
    speed - the walkway changes.csv and clinical.md compare the speed on."""
    return None if summary.get("ten_m_walk_speed_mps") is None else walkway_zones(summary)[1]


def timed_stretch(accel: float, timed: float, decel: float, whole: str = "a {total} m walkway") -> str:
    """Decision L536: the words for a walkway's timed stretch from its (acceleration, timed, deceleration) metres:
    "the middle 6 m of a 10 m walkway" only when the zones are equal and not 0; "the first 6 m of a 10 m walkway,
    from standing, 4 m left to decelerate" for ``--ten-m-walk 0,6,4``; "the 6 m after the first 1 m of ..."
    otherwise. ``whole`` names the walk, ``{total}`` its metres. The console line and clinical.md both say it."""
    of = whole.format(total=f"{accel + timed + decel:g}")
    left = f", {decel:g} m left to decelerate" if decel > 0 else ", no zone to decelerate"
    if accel == decel > 0:
        return f"the middle {timed:g} m of {of}"
    if accel == 0:
        return f"the first {timed:g} m of {of}, from standing" + (left if decel > 0 else "")
    return f"the {timed:g} m after the first {accel:g} m of {of}{left}"


def walk_test_name(summary: dict) -> str:
    """Decision C206: the name of a summary's ``ten_m_walk_*`` test: "10 m walk" on L312's walkway and on a 10 m one
    (``--ten-m-walk 2,6,2``, the clinic's 10 m walk test), else its own timed metres ("7.62 m walk" for trial T4's
    flying 25-foot walk, ``--ten-m-walk 1,7.62,3.38``: no 10 m was walked or timed)."""
    accel, timed, decel = walkway_zones(summary)
    return "10 m walk" if math.isclose(timed, TIMED_M) or math.isclose(accel + timed + decel, 10.0) else (
        f"{timed:g} m walk")


def trials_text(summary: dict) -> str:
    """Decision L531: "N trials, fastest V m/s" when a summary has two or more 10 m walk trials (L524), else ""."""
    n = summary.get("n_ten_m_walk_trials") or 0
    if n < 2 or summary.get("ten_m_walk_max_speed_mps") is None:
        return ""
    return f"{n} trials, fastest {summary['ten_m_walk_max_speed_mps']:.2f} m/s"


def free_walking_text(summary: dict) -> str:
    """Decision L679: the words that a summary's walk tests were found in free walking (``ten_m_walk_declared``
    False: no ``track --ten-m-walk``), not a declared test; "" when declared or for a summary without the key."""
    if summary.get("ten_m_walk_declared") is not False:
        return ""
    return "found in free walking, no walkway declared (track --ten-m-walk), L679"


def declared_refusal(summary: dict) -> tuple[str, str] | None:
    """Decision C194: (the declared walkway's timed stretch, :func:`timed_stretch`; the note) of a summary whose
    declared 10 m walk test (``ten_m_walk_declared``, ``track --ten-m-walk``) was not timed; None when it was timed
    or not declared (a walk found in free walking may be no test, L679)."""
    if summary.get("ten_m_walk_declared") is not True or summary.get("ten_m_walk_time_s") is not None:
        return None
    return timed_stretch(*walkway_zones(summary)), summary.get("ten_m_walk_note") or "no reason recorded"


#: decision L387: the timed 25-foot walk's distance (m; 25 ft, the MSFC's T25FW as recalled), from standing
T25FW_M = 7.62
#: the summary keys :func:`t25fw` gives (decision L387)
T25FW_KEYS = ("t25fw_time_s", "t25fw_speed_mps", "t25fw_note")
#: decision C251: the T25FW's trials (summary.json; ``t25fw_trial_times_s`` a list)
T25FW_TRIAL_KEYS = ("n_t25fw_trials", "t25fw_trial_times_s")
#: decision L387: the uncalibrated lower back gets no T25FW for L313's reason (its step lengths move the 7.62 m
#: mark); L649: nor a calibrated one (from standing)
T25FW_LOWER_BACK_NOTE = lower_back_note(0.0, 7.62, what="the timed 25-foot walk")


def _path(st: pd.DataFrame) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Times, path distance, x and y of a bout's rows: the start (the first row's ``start_s``, 0 m) then each row's
    contact (``event_s``, else its ``end_s``) at its rest position; NaN from a row without a length on."""
    length = st["length_m"].to_numpy(float)
    if "impossible" in st:
        length = np.where(flag_values(st["impossible"]), np.nan, length)
    h = st["heading_rad"].to_numpy(float) if "heading_rad" in st else np.zeros(len(st))
    t_end = st["event_s"].to_numpy(float) if "event_s" in st else st["end_s"].to_numpy(float)
    t_end = np.where(np.isfinite(t_end), t_end, st["end_s"].to_numpy(float))
    t = np.concatenate([[float(st["start_s"].iloc[0])], t_end])
    d = np.concatenate([[0.0], np.cumsum(np.abs(length))])  # NaN from a stride without a length on
    x = np.concatenate([[0.0], np.cumsum(length * np.cos(h))])
    y = np.concatenate([[0.0], np.cumsum(length * np.sin(h))])
    return t, d, x, y


def _row_turns(st: pd.DataFrame) -> np.ndarray:
    """Decision L673: each row's turn (rad): the foot's own ``turn_angle_rad`` where the table has it (L66), else the
    wrapped change of ``heading_rad`` from the previous row (a lower-back table); 0 where unknown."""
    if "turn_angle_rad" in st:
        turn = st["turn_angle_rad"].to_numpy(float)
    elif "heading_rad" in st:
        h = st["heading_rad"].to_numpy(float)
        turn = np.angle(np.exp(1j * np.diff(h, prepend=h[:1]))) if len(h) else h
    else:
        turn = np.zeros(len(st))
    return np.nan_to_num(turn)


def pass_rows(steps: pd.DataFrame, a: int, b: int) -> list[tuple[int, int]]:
    """Decision L673: the straight passes of the bout ``steps.iloc[a:b]``, as ``(first, last + 1)`` row ranges: each
    run of consecutive rows turning at least L79's :data:`STRAIGHT_MAX_RAD` (:func:`_row_turns`; one slower row
    between two turning rows bridged, as L104's turns bridge a turn's slower step) whose turns add up to
    :data:`PASS_TURN_DEG`, measured as :data:`PASS_TURN_MIN_DEG` or more, is a turn between two passes: its rows close
    the pass before it (the walker's deceleration runs into the turn, as a bout's last pass runs into its stop), the
    next pass starts after it. A smaller run stays in its pass (L313's straightness rule judges it). A bout without
    such a turn is one pass. Decision C188: these are not turns.csv's turns and do not follow them - the bridged row
    may be a walking stride (L653 ends a turns.csv turn there) and a row turns from 15 deg whatever its rate (L678's
    rate may leave a slow wide curve out of turns.csv) - a pass ends where the walk's heading has come round."""
    turns = _row_turns(steps.iloc[a:b])
    turning = np.abs(turns) >= STRAIGHT_MAX_RAD
    turning[1:-1] |= turning[:-2] & turning[2:]  # L673 (R2 finding 3): one slower row, any kind (C188)
    out, start, k = [], a, 0
    while k < b - a:
        if not turning[k]:
            k += 1
            continue
        j = k
        while j < b - a and turning[j]:
            j += 1
        # decision L673 (amended: the turn ends its pass; review R2 finding 4: L104's 80 deg, a 1e-9 rad tolerance)
        if abs(turns[k:j].sum()) >= math.radians(PASS_TURN_MIN_DEG) - 1e-9:
            out.append((start, a + j))
            start = a + j
        k = j
    if b > start:
        out.append((start, b))
    return out


def _timed_pieces(steps: pd.DataFrame, zone_m: float, timed_m: float, decel_m: float, max_bout_m: float | None = None,
                  passes: bool = True, ramps=None, short_share: float = 0.0,
                  any_recording: bool = False, unseen_lead: bool = False) -> list[tuple[str, object]]:
    """Decision L673: ``(name, _time_bout's result)`` of each piece a walk test times: with ``passes`` each straight
    pass of a walking bout (:func:`pass_rows`, "walking bout N pass P"), else each bout ("walking bout N"). A bout
    whose passes are all too short is judged whole for its note only (L313's: a walk that turns inside its first
    metres; review R2 finding 2: not when a pass is a near miss, :data:`RUN_OUT_M` short, whose L349 note stays, and
    never timed whole, so a pass is timed or refused by itself, whatever follows it), and a bout longer than
    ``max_bout_m`` stays whole for L552 to refuse (a march's legs are no walkway's passes). Decision L679: ``ramps``
    as :func:`_time_bout`'s; decision C193: ``short_share`` too. Decision L779: with no walkway declared
    (``max_bout_m`` set, L552) a recording that does not look like a walk test (:func:`free_recording_note`) is
    one refused piece, unless ``any_recording`` (the rule before L779). Decision C250: ``unseen_lead`` as
    :func:`_time_bout`'s."""
    out = []
    length = np.abs(np.nan_to_num(steps["length_m"].to_numpy(float)))
    free = free_recording_note(steps, timed_m) if max_bout_m is not None and not any_recording else None
    if free:  # decision L779: a mission or a free walk is no walk-test recording
        return [("the recording", free)]
    for n, (a, b) in enumerate(bout_rows(steps), start=1):
        split = passes and (max_bout_m is None or length[a:b].sum() <= max_bout_m)
        parts = pass_rows(steps, a, b) if split else [(a, b)]
        got = [(f"walking bout {n}" + (f" pass {p}" if len(parts) > 1 else ""),
                _time_bout(steps, c, d, zone_m, timed_m, decel_m, max_bout_m, ramps, short_share, unseen_lead))
               for p, (c, d) in enumerate(parts, 1)]
        need = zone_m + timed_m + decel_m
        if len(parts) > 1 and all(isinstance(g, float) and g < need - RUN_OUT_M for _, g in got):  # L673; R2 #2
            whole = _time_bout(steps, a, b, zone_m, timed_m, decel_m, max_bout_m, ramps, short_share)
            got = [(f"walking bout {n}", whole)] if isinstance(whole, str) else got  # its refusal only
        out += got
    return out


def free_recording_note(steps: pd.DataFrame, timed_m: float) -> str | None:
    """Decision L779 (our rule, no document gives one): the note refusing a whole recording's automatic walk tests
    (no walkway declared) when it does not look like a walk test: one of its walking bouts holds a stair flight
    (L779 amended: a flight of stairs.csv, :func:`pdrlearn.track.stair_flights.flight_spans` - L438's runs of 2 or
    more stair strides, |dz_m| >= 0.10 m, without L443's ramp climbs; a walk test is walked on a level walkway,
    L434) - a mission or a free walk, whose level corridors would read as walkway passes (trial s50t1 F7: "10 m walk
    test 5.85 s" on every mission). A bout's length plays no part (decision L781): a bout longer than L552's
    ``max_bout_m`` is L552's alone (:func:`_time_bout` refuses it, the recording's other bouts are timed: review R2
    finding 1; L779's ">100 m" clause was dropped at the merge). None when the recording looks like a walk test."""
    flights = flight_spans(steps) if "dz_m" in steps else []  # L779 amended: stairs.csv's flights (L443: no ramp)
    for n, (a, b) in enumerate(bout_rows(steps), start=1):
        n_stair = sum(max(0, min(b, f1) - max(a, f0)) for f0, f1, _ in flights)
        if n_stair:
            what = (f"a stair flight of {n_stair} stair stride(s) (stairs.csv, L438; a walk test is walked on a level "
                    "walkway, L434)")
            return (f"walking bout {n} holds {what}: a mission or a free walk, not a walk-test recording, so none of "
                    f"its walks is timed as a {timed_m:g} m walk test with no walkway declared (decision L779) - "
                    "give track --ten-m-walk ACCEL,TIMED,DECEL to time a walkway in it")
    return None


def _bout_limit(zones) -> float | None:
    """Decision L552: the longest bout the walk tests time: none with a declared walkway (``zones``), else
    :data:`WALKWAY_BOUT_MAX_M`."""
    return None if zones else WALKWAY_BOUT_MAX_M


def ramp_numbers(steps: pd.DataFrame, found) -> np.ndarray:
    """Decision L679: (N,) int, each row's ramps.csv ramp number (from 1; 0 outside every ramp) of ``found``
    (:func:`pdrlearn.track.grade.track_ramps` of ``steps``: each ramp's ``first`` / ``last`` row, numbered as
    ramps.csv numbers them)."""
    out = np.zeros(len(steps), int)
    for k, r in enumerate((found or ([],))[0], start=1):
        out[int(r["first"]):int(r["last"]) + 1] = k
    return out


def _ramp_note(steps: pd.DataFrame, a: int, k: int, need: float, timed_m: float, ramps) -> str | None:
    """Decision L679: the refusal of the walk-test stretch ``steps.iloc[a:a + k]`` (the rows whose path reaches
    ``need`` m, as L434's flight check reads them) when a row of it lies on a ramp of ``ramps``
    (:func:`ramp_numbers`); None otherwise."""
    if ramps is None:
        return None
    ramps = np.asarray(ramps)
    on = ramps[a:a + k]
    if not (on > 0).any():
        return None
    n = int(on[on > 0][0])
    rows = np.flatnonzero(ramps == n)
    t0, t1 = float(steps["start_s"].iloc[rows[0]]), float(steps["end_s"].iloc[rows[-1]])
    rows_are = "step(s)" if _is_lower_back(steps) else "stride(s)"  # a lower back's rows are steps (W515's words)
    return (f"the first {need:g} m of the walk hold {int((on == n).sum())} {rows_are} of ramp {n} of ramps.csv "
            f"({t0:.1f}-{t1:.1f} s): a {timed_m:g} m walk test is timed on a level walkway (decisions L434, L679); "
            "not timed")


def ten_metre_walk(steps: pd.DataFrame, zones: tuple[float, float, float] | None = None,
                   calibrated: bool = False, ramps=None, any_recording: bool = False) -> dict:
    """Decision L312: :data:`KEYS` of a tracked step table: the first walking bout (L104's bouts,
    :func:`pdrlearn.track.clinical.bout_rows`) whose path reaches ZONE_M + TIMED_M + ZONE_M = 14 m is timed over
    its middle 10 m (module docstring); ``ten_m_walk_note`` says why there is no time (decision L313: a walk shorter
    than 14 m is not timed - no zone is shortened and nothing extrapolated -, nor one that turns inside its first
    14 m or whose rows there lack a length; nor a lower-back track, :data:`LOWER_BACK_NOTE`), else None.
    ``zones`` (decision L522, ``track --ten-m-walk``): the walkway's (acceleration, timed, deceleration) metres
    instead of (2, 10, 2). Decision L524: :data:`TRIAL_KEYS` count every timed bout (:func:`ten_metre_walk_trials`).
    Decision L552: without ``zones`` a bout over :data:`WALKWAY_BOUT_MAX_M` is not timed. Decision L649:
    ``calibrated`` (a lower-back track with ``calibrate``'s parameters) times the lower back when the walkway has an
    acceleration zone (:func:`lower_back_note`). Decision L679: ``ramps`` (:func:`ramp_numbers`) a bout whose
    walkway holds a ramp's row is not timed; ``ten_m_walk_declared`` says whether ``zones`` declared the walkway.
    Decision L779: without ``zones`` a recording with a stair flight in any of its walking bouts has none of its walk
    tests timed (:func:`free_recording_note`; ``any_recording``: the rule before)."""
    accel, timed, decel = zones or (ZONE_M, TIMED_M, ZONE_M)
    short = declared_short_share(steps, zones, calibrated)  # decisions C193, C205: a declared walkway only
    more = LOWER_BACK_SHORT_NOTE if zones and calibrated and _is_lower_back(steps) else ""  # decision C205
    out = timed_walk(steps, accel, timed, KEYS, lower_back_note(accel, timed, calibrated),
                     lambda longest, need: short_walk_note(longest, need, (accel, timed, decel),
                                                           declared=zones is not None) + more, decel_m=decel,  # C272
                     max_bout_m=_bout_limit(zones), passes=True, ramps=ramps, short_share=short,  # decision L673
                     any_recording=any_recording)  # decision L779
    trials = ten_metre_walk_trials(steps, zones, calibrated, ramps=ramps, any_recording=any_recording)
    out["n_ten_m_walk_trials"] = len(trials)  # decision L524
    missed = _near_misses(steps, accel + timed + decel, lower_back_note(accel, timed, calibrated) is None,
                          _bout_limit(zones), ramps, any_recording)  # review R2 finding 1: L552's march stays whole
    missed = [(n, m) for n, m in missed if not _short_ok(m, accel, timed, accel + timed + decel, short)]  # C193
    if out["ten_m_walk_time_s"] is not None and missed:  # decision L524: a trial lost to L349's few cm is said
        out["ten_m_walk_note"] = "; ".join(filter(None, [out["ten_m_walk_note"], (  # L535's note kept before it
            "; ".join(f"{n} tracked {math.floor(m * 100.0 + 1e-6) / 100.0:.2f} m, short of "
                      f"{accel + timed + decel:g} m" for n, m in missed)
            + ": not timed, so the timed trial(s) in ten_m_walk_trials.csv may not be the first walk (L313); have the "
            "walker start and stop beyond the walkway's ends (a run-out, decisions L349, L524)")]))
    out["ten_m_walk_max_speed_mps"] = float(trials["speed_mps"].max()) if len(trials) else None
    out["ten_m_walk_zones_m"] = [accel, timed, decel]  # decision L522: the walkway the keys were timed on
    out["ten_m_walk_declared"] = zones is not None  # decision L679: False = found in free walking
    return out


#: decision L524: ten_m_walk_trials.csv's columns (one row per timed straight bout)
TRIAL_COLUMNS = ("trial", "start_s", "end_s", "time_s", "speed_mps")
#: decision L524: the summary keys of every timed bout (beside :data:`KEYS`, the first one's)
TRIAL_KEYS = ("n_ten_m_walk_trials", "ten_m_walk_max_speed_mps", "ten_m_walk_zones_m")


def ten_metre_walk_trials(steps: pd.DataFrame, zones: tuple[float, float, float] | None = None,
                          calibrated: bool = False, ramps=None, any_recording: bool = False) -> pd.DataFrame:
    """Decision L524: ``ten_m_walk_trials.csv``: every walking bout timed as L312 times the first one (its
    acceleration zone, timed metres, deceleration zone reached, straight, level, every length known; L313's
    refusals skip a bout), one row each (:data:`TRIAL_COLUMNS`: ``start_s`` / ``end_s`` where the path passes the
    timed stretch's start and end). A self-selected and a fast trial in one recording are two rows. Decision L649:
    ``calibrated`` as :func:`ten_metre_walk`'s; decision L679: ``ramps`` too; decision L779: ``any_recording`` too."""
    accel, timed, decel = zones or (ZONE_M, TIMED_M, ZONE_M)
    rows = []
    lower_back_ok = lower_back_note(accel, timed, calibrated) is None  # decision L649
    if len(steps) and {"start_s", "end_s", "length_m"} <= set(steps.columns) and (
            lower_back_ok or not _is_lower_back(steps)):
        for _, got in _timed_pieces(steps, accel, timed, decel, _bout_limit(zones), ramps=ramps,  # L552; L673; L679
                                    short_share=declared_short_share(steps, zones, calibrated),  # C193, C205
                                    any_recording=any_recording):  # L779
            if isinstance(got, tuple):
                rows.append((len(rows) + 1, got[0], got[1], got[1] - got[0], timed / (got[1] - got[0])))
    return pd.DataFrame(rows, columns=list(TRIAL_COLUMNS))


def _near_misses(steps: pd.DataFrame, need: float, lower_back_ok: bool = False, max_bout_m: float | None = None,
                 ramps=None, any_recording: bool = False) -> list[tuple[str, float]]:
    """Decisions L349, L524: (its name, tracked metres) of each walking bout (L673: pass) short of ``need`` by less than
    :data:`RUN_OUT_M` - a walk of the walkway's length that tracked a few cm short (L649: on the lower back only when
    ``lower_back_ok``). ``max_bout_m`` and ``ramps`` as :func:`_timed_pieces`' (review R2 finding 1: a march over
    L552's limit stays whole, its legs no near misses)."""
    if not len(steps) or not {"start_s", "end_s", "length_m"} <= set(steps.columns) or (
            _is_lower_back(steps) and not lower_back_ok):
        return []
    got = _timed_pieces(steps, 0.0, need, 0.0, max_bout_m, ramps=ramps, any_recording=any_recording)  # L673; L779
    return [(n, m) for n, m in got if isinstance(m, float) and need - RUN_OUT_M <= m < need]


def t25fw(steps: pd.DataFrame, walkway: bool = False, calibrated: bool = False, ramps=None,
          any_recording: bool = False, *, unseen_lead: bool = True, n_mean: int = 2) -> dict:
    """Decision L387: :data:`T25FW_KEYS` of a tracked step table: the timed 25-foot walk from a standing start - the
    first walking bout whose path reaches :data:`T25FW_M` is timed from its first row's start to where its path
    passes 7.62 m (no zone: the test starts from standing, L312's kernel with a zone of 0 m); a shorter, turning or
    lower-back walk is not timed (L313's rules), ``t25fw_note`` says why. Decision L552: unless ``walkway`` (a
    walkway declared, ``track --ten-m-walk``) a bout over :data:`WALKWAY_BOUT_MAX_M` is not timed. Decision L649: a
    calibrated lower back is not timed either (from standing it reads fast), its note says so. Decision L679:
    ``ramps`` (:func:`ramp_numbers`): a walk on a ramp is not timed. Decision L779: unless ``walkway``, a recording
    with a stair flight in any of its walking bouts has none of its walk tests timed (:func:`free_recording_note`;
    ``any_recording``: the rule before). Decision C250: ``unseen_lead`` starts
    each walk at the body's first step (:func:`body_start`; False: the foot's first row, L387's rule). Decision C251:
    every bout timed is a trial - ``n_t25fw_trials``, ``t25fw_trial_times_s`` - and the time is the mean of the first
    ``n_mean`` trials (the MSFC's T25FW score: the mean of two trials), the first one's when fewer were timed."""
    args = dict(max_bout_m=_bout_limit(walkway), ramps=ramps, any_recording=any_recording,  # decision L779
                unseen_lead=unseen_lead)  # decision C250
    out = timed_walk(steps, 0.0, T25FW_M, T25FW_KEYS,
                     lower_back_note(0.0, T25FW_M, calibrated, what="the timed 25-foot walk"),
                     lambda longest, need: (f"no walking bout of {need:g} m (25 ft, from standing; the longest "
                                            f"{math.floor(longest * 100.0 + 1e-6) / 100.0:.2f} m; decision L387): "
                                            "a shorter walk is not timed"), **args)
    trials = []
    if out["t25fw_time_s"] is not None:  # decision C251: every walk from standing timed as the first
        trials = [got[1] - got[0] for _, got in _timed_pieces(steps, 0.0, T25FW_M, 0.0, args["max_bout_m"],
                                                              False, ramps, 0.0, any_recording, unseen_lead)
                  if isinstance(got, tuple)]
    out["n_t25fw_trials"], out["t25fw_trial_times_s"] = len(trials), trials
    if len(trials) >= 2 and n_mean >= 2:  # decision C251: the mean of the first two trials
        k = min(n_mean, len(trials))
        out["t25fw_time_s"] = float(np.mean(trials[:k]))
        out["t25fw_speed_mps"] = T25FW_M / out["t25fw_time_s"]
        out["t25fw_note"] = "; ".join(filter(None, [
            f"mean of trials 1-{k} ({len(trials)} timed, t25fw_trial_times_s; the MSFC's score, decision C251)",
            out["t25fw_note"]]))
    return out


def _climb_tables(steps: pd.DataFrame, a: int, b: int) -> str:
    """Decision L571: where the climb of the rows ``a:b`` is listed - ramps.csv when its stair strides (L179) are
    all of climbs L302 calls ramps (under the stair grade; ramps.csv lists them with --altitude fused, L300),
    stairs.csv when none are, both otherwise."""
    from pdrlearn.track.evaluate import ramp_climb_rows
    from pdrlearn.track.gait import stair_rows

    stair = stair_rows(steps.iloc[a:b])
    ramp = ramp_climb_rows(steps)[a:b] & stair
    if ramp.any() and ramp.sum() == stair.sum():
        return "it is a ramp: ramps.csv has it (with --altitude fused, L300)"
    return "stairs.csv has the flights" + (", ramps.csv the ramps (with --altitude fused)" if ramp.any() else "")


def declared_short_share(steps: pd.DataFrame, zones, calibrated: bool = False) -> float:
    """Decisions C193, C205: the share of a declared walkway (``zones``; none: 0) a pass may track short and still be
    timed: :data:`DECLARED_SHORT_SHARE`, or on a calibrated lower back :data:`DECLARED_SHORT_SHARE_LOWER_BACK` when
    set."""
    if not zones:
        return 0.0
    if calibrated and DECLARED_SHORT_SHARE_LOWER_BACK is not None and _is_lower_back(steps):
        return DECLARED_SHORT_SHARE_LOWER_BACK
    return DECLARED_SHORT_SHARE


def _short_ok(known: float, zone_m: float, timed_m: float, need: float, short_share: float) -> bool:
    """Decision C193: whether a pass of ``known`` tracked metres, short of the walkway's ``need``, is timed: it passed
    the timed stretch's end mark (``zone_m`` + ``timed_m``) and falls short by at most ``short_share`` x ``need``."""
    return bool(short_share) and zone_m + timed_m <= known < need and need - known <= short_share * need + 1e-9


def body_start(steps: pd.DataFrame, a: int, b: int, t0: float, *, full_share: float = 0.75, n_next: int = 6
               ) -> float:
    """Decision C250 (ours, from trial s51t2's recordings): the start of a walk from standing (the bout
    ``steps.iloc[a:b]``, its foot's first row starting at ``t0``) as the body's first step. From standing the leading
    foot's first stride is one step long, the other foot's two: when the first row tracks at least ``full_share`` x
    the median length of the next ``n_next`` rows (a full stride), the unseen foot led and stepped one step time -
    half the median duration of those rows - before, so the start is ``t0`` less that (not before the previous
    row's end, or 0 s). ``t0`` unchanged on a lower back, a bout of under 3 rows or a half first stride."""
    if b - a < 3 or _is_lower_back(steps):
        return t0
    length = np.abs(steps["length_m"].to_numpy(float)[a:b])
    nxt = slice(1, 1 + n_next)
    ref = float(np.nanmedian(length[nxt])) if np.isfinite(length[nxt]).any() else float("nan")
    if not (np.isfinite(length[0]) and ref > 0 and length[0] >= full_share * ref):
        return t0
    dur = (steps["end_s"].to_numpy(float) - steps["start_s"].to_numpy(float))[a:b][nxt]
    step = 0.5 * float(np.nanmedian(dur)) if np.isfinite(dur).any() else 0.0  # one step: half a stride's time
    floor = float(steps["end_s"].iloc[a - 1]) if a > 0 else 0.0
    return max(t0 - step, floor)


def _time_bout(steps: pd.DataFrame, a: int, b: int, zone_m: float, timed_m: float, decel_m: float,
               max_bout_m: float | None = None, ramps=None, short_share: float = 0.0, unseen_lead: bool = False):
    """Decisions L312, L313, L434: the bout ``steps.iloc[a:b]`` timed over the ``timed_m`` after its first
    ``zone_m`` when its path reaches ``zone_m + timed_m + decel_m``: the times ``(t0, t1)``; a float (the bout's
    known length) when it is shorter; a str (the note) when it reaches that length but is refused - decision L552:
    also when the bout is longer than ``max_bout_m`` (a march, not a walkway); decision L679: when its stretch holds
    a row of a ramp of ``ramps`` (:func:`ramp_numbers`). Decision C193: a pass short of the walkway by at most
    ``short_share`` of it that passed the timed stretch's end mark (:func:`_short_ok`) is timed to its end, the
    times then ``(t0, t1, metres short)``. Decision C250: ``unseen_lead`` (a walk from standing, ``zone_m`` 0) starts
    at :func:`body_start`, one step earlier when the foot's first row is a full stride."""
    need = zone_m + timed_m + decel_m
    t, d, x, y = _path(steps.iloc[a:b])
    length = np.abs(steps["length_m"].to_numpy(float)[a:b])
    known = np.concatenate([[0.0], np.cumsum(np.nan_to_num(length))])  # a stride without a length as 0 m
    reach = np.flatnonzero(known >= need)
    short = 0.0
    if not len(reach):
        if not _short_ok(float(known[-1]), zone_m, timed_m, need, short_share):
            return float(known[-1])
        short, reach = need - float(known[-1]), [len(known) - 1]  # decision C193: read to the path's end
    if max_bout_m is not None and known[-1] > max_bout_m:  # decision L552
        return (f"the walking bout is {known[-1]:.0f} m long, far longer than a walkway (over {max_bout_m:g} m, "
                f"decision L552): a long walk or a march, not a {timed_m:g} m walk test; not timed - give track "
                "--ten-m-walk ACCEL,TIMED,DECEL to time a walkway on it")
    k = int(reach[0])
    if not np.isfinite(d[: k + 1]).all() or not np.isfinite(t[: k + 1]).all():
        return f"a stride of the first {need:g} m has no length or no time (decision L313); not timed"
    n_stair = flight_strides(steps.iloc[a:a + k])
    if n_stair:  # decision L434: a walkway test is timed on level ground only; L438: a flight, not one stride
        # decision L571: L179's stair strides are a ramp's too (L303): the note names the table that has the climb
        return (f"the first {need:g} m of the walk hold a climb of {n_stair} ramp or stair stride(s) "
                f"(|dz_m| >= 0.10 m, L179; 2 or more in a row, L438): a {timed_m:g} m walk test is "
                f"timed on a level walkway (decision L434); not timed - {_climb_tables(steps, a, a + k)}")
    on_ramp = _ramp_note(steps, a, k, need, timed_m, ramps)  # decision L679: a ramp is no level walkway
    if on_ramp:
        return on_ramp
    end_m = need - short  # decision C193: the path's end when it tracked short
    end = (np.interp(end_m, d[k - 1: k + 1], x[k - 1: k + 1]), np.interp(end_m, d[k - 1: k + 1], y[k - 1: k + 1]))
    if math.hypot(*end) < STRAIGHT_MIN * end_m:
        return (f"the first {need:g} m of the walk are not straight: a turn or a reversal "
                f"(straight-line {math.hypot(*end):.1f} m; decision L313): a {timed_m:g} m walk "
                "test needs a straight walkway; not timed")
    t0, t1 = np.interp([zone_m, zone_m + timed_m], d[: k + 1], t[: k + 1])
    if unseen_lead and zone_m == 0.0:  # decision C250: from the body's first step, whichever foot took it
        t0 = body_start(steps, a, b, float(t0))
    if not t1 > t0:
        return "the rows' times do not increase (decision L313); not timed"
    if short:  # decision C193
        return float(t0), float(t1), float(short)
    return float(t0), float(t1)


def timed_walk(steps: pd.DataFrame, zone_m: float, timed_m: float, keys: tuple[str, str, str], lower_back_note: str,
               short_note, decel_m: float | None = None, max_bout_m: float | None = None,
               passes: bool = False, ramps=None, short_share: float = 0.0, any_recording: bool = False,
               unseen_lead: bool = False) -> dict:
    """Decisions L312, L387: ``keys`` (time, speed, note) of the first walking bout whose path reaches ``zone_m`` +
    ``timed_m`` + ``decel_m`` (default ``zone_m``; L522), timed over the ``timed_m`` after its first ``zone_m``
    (L313's refusals, :func:`_time_bout`; ``short_note(longest, need)`` the note of a walk too short). Decision L535:
    a bout L313 refuses (a turn in it) does not end the search: the first bout timed is the keys', the note naming
    the refused bout before it; with none timed, the first refusal is the note (review R0 finding 3: the summary,
    console and clinical.md said "not timed" beside ten_m_walk_trials.csv's timed trials). Decision L552: a bout
    over ``max_bout_m`` is refused; decision L679: a bout on a ramp of ``ramps`` too. Decision L673: ``passes``
    (the 10 m walk) times each straight pass of a bout (:func:`pass_rows`) as a bout of its own. Decision C193:
    ``short_share`` (a declared walkway's) times a pass a little short (:func:`_short_ok`), its note says so.
    Decision L779: ``any_recording`` as :func:`_timed_pieces`'; decision C250: ``unseen_lead`` too."""
    time_key, speed_key, note_key = keys
    out = dict.fromkeys(keys)
    decel_m = zone_m if decel_m is None else decel_m
    if not len(steps) or not {"start_s", "end_s", "length_m"} <= set(steps.columns):
        out[note_key] = "no steps"
        return out
    if _is_lower_back(steps) and lower_back_note is not None:  # decision L313 (L649: None, a calibrated one timed)
        out[note_key] = lower_back_note
        return out
    longest, refused = 0.0, None
    for n, got in _timed_pieces(steps, zone_m, timed_m, decel_m, max_bout_m, passes, ramps, short_share,  # L673
                                any_recording, unseen_lead):  # L779, C250
        if isinstance(got, float):
            longest = max(longest, got)
            continue
        if isinstance(got, str):  # decision L535: a refused bout is said, and a later bout may still be timed
            refused = refused or (n, got)
            continue
        out[time_key], out[speed_key] = got[1] - got[0], timed_m / (got[1] - got[0])
        if refused:
            out[note_key] = f"timed {n}; {refused[0]} before it: {refused[1]} (L535)"
        if len(got) > 2:  # decision C193: timed though a little short
            need = zone_m + timed_m + decel_m
            out[note_key] = "; ".join(filter(None, [out[note_key], (
                f"the walk tracked {got[2]:.2f} m short of the {need:g} m walkway, within "
                f"{100 * short_share:g} % (the track's scale error): timed, the timed stretch's end mark "
                f"passed by {decel_m - got[2]:.2f} m (decision C193"
                f"{'' if short_share == DECLARED_SHORT_SHARE else ', C205'})")]))
        return out
    out[note_key] = refused[1] if refused else short_note(longest, zone_m + timed_m + decel_m)
    return out


def short_walk_note(longest: float, need: float = 2 * ZONE_M + TIMED_M,
                    zones: tuple[float, float, float] = (ZONE_M, TIMED_M, ZONE_M), *, declared: bool = True) -> str:
    """Decision L349: the note of a walk whose longest bout ``longest`` (m) is under ``need``: the longest shown
    rounded DOWN to 2 decimals (13.998 m read "14.0 m" beside "no walking bout of 14 m"), and when it falls short by
    under :data:`RUN_OUT_M` the advice to walk past the walkway's ends (an exact 14 m walk can track a little short).
    Decision C272: with no walkway declared (``declared`` False: no ``track --ten-m-walk``) and a walk that fell short
    of the default 14 m walkway by under :data:`RUN_OUT_M`, the advice names ``--ten-m-walk 2,10,2`` first: declaring
    the standard 14 m walkway times a pass tracked a little short (C193's share)."""
    shown = math.floor(longest * 100.0 + 1e-6) / 100.0  # + 1e-6: a cumulative sum of 12.25 m is 12.2499...
    note = (f"no walking bout of {need:g} m ({zones[0]:g} m to accelerate, {zones[1]:g} m timed, {zones[2]:g} m to "
            f"decelerate; the longest {shown:.2f} m; decision L313): a shorter walk is not timed")
    if need - RUN_OUT_M <= longest < need:  # L349: a 14 m walkway walked end to end can track a few cm short
        from pdrlearn.decision_refs import decision_ref

        default = not declared and tuple(zones) == (ZONE_M, TIMED_M, ZONE_M)
        declare = (f"if this is the standard 14 m walkway (2 m run-in, 10 m timed, 2 m run-out) declare it: "
                   f"track --ten-m-walk 2,10,2 times a pass tracked up to {100 * DECLARED_SHORT_SHARE:g} % short "
                   f"({decision_ref('C193', 'C272', topic='cohort')}); or ") if default else ""
        return (note + f" - the walk tracked {need - longest:.2f} m short of {need:g} m: {declare}have the walker "
                f"start and stop at least one step beyond the walkway's ends (a run-out), so the bout is longer than "
                f"{need:g} m (decision L349); or " + _ZONES_HINT)
    return note + " - " + _ZONES_HINT


#: decision L522: what a shorter walkway's note points to (the trial's 10 m walkway: 2 m, 6 m timed, 2 m)
_ZONES_HINT = ("a shorter walkway is timed with track --ten-m-walk ACCEL,TIMED,DECEL (e.g. 2,6,2 on a 10 m "
               "walkway: its middle 6 m; decision L522)")


def parse_ten_m_walk(text: str | None) -> tuple[float, float, float] | None:
    """Decision L522: ``track --ten-m-walk ACCEL,TIMED,DECEL``'s metres checked before any session (None: the
    default 2,10,2 walkway of L312)."""
    if text is None:
        return None
    from pdrlearn.errors import DataError

    try:
        parts = tuple(float(v) for v in str(text).split(","))
    except ValueError:
        parts = ()
    if (len(parts) != 3 or not all(math.isfinite(v) for v in parts) or parts[0] < 0 or parts[2] < 0
            or parts[1] <= 0):
        raise DataError(f"--ten-m-walk {text}: give the walkway's metres ACCEL,TIMED,DECEL - the acceleration "
                        "zone, the timed distance (> 0) and the deceleration zone (>= 0), e.g. --ten-m-walk 2,6,2 "
                        "for a 10 m walkway timed over its middle 6 m")
    return parts
