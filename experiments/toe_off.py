"""Decision L73: toe-off (tc_s), stance and swing time of the foot strides against mocap and the simulator.

Run: ``PYTHONPATH=$PWD python experiments/toe_off.py`` (datasets/external linked for the stair/turn walks).
Part 1 (the rule): gaitmap_level_left/right, strides matched to the mocap ones by their IC within 0.15 s (a
reference row spanning two strides, ic - pre_ic > 1.5 x the median, left out, as experiments/gait_parameters.py);
TC error = tc_s - mocap tc; stance error = stance_time_s - (tc - pre_ic); swing error = swing_time_s - (ic - tc).
Part 2 (the rule): the simulator (`walk`, 100 m, user seeds 1-3; its steps.csv tc_s is the scheduled toe-off),
tracked with the default M3 engine without a model; strides matched the same way to the simulated strides of
the instrumented foot.
Part 3 (no rule): the stair and turn recordings - ranges of stance/swing/stance %, no reference.
"""

from __future__ import annotations

import logging
import sys
import tempfile
from pathlib import Path

import numpy as np

from pdrlearn.io import read_session
from pdrlearn.track import get_pipeline

logging.disable(logging.WARNING)
ROOT = Path(__file__).resolve().parents[1] / "datasets"
LEVEL = ["real/gaitmap_level_left", "real/gaitmap_level_right"]
OTHER = ["real/gaitmap_stairs_up_left", "real/gaitmap_stairs_down_left", "external/gaitmap_stairs_up_right",
         "external/gaitmap_stairs_down_right", "external/gaitmap_ms_left", "external/gaitmap_ms_right",
         "external/gaitmap_lwalk", "external/gaitmap_walk4x10_left", "external/gaitmap_walk4x10_right"]


def stats(e: np.ndarray) -> str:
    e = e[np.isfinite(e)] * 1000.0
    if not len(e):
        return "none"
    return (f"n={len(e)} median {np.median(e):+.1f} ms, median |err| {np.median(np.abs(e)):.1f} ms, "
            f"mean {e.mean():+.1f}, SD {e.std(ddof=1) if len(e) > 1 else 0:.1f}, max |err| {np.abs(e).max():.1f}")


def errors(res, ref, check_span: bool = True) -> dict:
    t = res.steps
    ev = t["event_s"].to_numpy(float)
    r_ic, r_tc = ref["ic_s"].to_numpy(float), ref["tc_s"].to_numpy(float)
    j = np.array([np.nanargmin(np.abs(ev - x)) for x in r_ic])
    hit = np.abs(ev[j] - r_ic) <= 0.15
    out = {"tc": np.where(hit, t["tc_s"].to_numpy(float)[j] - r_tc, np.nan),
           "swing": np.where(hit, t["swing_time_s"].to_numpy(float)[j] - (r_ic - r_tc), np.nan)}
    if "pre_ic_s" in ref:
        r_st = (ref["ic_s"] - ref["pre_ic_s"]).to_numpy(float)
        if check_span:
            hit &= r_st <= 1.5 * np.nanmedian(r_st)
        out["stance"] = np.where(hit, t["stance_time_s"].to_numpy(float)[j] - (r_tc - ref["pre_ic_s"].to_numpy(float)),
                                 np.nan)
        out["tc"] = np.where(hit, out["tc"], np.nan)
        out["swing"] = np.where(hit, out["swing"], np.nan)
    out["n"] = (len(ref), int(hit.sum()), len(t))
    return out


def tracked(rels: list[str], missing: str = ""):
    """(rel, session, result of the plasys pipeline with toe-off) for each recording that is there."""
    for rel in rels:
        path = ROOT / rel
        if not path.exists():
            print(f"{rel}: missing{missing}")
            continue
        s = read_session(path)
        yield rel, s, get_pipeline("plasys")(s, toe_off=True)


def level() -> bool:
    ok = True
    for rel, s, res in tracked(LEVEL):
        e = errors(res, s.steps)
        print(f"{rel}: reference {e['n'][0]}, matched {e['n'][1]}, tracked {e['n'][2]}")
        for k in ("tc", "stance", "swing"):
            print(f"  {k} error: {stats(e[k])}")
        tc, st = e["tc"][np.isfinite(e["tc"])], e["stance"][np.isfinite(e["stance"])]
        rule = np.median(np.abs(tc)) <= 0.020 and np.std(st, ddof=1) <= 0.030
        print(f"  rule (median |TC err| <= 20 ms, stance SD <= 30 ms): {'met' if rule else 'NOT met'}")
        ok &= bool(rule)
    return ok


def simulated() -> bool:
    from typer.testing import CliRunner

    from pdrlearn.cli import app

    pooled = {"tc": [], "stance": [], "swing": []}
    with tempfile.TemporaryDirectory() as tmp:
        for u in (1, 2, 3):
            out = Path(tmp) / f"walk_u{u}"
            r = CliRunner().invoke(app, ["simulate", "--scenario", "walk", "--length-m", "100", "--user-seed",
                                         str(u), "--out", str(out)])
            if r.exit_code:
                print(r.output)
                raise SystemExit(1)
            paths = [p.parent for p in out.rglob("steps.csv")]
            for p in paths:
                s = read_session(p)
                res = get_pipeline("plasys")(s, toe_off=True)
                ref = s.steps
                if "foot" in ref:  # the instrumented foot's strides
                    foot = res.info.get("foot_side") or ref["foot"].mode().iloc[0]
                    ref = ref[ref["foot"] == foot]
                ref = ref.reset_index(drop=True)
                ref = ref.assign(pre_ic_s=np.concatenate([[np.nan], ref["ic_s"].to_numpy(float)[:-1]]))
                e = errors(res, ref)
                print(f"sim walk u{u} ({p.name}): reference {e['n'][0]}, matched {e['n'][1]}, tracked {e['n'][2]}")
                for k in pooled:
                    print(f"  {k} error: {stats(e[k])}")
                    pooled[k].append(e[k])
    for k in pooled:
        print(f"sim pooled {k} error: {stats(np.concatenate(pooled[k]))}")
    tc = np.concatenate(pooled["tc"])
    rule = np.nanmedian(np.abs(tc)) <= 0.020
    print(f"sim rule (pooled median |TC err| <= 20 ms): {'met' if rule else 'NOT met'}")
    return bool(rule)


def others() -> None:
    for rel, s, res in tracked(OTHER, " (link datasets/external)"):
        t = res.steps
        line = [f"{rel}: {len(t)} strides, tc_s on {int(np.isfinite(t['tc_s']).sum())}"]
        for c, sc in (("stance_time_s", 1000), ("swing_time_s", 1000), ("stance_pct", 1)):
            v = t[c].to_numpy(float)
            v = v[np.isfinite(v)] * sc
            u = "%" if c == "stance_pct" else " ms"
            line.append(f"{c} {len(v)}: " + (f"median {np.median(v):.0f}{u} [{v.min():.0f}, {v.max():.0f}]"
                                             if len(v) else "none"))
        print("; ".join(line))
        if s.steps is not None and "tc_s" in s.steps and "ic_s" in s.steps:
            e = errors(res, s.steps, check_span="pre_ic_s" in s.steps)
            print(f"  vs its reference: tc error {stats(e['tc'])}")


if __name__ == "__main__":
    parts = sys.argv[1:] or ["level", "sim", "other"]
    verdict = []
    if "level" in parts:
        verdict.append(level())
    if "sim" in parts:
        verdict.append(simulated())
    if "other" in parts:
        others()
    if verdict:
        print(f"L73 rule: {'met' if all(verdict) else 'NOT met'}")
