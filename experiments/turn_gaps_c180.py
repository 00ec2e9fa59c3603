"""Decisions C180 and C181's measurement (session 45): a slow walker's stepless cone turns and the walking bouts; the
corridor's lap count with cone turns on the spot, stepped round the cone, and a chair's swivel.

C180 (rule in docs/decisions/cohort.md): fresh users 12720-12729, slow and asymmetric, pendulum bounce, 100 Hz;
12720-12724 a 6MWT route (30 m corridor), 12725-12729 a 2MWT route (12 m corridor), 5 laps each with a 10 s stand at
the cone after lap 2; cone turns ``turn:180`` (even users) or ``curve:180:0.5`` (odd). Tracked with ``track --units
waist --corridor L`` (uncalibrated waist-pendulum); bouts today = :func:`detected_bouts` of the written steps.csv
without turn gaps (L104 / L119 alone), C182 = the written bouts.csv (``--corridor``: the cone turns fill their
gaps; session 45's first run, C180's general rule at 90 deg, wrote the same rows: every filled gap was a cone
turn). Truth: the simulator's contacts (ics.csv), the stand the longest gap between them.

C181 (ii) reads the same tracks' ``n_laps`` (truth 5) and turns.csv's ``carried``; (i) user 12731 on a 12 m
corridor, 4 laps, a 20 s sit mid-lap 3 with a 180 deg swivel spliced into the seated yaw rate (L622's splice):
``n_laps`` with C181 and with every turn taken as the walker's (today's cone turns).

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/turn_gaps_c180.py WORKDIR
Output: experiments/results/turn_gaps_c180.txt (the printed lines).
"""
from __future__ import annotations

import dataclasses
import json
import logging
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.cli import main
from pdrlearn.io import read_session, write_session
from pdrlearn.track.bouts import detected_bouts
from pdrlearn.track.corridor import corridor_laps

USERS = range(12720, 12730)
LINES: list[str] = []


def say(line: str) -> None:
    print(line, flush=True)
    LINES.append(line)


def route(u: int) -> tuple[str, float]:
    """User ``u``'s corridor route (5 laps, a 10 s stand at the cone after lap 2) and its corridor (m)."""
    length = 30.0 if u < 12725 else 12.0
    cone = "turn:180" if u % 2 == 0 else "curve:180:0.5"
    leg = f"straight:{length:g}"
    return ", ".join([leg, cone, leg, "stand:10", cone, leg, cone, leg, cone, leg]), length


def gait(u: int) -> list[str]:
    k = u % 5
    return ["--step-length", f"{0.30 + 0.035 * k:.3f}", "--step-time", f"{0.85 + 0.0375 * k:.4f}",
            "--step-time-asymmetry", f"{0.15 + 0.025 * k:.3f}", "--bounce", "pendulum", "--rate", "100"]


def truth_bouts(ics_s: np.ndarray) -> tuple[tuple[float, float], list[np.ndarray]]:
    """The stand (the longest gap between true contacts) and the true contacts of the walks before and after it."""
    k = int(np.argmax(np.diff(ics_s)))
    return (float(ics_s[k]), float(ics_s[k + 1])), [ics_s[:k + 1], ics_s[k + 1:]]


def cadence_errors(bouts: pd.DataFrame, ics_s: np.ndarray) -> list[float]:
    """Each bout's ``cadence_spm`` against the simulator's contacts over the bout's contact span (%)."""
    out = []
    for _, b in bouts.iterrows():
        c = ics_s[(ics_s >= b["start_s"] - 0.3) & (ics_s <= b["end_s"] + 0.3)]
        if len(c) >= 3 and np.isfinite(b["cadence_spm"]):
            out.append(100.0 * (b["cadence_spm"] / (60.0 * (len(c) - 1) / (c[-1] - c[0])) - 1.0))
    return out


def overlaps(bouts: pd.DataFrame, stand: tuple[float, float]) -> bool:
    a, b = stand[0] + 1.0, stand[1] - 1.0
    return bool(((bouts["start_s"] < b) & (bouts["end_s"] > a)).any())


