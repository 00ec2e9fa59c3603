"""Decisions L200-L202 / W182-W183 (session 27): turns.csv's turn timing and angle, transfers.csv's chair transfers and
``tug_time_s`` against simulated truth and the mobgap reference turns. Measured once, no tuning.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/turns_transfers.py sim    # users 3530-3559
     ... experiments/turns_transfers.py real   # datasets/real + datasets/external mobgap Test11 turns.csv
     ... experiments/turns_transfers.py sim28  # decision L208's rule: users 3870-3899, both turn timings
     ... experiments/turns_transfers.py sim210 # decision L210's rule: users 3900-3939, heading vs yaw-rate timing
     ... experiments/turns_transfers.py real210  # L210: the real turns, heading vs yaw-rate timing, same rows
     ... experiments/turns_transfers.py sim231  # decisions L231 / L233 / L235: users 4660-4699, L210's routes
     ... experiments/turns_transfers.py real231 # the same candidates on the mobgap turns
     ... experiments/turns_transfers.py sim255  # decision L255: users 4970-4999, the trial's and L210's routes
     ... experiments/turns_transfers.py real255 # L255 on the mobgap turns
     ... experiments/turns_transfers.py sim345  # decision L345: users 6590-6619, El-Gohary vs 5-95 % yaw times
     ... experiments/turns_transfers.py real345 # L345 on the mobgap turns (rows chosen under today's timing)
     ... experiments/turns_transfers.py real_w328 # decision W328 on the mobgap turns (yaw cut and yaw-rate angle)
Output: experiments/results/turns_transfers_sim.txt, turns_transfers_real.txt (the printed lines); L208 / L209:
turns_timing_sim.txt, turns_timing_real.txt (``real`` prints both timings since L208); L210 / L211:
turns_yaw_sim.txt, turns_yaw_real.txt; L231-L236: turns_yaw2_sim.txt, turns_yaw2_real.txt; L255 / L256:
turns_whole_sim.txt, turns_whole_real.txt; L345 / L346: turns_frac_sim.txt, turns_frac_real.txt; W328:
turns_w328_real.txt

Simulated truth. A turn: the route's one turn; its truth start / end are where the waist unit's true heading
(trajectory.csv ``heading_rad``, unwrapped, a 1 s moving mean: one stride's pelvis rotation averaged out) has gone
5 % / 95 % of the way from its value at the start to its value at the end; the truth angle is that change. The
detected turn is the turns.csv row nearest in time (midpoints). A transfer: transfers.csv (S36 / S43), a stand-to-sit
from ``start`` to ``seated``, a sit-to-stand from ``rise`` to ``end``; the detected one of the same kind that overlaps
it. TUG truth: the first rise to the last seated time of a session that starts and ends seated.
"""
import logging
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.io import read_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.bouts import detected_bouts
from pdrlearn.track.clinical import turn_table
from pdrlearn.track.plasys import track_plasys, track_streaming
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.transfers import SIT_TO_STAND, STAND_TO_SIT, transfer_summary

logging.disable(logging.WARNING)

#: decision L208: turns.csv's timings compared (L200's rows, L208's heading 5-95 %)
TIMINGS = ("rows", "heading")
USERS = range(3530, 3560)
#: (route, sit_start_s, sit_end_s) by user % 3: a TUG with a 180 deg turn on the spot, a walk with a 180 deg pivot,
#: a 90 deg turn with a chair sit inside the route
ROUTES = (("straight:3, turn:180, straight:3", 5.0, 5.0),
          ("straight:8, pivot:180, straight:8", 5.0, 5.0),
          ("straight:5, turn:90, straight:5, sit:8, straight:3", 0.0, 0.0))
#: decision L208's fresh users and routes (by user % 4): L201's three and a 360 deg turn on the spot
USERS28 = range(3870, 3900)
ROUTES28 = ROUTES + (("straight:5, turn:360, straight:5", 0.0, 0.0),)
#: decision L210's fresh users, 100 Hz, pendulum bounce; routes by user % 4: on-the-spot 90 / 180 / 360 deg turns and
#: L201's TUG; the gait by (user // 4) % 2: the user's "slow" speed or the trial's custom slow steps (0.58 s)
USERS210 = range(3900, 3940)
ROUTES210 = (("stand:3, straight:8, turn:90, straight:8, stand:3", 0.0, 0.0), ROUTES[0],
             ("stand:3, straight:8, turn:180, straight:8, stand:3", 0.0, 0.0),
             ("stand:3, straight:5, turn:360, straight:5, stand:3", 0.0, 0.0))
