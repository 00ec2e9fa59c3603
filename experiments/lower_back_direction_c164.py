"""Decision C164 (docs/decisions/classifiers.md): may a lower-back track warn "N steps look backward by the model"
from a per-user model's waist direction classifier?

Rule (written before measuring): on users 11580-11589 (normal speed), each with a model trained on one
``simulate --scenario direction`` walk (``train --tasks direction --methods heuristic,svm``), the svm/waist classifier
run on stride windows the lower back can cut (waist-ic contacts i -> i+2, foot files left out): (a) pooled recall of
true backward windows >= 80 %, (b) forward windows classed backward <= 5 %, (c) |N - true backward windows| <= 2 in
>= 8 of 10 users on ``stand:2, straight:4, backward:6, straight:4, stand:2``, (d) a forward walk
``stand:2, straight:14, stand:2`` gives N >= 2 in <= 1 of 10 users. Truth: the simulated stride holding the window's
middle. Also printed, not the rule's: the simulator's own foot-stride windows (trial T1's measurement; a lower-back
recording has none) and the waist windows shifted by a quarter stride.

    PYTHONPATH=. .venv/bin/python experiments/lower_back_direction_c164.py [--users 11580 ... 11589] [--work DIR]

Writes experiments/results/lower_back_direction_c164.md.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
from pathlib import Path

import pandas as pd

from pdrlearn.classify import load_model
from pdrlearn.io import read_session
from pdrlearn.steps import get_detector
from pdrlearn.track.units import keep_units

OUT = Path(__file__).resolve().parents[1] / "experiments" / "results" / "lower_back_direction_c164.md"
ROUTES = {"bwd": "stand:2, straight:4, backward:6, straight:4, stand:2", "fwd": "stand:2, straight:14, stand:2"}
WINDOWS = ("waist contacts i -> i+2 (the rule's)", "simulator's foot strides (T1's; not on a lower-back recording)",
           "waist contacts shifted +1/4 stride")


def _cli(*args: str) -> None:
    subprocess.run([sys.executable, "-m", "pdrlearn", *args], check=True, capture_output=True)


def windows(kind: int, session, truth: pd.DataFrame) -> pd.DataFrame:
    if kind == 1:
        return truth[["start_s", "end_s"]].reset_index(drop=True)
    ev = get_detector("waist-ic").detect(session)["event_s"].to_numpy(float)
    q = 0.25 * (ev[2:] - ev[:-2]) if kind == 2 else 0.0
    return pd.DataFrame({"start_s": ev[:-2] + q, "end_s": ev[2:] + q})


def rows_of(user: int, work: Path) -> list[dict]:
    cal, m = work / f"cal{user}", work / f"m{user}"
    if not m.exists():
        _cli("simulate", "--scenario", "direction", "--user-seed", str(user), "--out", str(cal / "direction"))
        _cli("train", str(cal), "--tasks", "direction", "--methods", "heuristic,svm", "--out", str(m))
    model, rows = load_model(m), []
    for route, spec in ROUTES.items():
        d = work / f"{route}{user}"
        if not d.exists():
            _cli("simulate", "--route", spec, "--user-seed", str(user), "--out", str(d))
        full = read_session(d)
        truth, s = full.steps, keep_units(full, ("waist",))
        for kind in range(len(WINDOWS)):
            win = windows(kind, s, truth)
            pred = model.predict_steps(s, win, tasks=["direction"], unit="waist", method="svm", windows="given")
            for i, t in enumerate((win["start_s"] + win["end_s"]) / 2):
                hit = truth[(truth["start_s"] <= t) & (truth["end_s"] >= t)]
                if hit.empty:
                    hit = truth.loc[[(truth["start_s"] - t).abs().idxmin()]]
                rows.append({"user": user, "route": route, "windows": WINDOWS[kind],
                             "pred": pred["direction"].iloc[i], "true": hit["direction"].iloc[0]})
    return rows


def rule_line(df: pd.DataFrame) -> str:
    users = sorted(df["user"].unique())
    back = df[(df["route"] == "bwd") & (df["true"] == "backward")]
    fwd = df[df["true"] == "forward"]
    n = {u: ((df["user"] == u) & (df["pred"] == "backward")) for u in users}
    within = sum(abs(int((n[u] & (df["route"] == "bwd")).sum()) - int(((df["user"] == u) & (df["route"] == "bwd")
                                                                      & (df["true"] == "backward")).sum())) <= 2
                 for u in users)
    warned = sum(int((n[u] & (df["route"] == "fwd")).sum()) >= 2 for u in users)
    hit_b, hit_f = int((back["pred"] == "backward").sum()), int((fwd["pred"] == "backward").sum())
    return (f"(a) {100 * hit_b / len(back):.1f} % ({hit_b}/{len(back)}) | (b) {100 * hit_f / len(fwd):.1f} % "
            f"({hit_f}/{len(fwd)}) | (c) {within}/{len(users)} | (d) {warned}/{len(users)}")


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", type=int, nargs="+", default=list(range(11580, 11590)))
    ap.add_argument("--work", type=Path, default=None, help="keep the simulated sessions and models here")
    args = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        work = args.work or Path(tmp)
        df = pd.DataFrame([r for u in args.users for r in rows_of(u, work)])
    lines = ["# C164: a per-user model's waist direction classifier on a lower-back track", "",
             f"Users {args.users[0]}-{args.users[-1]}. (a) recall of true backward windows; (b) forward windows "
             "classed backward; (c) users with |N - truth| <= 2 on the backward exercise; (d) users warned (N >= 2) "
             "on the forward walk. Rule: (a) >= 80 %, (b) <= 5 %, (c) >= 8 of 10, (d) <= 1 of 10.", "",
             "| windows | (a) | (b) | (c) | (d) |", "|---|---|---|---|---|"]
    lines += [f"| {w} | {rule_line(df[df['windows'] == w])} |" for w in WINDOWS]
    text = "\n".join(lines) + "\n"
    if args.users == list(range(11580, 11590)):
        OUT.parent.mkdir(parents=True, exist_ok=True)
        OUT.write_text(text)
    print(text)


if __name__ == "__main__":
    main()