def c180(work: Path) -> None:
    n2 = {"today": 0, "C182": 0}
    stand_ok = {"today": 0, "C182": 0}
    errs = {"today": [], "C182": []}
    laps_ok, carried_cones = 0, 0
    for u in USERS:
        r, length = route(u)
        sim, out = work / f"s{u}", work / f"t{u}"
        if not sim.is_dir():
            assert main(["simulate", "--route", r, *gait(u), "--user-seed", str(u), "--stand", "3", "--out",
                         str(sim)]) == 0
        if not (out / "summary.json").is_file():
            assert main(["track", str(sim), "--units", "waist", "--corridor", f"{length:g}", "--no-plot", "--out",
                         str(out), "--force"]) == 0
        ics_s = np.sort(pd.read_csv(sim / "ics.csv")["ic_ms"].to_numpy(float) / 1000.0)
        stand, _ = truth_bouts(ics_s)
        steps = pd.read_csv(out / "steps.csv")
        tables = {"today": detected_bouts(steps), "C182": pd.read_csv(out / "bouts.csv")}
        summary = json.loads((out / "summary.json").read_text())
        turns = pd.read_csv(out / "turns.csv")
        cones = turns[turns["angle_deg"].abs() >= 135]
        laps_ok += summary["n_laps"] == 5
        carried_cones += int(cones["carried"].astype(bool).sum())
        parts = []
        for key, t in tables.items():
            e = cadence_errors(t, ics_s)
            errs[key] += e
            n2[key] += len(t) == 2
            stand_ok[key] += not overlaps(t, stand)
            parts.append(f"{key} {len(t)} bouts (cadence error {' / '.join(f'{x:+.1f}' for x in e)} %)")
        say(f"user {u} ({r.split(', ')[1]}, {length:g} m): stand {stand[0]:.1f}-{stand[1]:.1f} s; " + "; ".join(parts)
            + f"; n_laps {summary['n_laps']} (truth 5), walk_test_distance_m {summary['walk_test_distance_m']:.2f}, "
              f"cone turns {len(cones)}, carried "
              f"{int(cones['carried'].astype(bool).sum())}; n_walking_bouts {summary['n_walking_bouts']}, n_pauses "
              f"{summary['n_pauses']}")
    for key in ("today", "C182"):
        e = np.abs(errs[key])
        say(f"C180 {key}: n_bouts == 2 on {n2[key]} of {len(USERS)}; the stand ends a bout on {stand_ok[key]} of "
            f"{len(USERS)}; bouts' median |cadence error| {np.median(e):.2f} % (n={len(e)}, max {e.max():.2f} %)")
    say(f"C181 (ii): n_laps == 5 on {laps_ok} of {len(USERS)}; cone turns marked carried: {carried_cones}")


def swivel(session, a: float, b: float, deg: float):
    """L622's splice: a ``deg`` turn of the lower back's yaw rate (simulator waist frame: y up) from ``a`` to ``b``."""
    g = session["wGyroscope"]
    v = g.values.copy()
    m = (g.t > a) & (g.t < b)
    v[m, 1] += np.radians(deg) / (b - a) * (1 - np.cos(2 * np.pi * (g.t[m] - a) / (b - a)))
    return dataclasses.replace(session, streams={**session.streams, "wGyroscope": dataclasses.replace(g, values=v)})