TIMINGS210 = ("heading", "yaw")
#: decisions L231 / L233 / L235's fresh users (L210's sessions and routes) and the turn tables compared, each
#: ``turn_table`` keywords under the yaw-rate timing: L211's default, each candidate alone, and all three
USERS231 = range(4660, 4700)
CONFIGS231 = {"L211": {}, "branch (L231)": {"branch": True}, "yaw-only (L233)": {"yaw_only": True},
              "yaw peak (L235)": {"yaw_peak": True}, "all three": {"branch": True, "yaw_only": True, "yaw_peak": True}}
#: decision L255's fresh users, the trial s29 routes (by user % 2: t2 and turn_4808, 0.2 m / 0.55 s steps) and the
#: tables compared: today's defaults (L231 + L235) and the full turns on the spot whose steps were missed
USERS255 = range(4970, 5000)
ROUTES255 = ("stand:2, straight:4, turn:180, straight:4, turn:360, straight:2, stand:2",
             "stand:3, straight:5, turn:180, straight:5, turn:360, straight:3, stand:3")
CONFIGS255 = {"today": {}, "whole (L255)": {"whole": True}}
# the lower-back tracks without a sit veto: as measured, before W185
TRACKS = {"plasys": lambda s: track_plasys(s), "plasys-stream": lambda s: track_streaming(s, method="M2"),
          "waist-pendulum": lambda s: track_waist(s, pipeline="waist-pendulum", sit_veto=False),
          "waist-pll": lambda s: track_waist(s, pipeline="waist-pll", sit_veto=False)}


