"""Decision W557's measurement (session 49, I3): the lower back's step-time / stride-time CV, step-time and
step-length asymmetry against the simulator's truth (ics.csv) and the foot unit's values, on fresh users.

Groups (100 Hz, route ``stand:3, straight:60, stand:3`` unless named):
``normal`` 16300-16311 (the user's own variability), ``var`` 16312-16315 (``--variability 2.5``), ``hd``
16316-16319 (``--variability 2.5 --trunk-jerks 1``, a Huntington's-like walker), ``sta`` 16320-16322
(``--step-time-asymmetry 0.2``), ``sla`` 16323-16325 (``--step-length-asymmetry 0.15``), ``track`` 16326-16329 (a
race walker's track session: ``--speed fast``, 84 m straight, a 180 deg bend of 36.5 m radius, 40 m straight;
step-length asymmetry 0 / 0.1 / 0 / 0.1; both feet simulated and paired by ``pdrlearn gait``).
Decision C208's check (16330-16349, ``gait`` pairs only): 16330-16341 track sessions, 16342-16349 straight 30 m walks
from standing to standing, step-length asymmetry 0 / 0.05 / 0.1 / 0.15 by ``uid % 4``; run once with main's code
(``PYTHONPATH=/work/main``) and once with this branch's.

Per session: the truth from ics.csv (steady steps: each walk's first and last 2 contacts out), the lower back's from
``track --units waist`` (summary.json and steps.csv: ``start_s`` is the contact, ``side`` its foot), the foot's from
the default track (summary ``stride_time_cv_pct``, L416's ``step_time_asymmetry_pct``), and for ``track`` the
``gait`` pair's ``step_length_m_si_pct`` against its ``reference`` (ics.csv's step lengths, L540).

Run: PYTHONPATH=. nice python experiments/gait_variability_s49_w557.py OUTDIR [FIRST LAST]
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

ROUTE = "stand:3, straight:60, stand:3"
TRACK_ROUTE = "stand:3, straight:84, curve:180:36.5, straight:40, stand:3"
#: C208's straight pairs: one straight length from standing to standing (L310's anchored walk)
STRAIGHT_ROUTE = "stand:3, straight:30, stand:3"


def group(uid: int) -> tuple[str, list[str]]:
    """The group of a user of W557's measurement (16300-16329) or C208's check (16330-16349) and its options."""
    k = (uid - 16300) % 30 if uid < 16330 else None
    if k is None:  # C208's fresh pairs: 16330-16341 track sessions, 16342-16349 straight walks (L310's kind)
        a = (0.0, 0.05, 0.1, 0.15)[uid % 4]
        asym = ["--step-length-asymmetry", str(a)] if a else []
        return ("track", ["--speed", "fast"] + asym) if uid < 16342 else ("straight", asym)
    if k < 12:
        return "normal", []
    if k < 16:
        return "var", ["--variability", "2.5"]
    if k < 20:
        return "hd", ["--variability", "2.5", "--trunk-jerks", "1"]
    if k < 23:
        return "sta", ["--step-time-asymmetry", "0.2"]
    if k < 26:
        return "sla", ["--step-length-asymmetry", "0.15"]
    return "track", ["--speed", "fast"] + (["--step-length-asymmetry", "0.1"] if k % 2 else [])


def _run(*args: str) -> None:
    subprocess.run([sys.executable, "-m", "pdrlearn", *args], check=True, capture_output=True, text=True)


def si(a: float, b: float) -> float:
    """The symmetry index 100 |a - b| / (0.5 (a + b)) (Robinson et al. 1987)."""
    return float(100.0 * abs(a - b) / (0.5 * (a + b)))


def cv(x) -> float:
    x = np.asarray(x, float)
    x = x[np.isfinite(x)]
    return float(100.0 * x.std(ddof=1) / x.mean()) if len(x) > 2 else float("nan")


def truth(session: Path) -> dict:
    """Step / stride-time CV and asymmetries of ics.csv's walk contacts (first and last 2 out)."""
    ics = pd.read_csv(session / "ics.csv")
    ics = ics[ics["kind"] == "walk"].reset_index(drop=True) if "kind" in ics else ics
    t = ics["ic_ms"].to_numpy(float) / 1000.0
    foot = ics["foot"].to_numpy()
    keep = slice(2, len(t) - 2)
    step = np.diff(t, prepend=np.nan)[keep]
    onto = foot[keep]
    stride = (t[2:] - t[:-2])[1:-1]
    out = {"true_step_cv": cv(step), "true_stride_cv": cv(stride),
           "true_step_time_si": si(np.nanmean(step[onto == "left"]), np.nanmean(step[onto == "right"]))}
    if "step_length_m" in ics:
        sl = ics["step_length_m"].to_numpy(float)[keep]
        out["true_step_length_si"] = si(np.nanmean(sl[onto == "left"]), np.nanmean(sl[onto == "right"]))
    return out