def c181_swivel(work: Path, u: int = 12731) -> None:
    sim, spliced, out = work / f"sw{u}", work / f"sw{u}_spliced", work / f"tsw{u}"
    r = "straight:12, turn:180, straight:12, turn:180, straight:6, sit:20, straight:6, turn:180, straight:12"
    if not sim.is_dir():
        assert main(["simulate", "--route", r, "--user-seed", str(u), "--bounce", "pendulum", "--rate", "100",
                     "--stand", "3", "--out", str(sim)]) == 0
    tr = pd.read_csv(sim / "transfers.csv")
    mid = 0.5 * (float(tr["seated_ms"].iloc[0]) + float(tr["rise_ms"].iloc[0])) / 1000.0
    if not spliced.is_dir():
        write_session(swivel(read_session(sim), mid - 5.0, mid + 5.0, 180.0), spliced)
    assert main(["track", str(spliced), "--units", "waist", "--corridor", "12", "--no-plot", "--out", str(out),
                 "--force"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    turns, bouts, steps = (pd.read_csv(out / f) for f in ("turns.csv", "bouts.csv", "steps.csv"))
    seat = turns[(turns["start_s"] < mid) & (turns["end_s"] > mid)]
    today, _, lines = corridor_laps(steps, turns.assign(carried=False), 12.0, bouts)
    rows = seat[["start_s", "end_s", "angle_deg", "carried"]].to_dict("records")
    n_today = int(today["corridor_laps"].sum())
    say(f"C181 (i) user {u}: swivel at {mid:.1f} s: turns.csv row(s) {rows}; n_laps C181 {summary['n_laps']} (truth "
        f"4), every turn the walker's (today) {n_today}; today's lap lines: {[x for x in lines if 'L384' in x]}")


def real(ext: Path) -> None:
    """C180 (d): the 9 mobgap recordings with INDIP WBs, uncalibrated waist-pendulum and waist-pll, default bout
    rule: the intervals C180 fills, each against INDIP's WBs (inside one: allowed), and the bouts today / C180."""
    from pdrlearn.steps.reference_clock import waist_clock_labels
    from pdrlearn.track import get_pipeline
    from pdrlearn.track.clinical import turn_filled
    from pdrlearn.track.turn_gaps import TurnGaps
    from pdrlearn.waist.evaluate import reference_wbs

    tests = [d for d in sorted(ext.glob("mobgap_*_Test*_Trial*")) if (d / "bouts.csv").is_file()
             and reference_wbs(read_session(d)) is not None]
    bad = n_filled = 0
    for d in tests:
        session = read_session(d)
        wbs = reference_wbs(waist_clock_labels(session))  # decision W380: on the tracked clock
        for pipe in ("waist-pendulum", "waist-pll"):
            res = get_pipeline(pipe)(session)
            st = res.steps.sort_values("start_s", kind="stable").reset_index(drop=True)
            gaps = TurnGaps.of(res.info)
            filled = np.flatnonzero(turn_filled(st, turn_gaps=gaps))
            t = st["start_s"].to_numpy(float)
            where = []
            for i in filled:
                inside = bool(((wbs["start_s"] <= t[i]) & (wbs["end_s"] >= t[i + 1])).any())
                bad += not inside
                where.append(f"{t[i]:.2f}-{t[i + 1]:.2f} s {'inside one WB' if inside else 'NOT inside one WB'}")
            n_filled += len(filled)
            say(f"C180 (d) {d.name} {pipe}: bouts today {len(detected_bouts(st))}, C180 "
                f"{len(detected_bouts(st, turn_gaps=gaps))}; INDIP WBs {len(wbs)}; filled: {where or 'none'}")
    say(f"C180 (d): {len(tests)} recordings x 2 pipelines, intervals filled {n_filled}, not inside one INDIP WB {bad}")


if __name__ == "__main__":
    logging.disable(logging.WARNING)
    work = Path(sys.argv[1])
    work.mkdir(parents=True, exist_ok=True)
    which = sys.argv[2] if len(sys.argv) > 2 else "all"
    if which in ("all", "c180"):
        c180(work)
    if which in ("all", "c181"):
        c181_swivel(work)
    if which in ("all", "real"):
        real(Path(sys.argv[3]) if len(sys.argv) > 3 else Path("datasets/external"))
    if which == "all":
        (Path(__file__).resolve().parent / "results" / "turn_gaps_c180.txt").write_text("\n".join(LINES) + "\n")
