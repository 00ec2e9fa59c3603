"""Decision E320 (session 50, I3): the lean runtime's gait values against E311's `run --gait` and offline `gait`.

    python experiments/runtime_gait_s50_e320.py 17100 17120 > users.txt   # fresh simulated users 17100-17119
    python experiments/runtime_gait_s50_e320.py 17120 17140 > e321.txt    # decision E321's fresh users 17120-17139
    python experiments/runtime_gait_s50_e320.py 0 0 real > real.txt        # the real foot pairs only (a check)

Sessions are simulated into $OUT (default /tmp/e320): 17100-17109 / 17120-17129 at 50 Hz, the next tens at 100 Hz,
a left and a right foot of E311's walk each. Per foot: lean = `pdrlearn.runtime.__main__.replay(units="foot",
contacts=True, gait=True)` (numpy only), E311 = `cli.run_gait.streamed_foot_track`'s table, offline = `track.bilateral.
offline_foot_track`'s. Strides matched by IC (|dIC| <= 20 ms)."""

import json
import logging
import os
import sys
from pathlib import Path

import numpy as np

from pdrlearn.cli import main
from pdrlearn.cli.run_gait import streamed_foot_track
from pdrlearn.runtime import load_bundle
from pdrlearn.runtime.__main__ import replay
from pdrlearn.track.bilateral import offline_foot_track, pair_sessions, read_pair
from pdrlearn.track.gait import gait_summary, stride_rows

REAL = Path("/work/shared/data")
EXTERNAL = Path(__file__).resolve().parents[1] / "datasets" / "external"
BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"
TOL_S = 0.020


def reference(table) -> tuple[dict, dict]:
    """A foot table's per-stride arrays and its summary medians (gait's own summary; the stride length's median
    over the stride rows)."""
    valid = stride_rows(table)
    length = np.where(valid, np.abs(table["length_m"].to_numpy(float)), np.nan)
    s = gait_summary(table)
    med_len = float(np.nanmedian(length)) if np.isfinite(length).any() else None
    return ({"event_s": table["event_s"].to_numpy(float), "stride_time_s": table["stride_time_s"].to_numpy(float),
             "stride_length_m": length},
            {"median_stride_time_s": s["median_stride_time_s"], "median_cadence_spm": s["median_cadence_spm"],
             "median_speed_mps": s["median_speed_mps"], "median_stride_length_m": med_len})


def compare(lean: dict, lean_sum: dict, ref: dict, ref_sum: dict, pool: dict) -> dict:
    ev = lean["event_s"]
    n_ref = n_match = 0
    for i, e in enumerate(ref["event_s"]):
        if not np.isfinite(e):
            continue
        j = int(np.nanargmin(np.abs(ev - e))) if np.isfinite(ev).any() else -1
        hit = j >= 0 and abs(ev[j] - e) <= TOL_S
        if np.isfinite(ref["stride_time_s"][i]):
            n_ref += 1
            n_match += bool(hit)
        if not hit:
            continue
        if np.isfinite(ref["stride_time_s"][i]) and np.isfinite(lean["stride_time_s"][j]):
            pool["dt"].append(lean["stride_time_s"][j] - ref["stride_time_s"][i])
        if np.isfinite(ref["stride_length_m"][i]) and np.isfinite(lean["stride_length_m"][j]):
            a, b = lean["stride_length_m"][j], ref["stride_length_m"][i]
            pool["dl"].append(100 * (a - b) / b)
    pool["n_ref"] += n_ref
    pool["n_match"] += n_match
    d = {}
    for k in ("median_stride_time_s", "median_cadence_spm", "median_speed_mps", "median_stride_length_m"):
        a, b = lean_sum[k], ref_sum[k]
        d[k] = None if a is None or b is None else (a - b if k in ("median_stride_time_s", "median_cadence_spm")
                                                    else 100 * (a - b) / b)
        if d[k] is not None:
            pool[k].append(d[k])
    return {"n_ref": n_ref, "matched": n_match, **{f"d_{k}": None if v is None else round(v, 5) for k, v in d.items()}}


def _pool() -> dict:
    return {"n_ref": 0, "n_match": 0, "dt": [], "dl": [], "median_stride_time_s": [], "median_cadence_spm": [],
            "median_speed_mps": [], "median_stride_length_m": []}


def one_foot(tag: str, side: str, d: Path, bundle, pools: dict):
    """One foot session: the lean tracker's values against E311's and offline's tables; the tracker."""
    from pdrlearn.io import read_session

    tracker, _ = replay(BUNDLE, d, units="foot", contacts=True, gait=True)
    mine, mine_sum = tracker.gait_strides(), tracker.gait_summary()
    for name, table in (("E311", streamed_foot_track(bundle)(read_session(d, streamed=True), False).steps),
                        ("offline", offline_foot_track(read_session(d), False).steps)):
        ref, ref_sum = reference(table)
        row = compare(mine, mine_sum, ref, ref_sum, pools[name])
        print(json.dumps({"tag": tag, "foot": side, "vs": name, "n_lean": len(mine["event_s"]), **row}), flush=True)
    return tracker


