"""Decision W223: the lower back's time split by posture (W222) against known postures.

- ``sim``: fresh simulated users 5480-5519 (seed = user, 100 Hz), route ``straight:10, sit:20, straight:10, stand:15,
  straight:5``, seated 8 s at the start and 10 s at the end for even users (S43), none for odd. Truth per 0.05 s:
  sitting from a transfer's ``seated_s`` to its ``rise_s``; the transfer movements not scored; the rest upright
  (walking or standing, pooled: the simulator's walking has no label of its own).
- ``hapt``: UCI HAPT (``pdrlearn fetch hapt --out datasets/hapt``): each labelled sample of walking (stairs pooled),
  standing, sitting, lying against the track's label (walking = inside L275's walking pieces); transitions and
  unlabelled samples not scored.

waist-pendulum, default options. Nothing is tuned here. One core.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/posture_time.py sim|hapt|w248
[--root datasets/hapt] (w248: decision W248's rule, SITTING_TILT_DEG chosen on HAPT users 1-10)
Output: experiments/results/posture_time_sim.txt / posture_time_hapt.txt
"""
from __future__ import annotations

import argparse
import logging
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError
from pdrlearn.io.plasys import read_session
from pdrlearn.track.gait import session_walking_pieces
from pdrlearn.track.waist import track_waist

logging.disable(logging.WARNING)

USERS = range(5480, 5520)
ROUTE = "straight:10, sit:20, straight:10, stand:15, straight:5"
DT = 0.05
CLASSES = ("walking", "standing", "sitting", "lying", "unknown")


def labels_at(result, grid: np.ndarray) -> np.ndarray:
    """The track's label at each time of ``grid``: walking inside L275's walking pieces (as the time accounting),
    else W222's posture run holding it, else unknown."""
    out = np.full(grid.size, "unknown", dtype=object)
    for a, b, p in result.info.get("postures") or []:
        out[(grid >= a) & (grid < b)] = p
    for a, b in session_walking_pieces(result.steps.sort_values("start_s", kind="stable").reset_index(drop=True)):
        out[(grid >= a) & (grid <= b)] = "walking"
    return out


def agreement(rows: list[tuple[str, str]], classes: tuple[str, ...], est_classes=CLASSES) -> list[str]:
    """Per truth class: seconds, time agreement, and the confusion row (seconds per estimated label)."""
    df = pd.DataFrame(rows, columns=["truth", "est"])
    out = ["| truth | s | agreement | " + " | ".join(f"as {c} s" for c in est_classes) + " |",
           "|---|---|---|" + "---|" * len(est_classes)]
    for c in classes:
        d = df[df.truth == c]
        if not len(d):
            continue
        cnt = d.est.value_counts()
        same = cnt.get(c, 0) if c != "upright" else cnt.get("walking", 0) + cnt.get("standing", 0)
        out.append(f"| {c} | {len(d) * DT:.1f} | {100 * same / len(d):.1f} % | "
                   + " | ".join(f"{cnt.get(e, 0) * DT:.1f}" for e in est_classes) + " |")
    return out


def sim() -> list[str]:
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    rows, per = [], []
    for user in USERS:
        seated = user % 2 == 0
        s = simulate_path(parse_route(ROUTE), UserProfile.from_seed(user), rate_hz=100.0, seed=user,
                          sit_start_s=8.0 if seated else 0.0, sit_end_s=10.0 if seated else 0.0)
        res = track_waist(s, pipeline="waist-pendulum")
        t = s["wAccelerometer"].t
        grid = np.arange(t[0], t[-1], DT)
        truth = np.full(grid.size, "upright", dtype=object)
        for r in s.extras["transfers"].itertuples():
            truth[(grid >= r.start_s) & (grid < r.seated_s)] = ""
            truth[(grid >= r.rise_s) & (grid < r.end_s)] = ""
            truth[(grid >= r.seated_s) & (grid < r.rise_s)] = "sitting"
        est = labels_at(res, grid)
        keep = truth != ""
        rows += list(zip(truth[keep], est[keep], strict=True))
        sit_t, sit_e = (truth == "sitting").sum() * DT, ((est == "sitting") & keep).sum() * DT
        per.append(f"user {user} ({'seated ends' if seated else 'mid-walk sit only'}): sitting truth "
                   f"{sit_t:.1f} s, track {sit_e:.1f} s")
        print(per[-1], file=sys.stderr, flush=True)
    return [f"# W223 (a): simulated users {USERS.start}-{USERS.stop - 1}, route '{ROUTE}', waist-pendulum defaults",
            "", "Scored every 0.05 s outside the transfer movements; upright = walking or standing.", "",
            *agreement(rows, ("sitting", "upright")), "", *per]


