"""Decisions E326 / E327 (session 51, I3): the lean runtime's stance / swing per stride and its two-foot double support
and stance / swing symmetry indices against E311's `run --gait`, offline `gait` and the simulator's truth.

    python experiments/runtime_stance_s51_e326.py 17860 17870 > users.txt   # fresh simulated users 17860-17869
    python experiments/runtime_stance_s51_e326.py 0 0 real > real.txt        # the real gaitmap pairs only (a check)

Sessions go to $OUT (default /tmp/e326), a left and a right foot of one walk each (`simulate --route "stand:2,
straight:20, stand:2" --seed 1 --foot left|right --user-seed U`): 17860-17863 100 Hz, 17864-17865 50 Hz,
17866-17867 `--stance-time-asymmetry 0.15 --longer-stance-side left` (E326's 0.3 is refused by the simulator:
below 0.2) (100 Hz), 17868-17869 `--speed slow` (100 Hz).
Per foot: lean = `pdrlearn.runtime.__main__.replay(units="foot", contacts=True, gait=True)` (numpy only), E311 =
`cli.run_gait.streamed_foot_track`'s table, offline = `track.bilateral.offline_foot_track`'s (`--toe-off`), truth =
the session's steps.csv (`ic_ms`, `tc_ms`). Strides matched by IC (|dIC| <= 20 ms; the truth's within 60 ms,
TRUTH_TOL_S)."""

import json
import logging
import os
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.cli import main
from pdrlearn.cli.run_gait import streamed_foot_track
from pdrlearn.runtime import load_bundle
from pdrlearn.runtime.__main__ import replay
from pdrlearn.runtime.gait import support_measures
from pdrlearn.track.bilateral import offline_foot_track, pair_sessions, read_pair

REAL = Path("/work/shared/data")
EXTERNAL = Path(__file__).resolve().parents[1] / "datasets" / "external"
BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"
TOL_S = 0.020
#: the truth's ICs are matched within this (s): the streamed contact comes ~30 ms after the simulator's (smoke run,
#: user 17860: lean 8.368 / 9.472 s, truth 8.342 / 9.442 s), so 20 ms matched none
TRUTH_TOL_S = 0.060
WALK_KEYS = ("double_support_pct", "stance_time_s_left", "stance_time_s_right", "stance_time_s_si_pct",
             "swing_time_s_si_pct")


def setup(u: int) -> tuple[str, list[str]]:
    k = u - 17860
    if k in (4, 5):
        return "50 Hz", ["--rate", "50"]
    if k in (6, 7):
        return "longer stance left", ["--rate", "100", "--stance-time-asymmetry", "0.15",
                                      "--longer-stance-side", "left"]
    if k in (8, 9):
        return "slow", ["--rate", "100", "--speed", "slow"]
    return "100 Hz", ["--rate", "100"]


def truth_rows(d: Path) -> dict | None:
    """The simulator's per-stride events of this foot (steps.csv: a row's toe-off starts its swing, its IC ends it),
    as :meth:`StrideGait.strides`' arrays (event_s, tc_s, stance_s = tc - the previous row's IC, swing_s)."""
    p = d / "steps.csv"
    if not p.exists():
        return None
    st = pd.read_csv(p)
    if "tc_ms" not in st:
        return None
    ic, tc = st["ic_ms"].to_numpy(float) / 1000, st["tc_ms"].to_numpy(float) / 1000
    prev = np.r_[np.nan, ic[:-1]]
    stance = np.where((tc > prev) & (ic - prev <= 3.0), tc - prev, np.nan)
    return {"event_s": ic, "tc_s": tc, "stance_s": stance, "swing_s": ic - tc, "stride_length_m":
            st["length_m"].abs().to_numpy(float)}


def table_rows(table) -> dict:
    return {"event_s": table["event_s"].to_numpy(float), "tc_s": table["tc_s"].to_numpy(float),
            "stance_s": table["stance_time_s"].to_numpy(float), "swing_s": table["swing_time_s"].to_numpy(float),
            "stance_pct": table["stance_pct"].to_numpy(float)}


def compare(lean: dict, ref: dict, pool: dict, tol_s: float = TOL_S) -> dict:
    ev = lean["event_s"]
    n_ref = n_hit = 0
    d_st, d_sw = [], []
    for i, e in enumerate(ref["event_s"]):
        if not np.isfinite(e) or not np.isfinite(ref["stance_s"][i]):
            continue
        n_ref += 1
        j = int(np.nanargmin(np.abs(ev - e))) if np.isfinite(ev).any() else -1
        if j < 0 or abs(ev[j] - e) > tol_s or not np.isfinite(lean["stance_s"][j]):
            continue
        n_hit += 1
        d_st.append(lean["stance_s"][j] - ref["stance_s"][i])
        if np.isfinite(ref["swing_s"][i]) and np.isfinite(lean["swing_s"][j]):
            d_sw.append(lean["swing_s"][j] - ref["swing_s"][i])
    pool["n_ref"] += n_ref
    pool["n_hit"] += n_hit
    pool["dst"] += d_st
    pool["dsw"] += d_sw
    out = {"n_ref_stance": n_ref, "lean_has": n_hit,
           "med_abs_d_stance_ms": round(1000 * float(np.median(np.abs(d_st))), 3) if d_st else None,
           "med_abs_d_swing_ms": round(1000 * float(np.median(np.abs(d_sw))), 3) if d_sw else None}
    if "stance_pct" in ref:
        a, b = np.nanmedian(lean["stance_pct"]), np.nanmedian(ref["stance_pct"])
        pool["dpct"].append(float(a - b))
        out["median_stance_pct"] = [round(float(a), 3), round(float(b), 3)]
    return out