def lower_back(track: Path) -> dict:
    """The lower back's CVs and asymmetries: steps.csv's contacts inside each bout (first and last 2 out)."""
    s = json.loads((track / "summary.json").read_text())
    st = pd.read_csv(track / "steps.csv").sort_values("start_s")
    bouts = pd.read_csv(track / "bouts.csv")
    steps, strides, lengths, sides = [], [], [], []
    for _, b in bouts.iterrows():
        rows = st[(st["start_s"] >= b["start_s"] - 1e-6) & (st["start_s"] <= b["end_s"] + 1e-6)]
        t = rows["start_s"].to_numpy(float)
        if len(t) < 8:
            continue
        steps += list(np.diff(t)[2:-2])
        strides += list((t[2:] - t[:-2])[2:-2])
        lengths += list(rows["length_m"].to_numpy(float)[2:-2])
        sides += list(rows["side"].to_numpy()[2:-2])
    lengths, sides = np.asarray(lengths, float), np.asarray(sides)
    sl = (si(lengths[sides == "left"].mean(), lengths[sides == "right"].mean())
          if (sides == "left").any() and (sides == "right").any() else float("nan"))
    return {"lb_step_cv": cv(steps), "lb_stride_cv": cv(strides), "lb_step_length_si": sl,
            "lb_stride_time_cv_pct": s.get("stride_time_cv_pct"),
            "lb_step_time_si_raw": s.get("step_time_asymmetry_raw_pct"),
            "lb_step_time_si": s.get("step_time_asymmetry_pct"), "lb_n_steps": s.get("n_steps")}


def foot(track: Path) -> dict:
    s = json.loads((track / "summary.json").read_text())
    return {"foot_stride_cv": s.get("stride_time_cv_pct"), "foot_step_time_si": s.get("step_time_asymmetry_pct")}


def measure(uid: int, out: Path) -> dict:
    name, extra = group(uid)
    route = {"track": TRACK_ROUTE, "straight": STRAIGHT_ROUTE}.get(name, ROUTE)
    ses = out / f"u{uid}"
    _run("simulate", "--route", route, "--rate", "100", "--user-seed", str(uid), "--out", str(ses), "--force", *extra)
    row = {"user": uid, "group": name, **truth(ses)}
    if name in ("track", "straight"):  # the race walker's pair: step-length asymmetry from two feet (L310)
        left = out / f"u{uid}_left"
        _run("simulate", "--route", route, "--rate", "100", "--user-seed", str(uid), "--foot", "left", "--out",
             str(left), "--force", *extra)
        _run("gait", str(left), str(ses), "--out", str(out / f"g{uid}"), "--force")
        g = json.loads((out / f"g{uid}" / "gait_summary.json").read_text())
        ref = g.get("reference") or {}
        row |= {"gait_step_length_si": g["walk"].get("step_length_m_si_pct"),
                "ref_step_length_si": (ref.get("walk") or ref).get("step_length_m_si_pct"),
                "gait_scale_pct": g["walk"].get("step_length_scale_pct"),
                "gait_step_length_left": g["walk"].get("step_length_m_left"),
                "gait_step_length_right": g["walk"].get("step_length_m_right")}
        return row
    _run("track", str(ses), "--units", "waist", "--out", str(out / f"w{uid}"), "--force")
    _run("track", str(ses), "--out", str(out / f"f{uid}"), "--force")
    return row | lower_back(out / f"w{uid}") | foot(out / f"f{uid}")


def main(argv: list[str]) -> None:
    out = Path(argv[0])
    first, last = (int(argv[1]), int(argv[2])) if len(argv) > 2 else (16300, 16329)
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for uid in range(first, last + 1):
        rows.append(measure(uid, out))
        print(json.dumps(rows[-1]), flush=True)
    table = pd.DataFrame(rows)
    table.to_csv(out / f"w557_{first}_{last}.csv", index=False)
    with pd.option_context("display.width", 250, "display.max_columns", 40, "display.precision", 2):
        print(table.to_string(index=False))
        print(table.groupby("group").median(numeric_only=True).to_string())


if __name__ == "__main__":
    main(sys.argv[1:])
