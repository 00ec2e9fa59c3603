"""A corridor walk test (6MWT / 2MWT): laps between cone turns and the corridor's distance (decisions L383, L384,
docs/decisions/localization.md).

A timed walk up and down a corridor of known length (the ATS 2002 six-minute walk test: 30 m, cones at both ends)
is scored as the laps completed x the course length + the final partial lap (ATS 2002 guideline, as recalled). From
a track: the laps are the stretches between cone turns (turns.csv rows of at least :data:`CONE_TURN_MIN_DEG`, the
walker's: decision C181 leaves out L622's ``carried`` turns, made seated or riding); each
stretch that ends at a cone turn counts its corridor lengths, the final one its tracked distance scaled by the last
lap's corridor / tracked ratio. Pure functions of the step table, the turn table and the bouts table.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.track.clinical import _is_lower_back, data_gap_lengths, walked_turns
from pdrlearn.track.rests import rest_seconds, window_rests
from pdrlearn.track.walk_test import _path
from pdrlearn.warning_lines import coded

#: decision L383: a turns.csv row of at least this |angle| (deg) is a cone turn (a corridor's turnaround is ~180 deg;
#: halfway from a 90 deg corner, which ends no lap)
CONE_TURN_MIN_DEG = 135.0
#: decision L384: a final stretch of at least this many median stretches warns of a missed turn
MISSED_TURN_RATIO = 1.5
#: decision L518 (amends L384's 0.5-2 x on the foot): the relative scale error a track's laps may carry against the
#: true corridor, by unit: foot 15 % (measured: the simulated 6MWT's tracked distance -0.93..+0.78 %, L385; the real
#: foot's stride length 3.44 % MAE, README). The lower back: decision C213 (amends L518's not-adopted 50 % and L384's
#: 0.5-2 x): 35 %, 1.25 x the largest uncalibrated lap scale error of tuning users 16520-16539 (|ln| 0.2354: +26.5 % at
#: 0.35 m steps with S74's population bounce), rounded up to 5 %; 0 of 20 right corridors of held-out users fired
CORRIDOR_SCALE_TOL = {"foot": 0.15, "lower back": 0.35}
#: decision L518: the laps' robust relative spread (1.4826 x MAD / median) counts this many times on top (the foot;
#: the lower back's band is fixed, C213)
CORRIDOR_SPREAD_K = {"foot": 2.0, "lower back": 0.0}
#: decision L407: a lap whose tracked metres are off its corridor lengths x the median lap by more than this fraction
#: warns (uneven legs, e.g. a 5-10-5 shuttle, or a wrong --corridor); halfway between a turn placed a stride off on a
#: 10 m corridor (~0.14) and the 0.5 at which L384 changes the lap's count
LAP_AGREEMENT_TOL = 0.25
# decision C207 (not adopted; W413: a keyword, off by default): ``corridor_laps(..., lap_margin=F)`` gives one line when
# a foot track's own corridor length (its median lap less C181's cone-turn arc) is off --corridor by more than F. The
# candidates 0.03 (about three times the foot's worst 6MWT distance error, 0.93 %, L385) and 0.04 failed their rule on
# fresh users 16160-16179: on laps stepped round a 0.5 m cone arc C181's arc reads long and the right 30 m corridors
# measured 28.8-30.0 m (3 and 2 of 20 right corridors got the line)
#: decision C207: at least this many laps ending at cone turns give the track's own corridor length
CORRIDOR_LAP_MIN_LAPS = 2
#: decision L383: the per-minute distances' period (s; the 6MWT's minutes, from the first step)
MINUTE_S = 60.0
#: decision L383: laps.csv's columns
LAP_COLUMNS = ("lap", "start_s", "end_s", "duration_s", "corridor_laps", "tracked_m", "distance_m", "distance_source",
               "speed_mps", "rest_s", "n_steps")  # E98: speed_mps, not the old speed_m_s
#: decision L462: the six-minute walk test's duration (s; ATS statement, Am J Respir Crit Care Med 2002;166:111-117,
#: as recalled); a test span without --window longer than this plus one of L383's minutes gets a note
SIX_MINUTES_S = 360.0
#: decision L517: the last lap that ends at a cone turn is short (a turn back mid-corridor, e.g. the walk back to the
#: chair after the test) when it tracks less than its corridor lengths x the median lap by more than this fraction
#: (a foot track's laps agree within ~1 %: trial T1's 30.2 m +-1 %; a cone turn placed a stride off moves a 15 m
#: lap's end ~9 %) ...
SHORT_LAP_MIN_FRAC = 0.10
#: decision L517: ... or by more than this many robust SDs (1.4826 x MAD) of the other single laps' tracked metres,
#: whichever is larger (a lower-back track whose lap lengths change with speed, L407's waist-pll, spreads them)
SHORT_LAP_SPREAD_K = 4.0
#: decision L517: at least this many other single laps judge a last lap short (fewer: no spread to judge by)
SHORT_LAP_MIN_LAPS = 2
#: decision L642: a standstill (no step from one row's end to the next row's start) of at least this long (s)
#: before the first full lap can be the wait for "go" (ours: longer than a slow walker's stepless cone turn, 3-4.9 s
#: in trial T1)
GO_WAIT_MIN_S = 5.0
#: decision L739: on a lower-back table an auto "go" is its first contact less this many step times (the median of
#: the next :data:`LB_GO_CONTACTS` contacts' step times): gait initiation's weight shift and first swing come before the
#: first heel strike (trial s49t1's 12 sessions: 1.08-1.64 step times after the simulator's first step, median 1.4)
LB_GO_STEPS = 1.4
#: decision L739: the contacts whose step times date the lower back's "go"
LB_GO_CONTACTS = 12
#: decision L643: a lap time whose corridor length is faster than this (m/s) is no walk (a 900 m 6MWT; ours)
MAX_LAP_SPEED_MPS = 2.5
#: decision L643: ... when the median lap also tracks less than this fraction of the corridor (L384's lower bound)
NOT_CORRIDOR_FRAC = 0.5
#: decision L644: the walking ended this long (s) before the timed test's end: the test stopped early (ours)
STOP_MIN_S = 10.0
#: decision L645: a final partial lap scaled to at least this fraction of the corridor reached the cone (ours)
LAST_LAP_REACHED_FRAC = 0.95
#: decision L659 (amends L644's 1e-6 s): a data end at most this short (s) of "go" + the duration is the test's end:
#: a recording stopped at the end beep misses the lag of L642's go (the first step) behind the spoken "go" (trial T1's
#: P06: 0.8 s) and the hand's stop; ours: over twice that lag, about one slow walker's stride, far under STOP_MIN_S
END_TOL_S = 2.0
#: decision L644: the names of the timed tests by their duration (s; the 2- and 6-minute walk tests)
TEST_LABELS = {120.0: "2MWT", 360.0: "6MWT"}
#: decision L383: the summary keys :func:`corridor_walk_test` gives
KEYS = ("corridor_m", "n_laps", "walk_test_distance_m", "walk_test_duration_s", "walk_test_distance_per_minute_m",
        "fatigue_index",  # L462: walk_test_duration_s in the no-steps path and the report's walk-test table too
        "walk_test_start_s", "walk_test_protocol_s", "walk_test_stopped_s", "walk_test_note")  # L642-L646
#: decision C217: the summary keys of the rests inside a timed test's window (``walk_test_rests``: [start from the
#: go, seconds] each; summary.json only)
REST_KEYS = ("walk_test_n_rests", "walk_test_rest_time_s", "walk_test_rests")
#: decision W562: the summary keys of the corridor's scale on a lower-back track (``gait_speed_corridor_mps`` is set
#: by :func:`corridor_gait_speed` from the summary's ``gait_speed_mps``)
SCALE_KEYS = ("walk_test_scale", "gait_speed_corridor_mps")


def _distance_in_time(steps: pd.DataFrame) -> tuple[np.ndarray, np.ndarray]:
    """Times and tracked path distance (m) of the whole step table: each row's start at the distance before it and
    its contact at its cumulative length (:func:`pdrlearn.track.walk_test._path`; a row without a length as 0 m), so
    that a rest between two rows adds no distance (decision L384)."""
    t, d, _, _ = _path(steps)
    cum = np.concatenate([[0.0], np.cumsum(np.nan_to_num(np.diff(d)))])  # a stride without a length adds 0 m
    starts = steps["start_s"].to_numpy(float)
    times = np.column_stack([starts, t[1:]]).ravel()  # start_0, contact_0, start_1, contact_1, ...
    dist = np.column_stack([cum[:-1], cum[1:]]).ravel()
    return np.maximum.accumulate(np.nan_to_num(times, nan=float(t[0]))), dist


def _row_steps(steps: pd.DataFrame) -> np.ndarray:
    """(N,) the steps each row stands for (bouts.csv's ``n_steps``, decision L124): a foot stride 2, a foot-data gap
    row 0, a lower-back row (a contact) 1."""
    if _is_lower_back(steps):
        return np.ones(len(steps))
    return np.where(data_gap_lengths(steps) > 0, 0.0, 2.0)


def corridor_laps(steps: pd.DataFrame, turns: pd.DataFrame, corridor_m: float,
                  bouts: pd.DataFrame | None = None,
                  span: tuple[float, float] | None = None,
                  duration_s: float | None = None, *, start: float | str = "auto",
                  data_end: float | None = None, lap_margin: float | None = None,
                  min_share: float | None = 0.5) -> tuple[pd.DataFrame, dict, list[str]]:
    """Decisions L383, L384: ``(laps, summary, warnings)`` of a tracked step table walked up and down a corridor of
    ``corridor_m`` metres: laps.csv's rows (:data:`LAP_COLUMNS`), the summary's :data:`KEYS` and the warning lines
    (missed or extra turns, a corridor length far from the tracked laps). ``span``: the test's start and end (s;
    ``track --window``'s), else the first step's start and the last step's end. ``duration_s`` (decision L516,
    ``track --walk-test-duration``): the test runs ``duration_s`` seconds from "go" (inside ``span`` when both are
    given): ``start`` (L642) a time (s), ``"first-step"`` or ``"auto"`` (:func:`go_time`); it ends at ``data_end``
    (the recording's end) at the latest (L644). Decision C249: with ``duration_s``, a recording (or window) holding
    under ``min_share`` of it after the go is no walk-test recording (:func:`too_short_note`): no walk test is scored
    (None: L644's incomplete test whatever its length, the rule before)."""
    out = dict.fromkeys(KEYS)
    out["corridor_m"] = float(corridor_m)
    out["walk_test_protocol_s"] = None if duration_s is None else float(duration_s)
    empty = pd.DataFrame(columns=list(LAP_COLUMNS))
    if not len(steps) or not {"start_s", "end_s", "length_m"} <= set(steps.columns):
        return empty, out, [coded("corridor walk test: no steps; no laps", "corridor-walk-test")]
    st = steps.sort_values("start_s", kind="stable").reset_index(drop=True)
    t, d = _distance_in_time(st)
    t0, t_end = (float(t[0]), float(st["end_s"].max())) if span is None else (float(span[0]), float(span[1]))
    turns = turns if turns is not None else pd.DataFrame(columns=["start_s", "end_s", "angle_deg"])
    walked = walked_turns(turns)  # decision C181: a turn made seated or riding (L622's carried) ends no lap
    cone = walked[np.abs(walked["angle_deg"].to_numpy(float)) >= CONE_TURN_MIN_DEG] if len(walked) else walked
    mids = ((cone["start_s"].to_numpy(float) + cone["end_s"].to_numpy(float)) / 2.0) if len(cone) else np.array([])
    warnings: list[str] = []
    if duration_s is not None:  # decision L516: the 6MWT's minutes from "go" (ATS 2002); L642: "go" found or given
        t0, go_line = go_time(st, t, d, np.sort(mids), start, corridor_m)
        if go_line:
            warnings.append(go_line)
        end = t_end if span is not None else data_end  # decision L644: the data's end (the recording's or window's)
        go_inside(t0, start, span, end)  # decision L661
        full = t0 + float(duration_s)
        # decision L659: a data end within END_TOL_S of the test's end is its end (the full minutes counted, L399's
        # "no step after the last one adds 0 m"); further short, L644's incomplete test
        t_end = float(end) if end is not None and full - float(end) > END_TOL_S else full
        if t_end < full:
            warnings.append(coded(f"corridor walk test: the {'window' if span is not None else 'recording'} ends "
                                  f"{t_end - t0:.0f} s after the test's start, before the {duration_s:g} s test: the "
                                  f"test is incomplete; walk_test_duration_s is the {t_end - t0:.0f} s recorded "
                                  "(decision L644)", "L644"))
        out["walk_test_start_s"] = t0
        rest_from = rest_window_start(st, t0, start)  # decision C253 (``start`` is reused by the laps below)
    out["walk_test_duration_s"] = t_end - t0  # decision L462: the span the distance is over
    warnings_l462 = duration_note(t_end - t0, windowed=span is not None or duration_s is not None)
    if warnings_l462 is not None:
        warnings.insert(0, warnings_l462)
    contact = t[1::2]  # each row's contact
    n_row = _row_steps(st)
    mids = np.sort(mids[(mids > t0) & (mids < t_end)])
    # decision L399: lap 1 starts at the first step, the final lap ends at the last step (inside the span), so that
    # standing before the first or after the last step is no lap's time; the minutes stay the span's (L383)
    lap_t0, lap_end = max(t0, float(t[0])), min(t_end, float(st["end_s"].max()))
    bounds = np.concatenate([[lap_t0], mids[(mids > lap_t0) & (mids < lap_end)], [lap_end]])
    tracked = np.diff(np.interp(bounds, t, d))  # the stretches between cone turns (and the test's ends)
    ref = float(np.median(tracked[:-1])) if len(tracked) > 1 else float("nan")
    note = not_a_corridor(tracked, np.diff(bounds), corridor_m)
    if note:  # decision L643: no walk test scored
        out["walk_test_note"] = note
        return empty, out, [*(w for w in warnings if "L644" not in w), coded(f"corridor walk test: {note}", "L643")]
    note = too_short_note(t_end - t0, float(duration_s), min_share) if duration_s is not None else None
    if note:  # decision C249 (after L643's own note): a T25FW's or a TUG's recording is no 6MWT
        out["walk_test_note"] = note
        return empty, out, [*(w for w in warnings if "L644" not in w), coded(f"corridor walk test: {note}", "C249")]
    line = corridor_agreement(tracked, corridor_m, lower_back=_is_lower_back(st))
    if line:
        warnings.append(line)
    elif lap_margin is not None and not _is_lower_back(st):  # decision C207 (not adopted: off by default)
        line = own_corridor_line(tracked, cone_turn_m(cone, t, d, lap_t0, lap_end), corridor_m, lap_margin)
        if line:
            warnings.append(line)
    # decision L384: a stretch ending at a cone turn counts round(tracked / median) corridor lengths; 0 joins the next
    stretches: list[tuple[float, float, float, int]] = []  # (start, end, tracked, corridor laps; -1 = the final one)
    start, acc = lap_t0, 0.0
    for k, m in enumerate(tracked[:-1]):
        acc += m
        c = int(np.floor(acc / ref + 0.5)) if ref > 0 else 0
        if c == 0:
            warnings.append(coded(f"corridor walk test: the turn at {bounds[k + 1]:.1f} s came after {acc:.1f} m of "
                                  f"a {ref:.1f} m lap: counted as no lap end (an extra turn; decision L384)", "L384"))
            continue
        if c >= 2:
            warnings.append(coded(f"corridor walk test: lap {len(stretches) + 1} tracked {acc:.1f} m, {c} laps of "
                                  f"{ref:.1f} m: counted as {c} laps (a missed turn; decision L384)", "L384"))
        stretches.append((start, float(bounds[k + 1]), acc, c))
        start, acc = float(bounds[k + 1]), 0.0
    last = acc + tracked[-1]
    short = _short_last_lap(stretches, ref)
    if short is not None:  # decision L517: scored as its tracked metres x the lap scale, not a corridor length
        a, b, m, c = stretches[short]
        stretches[short] = (a, b, m, -1)
        warnings.append(coded(f"corridor walk test: lap {short + 1} turned back after {m:.1f} m of a {c * ref:.1f} m "
                              f"lap (at {b:.1f} s), and {last:.1f} m more were walked after it: walking after the "
                              f"test (back to a chair)? lap {short + 1} is scored as its tracked metres x the lap "
                              "scale, not a corridor length, and the walk after it is scored too; for a 6MWT give "
                              "--walk-test-duration 360 (six minutes from the first step) or its --window "
                              "(decision L517)", "L517"))
    uneven = [(i, m, c) for i, (_, _, m, c) in enumerate(stretches, start=1) if c > 0 and abs(m / (c * ref) - 1.0)
              > LAP_AGREEMENT_TOL]
    if uneven:
        warnings.append(coded("corridor walk test: " + ", ".join(f"lap {i} tracked {m:.1f} m" for i, m, _ in uneven)
                              + f" against the median lap's {ref:.1f} m per --corridor {corridor_m:g} m length "
                              f"(off by more than {LAP_AGREEMENT_TOL:.0%}): the laps disagree with the corridor "
                              "(uneven legs, e.g. a shuttle, or a wrong --corridor?); counted as whole corridor "
                              "lengths (decision L407)", "L407"))
    stretches.append((start, lap_end, last, -1))
    if np.isfinite(ref) and ref > 0 and last >= MISSED_TURN_RATIO * ref:
        warnings.append(coded(f"corridor walk test: the final stretch tracked {last:.1f} m, {last / ref:.1f} laps "
                              f"of {ref:.1f} m: a missed turn? counted as at most one corridor length (decision L384)",
                              "L384"))
    singles = [s for s in stretches if s[3] == 1 and s[2] > 0]
    scale = corridor_m / singles[-1][2] if singles else 1.0  # L383: the last single lap's corridor / tracked
    rows, known = [], [(lap_t0, 0.0)]  # known: (time, corridor distance) at each stretch's end
    a, b, m, _ = stretches[-1]
    # decision L645: the final lap reached the cone; L660: not after an L517 short lap (the walk back to the chair);
    # C181: with the half cone turn it did not walk (a lap between two turns' middles holds two halves); L740: not in
    # a timed test (it ends at the timer, wherever the walker is: a partial lap, capped at the corridor)
    if duration_s is None and short is None and (m + 0.5 * cone_turn_m(cone, t, d, lap_t0, lap_end)) * scale >= (
            LAST_LAP_REACHED_FRAC * corridor_m):
        stretches[-1] = (a, b, m, 1)
    for i, (a, b, m, c) in enumerate(stretches, start=1):
        dist = c * corridor_m if c > 0 else min(m * scale, corridor_m)
        source = "corridor" if c > 0 else ("tracked x scale" if singles else "tracked")
        inside = (contact > a) & (contact <= b)
        rows.append({"lap": i, "start_s": a, "end_s": b, "duration_s": b - a, "corridor_laps": max(c, 0),
                     "tracked_m": m, "distance_m": dist, "distance_source": source,
                     "speed_mps": dist / (b - a) if b > a else float("nan"), "rest_s": rest_seconds(a, b, bouts, turns),
                     "n_steps": int(n_row[inside].sum())})
        known.append((b, known[-1][1] + dist))
    laps = pd.DataFrame(rows, columns=list(LAP_COLUMNS))
    out["n_laps"] = int(laps["corridor_laps"].sum())
    out["walk_test_distance_m"] = float(laps["distance_m"].sum())
    if duration_s is not None:  # decision C217: the rests inside the timed test's window (L647's rests)
        found = window_rests(bouts, turns, rest_from, t_end)
        out.update(walk_test_n_rests=len(found), walk_test_rest_time_s=float(sum(r[1] for r in found)),
                   walk_test_rests=[[a - t0, r] for a, r in found])
    walked_end = t_end
    last_step = float(st.loc[st["start_s"] < t_end, "end_s"].max()) if (st["start_s"] < t_end).any() else t0
    if duration_s is not None and t_end - last_step > STOP_MIN_S:  # decision L644: the walking stopped early
        walked_end = last_step
        out["walk_test_stopped_s"] = last_step - t0
        warnings.append(coded(f"corridor walk test: the walking stopped {clock_text(last_step - t0)} after the "
                              f"test's start ({t_end - last_step:.0f} s before its end): the test stopped early (or "
                              "a rest to the end); the per-minute distances and the fatigue index are of the full "
                              "minutes walked (decision L644)", "L644"))
    if ref < NOT_CORRIDOR_FRAC * corridor_m:  # decision L646: the tracked metres cannot share a lap out by minute
        out["walk_test_note"] = ("per-minute distances and fatigue index withheld: the laps tracked "
                                 f"{ref:.1f} m (median) against the {corridor_m:g} m corridor, so the track lost "
                                 "steps (a pipeline unsuited to this gait?) or the corridor length is wrong; the lap "
                                 "count and distance come from the cone turns (decision L646)")
        warnings.append(coded(f"corridor walk test: {out['walk_test_note']}", "L646"))
        return laps, out, warnings
    if _is_lower_back(st):  # decision W562: the corridor's scale of the lower back's step lengths
        out["walk_test_scale"] = lap_scale([m for _, _, m, c in stretches[:-1] if c == 1],
                                           cone_turn_m(cone, t, d, lap_t0, lap_end), corridor_m,
                                           first_stretch=stretches[0][3] == 1)  # review R2: its half arc
    per_minute = _per_minute(t, d, stretches, laps["distance_m"].to_numpy(float), t0, walked_end)
    out["walk_test_distance_per_minute_m"] = per_minute
    out["fatigue_index"] = per_minute[-1] / per_minute[0] if len(per_minute) >= 2 and per_minute[0] > 0 else None
    return laps, out, warnings


def lap_metres(laps, arc_m: float, *, first_stretch: bool = True) -> np.ndarray:
    """Decisions C181, W562, C207 (review R2 F1): the corridor metres of the tracked ``laps`` ending at a cone turn:
    each less the metres walked round a cone (``arc_m``, :func:`cone_turn_m`; the ATS rule counts the corridor, not
    the arc). A lap between two turns' middles holds two half arcs, one arc; the first stretch (from the first step to
    the first turn's middle; ``first_stretch``: ``laps[0]`` is it) holds one half only."""
    own = np.asarray(laps, float) - float(arc_m)
    if first_stretch and len(own):
        own[0] += 0.5 * float(arc_m)
    return own


def lap_scale(single_laps: list[float], arc_m: float, corridor_m: float, *, first_stretch: bool = True
              ) -> float | None:
    """Decision W562: the factor that puts a track's metres on the corridor's: ``corridor_m`` / the median of
    ``single_laps`` (the tracked metres of the laps between two cone turns; ``first_stretch``: the first of them is
    the stretch from the first step) less the cone's arc, :func:`lap_metres`; None with fewer than
    :data:`CORRIDOR_LAP_MIN_LAPS` laps or no length left."""
    if len(single_laps) < CORRIDOR_LAP_MIN_LAPS:
        return None
    own = float(np.median(lap_metres(single_laps, arc_m, first_stretch=first_stretch)))
    return float(corridor_m) / own if own > 0 else None


def corridor_gait_speed(summary: dict) -> float | None:
    """Decision W562: ``gait_speed_mps`` (the recording's walking, from the step lengths) x ``walk_test_scale`` (the
    corridor's scale, :func:`lap_scale`); None without either."""
    speed, scale = summary.get("gait_speed_mps"), summary.get("walk_test_scale")
    return float(speed) * float(scale) if speed is not None and scale is not None else None


def rests_text(summary: dict) -> str | None:
    """Decision C217: "Rests during the test: N (15 s at 1:52, 31 s at 4:57)" of a summary's test-window rests
    (``walk_test_rests``); "none" when the test had none; None without the keys (no timed test)."""
    found = summary.get("walk_test_rests")
    if found is None:
        return None
    if not found:
        return "Rests during the test: none (C217)"
    listed = ", ".join(f"{r:.0f} s at {clock_text(a)}" for a, r in found)
    total = summary.get("walk_test_rest_time_s") or 0.0
    return f"Rests during the test: {len(found)} ({listed}; {total:.0f} s in all, C217)"


def rest_window_start(st: pd.DataFrame, go: float, start: float | str) -> float:
    """Decision C253: where C217's rests of a timed test are looked for: from "go" when it was given (``start`` a
    time, a wait after a real "go" is the walker's), else (``"auto"``, L642 / L739, or ``"first-step"``) from the
    first step at or after "go" - the time between is L739's dating back of the first contact, no standing."""
    if not isinstance(start, str):
        return float(go)
    later = st["start_s"].to_numpy(float)
    later = later[later >= go]
    return float(later.min()) if len(later) else float(go)


def fatigue_rest_text(summary: dict) -> str | None:
    """Decision C218: when a C217 rest overlaps the first or the last full minute of the test, the words that it,
    not slowing, drives the fatigue index (last / first full minute): "a 31 s rest at 5:10 (minute 6) drives it,
    not slowing (C218)"; None otherwise."""
    per, found = summary.get("walk_test_distance_per_minute_m") or [], summary.get("walk_test_rests") or []
    if summary.get("fatigue_index") is None or len(per) < 2 or not found:
        return None
    last = len(per) - 1
    named = []
    for start, dur in found:  # the rest's overlap with the first and with the last full minute
        hit = [k for k in (0, last) if min(start + dur, MINUTE_S * (k + 1)) - max(start, MINUTE_S * k) > 0]
        if hit:
            named.append(f"a {dur:.0f} s rest at {clock_text(start)} (minute "
                         + " and ".join(str(k + 1) for k in dict.fromkeys(hit)) + ")")
    if not named:
        return None
    return f"{' and '.join(named)} drive{'s' if len(named) == 1 else ''} it, not slowing (C218)"


def cone_turn_m(cone: pd.DataFrame, t: np.ndarray, d: np.ndarray, t0: float, t1: float) -> float:
    """Decision C181: the median tracked metres (``d`` over times ``t``) inside the cone turns of ``cone`` (from its
    ``start_s`` to its ``end_s``) whose middle lies in ``(t0, t1)``: the arc of a turn stepped round the cone, ~0 for
    a turn on the spot; 0 without one."""
    if not len(cone):
        return 0.0
    a, b = cone["start_s"].to_numpy(float), cone["end_s"].to_numpy(float)
    inside = ((a + b) / 2 > t0) & ((a + b) / 2 < t1)
    return float(np.median(np.interp(b[inside], t, d) - np.interp(a[inside], t, d))) if inside.any() else 0.0


def clock_text(seconds: float) -> str:
    """Decision L644: ``m:ss`` of a time in a test (250.4 -> ``4:10``)."""
    whole = int(round(seconds))
    return f"{whole // 60}:{whole % 60:02d}"


def walk_test_label(protocol_s: float | None) -> str:
    """Decision L644: a timed corridor test's name by the duration asked (:data:`TEST_LABELS`, else "N-min walk
    test"); without one "corridor walk test"."""
    if protocol_s is None:
        return "corridor walk test"
    return TEST_LABELS.get(float(protocol_s), f"{float(protocol_s) / 60:g}-min walk test")


def go_time(st: pd.DataFrame, t: np.ndarray, d: np.ndarray, mids: np.ndarray,
            start: float | str, corridor_m: float) -> tuple[float, str | None]:
    """Decision L642: the timed test's start ("go", s) and a line when it is not the first step. ``start``: a time
    (s, taken as given), ``"first-step"`` (L516) or ``"auto"``: the first step after the last standstill of at least
    :data:`GO_WAIT_MIN_S` (one row's end to the next row's start) that lies before the first full lap's end and is
    followed by a full lap to the next cone turn (a full lap: at least (1 - :data:`LAP_AGREEMENT_TOL`) x the median
    stretch between cone turns); none on a track whose median stretch is under :data:`NOT_CORRIDOR_FRAC` of the
    corridor (L646: it lost steps, so its gaps are not known to be standstills). L739: an auto "go" on a lower-back
    table is that first contact dated back by :func:`onset`."""
    first = float(t[0])
    if not isinstance(start, str):
        last = float(st["end_s"].max())
        if not float(start) < last:
            from pdrlearn.errors import DataError

            raise DataError(f"the walk test's start {float(start):g} s (--walk-test-start or meta.json "
                            f"walk_test_start_s) is not before the track's last step ({last:.1f} s): give the "
                            "test's 'go' in seconds of the session's clock, inside the walk (decision L642)")
        return float(start), None
    if start != "auto" or len(st) < 2:
        return (first if start != "auto" else onset(st, 0)), None
    inner = mids[(mids > first) & (mids < float(st["end_s"].max()))]
    if len(inner) < 2:
        return onset(st, 0), None
    at = np.interp(inner, t, d)
    ref = float(np.median(np.diff(at)))
    if ref < NOT_CORRIDOR_FRAC * corridor_m:  # decision L642 amended: a track that lost steps has false standstills
        return onset(st, 0), None
    full = (1.0 - LAP_AGREEMENT_TOL) * ref
    ends = np.concatenate([[d[0]], at])
    first_full = next((float(m) for m, a, b in zip(inner, ends[:-1], ends[1:], strict=True) if b - a >= full),
                      float("inf"))
    stop, go = st["end_s"].to_numpy(float)[:-1], st["start_s"].to_numpy(float)[1:]
    best = None
    for i, (a, b) in enumerate(zip(stop, go, strict=True), start=1):
        nxt = inner[inner > b]
        if b - a < GO_WAIT_MIN_S or b >= first_full or not len(nxt):
            continue
        if float(np.interp(nxt[0], t, d) - np.interp(b, t, d)) >= full:
            best = (a, b, i)
    if best is None:
        return onset(st, 0), None
    before = float(np.interp(best[0], t, d) - d[0])
    go_s = onset(st, best[2])
    dated = f" (its first contact {best[1]:.1f} s less {LB_GO_STEPS:g} step times, L739)" if go_s < best[1] else ""
    return go_s, coded(f"corridor walk test: started at {go_s:.1f} s{dated}, the first step after a "
                          f"{best[1] - best[0]:.1f} s standstill before the first full lap (the walk to the start "
                          f"line and the wait for 'go'?); the {before:.1f} m walked before it are not scored; "
                          "give --walk-test-start SECONDS (or first-step, or meta.json walk_test_start_s) to set "
                          "it (decision L642)", "L642")


def onset(st: pd.DataFrame, i: int) -> float:
    """Decision L739: the walk's start at row ``i`` of the sorted step table ``st``: its ``start_s`` on a foot table;
    on a lower-back table (a row per contact) the contact less :data:`LB_GO_STEPS` x the median step time of the next
    :data:`LB_GO_CONTACTS` contacts, not before the previous row's end (or 0 s)."""
    starts = st["start_s"].to_numpy(float)
    if not _is_lower_back(st) or len(starts) < i + 2:
        return float(starts[i])
    step_s = float(np.median(np.diff(starts[i:i + LB_GO_CONTACTS + 1])))
    floor = float(st["end_s"].iloc[i - 1]) if i > 0 else 0.0
    return float(max(starts[i] - LB_GO_STEPS * step_s, floor, 0.0))


def go_inside(t0: float, start: float | str, span: tuple[float, float] | None, end: float | None) -> None:
    """Decision L661: one :class:`DataError` line when the timed test's "go" ``t0`` is not before the data's ``end``
    (the window's or the recording's) or, given (``start`` a time: ``--walk-test-start`` / meta.json
    ``walk_test_start_s``), before the window's start - a test the window (``span``) does not hold."""
    given = not isinstance(start, str)
    if not (given and span is not None and t0 < float(span[0])) and (end is None or t0 < float(end)):
        return
    from pdrlearn.errors import DataError

    what = "--walk-test-start or meta.json walk_test_start_s" if given else "its first step"
    if span is not None:
        raise DataError(f"the walk test's start {t0:g} s ({what}) is outside --window {float(span[0]):g},"
                        f"{float(span[1]):g}: give the test's 'go' inside the window, or a --window that holds the "
                        "test (decision L661)")
    raise DataError(f"the walk test's start {t0:g} s ({what}) is not before the recording's end ({float(end):.1f} s): "
                    "give the test's 'go' in seconds of the session's clock, inside the recording (decision L661)")


def too_short_note(recorded_s: float, duration_s: float, min_share: float | None = 0.5) -> str | None:
    """Decision C249 (ours): why a recording holding ``recorded_s`` seconds after the go is no recording of a
    ``duration_s`` s walk test - under ``min_share`` of it (a T25FW's or a TUG's recording beside the visit's 6MWT) -
    or None (``min_share`` None: never)."""
    if min_share is None or recorded_s >= min_share * duration_s:
        return None
    return (f"not a {walk_test_label(duration_s)} recording: it holds {recorded_s:.0f} s after the test's start, "
            f"under {min_share:.0%} of the {duration_s:g} s test (another test's recording, a T25FW or a TUG?); no "
            "walk test scored (decision C249)")


def not_a_corridor(tracked: np.ndarray, durations: np.ndarray, corridor_m: float) -> str | None:
    """Decision L643: why the laps (``tracked`` metres and ``durations`` of the stretches between cone turns, the
    last one the final stretch) are not a corridor's - the median lap tracks under :data:`NOT_CORRIDOR_FRAC` of the
    corridor and its time gives the corridor faster than :data:`MAX_LAP_SPEED_MPS` - or None."""
    if len(tracked) < 2:
        return None
    ref, lap_s = float(np.median(tracked[:-1])), float(np.median(durations[:-1]))
    if not (ref < NOT_CORRIDOR_FRAC * corridor_m and lap_s > 0 and corridor_m / lap_s > MAX_LAP_SPEED_MPS):
        return None
    return (f"not a corridor test: the laps tracked {ref:.1f} m (median) in {lap_s:.1f} s, so {corridor_m:g} m "
            f"laps would be walked at {corridor_m / lap_s:.1f} m/s, faster than walking ({MAX_LAP_SPEED_MPS:g} m/s): "
            "a shorter course (a TUG?); no walk test scored (decision L643)")


def corridor_agreement(tracked: np.ndarray, corridor_m: float, *, lower_back: bool) -> str | None:
    """Decision L518: one line when ``--corridor`` disagrees with the track's own laps (``tracked``: the stretches'
    tracked metres, the last one the final stretch after the last cone turn) by more than the unit's scale error
    (:data:`CORRIDOR_SCALE_TOL`) + :data:`CORRIDOR_SPREAD_K` x the laps' robust relative spread (the lower back:
    C213's 0.74-1.35 x); a walk without a lap
    when its final stretch tracks more than that over one corridor length (capped at it); None otherwise."""
    unit = "lower back" if lower_back else "foot"
    tol = CORRIDOR_SCALE_TOL[unit]
    laps = np.asarray(tracked[:-1], float)
    if len(laps) and np.median(laps) > 0:
        ref = float(np.median(laps))
        spread = 1.4826 * float(np.median(np.abs(laps - ref))) / ref  # a robust relative SD (1.4826 x MAD)
        tol += CORRIDOR_SPREAD_K[unit] * spread
        if abs(np.log(ref / corridor_m)) <= np.log1p(tol):
            return None
        lost = " or did the track lose steps?" if ref < corridor_m else ""  # decision L646
        return coded(f"corridor walk test: the median lap tracked {ref:.1f} m (laps {np.min(laps):.1f}-"
                     f"{np.max(laps):.1f} m) against --corridor {corridor_m:g} m ({ref / corridor_m:.2f} x), outside "
                     f"the {1 / (1 + tol):.2f}-{1 + tol:.2f} x a {unit} track's scale error allows: is the corridor "
                     f"length right?{lost} the laps count {corridor_m:g} m each (decisions L518, L646"
                     f"{', C213' if lower_back else ''})", "L518")
    last = float(np.sum(tracked)) if len(tracked) else 0.0
    if last <= (1.0 + tol) * corridor_m:
        return None
    return coded(f"corridor walk test: the walk tracked {last:.1f} m without a cone turn, {last / corridor_m:.1f} x "
                 f"--corridor {corridor_m:g} m (more than a {unit} track's {tol:.0%} scale error): capped at one "
                 "corridor length; is the corridor length right, or were the cone turns missed? (decision L518)",
                 "L518")


def own_corridor_line(tracked: np.ndarray, arc_m: float, corridor_m: float, margin: float) -> str | None:
    """Decision C207 (the candidate, not adopted: :func:`corridor_laps`' ``lap_margin`` is None by default): one line
    when a foot track's own corridor length - the median of ``tracked`` (the stretches between cone turns, the last one
    the final stretch, left out) less ``arc_m`` (the metres walked round a cone, :func:`cone_turn_m`; the ATS rule
    counts the corridor, not the arc) - differs from ``corridor_m`` by more than ``margin``; None otherwise or with
    fewer than :data:`CORRIDOR_LAP_MIN_LAPS` laps."""
    laps = np.asarray(tracked[:-1], float)
    if len(laps) < CORRIDOR_LAP_MIN_LAPS or not np.median(laps) > 0:
        return None
    own = float(np.median(lap_metres(laps, arc_m)))  # review R2 F1: the first stretch holds half an arc
    if abs(own / corridor_m - 1.0) <= margin:
        return None
    return coded(f"corridor walk test: the foot track's laps measure the corridor {own:.1f} m (the median lap less "
                 f"{arc_m:.1f} m round the cone, half that on the first) against --corridor {corridor_m:g} m "
                 f"({own / corridor_m - 1.0:+.1%}, more than the {margin:.0%} a foot track's laps "
                 f"allow): each lap still counts {corridor_m:g} m, so walk_test_distance_m is off by about as much; "
                 "is the corridor length right? (decision C207)", "C207")


def _short_last_lap(stretches: list[tuple[float, float, float, int]], ref: float) -> int | None:
    """Decision L517: the index of the last stretch ending at a cone turn when it tracks short of its corridor
    lengths x the median lap ``ref`` by more than :data:`SHORT_LAP_MIN_FRAC` or :data:`SHORT_LAP_SPREAD_K` robust
    SDs of the other single laps (at least :data:`SHORT_LAP_MIN_LAPS` of them); None otherwise."""
    if not stretches or not np.isfinite(ref) or ref <= 0:
        return None
    i = len(stretches) - 1
    m, c = stretches[i][2], stretches[i][3]
    others = np.array([s[2] for s in stretches[:i] if s[3] == 1])
    if c < 1 or len(others) < SHORT_LAP_MIN_LAPS:
        return None
    spread = 1.4826 * float(np.median(np.abs(others - np.median(others))))  # a robust SD (1.4826 x MAD)
    return i if c * ref - m > max(SHORT_LAP_MIN_FRAC * ref, SHORT_LAP_SPREAD_K * spread) else None


def duration_note(duration_s: float, *, windowed: bool) -> str | None:
    """Decision L462: one line when a corridor walk test without ``--window`` spans much more than six minutes (a 6MWT
    entered from the whole recording's laps); None otherwise."""
    if windowed or not duration_s > SIX_MINUTES_S + MINUTE_S:
        return None
    return coded(f"corridor walk test: the laps and walk_test_distance_m cover the whole {duration_s:.0f} s from the "
                 f"first to the last step, not a {SIX_MINUTES_S / 60:.0f}-minute test; for a 6MWT give its span, "
                 "--window T0,T0+360 (decision L462)", "L462")


def _per_minute(t: np.ndarray, d: np.ndarray, stretches, dist: np.ndarray, t0: float, t_end: float) -> list[float]:
    """Decision L383: the corridor distance walked in each full minute from ``t0``: inside a stretch its corridor
    distance is shared out in proportion to its tracked distance."""
    n = int(np.floor((t_end - t0) / MINUTE_S + 1e-9))
    if n < 1:
        return []
    edges = t0 + MINUTE_S * np.arange(n + 1)
    total = np.zeros(n + 1)
    before = 0.0
    for (a, b, m, _), dd in zip(stretches, dist, strict=True):
        inside = (edges > a) & (edges <= b)
        if m > 0:
            share = (np.interp(edges[inside], t, d) - np.interp(a, t, d)) / m
        else:
            share = (edges[inside] - a) / (b - a) if b > a else np.ones(inside.sum())
        total[inside] = before + dd * np.clip(share, 0.0, 1.0)
        before += dd
    total[edges > stretches[-1][1]] = before  # decision L399: the span's minutes after the last step (no lap) add 0 m
    return [float(v) for v in np.diff(total)]


def corridor_length(corridor: float | None) -> float | None:
    """Decision B293: ``--corridor``'s metres checked before any session (None: no corridor walk test)."""
    if corridor is None:
        return None
    import math

    from pdrlearn.errors import DataError

    if not math.isfinite(corridor) or corridor <= 0:
        raise DataError(f"--corridor {corridor:g}: give the corridor's length in metres, a positive number "
                        "(e.g. --corridor 30 for the ATS 6MWT's 30 m course)")
    return float(corridor)


def walk_test_duration(duration: float | None, corridor_m: float | None) -> float | None:
    """Decision B396: ``--walk-test-duration``'s seconds checked before any session (None: the test runs over the
    track or its --window, L383)."""
    if duration is None:
        return None
    import math

    from pdrlearn.errors import DataError

    if not math.isfinite(duration) or duration <= 0:
        raise DataError(f"--walk-test-duration {duration:g}: give the test's duration in seconds from the first step, "
                        "a positive number (e.g. --walk-test-duration 360 for the 6MWT, 120 for the 2MWT)")
    if corridor_m is None:
        raise DataError(f"--walk-test-duration {duration:g} times the corridor walk test: add --corridor METRES "
                        "(e.g. --corridor 30), or drop --walk-test-duration")
    return float(duration)


def walk_test_start(start: str | None, duration_s: float | None) -> float | str:
    """Decision L642: ``--walk-test-start``'s value checked before any session: ``"auto"``, ``"first-step"`` or a
    time (s); one :class:`DataError` line otherwise, or when it is given without ``--walk-test-duration``."""
    import math

    from pdrlearn.errors import DataError

    text = "auto" if start is None else str(start).strip()
    if text in ("auto", "first-step"):
        value: float | str = text
    else:
        try:
            value = float(text)
        except ValueError:
            value = math.nan
        if not math.isfinite(value) or value < 0:
            raise DataError(f"--walk-test-start {text}: give auto, first-step or the test's start in seconds of the "
                            "session's clock (e.g. --walk-test-start 37.1)")
    if value != "auto" and duration_s is None:
        raise DataError(f"--walk-test-start {text} starts a timed corridor walk test: add --walk-test-duration SECONDS "
                        "(e.g. 360) and --corridor METRES, or drop --walk-test-start")
    return value


def session_go(start: float | str, session) -> float | str:
    """Decision L642: the session's "go": ``--walk-test-start`` when it gives a time or first-step, else the
    session's meta.json ``walk_test_start_s`` (a number of seconds; anything else is one :class:`DataError` line),
    else ``"auto"``."""
    if start != "auto":
        return start
    meta = getattr(session, "meta", None) or {}
    if meta.get("walk_test_start_s") is None:
        return "auto"
    import math

    from pdrlearn.errors import DataError

    value = meta["walk_test_start_s"]
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value) or value < 0:
        raise DataError(f"{session.where}: meta.json walk_test_start_s {value!r}: give the walk test's start in "
                        "seconds of the session's clock (a number, e.g. 37.1), or remove the key")
    return float(value)


def corridor_line(summary: dict) -> str:
    """Decision L383: ``track``'s line of the corridor walk test; L642-L646: where a timed test started, a stop, a
    span shorter than asked, and the note of a test not scored or of withheld minutes."""
    per = summary.get("walk_test_distance_per_minute_m") or []
    fatigue = summary.get("fatigue_index")
    head = f"corridor walk test ({summary['corridor_m']:g} m)"
    protocol = summary.get("walk_test_protocol_s")
    if protocol is not None:
        head = f"corridor {walk_test_label(protocol)} ({summary['corridor_m']:g} m)"
    if summary.get("walk_test_distance_m") is None:  # decision L643: not scored
        return f"{head}: {summary.get('walk_test_note') or 'not scored'}"
    timing = ""
    if protocol is not None and summary.get("walk_test_start_s") is not None:
        dur = summary.get("walk_test_duration_s") or 0.0
        timing = (f"; from {summary['walk_test_start_s']:.1f} s for {clock_text(dur)}"
                  + (f" of {clock_text(protocol)} (incomplete)" if dur < protocol - 1e-6 else "")
                  + (f", walking stopped at {clock_text(summary['walk_test_stopped_s'])}"
                     if summary.get("walk_test_stopped_s") is not None else ""))
    return (f"{head}: {summary.get('n_laps') or 0} lap(s), "
            f"{(summary.get('walk_test_distance_m') or 0.0):.1f} m (laps x {summary['corridor_m']:g} m + the final "
            f"partial lap, laps.csv; L383){timing}"
            + (f"; per minute from the test's start {' / '.join(f'{v:.1f}' for v in per)} m" if per else "")
            + (f"; fatigue index {fatigue:.2f} (last / first full minute)" if fatigue is not None else "")
            + (f": {fatigue_rest_text(summary)}" if fatigue_rest_text(summary) else "")  # decision C218
            + (f"; {rests_text(summary)[0].lower()}{rests_text(summary)[1:]}" if rests_text(summary) else "")  # C217
            + (f"; {summary['walk_test_note']}" if summary.get("walk_test_note") else "")
            + walk_test_speed_text(summary))


def walk_test_speed(summary: dict) -> float | None:
    """Decision L650: the walk test's own mean speed (m/s): its distance (from the corridor's laps) / its duration;
    None without a walk test."""
    dist, dur = summary.get("walk_test_distance_m"), summary.get("walk_test_duration_s")
    return float(dist) / float(dur) if dist is not None and dur else None


def walk_test_speed_text(summary: dict) -> str:
    """Decision L650: :func:`walk_test_speed` named as the test's beside the gait speed line's (the whole recording's
    walking, from the step lengths); "" without one."""
    speed = walk_test_speed(summary)
    if speed is None:
        return ""
    return (f"; test speed {speed:.2f} m/s (the test's distance / its {summary['walk_test_duration_s']:.0f} s; the "
            "gait speed line is the whole recording's walking, from step lengths: L650)")


def steps_per_minute(steps: pd.DataFrame, start_s: float, n_minutes: int) -> list[int]:
    """Decision C230: the steps in each of ``n_minutes`` full minutes from ``start_s`` (the walk test's go), rests
    included: a lower-back row is one step at its contact; a foot stride row two, the other foot's at the middle of
    the stride (between its ``start_s`` and its contact) and its own at the contact; a foot-data gap row none (L124's
    weights, :func:`_row_steps`)."""
    if not len(steps) or n_minutes <= 0 or not {"start_s", "end_s"} <= set(steps.columns):
        return []
    st = steps.sort_values("start_s", kind="stable").reset_index(drop=True)
    if "length_m" not in st:
        st = st.assign(length_m=np.nan)
    contact = _path(st)[0][1:]
    weights = _row_steps(st)
    if _is_lower_back(st):
        times = contact
    else:  # a stride: the other foot's contact about its middle, its own at its end
        middle = (st["start_s"].to_numpy(float) + contact) / 2.0
        times = np.concatenate([middle[weights > 0], contact[weights > 0]])
    edges = float(start_s) + MINUTE_S * np.arange(n_minutes + 1)
    counts, _ = np.histogram(times[np.isfinite(times)], bins=edges)
    return [int(c) for c in counts]