def pair(tag: str, left: Path, right: Path, bundle, pools: dict, *, paired: bool = True) -> None:
    """Both feet (:func:`one_foot`) and, ``paired`` (one walk on one clock), the symmetry indices against
    `run --gait`'s walk."""
    if paired:
        read_pair(left, right, streamed=True)  # gait's checks: one walk, one clock
    lean = {side: one_foot(tag, side, d, bundle, pools) for side, d in (("left", left), ("right", right))}
    if not paired:
        return
    both = lean["left"].gait_summary(lean["right"])
    walk = pair_sessions(left, right, streamed=True, track_foot=streamed_foot_track(bundle))["walk"]
    for k in ("stride_time_s_si_pct", "stride_length_m_si_pct"):  # decision E321's rule
        if both[k] is not None and walk[k] is not None:
            pools["si"].setdefault(k, []).append(abs(both[k] - walk[k]))
    print(json.dumps({"tag": tag, "si": {k: (None if both[k] is None else round(both[k], 3)) for k in
                                         ("stride_time_s_si_pct", "stride_length_m_si_pct")},
                      "run_gait_si": {k: (None if walk[k] is None else round(walk[k], 3)) for k in
                                      ("stride_time_s_si_pct", "stride_length_m_si_pct")},
                      "si_withheld": both["si_withheld"]}), flush=True)


def report(name: str, pool: dict) -> None:
    print(f"vs {name}: matched", pool["n_match"], "of", pool["n_ref"], "reference strides with a stride time,",
          round(100 * pool["n_match"] / max(pool["n_ref"], 1), 2), "%")
    print(f"vs {name}: median |d stride time| ms", round(1000 * float(np.median(np.abs(pool["dt"]))), 3),
          "max", round(1000 * float(np.max(np.abs(pool["dt"]))), 3), "n", len(pool["dt"]))
    print(f"vs {name}: median |d stride length| %", round(float(np.median(np.abs(pool["dl"]))), 4),
          "max", round(float(np.max(np.abs(pool["dl"]))), 4), "n", len(pool["dl"]))
    for k, unit in (("median_stride_time_s", "ms"), ("median_cadence_spm", "steps/min"), ("median_speed_mps", "%"),
                    ("median_stride_length_m", "%")):
        v = np.abs(pool[k]) * (1000 if unit == "ms" else 1)
        print(f"vs {name}: summary |d {k}| {unit} median over feet", round(float(np.median(v)), 4),
              "max", round(float(np.max(v)), 4), "n", len(v))


def run(first: int, stop: int, real: bool) -> None:
    logging.disable(logging.WARNING)
    bundle = load_bundle(BUNDLE)
    root = Path(os.environ.get("OUT", "/tmp/e320"))
    pools = {"E311": _pool(), "offline": _pool(), "si": {}}
    for u in range(first, stop):
        rate = "50" if (u // 10) % 2 == 0 else "100"  # 17100-17109, 17120-17129: 50 Hz; the next tens 100 Hz
        for f in ("left", "right"):
            d = root / f"u{u}_{f}"
            if not d.exists():
                assert main(["simulate", "--route", "stand:2, straight:20, stand:2", "--rate", rate, "--seed", "1",
                             "--foot", f, "--user-seed", str(u), "--out", str(d)]) == 0
        pair(f"user {u} ({rate} Hz)", root / f"u{u}_left", root / f"u{u}_right", bundle, pools)
    if real:
        pair("gaitmap_level", REAL / "gaitmap_level_left", REAL / "gaitmap_level_right", bundle, pools)
        for name in ("gaitmap_ms", "gaitmap_walk4x10"):  # datasets/external's foot pairs (a check too)
            if (EXTERNAL / f"{name}_left").is_dir():
                pair(name, EXTERNAL / f"{name}_left", EXTERNAL / f"{name}_right", bundle, pools,
                     paired=False)  # each foot alone: gait refuses the pair (not one clock)
    for name in ("E311", "offline"):
        if pools[name]["dt"]:
            report(name, pools[name])
    for k, v in pools["si"].items():
        print(f"|lean - run --gait| {k} (points) median over pairs", round(float(np.median(v)), 3),
              "max", round(float(np.max(v)), 3), "n", len(v))


if __name__ == "__main__":
    run(int(sys.argv[1]), int(sys.argv[2]), len(sys.argv) > 3)
