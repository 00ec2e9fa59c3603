"""Decisions L195-L197, W177-W178 (docs/decisions/localization.md, waist.md): the gait-range checks per bout, the
pooled stride-time CV line and the fast-gait wording, measured once.

(a) fresh simulated users 3430-3459, normal walks: scenarios A-D (20 Hz, the thesis scenarios) and W111's simulated
    daily-activity route (100 Hz), speed slow / normal / fast by user (u % 3), each tracked by the foot pipeline
    (``plasys``, no model, as ``pdrlearn track DIR``) and the lower back (``waist-pendulum``, defaults): how many
    sessions get L195's bout line, L196's pooled-CV line, ``gait_out_of_range`` true, W177's / W178's wording;
(b) the real recordings (datasets/real, datasets/external), ``pdrlearn track DIR`` (its own pipeline choice): the
    same counts;
(c) the trial's sessions (session 27 runner trial, /tmp/trial_runner/rt when present): the lines and flags printed.

Run: ``OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/gait_range_bouts.py [--users 3430-3459]``
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import logging
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from pdrlearn.cli import main as cli  # noqa: E402
from pdrlearn.sim import UserProfile, simulate  # noqa: E402
from pdrlearn.sim.route import parse_route  # noqa: E402
from pdrlearn.sim.simulate import simulate_path  # noqa: E402
from pdrlearn.track import get_pipeline  # noqa: E402

#: W111's simulated daily activities (experiments/waist_vault_veto.py)
ROUTE = ("stand:3, straight:6, turn:180, straight:4, stand:4, straight:3, turn:-90, straight:5, sit:10, "
         "straight:4, turn:-135, straight:4, stand:3")
SPEEDS = ("slow", "normal", "fast")
MARKS = {"L195": "decision L195)", "L196": "decision L196)", "W177": "at a running cadence",
         "W178": "running, or short fast steps (a festinating", "L95": "(decision L95)"}


def marks(summary: dict) -> dict:
    lines = (summary.get("info") or {}).get("warnings") or []
    got = {k: sum(1 for ln in lines if m in ln and (k != "L95" or "walking bout(s) lie above" not in ln))
           for k, m in MARKS.items()}
    return {**got, "flag": bool(summary.get("gait_out_of_range")),
            "n_bouts_flagged": int(summary.get("n_bouts_out_of_range") or 0)}


def simulated(users: range) -> list[dict]:
    rows = []
    for u in users:
        speed = SPEEDS[u % 3]
        sessions = {sc: simulate(sc, u, speed) for sc in "ABCD"}
        sessions["daily"] = simulate_path(parse_route(ROUTE), UserProfile.from_seed(u), rate_hz=100, seed=u)
        for name, s in sessions.items():
            for pipe in ("plasys", "waist-pendulum"):
                with contextlib.redirect_stderr(io.StringIO()):
                    summ = get_pipeline(pipe)(s).summary(s)
                rows.append({"user": u, "speed": speed, "session": name, "pipeline": pipe, **marks(summ)})
    return rows


def tracked(folder: Path) -> dict:
    with tempfile.TemporaryDirectory() as tmp, contextlib.redirect_stdout(io.StringIO()) as out, \
            contextlib.redirect_stderr(io.StringIO()):
        code = cli(["track", str(folder), "--out", str(Path(tmp) / "o"), "--json"])
    if code != 0:
        raise SystemExit(f"track {folder} failed (exit {code})")
    return json.loads(out.getvalue())


def real() -> list[dict]:
    rows = []
    for base in (ROOT / "datasets" / "real", ROOT / "datasets" / "external"):
        for d in sorted(p for p in base.iterdir() if (p / "meta.json").exists()):
            summ = tracked(d)
            rows.append({"session": d.name, "pipeline": summ.get("pipeline"), **marks(summ)})
    return rows


def table(rows: list[dict], keys: tuple[str, ...]) -> str:
    head = "| " + " | ".join(keys) + " |\n|" + "---|" * len(keys) + "\n"
    return head + "".join("| " + " | ".join(str(r.get(k)) for k in keys) + " |\n" for r in rows)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--users", default="3430-3459")
    ap.add_argument("--trial", default="/tmp/trial_runner/rt")
    a = ap.parse_args()
    logging.disable(logging.WARNING)
    lo, hi = (int(v) for v in a.users.split("-"))
    sim = simulated(range(lo, hi + 1))
    keys = ("L195", "L196", "W177", "W178", "L95", "flag")
    print(f"(a) simulated users {lo}-{hi}: {len(sim)} tracks (5 sessions x 2 pipelines per user)")
    for k in keys:
        hits = [r for r in sim if r[k]]
        print(f"  {k}: {len(hits)} of {len(sim)}" + (f"  {[(r['user'], r['session'], r['pipeline']) for r in hits]}"
                                                      if hits else ""))
    rl = real()
    print(f"(b) real recordings: {len(rl)}")
    for k in keys:
        hits = [r["session"] for r in rl if r[k]]
        print(f"  {k}: {len(hits)} of {len(rl)}" + (f"  {hits}" if hits else ""))
    trial = Path(a.trial)
    if trial.exists():
        rows = []
        for name, pipe in (("fo_mixWRW", None), ("mixWRW", None), ("intervals", None), ("intervals", "waist-pendulum"),
                           ("jog25", "waist-pendulum"), ("run31", "waist-pendulum"), ("downhill", None),
                           ("fo_run31", None)):
            if not (trial / name).exists():
                continue
            args = [] if pipe is None else ["--pipeline", pipe]
            with tempfile.TemporaryDirectory() as tmp, contextlib.redirect_stdout(io.StringIO()) as out, \
                    contextlib.redirect_stderr(io.StringIO()):
                cli(["track", str(trial / name), "--out", str(Path(tmp) / "o"), "--json", *args])
            summ = json.loads(out.getvalue())
            rows.append({"session": name, "pipeline": summ.get("pipeline"), **marks(summ),
                         "cv": None if summ.get("stride_time_cv_pct") is None else round(summ["stride_time_cv_pct"], 1),
                         "within": None if summ.get("stride_time_cv_within_bouts_pct") is None
                         else round(summ["stride_time_cv_within_bouts_pct"], 1),
                         "err_pct": None if summ.get("distance_error_pct") is None
                         else round(summ["distance_error_pct"], 2)})
        print("(c) the trial's sessions")
        print(table(rows, ("session", "pipeline", *keys, "n_bouts_flagged", "cv", "within", "err_pct")))


if __name__ == "__main__":
    main()
