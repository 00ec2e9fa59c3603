"""Decision L675's measurement: ``track``'s foot contacts (which detection a rest-to-rest stride keeps) before and after
the rule, on slow walkers without insoles (trial T1's users 12760-12765, fresh 12840-12849), normal-speed walkers
(fresh 12850-12855) and the real foot recordings.

Per session: the tracked ``stride_time_cv_pct`` against the true CV (the right foot's labelled IC-to-IC times under
2.2 x their median, trial T1's cmp.py), ``pdrlearn score-steps SESSION steps.csv --all-rows`` of track's steps.csv
(F1, mean timing error) and the distance. The baseline is another checkout's ``pdrlearn`` (BASE, e.g. ``git archive
5c85cf8c pdrlearn | tar -x -C BASE``), the candidate this one.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/slow_contacts_l675.py TMPDIR BASE [T1_F1_DIR]
(T1_F1_DIR: the trial's sessions s_12760 ... s_12765; without it they are simulated here the same way; T1_F1_DIR
``long``: only the check added after the rule's run, the slow route for the users 12870-12899 whose drawn stance
fraction is at least 0.657 - only one of 12840-12849 was)
"""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

SLOW = [*range(12760, 12766), *range(12840, 12850)]
NORMAL = range(12850, 12856)
#: after the rule's run (L675): the users of 12870-12899 drawn with a stance fraction of at least 0.657
LONG_STANCE_FROM = range(12870, 12900)
REAL = ["gaitmap_level_left", "gaitmap_level_right", "gaitmap_stairs_up_left", "gaitmap_stairs_down_left"]
REPO = Path(__file__).resolve().parents[1]


def cli(args: list[str], pythonpath: Path) -> str:
    env = {**os.environ, "PYTHONPATH": str(pythonpath), "OMP_NUM_THREADS": "1"}
    run = subprocess.run([sys.executable, "-m", "pdrlearn", *args], env=env, capture_output=True, text=True,
                         cwd=pythonpath)  # python -m puts the working directory first on the path
    if run.returncode:
        raise SystemExit(f"pdrlearn {' '.join(args)}: {run.stderr.strip().splitlines()[-1]}")
    return run.stdout


def simulate(out: Path, user: int, slow: bool) -> Path:
    if not (out / "meta.json").exists():
        route = "stand:3, straight:15, stand:3" if slow else "stand:3, straight:30, stand:3"
        pace = ["--step-length", "0.3", "--step-time", "0.9"] if slow else []
        cli(["simulate", "--route", route, *pace, "--rocker", "smooth", "--rate", "100", "--user-seed", str(user),
             "--out", str(out), "--force"], REPO)
        for f in out.glob("fForce*.csv"):
            f.unlink()
    return out


def true_cv(session: Path) -> float:
    ics = pd.read_csv(session / "ics.csv")
    r = np.sort(ics.loc[ics["foot"] == "right", "ic_ms"].to_numpy(float) / 1000)
    st = np.diff(r)
    st = st[st < 2.2 * np.median(st)]
    return float(100 * st.std(ddof=1) / st.mean())


def measure(session: Path, out: Path, code: Path, truth: bool) -> dict:
    cli(["track", str(session), "--out", str(out), "--force"], code)
    summary = json.loads((out / "summary.json").read_text())
    score = json.loads(cli(["score-steps", str(session), str(out / "steps.csv"), "--all-rows", "--json"], code))
    row = {"cv": summary.get("stride_time_cv_pct"), "f1": score.get("f1"),
           "timing_ms": 1000 * score["timing_error_mean_s"] if score.get("timing_error_mean_s") is not None else None,
           "distance_m": summary.get("distance_m"), "asym": summary.get("step_time_asymmetry_pct")}
    if truth:
        row["true_cv"] = true_cv(session)
    return row


def long_stance_users() -> list[int]:
    from pdrlearn.sim import UserProfile

    return [u for u in LONG_STANCE_FROM if UserProfile.from_seed(u).stance_fraction >= 0.657]


def main(tmp: Path, base: Path, t1: Path | None) -> None:
    rows = []
    sessions = []
    if t1 is not None and str(t1) == "long":
        sessions = [("a2 slow, long stance", str(u), simulate(tmp / f"s_{u}", u, True), True)
                    for u in long_stance_users()]
    for u in (SLOW if not sessions else []):
        given = t1 / f"s_{u}" if t1 is not None and u < 12840 else None
        sessions.append(("a slow", str(u), given if given is not None and given.exists()
                         else simulate(tmp / f"s_{u}", u, True), True))
    if not sessions or sessions[0][0] != "a2 slow, long stance":
        sessions += [("b normal", str(u), simulate(tmp / f"s_{u}", u, False), True) for u in NORMAL]
        data = Path("/work/shared/data")
        sessions += [("c real", name, data / name, False) for name in REAL if (data / name).exists()]
    for group, name, session, truth in sessions:
        meta = json.loads((Path(session) / "meta.json").read_text())
        sf = (meta.get("user") or {}).get("stance_fraction")
        for label, code in (("base", base), ("cand", REPO)):
            out = tmp / f"t_{label}_{name}"
            r = measure(Path(session), out, code, truth)
            shutil.rmtree(out, ignore_errors=True)
            rows.append({"group": group, "session": name, "stance_fraction": sf, "code": label, **r})
            print(rows[-1], flush=True)
    df = pd.DataFrame(rows)
    if "true_cv" in df:
        df["cv_bias"] = df["cv"] - df["true_cv"]
    wide = df.pivot_table(index=["group", "session"], columns="code",
                          values=[c for c in ("cv_bias", "f1", "timing_ms", "distance_m", "asym") if c in df],
                          aggfunc="first")
    pd.set_option("display.width", 200)
    print(wide.round(4).to_string())
    for group, g in df[df["true_cv"].notna()].groupby("group") if "true_cv" in df else []:
        for label in ("base", "cand"):
            b = g[g["code"] == label]["cv_bias"].abs()
            print(f"{group} {label}: mean |CV bias| {b.mean():.2f} points, max {b.max():.2f}")


if __name__ == "__main__":
    main(Path(sys.argv[1]), Path(sys.argv[2]), Path(sys.argv[3]) if len(sys.argv) > 3 else None)
