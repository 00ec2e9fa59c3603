"""Simulated lying sessions (S58-S60) through the lower-back track (W222, W245-W249, W258, B263): each lying
transfer row against lying.csv's truth, lying_time_s against the truth, no step and no turn while lying, no axis
warning. Users 6290-6293 (session 31, brief W258-W259 / B263-B264); run from the repo root:

    OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/lying_sessions.py > experiments/results/lying_sessions.txt

Truth (S60): the lying down is lying.csv's start-lying span, the getting up its rise-end span, both from / to the
bed-edge sit (truth kinds sit-to-lie / lie-to-sit); lying lasts lying-rise. A row matches a truth span when its
peak_s lies in [start - 1 s, end + 1 s] (W232's rule) with the same direction."""

from __future__ import annotations

import contextlib
import io
import json
import sys
import tempfile
from pathlib import Path

import pandas as pd

from pdrlearn.cli import main as cli

SESSIONS = [  # (user, route)
    (6290, "stand:5, straight:10, lie:600:12, straight:10, stand:5"),
    (6291, "stand:5, straight:10, lie:600:12, straight:10, stand:5"),
    (6292, "stand:5, straight:10, lie:3600:12, straight:10, stand:5"),
    (6293, "stand:5, straight:10, lie:300:30, straight:5, lie:300:12, straight:10, stand:5"),
]
DOWN, UP = ("sit-to-lie", "stand-to-lie"), ("lie-to-sit", "lie-to-stand")


def run(user: int, route: str, root: Path) -> list[str]:
    sim, out = root / f"s{user}", root / f"t{user}"
    with contextlib.redirect_stdout(io.StringIO()):
        assert cli(["simulate", "--route", route, "--user-seed", str(user), "--out", str(sim)]) == 0
    err = io.StringIO()
    with contextlib.redirect_stdout(io.StringIO()) as so, contextlib.redirect_stderr(err):
        assert cli(["track", str(sim), "--pipeline", "waist-pendulum", "--out", str(out)]) == 0
    printed = so.getvalue() + err.getvalue()
    ly = pd.read_csv(sim / "lying.csv")
    rolls = pd.read_csv(sim / "rolls.csv")
    tr, steps, turns = (pd.read_csv(out / f) for f in ("transfers.csv", "steps.csv", "turns.csv"))
    summary = json.loads((out / "summary.json").read_text())
    lines = []
    truth_lying = float(((ly["rise_ms"] - ly["lying_ms"]) / 1000).sum())
    spans = list(zip(ly["lying_ms"] / 1000, ly["rise_ms"] / 1000, strict=True))

    def in_lying(t: float) -> bool:
        return any(a <= t <= b for a, b in spans)

    for _, r in ly.iterrows():
        for what, a, b, kinds, truth_kind in (("down", r.start_ms, r.lying_ms, DOWN, "sit-to-lie"),
                                              ("up", r.rise_ms, r.end_ms, UP, "lie-to-sit")):
            a, b = a / 1000, b / 1000
            m = tr[tr["kind"].isin(kinds) & (tr["peak_s"] >= a - 1) & (tr["peak_s"] <= b + 1)]
            if not len(m):
                lines.append(f"| {user} | {what} | {truth_kind} {a:.2f}-{b:.2f} | none | | |")
                continue
            row = m.iloc[0]
            lines.append(f"| {user} | {what} | {truth_kind} {a:.2f}-{b:.2f} | {row.kind} {row.start_s:.2f}-"
                         f"{row.end_s:.2f} | {row.start_s - a:+.2f} / {row.end_s - b:+.2f} | "
                         f"{'right' if row.kind == truth_kind else 'kind error'} |")
    n_rows = int(tr["kind"].isin(DOWN + UP).sum())
    steps_lying = sum(in_lying(t) for t in steps["start_s"])
    turns_lying = sum(in_lying(0.5 * (a + b)) for a, b in zip(turns["start_s"], turns["end_s"], strict=True))
    lines.append(f"| {user} | session | lying {truth_lying:.1f} s, {len(rolls)} rolls, {2 * len(ly)} lying transfers "
                 f"| lying_time_s {summary.get('lying_time_s'):.2f}, {n_rows} lying rows, n_lie_down "
                 f"{summary.get('n_lie_down')}, n_get_up {summary.get('n_get_up')} | steps while lying "
                 f"{steps_lying}, turns while lying {turns_lying}, turns.csv {len(turns)} | axis warning: "
                 f"{'yes' if 'disagree' in printed else 'no'} |")
    return lines


def table(sessions, root: Path) -> list[str]:
    out = ["| user | what | truth | track row | start / end error (s) | verdict |", "|---|---|---|---|---|---|"]
    for user, route in sessions:
        out += [f"<!-- {user}: {route} -->", *run(user, route, root)]
    return out


def w259() -> None:
    """Decision W259's rule, item (a): fresh users 6294-6297 (the four routes), today vs the candidate."""
    import contextlib

    from hapt_transfers import before_w259

    fresh = [(u + 4, r) for u, r in SESSIONS]
    for label, v in (("today", False), ("candidate", True)):
        with tempfile.TemporaryDirectory() as d, contextlib.nullcontext() if v else before_w259():
            rows = table(fresh, Path(d))
        body = [r for r in rows if r.startswith("| 6") and "| session |" not in r]
        right = sum(r.rstrip().endswith("| right |") for r in body)
        direction = sum("| none |" not in r for r in body)
        print(f"## W259 (a), {label} (SIDE_AFTER_CHAIR = {v}): {len(body)} truth lying transfers, right direction "
              f"{direction}, right kind {right}", "", *rows, "", sep="\n")


def main() -> None:
    if "--w259" in sys.argv[1:]:
        return w259()
    with tempfile.TemporaryDirectory() as d:
        print("\n".join(table(SESSIONS, Path(d))))


if __name__ == "__main__":
    main()