def true_turn(session) -> tuple[float, float, float]:
    tr = session.trajectory
    t = tr["t"].to_numpy(float)
    h = np.degrees(np.unwrap(tr["heading_rad"].to_numpy(float)))
    w = max(int(round(1.0 / np.median(np.diff(t)))), 1)
    hs = np.convolve(np.pad(h, (w // 2, w - 1 - w // 2), mode="edge"), np.ones(w) / w, mode="valid")
    h0, h1 = hs[0], hs[-1]
    frac = (hs - h0) / (h1 - h0)
    return float(t[np.argmax(frac >= 0.05)]), float(t[np.argmax(frac >= 0.95)]), float(h1 - h0)


def true_peak_dps(session, ta: float, tb: float, pad_s: float = 0.5) -> float:
    """Decision L229's true peak rate of a simulated turn: the largest |change| of the waist unit's true heading
    (trajectory.csv, unwrapped) over 0.1 s, from ``pad_s`` before the truth turn's start to ``pad_s`` after its
    end."""
    tr = session.trajectory
    t = tr["t"].to_numpy(float)
    h = np.degrees(np.unwrap(tr["heading_rad"].to_numpy(float)))
    k = max(int(round(0.1 / np.median(np.diff(t)))), 1)
    r = np.abs(h[k:] - h[:-k]) / (t[k:] - t[:-k])
    mid = 0.5 * (t[k:] + t[:-k])
    inside = (mid >= ta - pad_s) & (mid <= tb + pad_s)
    return float(r[inside].max()) if inside.any() else float("nan")


def true_turns(session, route: str) -> list[tuple[float, float, float]]:
    """Decision L255's truth of a route with several turns: per route turn (``parse_route``'s ``Turn`` items, in
    order), L201's start / end where the waist's true heading (1 s mean, as :func:`true_turn`) has gone 5 % / 95 % of
    its route angle beyond the earlier turns' route angles (searched after the previous turn's end), and its angle
    the heading's change between the midpoints of the gaps to the turns around it (the recording's ends)."""
    from pdrlearn.sim.tug_truth import turn_span_indices

    t, hs, spans = turn_span_indices(session.trajectory, route)
    cut = [0] + [(spans[j][1] + spans[j + 1][0]) // 2 for j in range(len(spans) - 1)] + [len(hs) - 1]
    return [(float(t[i0]), float(t[i1]), float(hs[cut[j + 1]] - hs[cut[j]])) for j, (i0, i1) in enumerate(spans)]


def match_truth_rows(tt: pd.DataFrame, truth) -> tuple[list, int]:
    """Decision L255's matching: per truth turn ``(start, end, angle)`` the turns.csv row of largest |angle| that
    overlaps it and no earlier truth turn took (None without one) and whether it is found (its sign and |angle error|
    < 90 deg: 1.0 / 0.0); and the number of rows no truth turn took (the extra rows). Shared with
    ``experiments/turns_in_place.py``."""
    free = np.ones(len(tt), bool)
    out = []
    for ta, tb, g in truth:
        ov = np.flatnonzero(free & (tt["start_s"].to_numpy(float) <= tb)
                            & (tt["end_s"].to_numpy(float) >= ta)) if len(tt) else np.zeros(0, int)
        if not ov.size:
            out.append((None, 0.0))
            continue
        k = int(ov[int(np.argmax(tt["angle_deg"].abs().to_numpy()[ov]))])
        free[k] = False
        r = tt.iloc[k]
        out.append((r, float(np.sign(r.angle_deg) == np.sign(g) and abs(r.angle_deg - g) < 90.0)))
    return out, int(free.sum())


def med(x) -> str:
    x = np.asarray([v for v in x if np.isfinite(v)], float)
    return f"{np.median(x):+.2f}" if x.size else "n/a"


def _session(u: int, route: str, s0: float, s1: float):
    """L201 / L208's simulated session of user ``u`` (20 Hz, normal / slow by ``(u // 3) % 2``) and its label."""
    speed = "slow" if (u // 3) % 2 else "normal"
    return simulate_path(parse_route(route), UserProfile.from_seed(u), speed=speed, seed=u, sit_start_s=s0,
                         sit_end_s=s1), speed


def _session210(u: int, route: str, s0: float, s1: float):
    """Decision L210's session: 100 Hz, ``bounce="pendulum"``, slow: the user's own or custom steps (as
    ``simulate --step-length L --step-time 0.58``)."""
    from pdrlearn.cli.simulate import _custom_gait

    user = UserProfile.from_seed(u)
    label = "slow"
    if (u // 4) % 2:
        length = (0.30, 0.35, 0.40)[(u // 8) % 3]
        user = _custom_gait(user, "slow", length, 0.58, route)
        label = f"slow {length:g} m / 0.58 s"
    return simulate_path(parse_route(route), user, speed="slow", rate_hz=100.0, seed=u, sit_start_s=s0,
                         sit_end_s=s1, bounce="pendulum"), label


def sim(users=USERS, routes=ROUTES, timings=("rows",), make=_session, tracks=None) -> None:
    tracks = TRACKS if tracks is None else {k: TRACKS[k] for k in tracks}
    turn_err = {(k, m): [] for k in tracks for m in timings}
    counts = {k: [] for k in tracks}  # decision L208's check: turns and angles the same under every timing
    tr_err = {k: {SIT_TO_STAND: [], STAND_TO_SIT: []} for k in ("waist-pendulum", "waist-pll")}
    tr_count = {k: [0, 0, 0] for k in tr_err}  # truth, matched, detected
    tug = {k: [] for k in tr_err}
    for u in users:
        route, s0, s1 = routes[u % len(routes)]
        s, speed = make(u, route, s0, s1)
        ta, tb, ang = true_turn(s)
        truth_tr = s.extras.get("transfers", pd.DataFrame(columns=["start_s", "seated_s", "rise_s", "end_s"]))
        line = [f"user {u} {speed} [{route}] sit {s0:g}/{s1:g}: truth turn {ta:.2f}-{tb:.2f} s "
                f"({tb - ta:.2f} s) {ang:+.1f} deg"]
        for name, fn in tracks.items():
            res = fn(s)
            tabs = {m: turn_table(res.steps, detected_bouts(res.steps), timing=m,
                                  yaw_turns=res.info.get("yaw_turns")) for m in timings}
            ref = tabs[timings[0]]
            counts[name].append(all(len(t) == len(ref) and np.array_equal(t["angle_deg"], ref["angle_deg"])
                                    for t in tabs.values()))
            # the nearest turn by the first timing's midpoints: the same turn (row) under every timing
            i_near = (int(np.argmin(np.abs(0.5 * (ref["start_s"] + ref["end_s"]).to_numpy(float) - 0.5 * (ta + tb))))
                      if len(ref) else None)
            for m, tt in tabs.items():
                tag = name if len(timings) == 1 else f"{name} [{m}]"
                if i_near is None:
                    line.append(f"  {tag}: no turn")
                    turn_err[(name, m)].append((np.nan,) * 4)
                    continue
                r = tt.iloc[i_near]
                e = (r.start_s - ta, r.end_s - tb, r.duration_s - (tb - ta), r.angle_deg - ang)
                turn_err[(name, m)].append(e)
                line.append(f"  {tag}: {len(tt)} turn(s); nearest {r.start_s:.2f}-{r.end_s:.2f} s "
                            f"({r.duration_s:.2f} s) {r.angle_deg:+.1f} deg, peak {r.peak_rate_dps:.0f} deg/s; "
                            f"errors start {e[0]:+.2f} end "
                            f"{e[1]:+.2f} duration {e[2]:+.2f} s angle {e[3]:+.1f} deg")
            if name not in tr_err:
                continue
            det = pd.DataFrame(res.info["transfers"])
            truth_rows = []
            for row in truth_tr.itertuples():
                if row.seated_s > row.start_s:  # a sit-down inside the recording
                    truth_rows.append((STAND_TO_SIT, row.start_s, row.seated_s))
                if row.end_s > row.rise_s:  # a stand-up inside the recording
                    truth_rows.append((SIT_TO_STAND, row.rise_s, row.end_s))
            tr_count[name][0] += len(truth_rows)
            tr_count[name][2] += len(det)
            parts = []
            for kind, a, b in truth_rows:
                m = det[(det["kind"] == kind) & (det["start_s"] <= b) & (det["end_s"] >= a)] if len(det) else det
                if len(m):
                    d = m.iloc[0]
                    tr_err[name][kind].append((d.start_s - a, d.end_s - b, d.duration_s - (b - a)))
                    tr_count[name][1] += 1
                    parts.append(f"{kind} {a:.2f}-{b:.2f} vs {d.start_s:.2f}-{d.end_s:.2f} "
                                 f"({d.height_change_m:+.2f} m)")
                else:
                    parts.append(f"{kind} {a:.2f}-{b:.2f} missed")
            summ = transfer_summary(res.info["transfers"], res.steps)
            t_tug = None
            if s0 > 0 and s1 > 0:
                t_tug = float(truth_tr["seated_s"].iloc[-1] - truth_tr["rise_s"].iloc[0])
                if summ["tug_time_s"] is not None:
                    tug[name].append(summ["tug_time_s"] - t_tug)
                else:
                    tug[name].append(np.nan)
            line.append(f"    transfers: {len(det)} detected; " + "; ".join(parts)
                        + f"; tug_time_s {summ['tug_time_s']} (truth {t_tug})")
        print("\n".join(line), flush=True)
    print("\nTURNS (median signed error, median |error|; over the users with a turn detected):")
    for (name, m), e in turn_err.items():
        a = np.array(e, float)
        n = int(np.isfinite(a[:, 0]).sum())
        tag = name if len(timings) == 1 else f"{name} [{m}] (turns and angles equal across timings in "
        tag += "" if len(timings) == 1 else f"{sum(counts[name])}/{len(counts[name])} sessions)"
        print(f"{tag}: {n}/{len(a)} turns found; start {med(a[:, 0])} s (|.| {med(np.abs(a[:, 0]))}), end "
              f"{med(a[:, 1])} s (|.| {med(np.abs(a[:, 1]))}), duration {med(a[:, 2])} s (|.| {med(np.abs(a[:, 2]))}),"
              f" angle {med(a[:, 3])} deg (|.| {med(np.abs(a[:, 3]))})")
    print("TRANSFERS (median signed error, median |error|):")
    for name, per in tr_err.items():
        print(f"{name}: truth {tr_count[name][0]}, matched {tr_count[name][1]}, detected {tr_count[name][2]}")
        for kind, e in per.items():
            a = np.array(e, float).reshape(-1, 3)
            print(f"  {kind}: n {len(a)}; start {med(a[:, 0])} s (|.| {med(np.abs(a[:, 0]))}), end {med(a[:, 1])} s "
                  f"(|.| {med(np.abs(a[:, 1]))}), duration {med(a[:, 2])} s (|.| {med(np.abs(a[:, 2]))})")
        g = np.array(tug[name], float)
        print(f"  tug_time_s: given {int(np.isfinite(g).sum())}/{len(g)} seated-start-and-end sessions; error "
              f"{med(g)} s (|.| {med(np.abs(g))})")


def sim28() -> None:
    """Decision L208's adoption rule: fresh users 3870-3899, both timings from the same tracks."""
    sim(USERS28, ROUTES28, TIMINGS)


def sim210() -> None:
    """Decision L210's adoption rule: fresh users 3900-3939, heading vs yaw-rate timing from the same tracks."""
    sim(USERS210, ROUTES210, TIMINGS210, make=_session210, tracks=("waist-pendulum", "waist-pll"))


def real210() -> None:
    """Decision L210's rule on the mobgap turns: each reference turn's row chosen under L208's timing, scored under
    both."""
    real(TIMINGS210, same_rows=True)


def sim231() -> None:
    """Decisions L231 / L233 / L235's rules: fresh users 4660-4699 (L210's sessions), the nearest turn of each
    table (:data:`CONFIGS231`) against the truth: found, angle, sign, times, peak rate; and the extra rows (each
    route has one turn)."""
    names = ("waist-pendulum", "waist-pll")
    err = {(n, c): [] for n in names for c in CONFIGS231}  # (start, end, duration, angle, sign ok, peak) errors
    extra = {(n, c): 0 for n in names for c in CONFIGS231}
    for u in USERS231:
        route, s0, s1 = ROUTES210[u % len(ROUTES210)]
        s, label = _session210(u, route, s0, s1)
        ta, tb, ang = true_turn(s)
        pk = true_peak_dps(s, ta, tb)
        line = [f"user {u} {label} [{route}]: truth turn {ta:.2f}-{tb:.2f} s {ang:+.1f} deg, peak {pk:.0f} deg/s"]
        for n in names:
            res = TRACKS[n](s)
            for c, kw in CONFIGS231.items():
                tt = turn_table(res.steps, detected_bouts(res.steps), timing="yaw",
                                yaw_turns=res.info.get("yaw_turns"), **kw)
                extra[(n, c)] += max(len(tt) - 1, 0)
                if not len(tt):
                    err[(n, c)].append((np.nan,) * 6)
                    line.append(f"  {n} [{c}]: no turn")
                    continue
                r = tt.iloc[int(np.argmin(np.abs(0.5 * (tt["start_s"] + tt["end_s"]).to_numpy(float)
                                                 - 0.5 * (ta + tb))))]
                e = (r.start_s - ta, r.end_s - tb, r.duration_s - (tb - ta), r.angle_deg - ang,
                     float(np.sign(r.angle_deg) == np.sign(ang)), r.peak_rate_dps - pk)
                err[(n, c)].append(e)
                line.append(f"  {n} [{c}]: {len(tt)} turn(s); nearest {r.start_s:.2f}-{r.end_s:.2f} s "
                            f"{r.angle_deg:+.1f} deg, peak {r.peak_rate_dps:.0f} deg/s, n_rows {r.n_rows}")
        print("\n".join(line), flush=True)
    print("\nTURNS (nearest turn; median |error| (signed median)):")
    for (n, c), e in err.items():
        a = np.array(e, float)
        ok = np.isfinite(a[:, 0])
        print(f"{n} [{c}]: {int(ok.sum())}/{len(a)} found, {extra[(n, c)]} extra rows; wrong sign "
              f"{int((a[ok, 4] == 0).sum())}; |angle error| {med(np.abs(a[:, 3]))} deg ({med(a[:, 3])}); "
              f"|start| {med(np.abs(a[:, 0]))} s, |end| {med(np.abs(a[:, 1]))} s, |duration| {med(np.abs(a[:, 2]))}"
              f" s ({med(a[:, 2])}); |peak error| {med(np.abs(a[:, 5]))} deg/s ({med(a[:, 5])})")


def _session255(u: int, route: str):
    """Decision L255's trial session: as ``simulate --route ROUTE --step-length 0.2 --step-time 0.55 --bounce
    pendulum --rate 100 --user-seed U --seed U``."""
    from pdrlearn.cli.simulate import _custom_gait

    user = _custom_gait(UserProfile.from_seed(u), "normal", 0.2, 0.55, route)
    return simulate_path(parse_route(route), user, speed="normal", rate_hz=100.0, seed=u, bounce="pendulum")


def sim255() -> None:
    """Decision L255's rule: fresh users 4970-4999, each on the trial's route (:data:`ROUTES255`) and L210's
    (:data:`ROUTES210`); each truth turn takes the overlapping row of largest |angle| not yet taken; found: its sign
    and |angle error| < 90 deg; extra rows: the rows no truth turn took."""
    names = ("waist-pendulum", "waist-pll")
    err = {(n, c): [] for n in names for c in CONFIGS255}  # per truth turn: (route angle, found, errors...)
    extra = {(n, c): 0 for n in names for c in CONFIGS255}
    for u in USERS255:
        for route, s in ((ROUTES255[u % 2], _session255(u, ROUTES255[u % 2])),
                         (ROUTES210[u % 4][0], _session210(u, *ROUTES210[u % 4])[0])):
            truth = true_turns(s, route)
            line = [f"user {u} [{route}]: truth " + ", ".join(f"{a:.2f}-{b:.2f} s {g:+.1f} deg" for a, b, g in truth)]
            for n in names:
                res = TRACKS[n](s)
                for c, kw in CONFIGS255.items():
                    tt = turn_table(res.steps, detected_bouts(res.steps), timing="yaw",
                                    yaw_turns=res.info.get("yaw_turns"), **kw)
                    got = []
                    matched, n_extra = match_truth_rows(tt, truth)
                    for (ta, tb, g), (r, ok) in zip(truth, matched, strict=True):
                        if r is None:
                            err[(n, c)].append((round(g, -1), 0.0) + (np.nan,) * 4)
                            got.append("-")
                            continue
                        err[(n, c)].append((round(g, -1), ok, r.angle_deg - g, r.start_s - ta, r.end_s - tb,
                                            r.duration_s - (tb - ta)))
                        got.append(f"{r.start_s:.2f}-{r.end_s:.2f} s {r.angle_deg:+.1f} n_rows {r.n_rows}")
                    extra[(n, c)] += n_extra
                    line.append(f"  {n} [{c}]: {len(tt)} row(s), {n_extra} extra; " + "; ".join(got))
            print("\n".join(line), flush=True)
    print("\nTURNS (each truth turn's overlapping row; median |error| (signed median) of the found):")
    for (n, c), e in err.items():
        a = np.array(e, float)
        ok = a[:, 1] == 1
        full = np.abs(a[:, 0]) >= 300
        print(f"{n} [{c}]: found {int(ok.sum())}/{len(a)}, 360 deg turns found {int((ok & full).sum())}/"
              f"{int(full.sum())}, {extra[(n, c)]} extra rows over {2 * len(USERS255)} sessions; |angle error| "
              f"{med(np.abs(a[ok, 2]))} deg ({med(a[ok, 2])}); |start| {med(np.abs(a[ok, 3]))} s, |end| "
              f"{med(np.abs(a[ok, 4]))} s, |duration| {med(np.abs(a[ok, 5]))} s ({med(a[ok, 5])})")
    for n in names:  # decision L255's rule (b): a truth turn found today and not by the candidate
        a, b = (np.array(err[(n, c)], float)[:, 1] for c in CONFIGS255)
        print(f"{n}: turns lost {int(((a == 1) & (b == 0)).sum())}, gained {int(((a == 0) & (b == 1)).sum())}")


def real_w328() -> None:
    """Decision W328 on the mobgap turns (:func:`real231`): today's table against L370's yaw cut with the yaw-rate
    turn's angle."""
    real231({"today": {"yaw_split": False, "yaw_angle": False}, "W328": {"yaw_split": True, "yaw_angle": True}})


def real_w466() -> None:
    """Decision W466 on the mobgap turns (:func:`real231`): L370's runs against W466's sustained-reversal cut."""
    real231({"today": {"sustained": False}, "W466": {"sustained": True}})


def real255() -> None:
    """Decision L255 on the mobgap turns (:func:`real231` with :data:`CONFIGS255`)."""
    real231(CONFIGS255)


def real231(configs=CONFIGS231) -> None:
    """Decisions L231 / L233 / L235 on the mobgap turns: each INDIP turn of >= 80 deg and the overlapping row of
    largest |angle| of each table (``configs``, :data:`CONFIGS231`), pooled over the three recordings."""
    folders = [Path("datasets/real") / n for n in ("mobgap_HA001_Test11_Trial1",)]
    folders += [Path("datasets/external") / n for n in ("mobgap_HA002_Test11_Trial1", "mobgap_MS001_Test11_Trial1")]
    pooled, n_det, n_ref, n_free = {}, {}, 0, {}
    for f in folders:
        s = read_session(f)
        ref = s.extras["turns"]
        big = ref[ref["angle_deg"].abs() >= 80]
        n_ref += len(big)
        for name in ("waist-pendulum", "waist-pll"):
            res = track_waist(s, pipeline=name, sit_veto=False)  # as measured, before W185
            for c, kw in configs.items():
                tt = turn_table(res.steps, detected_bouts(res.steps), timing="yaw",
                                yaw_turns=res.info.get("yaw_turns"), **kw)
                n_det[(name, c)] = n_det.get((name, c), 0) + len(tt)
                free = sum(not ((ref["start_s"] <= r.end_s) & (ref["end_s"] >= r.start_s)).any()  # W466's (a)
                           for r in tt.itertuples())
                n_free[(name, c)] = n_free.get((name, c), 0) + free
                pooled.setdefault((name, c), []).extend(_real_line(f, f"{name} [{c}]", "yaw", big, ref, res, tt,
                                                                   all_columns=True))
    for (name, c), d in pooled.items():
        a = np.asarray(d, float).reshape(-1, 5)
        print(f"pooled {name} [{c}]: {n_det[(name, c)]} detected turns ({n_free[(name, c)]} overlapping no "
              f"reference turn), {len(a)} of {n_ref} reference turns >= 80 "
              f"deg overlapped; |duration error| {med(np.abs(a[:, 0]))} s ({med(a[:, 0])}), |start| "
              f"{med(np.abs(a[:, 3]))} s, |end| {med(np.abs(a[:, 4]))} s, ||angle| error| {med(np.abs(a[:, 1]))} deg "
              f"({med(a[:, 1])}), sign agreement {np.mean(a[:, 2]) if len(a) else float('nan'):.2f}")


def real(timings=TIMINGS, same_rows: bool = False) -> None:
    folders = [Path("datasets/real") / n for n in ("mobgap_HA001_Test11_Trial1",)]
    folders += [Path("datasets/external") / n for n in ("mobgap_HA002_Test11_Trial1", "mobgap_MS001_Test11_Trial1")]
    pooled = {}
    for f in folders:
        s = read_session(f)
        ref = s.extras["turns"]
        big = ref[ref["angle_deg"].abs() >= 80]
        for name in ("waist-pendulum", "waist-pll"):
            res = track_waist(s, pipeline=name, sit_veto=False)  # as measured, before W185
            first = None
            for timing in timings:
                tt = turn_table(res.steps, detected_bouts(res.steps), timing=timing,
                                yaw_turns=res.info.get("yaw_turns"))
                first = tt if first is None or not same_rows else first
                pooled.setdefault((name, timing), []).extend(_real_line(f, name, timing, big, ref, res, tt, first))
    for (name, timing), d in pooled.items():  # decision L208's rule: the pooled median |duration error|
        a = np.asarray(d, float).reshape(-1, 3)
        print(f"pooled {name} [{timing}]: {len(a)} overlapped reference turns; duration error median "
              f"{med(a[:, 0])} s (|.| {med(np.abs(a[:, 0]))})" + (
                  f"; |start error| {med(np.abs(a[:, 1]))} s, |end error| {med(np.abs(a[:, 2]))} s" if same_rows
                  else ""))


def _real_line(f, name, timing, big, ref, res, tt, match=None, all_columns: bool = False) -> list[tuple]:
    """Print one recording's line for one pipeline and timing; return its (duration, start, end) errors (s)
    (``all_columns``: (duration, |angle| error, sign agreement, start, end)). ``match``: the table whose overlap
    picks each reference turn's row (decision L210: L208's timing; default ``tt``)."""
    match = tt if match is None else match
    err, found = [], 0
    for r in big.itertuples():
        m = match[(match["start_s"] <= r.end_s) & (match["end_s"] >= r.start_s)] if len(match) else match
        if not len(m):
            continue
        found += 1
        d = tt.loc[m.index[int(np.argmax(m["angle_deg"].abs().to_numpy()))]]
        err.append((d.duration_s - (r.end_s - r.start_s), abs(d.angle_deg) - abs(r.angle_deg),
                    float(np.sign(d.angle_deg) == np.sign(r.angle_deg)), d.start_s - r.start_s,
                    d.end_s - r.end_s))
    a = np.array(err, float).reshape(-1, 5)
    print(f"{f.name} {name} [{timing}]: reference turns >= 80 deg {len(big)} (of {len(ref)}), detected turns "
          f"{len(tt)}, overlapping {found}; duration error median {med(a[:, 0])} s (|.| {med(np.abs(a[:, 0]))}), "
          f"start {med(a[:, 3])} s, end {med(a[:, 4])} s, |angle| error median {med(a[:, 1])} deg "
          f"(|.| {med(np.abs(a[:, 1]))}), sign agreement {np.mean(a[:, 2]) if len(a) else float('nan'):.2f}; "
          f"transfers detected {len(res.info['transfers'])} "
          f"({', '.join(t['kind'] + ' ' + format(t['start_s'], '.1f') for t in res.info['transfers'])})",
          flush=True)
    return [tuple(x) for x in (a if all_columns else a[:, [0, 3, 4]]).tolist()]


#: decision L345's fresh users, routes (by user % 3: the trial's TUG, a pivot, a 90 deg turn on the spot) and the two
#: tables compared: today's El-Gohary boundaries and the 5-95 % yaw times
USERS345 = range(6590, 6620)
ROUTES345 = (ROUTES[0], ("straight:8, pivot:180, straight:8", 0.0, 0.0),
             ("stand:3, straight:5, turn:90, straight:5, stand:3", 0.0, 0.0))
CONFIGS345 = {"El-Gohary (L211)": {"yaw_fractions": False}, "5-95 % (L345)": {"yaw_fractions": True}}


def sim345() -> None:
    """Decision L345's adoption rule on the simulator: per pipeline, each config's errors on the row nearest the
    truth under today's table; mean rate error in percent of 0.90 x |true angle| / true duration."""
    err = {(p, c): [] for p in ("waist-pendulum", "waist-pll") for c in CONFIGS345}
    same = {p: [] for p in ("waist-pendulum", "waist-pll")}
    for u in USERS345:
        route, s0, s1 = ROUTES345[u % 3]
        speed = "slow" if (u // 3) % 2 else "normal"
        hz = 20.0 if (u // 6) % 2 == 0 else 100.0
        s = simulate_path(parse_route(route), UserProfile.from_seed(u), speed=speed, rate_hz=hz, seed=u,
                          sit_start_s=s0, sit_end_s=s1)
        ta, tb, ang = true_turn(s)
        true_rate = 0.90 * abs(ang) / (tb - ta)
        line = [f"user {u} {speed} {hz:g} Hz [{route}]: truth {ta:.2f}-{tb:.2f} s ({tb - ta:.2f} s) {ang:+.1f} deg, "
                f"mean rate {true_rate:.1f} deg/s"]
        for p in same:
            res = track_waist(s, pipeline=p)
            tabs = {c: turn_table(res.steps, detected_bouts(res.steps), yaw_turns=res.info.get("yaw_turns"), **kw)
                    for c, kw in CONFIGS345.items()}
            ref = tabs["El-Gohary (L211)"]
            same[p].append(all(len(t) == len(ref) and np.array_equal(t["angle_deg"], ref["angle_deg"])
                               for t in tabs.values()))
            if not len(ref):
                line.append(f"  {p}: no turn")
                for c in CONFIGS345:
                    err[(p, c)].append((np.nan,) * 5)
                continue
            i = int(np.argmin(np.abs(0.5 * (ref["start_s"] + ref["end_s"]).to_numpy(float) - 0.5 * (ta + tb))))
            for c, tt in tabs.items():
                r = tt.iloc[i]
                e = (r.start_s - ta, r.end_s - tb, r.duration_s - (tb - ta), r.angle_deg - ang,
                     100.0 * (r.mean_rate_dps - true_rate) / true_rate)
                err[(p, c)].append(e)
                line.append(f"  {p} [{c}]: {len(tt)} turn(s); nearest {r.start_s:.2f}-{r.end_s:.2f} s "
                            f"({r.duration_s:.2f} s) {r.angle_deg:+.1f} deg, mean rate {r.mean_rate_dps:.1f} deg/s; "
                            f"errors start {e[0]:+.2f} end {e[1]:+.2f} duration {e[2]:+.2f} s angle {e[3]:+.1f} deg "
                            f"mean rate {e[4]:+.1f} %")
        print("\n".join(line), flush=True)
    print("\nL345 (median signed error, median |error|; the row nearest the truth under today's table):")
    for (p, c), e in err.items():
        a = np.array(e, float)
        print(f"{p} [{c}]: {int(np.isfinite(a[:, 0]).sum())}/{len(a)} turns found (tables' counts and angles equal "
              f"in {sum(same[p])}/{len(same[p])} sessions); start {med(a[:, 0])} s (|.| {med(np.abs(a[:, 0]))}), "
              f"end {med(a[:, 1])} s (|.| {med(np.abs(a[:, 1]))}), duration {med(a[:, 2])} s "
              f"(|.| {med(np.abs(a[:, 2]))}), angle {med(a[:, 3])} deg (|.| {med(np.abs(a[:, 3]))}), mean rate "
              f"{med(a[:, 4])} % (|.| {med(np.abs(a[:, 4]))})")


def real345() -> None:
    """Decision L345's rule on the mobgap turns: each INDIP turn's row chosen under today's table, scored under
    both."""
    folders = [Path("datasets/real") / "mobgap_HA001_Test11_Trial1"]
    folders += [Path("datasets/external") / n for n in ("mobgap_HA002_Test11_Trial1", "mobgap_MS001_Test11_Trial1")]
    pooled = {}
    for f in folders:
        s = read_session(f)
        ref = s.extras["turns"]
        big = ref[ref["angle_deg"].abs() >= 80]
        for p in ("waist-pendulum", "waist-pll"):
            res = track_waist(s, pipeline=p)
            tabs = {c: turn_table(res.steps, detected_bouts(res.steps), yaw_turns=res.info.get("yaw_turns"), **kw)
                    for c, kw in CONFIGS345.items()}
            first = tabs["El-Gohary (L211)"]
            for c, tt in tabs.items():
                pooled.setdefault((p, c), []).extend(_real_line(f, p, c, big, ref, res, tt, first))
    for (p, c), d in pooled.items():
        a = np.asarray(d, float).reshape(-1, 3)
        print(f"pooled {p} [{c}]: {len(a)} overlapped reference turns; duration error median {med(a[:, 0])} s "
              f"(|.| {med(np.abs(a[:, 0]))}); |start error| {med(np.abs(a[:, 1]))} s, |end error| "
              f"{med(np.abs(a[:, 2]))} s")


if __name__ == "__main__":
    {"sim": sim, "sim28": sim28, "real": real, "sim210": sim210, "real210": real210, "sim231": sim231,
     "real231": real231, "sim255": sim255, "real255": real255, "real_w328": real_w328, "real_w466": real_w466,
     "sim345": sim345, "real345": real345}[sys.argv[1]]()