def hapt_rows(root: Path, users=None) -> tuple[list[tuple[str, str]], list[str], int]:
    """(truth, track label) every 0.05 s of HAPT's labelled walking / standing / sitting / lying (W223 (b)), the
    refused recordings, and the number of folders; ``users``: HAPT user numbers (None: all)."""
    from pdrlearn.io.external.hapt import GAIT

    folders = sorted(p for p in root.glob("hapt_u*_r*") if p.is_dir()
                     and (users is None or int(p.name.split("_")[1][1:]) in users))
    if not folders:
        raise SystemExit(f"{root}: no hapt_u*_r* sessions; run `pdrlearn fetch hapt --out {root}` first")
    name = {"standing": "standing", "sitting": "sitting", "lying": "lying", **dict.fromkeys(GAIT, "walking")}
    rows, refused = [], []
    for folder in folders:
        s = read_session(folder)
        try:
            res = track_waist(s, pipeline="waist-pendulum")
        except DataError as exc:
            refused.append(f"{folder.name}: {str(exc)[:120]}")
            continue
        act = pd.read_csv(folder / "activities.csv")
        for r in act.itertuples():
            if r.activity not in name:
                continue
            grid = np.arange(r.start_ms / 1000.0, (r.end_ms + 20) / 1000.0, DT)  # H4: end inclusive
            rows += [(name[r.activity], e) for e in labels_at(res, grid)]
        print(f"{folder.name} done", file=sys.stderr, flush=True)
    return rows, refused, len(folders)


def hapt(root: Path) -> list[str]:
    rows, refused, n_folders = hapt_rows(root)
    n = n_folders - len(refused)
    return [f"# W223 (b): UCI HAPT, {n} recordings tracked (waist-pendulum defaults); stairs pooled into walking", "",
            *agreement(rows, ("walking", "standing", "sitting", "lying")), "",
            f"Refused: {len(refused)}", *[f"- {r}" for r in refused]]


def shares(rows: list[tuple[str, str]]) -> dict[str, float]:
    """Per truth class: the share (%) of its time the track labels the same (upright = walking or standing)."""
    df = pd.DataFrame(rows, columns=["truth", "est"])
    out = {}
    for c, d in df.groupby("truth"):
        same = d.est.isin(("walking", "standing")) if c == "upright" else d.est == c
        out[c] = 100.0 * float(same.mean())
    return out


W248_GRID = (6.0, 8.0, 10.0, 12.0, 15.0, 20.0)  # decision W248's values (deg), chosen on HAPT users 1-10


def w248(root: Path) -> list[str]:
    """Decision W248's one run: SITTING_TILT_DEG chosen on HAPT users 1-10, then (a) users 11-30, (b) simulated
    users 5980-5999, (c) the mobgap recordings, today (15 deg) vs the chosen value."""
    from pdrlearn.waist import posture_time

    today = posture_time.SITTING_TILT_DEG
    lines = ["# Decision W248's rule: W222's SITTING_TILT_DEG re-chosen on HAPT users 1-10", ""]

    def say(x: str) -> None:
        print(x, flush=True)
        lines.append(x)

    best = None
    for v in W248_GRID:
        posture_time.SITTING_TILT_DEG = v
        sh = shares(hapt_rows(root, range(1, 11))[0])
        score = 0.5 * (sh["sitting"] + sh["standing"])
        say(f"selection, HAPT users 1-10, {v:g} deg: sitting {sh['sitting']:.1f} %, standing {sh['standing']:.1f} %, "
            f"mean {score:.1f} %, walking {sh['walking']:.1f} %, lying {sh['lying']:.1f} %")
        if best is None or score > best[0] or (score == best[0] and abs(v - today) < abs(best[1] - today)):
            best = (score, v)
    chosen = best[1]
    say(f"chosen: {chosen:g} deg")
    if chosen != today:
        global USERS
        users, USERS = USERS, range(5980, 6000)
        for label, v in (("today", today), ("candidate", chosen)):
            posture_time.SITTING_TILT_DEG = v
            sh = shares(hapt_rows(root, range(11, 31))[0])
            say(f"(a) HAPT users 11-30, {label} {v:g} deg: sitting {sh['sitting']:.1f} %, standing "
                f"{sh['standing']:.1f} %, mean {0.5 * (sh['sitting'] + sh['standing']):.1f} %, walking "
                f"{sh['walking']:.1f} %, lying {sh['lying']:.1f} %")
            sim_lines = sim()
            say(f"(b) simulated users 5980-5999, {label} {v:g} deg:")
            for x in sim_lines[4:8]:
                say(x)
            for folder in sorted(Path("datasets/real").glob("mobgap_*")):
                res = track_waist(read_session(folder), pipeline="waist-pendulum")
                secs = {}
                for a, b, p in res.info.get("postures") or []:
                    secs[p] = secs.get(p, 0.0) + b - a
                say(f"(c) {folder.name}, {label}: " + ", ".join(f"{k} {x:.1f} s" for k, x in sorted(secs.items())))
        USERS = users
    posture_time.SITTING_TILT_DEG = today
    return lines


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("what", choices=("sim", "hapt", "w248"))
    ap.add_argument("--root", type=Path, default=Path("datasets/hapt"))
    a = ap.parse_args(argv)
    if a.what == "w248":
        text = "\n".join(w248(a.root)) + "\n"
        Path("experiments/results/posture_time_w248.txt").write_text(text)
        return
    lines = sim() if a.what == "sim" else hapt(a.root)
    text = "\n".join(lines) + "\n"
    print(text)
    Path(f"experiments/results/posture_time_{a.what}.txt").write_text(text)


if __name__ == "__main__":
    main()