def _pool() -> dict:
    return {"n_ref": 0, "n_hit": 0, "dst": [], "dsw": [], "dpct": []}


def one_foot(tag: str, side: str, d: Path, bundle, pools: dict, *, sim: bool):
    from pdrlearn.io import read_session

    tracker, _ = replay(BUNDLE, d, units="foot", contacts=True, gait=True)
    mine = tracker.gait_strides()
    refs = [("E311", table_rows(streamed_foot_track(bundle)(read_session(d, streamed=True), False).steps)),
            ("offline", table_rows(offline_foot_track(read_session(d), False).steps))]
    truth = truth_rows(d) if sim else None
    if truth is not None:
        refs.append(("truth", truth))
    for name, ref in refs:
        row = compare(mine, ref, pools[name], TRUTH_TOL_S if name == "truth" else TOL_S)
        print(json.dumps({"tag": tag, "foot": side, "vs": name, "n_lean": len(mine["event_s"]), **row}), flush=True)
    return tracker, truth


def pair(tag: str, left: Path, right: Path, bundle, pools: dict, *, sim: bool = True) -> None:
    read_pair(left, right, streamed=True)  # gait's checks: one walk, one clock
    got = {side: one_foot(tag, side, d, bundle, pools, sim=sim) for side, d in (("left", left), ("right", right))}
    lean = got["left"][0].gait_summary(got["right"][0])
    walks = {"E311": pair_sessions(left, right, streamed=True, track_foot=streamed_foot_track(bundle))["walk"],
             "offline": pair_sessions(left, right)["walk"]}
    if sim and got["left"][1] is not None and got["right"][1] is not None:
        walks["truth"] = support_measures(got["left"][1], got["right"][1])
    for name, walk in walks.items():
        for k in ("double_support_pct", "stance_time_s_si_pct", "swing_time_s_si_pct"):
            if lean.get(k) is not None and walk.get(k) is not None:
                pools["walk"].setdefault(name, {}).setdefault(k, []).append(abs(lean[k] - walk[k]))
    print(json.dumps({"tag": tag, "lean": {k: None if lean.get(k) is None else round(lean[k], 4) for k in WALK_KEYS},
                      "n_support_cycles": lean.get("n_support_cycles"), "si_withheld": lean.get("si_withheld"),
                      **{name: {k: None if walk.get(k) is None else round(walk[k], 4) for k in WALK_KEYS}
                         for name, walk in walks.items()}}), flush=True)


def report(name: str, pool: dict) -> None:
    print(f"vs {name}: lean stance for", pool["n_hit"], "of", pool["n_ref"], "reference stance times,",
          round(100 * pool["n_hit"] / max(pool["n_ref"], 1), 2), "%")
    for k, what in (("dst", "stance"), ("dsw", "swing")):
        v = np.abs(pool[k]) * 1000
        if len(v):
            print(f"vs {name}: median |d {what} time| ms", round(float(np.median(v)), 3), "max",
                  round(float(v.max()), 3), "mean d ms", round(1000 * float(np.mean(pool[k])), 3), "n", len(v))
    if pool["dpct"]:
        v = np.abs(pool["dpct"])
        print(f"vs {name}: per foot |d median stance %| max", round(float(v.max()), 4), "median",
              round(float(np.median(v)), 4), "n", len(v))


def run(first: int, stop: int, real: bool) -> None:
    logging.disable(logging.WARNING)
    bundle = load_bundle(BUNDLE)
    root = Path(os.environ.get("OUT", "/tmp/e326"))
    pools = {"E311": _pool(), "offline": _pool(), "truth": _pool(), "walk": {}}
    for u in range(first, stop):
        label, opts = setup(u)
        for f in ("left", "right"):
            d = root / f"u{u}_{f}"
            if not d.exists():
                assert main(["simulate", "--route", "stand:2, straight:20, stand:2", *opts, "--seed", "1",
                             "--foot", f, "--user-seed", str(u), "--out", str(d)]) == 0
        pair(f"user {u} ({label})", root / f"u{u}_left", root / f"u{u}_right", bundle, pools)
    if real:
        pair("gaitmap_level", REAL / "gaitmap_level_left", REAL / "gaitmap_level_right", bundle, pools, sim=False)
    for name in ("E311", "offline", "truth"):
        if pools[name]["dst"]:
            report(name, pools[name])
    for name, ks in pools["walk"].items():
        for k, v in ks.items():
            print(f"|lean - {name}| {k} median over pairs", round(float(np.median(v)), 3), "max",
                  round(float(np.max(v)), 3), "n", len(v))


if __name__ == "__main__":
    run(int(sys.argv[1]), int(sys.argv[2]), len(sys.argv) > 3)
