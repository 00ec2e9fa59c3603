"""Decision W520's measurement: how often the step-time asymmetry index calls symmetric slow walkers asymmetric.

Users 14080-14089, symmetric (the simulator's default), 0.4 m steps in 0.80-1.10 s (0.8 + 0.3 k / 9 for user
14080 + k), `stand:3, straight:40, stand:3`, 100 Hz, pendulum bounce, smooth rocker. Each session tracked twice:
the lower back alone (`track --units waist`: L121's index, given from 20 %) and the default foot + lower-back track
(L416's labelled index, L490 / L677's standard error and its "uncertain" note). Truth: the simulator's ics.csv
walk contacts, step times under 1.5 x their median, by the foot they land on.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/slow_asymmetry_s46_w520.py TMPDIR
"""
from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.cli import main

ROUTE = "stand:3, straight:40, stand:3"


def truth(sim: Path) -> tuple[float, float]:
    ics = pd.read_csv(sim / "ics.csv")
    ics = ics[ics["kind"] == "walk"].sort_values("ic_ms")
    d = np.diff(ics["ic_ms"].to_numpy(float) / 1000)
    onto = ics["foot"].to_numpy()[1:]
    ok = d < 1.5 * np.median(d)
    return float(d[ok & (onto == "left")].mean()), float(d[ok & (onto == "right")].mean())


def run(tmp: Path) -> None:
    called_alone = called_two = uncertain = given_two = 0
    for u in range(14080, 14090):
        step_t = 0.8 + 0.3 * (u - 14080) / 9
        sim = tmp / f"u{u}"
        if not (sim / "ics.csv").exists():
            assert main(["simulate", "--route", ROUTE, "--step-length", "0.4", "--step-time", f"{step_t:.3f}",
                         "--bounce", "pendulum", "--rocker", "smooth", "--rate", "100", "--user-seed", str(u),
                         "--out", str(sim), "--force"]) == 0
        tl, tr = truth(sim)
        for name, extra in (("tw", ["--units", "waist"]), ("t2", [])):
            out = tmp / f"{name}_u{u}"
            if not (out / "summary.json").exists():
                assert main(["track", str(sim), *extra, "--out", str(out), "--force"]) == 0
        a = json.load(open(tmp / f"tw_u{u}" / "summary.json"))
        b = json.load(open(tmp / f"t2_u{u}" / "summary.json"))
        noted = "uncertain" in (b["step_time_asymmetry_reason"] or "")
        called_alone += a["step_time_asymmetry_pct"] is not None
        given_two += b["step_time_asymmetry_pct"] is not None
        uncertain += b["step_time_asymmetry_pct"] is not None and noted
        called_two += b["step_time_asymmetry_pct"] is not None and not noted and b["step_time_asymmetry_pct"] >= 20
        print(f"u{u} step {step_t:.3f} s, true L/R {tl:.3f} / {tr:.3f} (SI {200 * abs(tl - tr) / (tl + tr):.2f} %); "
              f"lower back alone: raw {a['step_time_asymmetry_raw_pct']:.2f} % given {a['step_time_asymmetry_pct']}"
              f", L/R {a['step_time_s_left']:.3f} / {a['step_time_s_right']:.3f}; foot + lower back: index "
              f"{b['step_time_asymmetry_pct']} se {b['step_time_asymmetry_se_points']} uncertain {noted}", flush=True)
    print(f"lower back alone: called asymmetric (given, >= 20 %) {called_alone} of 10; foot + lower back: index "
          f"given {given_two} of 10, of them noted uncertain {uncertain}, given >= 20 % without the note "
          f"{called_two}")


if __name__ == "__main__":
    run(Path(sys.argv[1]))
