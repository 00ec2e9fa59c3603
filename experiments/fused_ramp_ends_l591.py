"""Decision L591: a fused track's gentle ramps start late and run on (trial s41 T4 #2). Judges L591's candidate,
L564's ``fused_climb`` whose stair climbs keep L39's level heights (``apply_altitude(stairs_level=True)``), by
L591's adoption rule (docs/decisions/localization.md): held-out users 11772-11779 on RAMP / STEEP / STAIRS+LEVEL
routes, each tracked ``track --altitude fused --no-plot`` offline without a model, before (today's fusion) and
after (the candidate).

Usage::

    PYTHONPATH=. OMP_NUM_THREADS=1 .venv/bin/python experiments/fused_ramp_ends_l591.py --out DIR
"""

from __future__ import annotations

import argparse
import contextlib
import functools
import io
import json
from pathlib import Path
from unittest import mock

import numpy as np
import pandas as pd

from pdrlearn.cli import main
from pdrlearn.track.altitude import apply_altitude

RAMP = "stand:3, straight:5, slope:15:{g}, straight:12, stand:3"
STEEP = "stand:3, straight:5, slope:15:8.33, straight:5, slope:10:-10, straight:12, stand:3"
STAIRS_LEVEL = "stand:3, straight:5, up:17, turn:180, down:17, straight:20, turn:90, straight:10, stand:3"
#: L591's held-out sessions: (user, kind, route, true grades in walking order)
SESSIONS = ([(u, "ramp", RAMP.format(g=g), (g,)) for u, g in ((11772, 4), (11773, 5), (11774, 6), (11775, 7),
                                                               (11776, -5), (11777, -7))]
            + [(11778, "steep", STEEP, (8.33, -10)), (11779, "stairs", STAIRS_LEVEL, ())])


def truth_ramps(sim: pd.DataFrame) -> list[tuple[float, float]]:
    """The simulator's ramps: (start_s, end_s) of each run of strides with height_m != 0 of one sign."""
    sign = np.sign(sim["height_m"].fillna(0).to_numpy(float))
    out, i = [], 0
    while i < len(sign):
        if sign[i] == 0:
            i += 1
            continue
        j = i
        while j + 1 < len(sign) and sign[j + 1] == sign[i]:
            j += 1
        out.append((sim["start_ms"].iloc[i] / 1000.0, sim["end_ms"].iloc[j] / 1000.0))
        i = j + 1
    return out


def walked(sim: pd.DataFrame, t) -> float:
    """The truth's walked distance (m, cumulative stride length) at time ``t`` (s)."""
    tt = np.concatenate([[sim["start_ms"].iloc[0] / 1000.0], sim["end_ms"].to_numpy(float) / 1000.0])
    return float(np.interp(t, tt, np.concatenate([[0.0], np.cumsum(sim["length_m"].to_numpy(float))])))


def track(session: Path, out: Path, candidate: bool) -> tuple[pd.DataFrame, dict, pd.DataFrame]:
    """``track --altitude fused --no-plot`` of ``session``; with ``candidate`` L591's: L564's ``fused_climb`` whose
    stair climbs keep the levelled heights (``apply_altitude(stairs_level=True)``)."""
    args = []
    if candidate:
        (out.parent / "fc.json").write_text('{"fused_climb": true}')
        args = ["--params", str(out.parent / "fc.json")]
    patch = (mock.patch("pdrlearn.track.plasys.apply_altitude", functools.partial(apply_altitude, stairs_level=True))
             if candidate else contextlib.nullcontext())
    with patch, contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        assert main(["track", str(session), "--altitude", "fused", "--no-plot", "--out", str(out), *args]) == 0
    return (pd.read_csv(out / "ramps.csv"), json.loads((out / "summary.json").read_text()),
            pd.read_csv(out / "stairs.csv"))


def ramp_errors(ramps: pd.DataFrame, sim: pd.DataFrame, grades) -> list[dict]:
    """Per true ramp: the found ramp (ramps.csv row of the true direction with the largest |rise_m|), its start /
    end errors (m along the path, signed: + late) and grade error (points); ``found`` False without one."""
    out = []
    for (t0, t1), g in zip(truth_ramps(sim), grades, strict=False):
        rows = ramps[ramps["direction"] == ("up" if g > 0 else "down")]
        if not len(rows):
            out.append({"grade": g, "found": False})
            continue
        r = rows.loc[rows["rise_m"].abs().idxmax()]
        out.append({"grade": g, "found": True, "start_err_m": walked(sim, r["start_s"]) - walked(sim, t0),
                    "end_err_m": walked(sim, r["end_s"]) - walked(sim, t1),
                    "grade_err": float(r["mean_grade_pct"]) - g, "start_s": float(r["start_s"]),
                    "end_s": float(r["end_s"]), "true": (round(t0, 2), round(t1, 2))})
    return out


def main_(out: Path) -> None:
    out.mkdir(parents=True, exist_ok=True)
    res = {}
    for user, kind, route, grades in SESSIONS:
        s = out / f"u{user}"
        if not (s / "steps.csv").exists():
            with contextlib.redirect_stdout(io.StringIO()):
                assert main(["simulate", "--route", route, "--user-seed", str(user), "--rate", "50",
                             "--out", str(s)]) == 0
        sim = pd.read_csv(s / "steps.csv")
        for mode in ("before", "after"):
            ramps, summ, stairs = track(s, out / f"t{user}_{mode}", mode == "after")
            res[(user, mode)] = {"kind": kind, "ramps": ramp_errors(ramps, sim, grades), "n_ramps": len(ramps),
                                 "n_flights": len(stairs), "floors": (summ.get("floors_up"), summ.get("floors_down")),
                                 "alt_err": abs(summ["altitude_change_m"] - float(sim["height_m"].fillna(0).sum()))}
            print(user, kind, mode, json.dumps(res[(user, mode)], default=str))
    for mode in ("before", "after"):
        r = [e for (u, m), v in res.items() if m == mode and v["kind"] == "ramp" for e in v["ramps"]]
        st = [abs(e["start_err_m"]) for e in r if e["found"]]
        en = [abs(e["end_err_m"]) for e in r if e["found"]]
        print(f"RAMP {mode}: found {sum(e['found'] for e in r)}/{len(r)}, median |start error| "
              f"{np.median(st):.2f} m, median |end error| {np.median(en):.2f} m, mean |grade error| "
              f"{np.mean([abs(e['grade_err']) for e in r if e['found']]):.3f} points")


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, required=True)
    main_(ap.parse_args().out)
