"""Decision W519's measurement: a lower-back ramp must rise more than 2 x the barometer's rest swing.

(a) users 14070-14079, level walks with barometer noise and weather drift (`--baro-drift 3`), 14070-14074 slow
(0.3 m / 0.85 s steps), 14075-14079 default pace: ramps without and with the rule (the truth: none);
(b) W517's ramp sessions (users 12910-12919, its route with four ramps; 12910-12914 slow): true ramps found (a ramp
of its direction overlapping the true ramp's time), mean |rise error| and extra ramps, without and with the rule;
(a1) the same with `--baro-drift 1` (W519's second rule);
(c) the real HA001 Test11 Trial1 (INDIP: no incline in any bout).
Each track once (`track --units waist`); "without" is the same steps.csv read with W519's floor off.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/ramps_rest_swing_s46_w519.py TMPDIR [a|a1|b|c]
"""
from __future__ import annotations

import sys
from pathlib import Path
from unittest import mock

import numpy as np
import pandas as pd

from pdrlearn.cli import main
from pdrlearn.track import grade

LEVEL = ("stand:4, straight:15, stand:3, straight:15, stand:3, turn:180, straight:15, stand:3, straight:15, "
         "stand:4")
RAMPS = ("stand:5, straight:4, slope:9:8.33, stand:4, straight:6, slope:10:5, stand:6, turn:180, stand:2, "
         "slope:10:-5, straight:6, stand:4, slope:9:-8.33, straight:4, stand:5")
TRUE_RISE = (0.75, 0.50, -0.50, -0.75)
SLOW = ["--step-length", "0.3", "--step-time", "0.85"]


def session(tmp: Path, name: str, route: str, user: int, extra: list[str]) -> Path:
    sim, out = tmp / name, tmp / f"t_{name}"
    if not (sim / "meta.json").exists():
        assert main(["simulate", "--route", route, "--rate", "100", "--bounce", "pendulum", "--user-seed",
                     str(user), "--out", str(sim), "--force", *extra]) == 0
    if not (out / "steps.csv").exists():
        assert main(["track", str(sim), "--units", "waist", "--out", str(out), "--force"]) == 0
    return sim


def ramps(steps: pd.DataFrame, rule: bool) -> list[dict]:
    info = {"grade_source": "barometer"}
    if rule:
        return grade.track_ramps(steps, info)[0]
    with mock.patch.object(grade, "rest_rise_floor_m", lambda _steps: None):
        return grade.track_ramps(steps, info)[0]


def true_spans(sim: Path) -> list[tuple[float, float]]:
    """The four ramps' times, in walking order: where the body's height (trajectory.csv z) averaged over 2 s (its
    step bounce out) changes by more than 8 mm/s (a 1:20 ramp at 0.35 m/s climbs 17.5 mm/s) for over 5 s."""
    tr = pd.read_csv(sim / "trajectory.csv")
    t, z = tr["timestamp"].to_numpy(float) / 1000, tr["z"].to_numpy(float)
    k = max(1, int(round(2.0 / float(np.median(np.diff(t))))))
    zs = np.convolve(z, np.ones(k) / k, mode="same")
    moving = np.abs(np.gradient(zs, t)) > 0.008
    edges = np.flatnonzero(np.diff(np.r_[0, moving.astype(int), 0]))
    return [(t[a], t[b - 1]) for a, b in zip(edges[::2], edges[1::2], strict=True) if t[b - 1] - t[a] > 5.0]


def part_a(tmp: Path, drift: str = "3", name: str = "level") -> None:
    n = {False: 0, True: 0}
    for u in range(14070, 14080):
        sim = session(tmp, f"{name}_u{u}", LEVEL, u, ["--baro-drift", drift, *(SLOW if u < 14075 else [])])
        st = pd.read_csv(tmp / f"t_{sim.name}" / "steps.csv")
        got = {rule: ramps(st, rule) for rule in (False, True)}
        for rule in got:
            n[rule] += len(got[rule])
        floor = grade.rest_rise_floor_m(st)
        print(f"{name} u{u}: ramps without {len(got[False])} {[round(r['rise_m'], 3) for r in got[False]]}, with "
              f"{len(got[True])}; floor {floor if floor is None else round(floor, 3)} m", flush=True)
    print(f"{name} (--baro-drift {drift}): ramps on the 10 level walks without the rule {n[False]}, with {n[True]}")


def part_b(tmp: Path) -> None:
    tot = {False: [0, [], 0], True: [0, [], 0]}
    for u in range(12910, 12920):
        sim = session(tmp, f"ramps_u{u}", RAMPS, u, SLOW if u < 12915 else [])
        st = pd.read_csv(tmp / f"t_{sim.name}" / "steps.csv")
        spans = true_spans(sim)
        floor = grade.rest_rise_floor_m(st)
        for rule in (False, True):
            got = ramps(st, rule)
            t0 = [float(st["start_s"].iloc[r["first"]]) for r in got]
            t1 = [float(st["end_s"].iloc[r["last"]]) for r in got]
            used = set()
            for (a, b), rise in zip(spans, TRUE_RISE, strict=False):
                hit = [k for k, r in enumerate(got) if t0[k] < b and t1[k] > a
                       and r["direction"] == ("up" if rise > 0 else "down")]
                used |= set(hit)
                tot[rule][0] += bool(hit)
                tot[rule][1].append(abs(sum(got[k]["rise_m"] for k in hit) - rise) if hit else abs(rise))
            tot[rule][2] += len(got) - len(used)
            print(f"b u{u} {'with' if rule else 'without'}: {len(spans)} true spans, ramps "
                  f"{[(round(a, 1), round(b, 1), round(r['rise_m'], 2)) for a, b, r in zip(t0, t1, got, strict=True)]}"
                  f"; floor {floor if floor is None else round(floor, 3)} m", flush=True)
    for rule in (False, True):
        f, err, extra = tot[rule]
        print(f"b {'with' if rule else 'without'} the rule: true ramps found {f} / 40, mean |rise error| "
              f"{np.mean(err):.3f} m, extra ramps {extra}")


def part_c(tmp: Path) -> None:
    out = tmp / "t_test11"
    if not (out / "steps.csv").exists():
        assert main(["track", "datasets/real/mobgap_HA001_Test11_Trial1", "--out", str(out), "--force"]) == 0
    st = pd.read_csv(out / "steps.csv")
    for rule in (False, True):
        got = ramps(st, rule)
        print(f"c Test11 {'with' if rule else 'without'}: {len(got)} ramps "
              f"{[(float(st['start_s'].iloc[r['first']]), round(r['rise_m'], 3)) for r in got]}")
    print(f"c Test11 floor {grade.rest_rise_floor_m(st):.3f} m")


if __name__ == "__main__":
    tmp = Path(sys.argv[1])
    parts = sys.argv[2:] or ["a", "b", "c"]
    for p in parts:
        {"a": part_a, "a1": lambda t: part_a(t, "1", "level1"), "b": part_b, "c": part_c}[p](tmp)
