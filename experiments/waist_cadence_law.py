"""Decision W240's adoption rule for the ``cadence_law`` candidate (waist-pendulum), defaults vs candidate; with
``--candidate steady`` decision W261's rule for ``cadence_law="steady"`` (the law on steady walking steps only).

Prints (rule written in docs/decisions/waist.md before this ran):
(a)/(c) Test11 (mobgap HA001, HA002, MS001; 15 bouts) calibrated on each subject's Test5 walks (experiments/waist.py's
    protocol): median |bout error| vs INDIP ``Length`` (and vs the bouts' strides), pooled and per subject;
(b) the same bouts uncalibrated (meta.json defaults);
(d) Test5, each trial calibrated on the other: each run's distance error and the median |error|;
(e1) fresh simulated users: W211's 20 m walkways at 0.6, 1.0, 1.4, 2.0 m/s (seed user + 1000), calibrated with
    ``--distance 20`` on the user's 1.0 m/s walk (seed user): median |distance error| per speed;
(e2) the same users' scenarios A-D and W150's S41 turning route, calibrated on the simulated 60 m walk (W150's
    protocol, experiments/waist_pivot_steps.py): median |distance error| per scenario.

Run: OMP_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python experiments/waist_cadence_law.py --external datasets/external
     [--users 5860-5919] [--no-sim] [--no-real] [--csv rows.csv] [--candidate law|steady]
W261: ... --candidate steady --users 6320-6379
"""

from __future__ import annotations

import argparse
import logging
import sys
from pathlib import Path

import numpy as np
import pandas as pd

import _results as R  # noqa: E402  (the shared options and tables, E294)
import waist as W  # noqa: E402
import waist_calibration_speed as CS  # noqa: E402  (W211's walkways)
import waist_pivot_steps as PV  # noqa: E402  (W150's protocol: its _track and turning route)
from pdrlearn.track import get_pipeline  # noqa: E402
from pdrlearn.waist.calibration import calibrate  # noqa: E402
from pdrlearn.waist.params import WaistParams, resolve_params  # noqa: E402
from pdrlearn.waist.steplength import steady_steps  # noqa: E402

#: the candidates: W240's law on every calibrated pendulum step, W261's on steady walking steps only
CANDIDATES = {"law": ("cadence_law", {"cadence_law": True}), "steady": ("steady", {"cadence_law": "steady"})}
CONFIGS = {"defaults": {}, "cadence_law": {"cadence_law": True}}  # main() sets the candidate (--candidate)
PIPELINE = "waist-pendulum"


def _candidate() -> str:
    return [k for k in CONFIGS if k != "defaults"][0]


def _gate_counts(res) -> dict:
    """W261 read-out (information, not part of the rule): the run's walking steps, those W261's gate calls steady,
    and those whose window is full with its median cadence in 1.5-2.2 Hz (the gate without its CV limit)."""
    st = res.steps
    t, has_next = 1.0 / st["frequency_hz"].to_numpy(float), st["has_next"].to_numpy(bool)
    scale = WaistParams.from_dict(res.info["params"]).frequency_scale()
    return {"n_walk": int(has_next.sum()), "n_steady": int(steady_steps(t, has_next, frequency_scale=scale).sum()),
            "n_in_range": int(steady_steps(t, has_next, frequency_scale=scale, max_cv=np.inf).sum()),
            "median_cadence_spm": float(60.0 * np.nanmedian(st["frequency_hz"].to_numpy(float)[has_next])),
            "cal_cadence_spm": (res.info["params"].get("gait") or {}).get("median_cadence_spm", np.nan)}


def real(ext: Path) -> pd.DataFrame:
    """One row per (config, run, calibrated?, bout) with the bout's errors (W150's protocol, PV.tracked_runs)."""
    rows = []
    for _, label, cal_names, name, calibrated, res, d in PV.tracked_runs(ext, (PIPELINE,), CONFIGS):
        gate = _gate_counts(res)
        for b in d["bouts"]:
            rows.append({"config": label, "subject": name.split("_")[1], "test": name,
                         "cal": "+".join(cal_names), "calibrated": calibrated,
                         "run_error_pct": d["distance_error_pct"], "err_L": b["error_pct"],
                         "err_strides": b.get("error_strides_pct", np.nan), "bout_s": b.get("start_s"),
                         **gate})
    return pd.DataFrame(rows)


def real_tables(df: pd.DataFrame) -> None:
    t11 = df[df.test.str.contains("_Test11_")].assign(aL=lambda x: x.err_L.abs(), aS=lambda x: x.err_strides.abs())
    pooled = t11.assign(subject="pooled")
    g = pd.concat([t11, pooled]).groupby(["calibrated", "subject", "config"])
    tab = pd.DataFrame({"vs_Length": g.aL.median(), "vs_strides": g.aS.median(), "bouts": g.size()})
    print("(a)/(b)/(c) Test11 median |bout error| vs Length / vs the bouts' strides (%):")
    print(tab.round(3).to_string())
    wide = tab.vs_Length.unstack("config")
    print("\nchange vs Length (candidate - defaults, points):")
    print((wide[_candidate()] - wide["defaults"]).round(3).to_string())
    t5 = df[df.test.str.contains("_Test5_") & df.calibrated]
    runs = t5.groupby(["config", "cal", "test"], sort=False).run_error_pct.first().unstack("config")
    runs["change"] = runs[_candidate()] - runs["defaults"]
    print("\n(d) Test5, each trial calibrated on the other: distance error per run (%):")
    print(runs.round(3).to_string())
    print("(d) median |distance error|: " + ", ".join(f"{c} {runs[c].abs().median():.3f} %" for c in CONFIGS))
    cal11 = t11[t11.calibrated]
    bouts = cal11.pivot_table(index=["subject", "bout_s"], columns="config", values="err_L")
    print("\nTest11 calibrated, each bout's error vs Length (%):")
    print(bouts.round(2).to_string())
    g = cal11.groupby(["subject", "config"]).first()[["n_walk", "n_in_range", "n_steady", "median_cadence_spm",
                                                         "cal_cadence_spm"]]
    print("\nW261's gate on Test11 (information): walking steps, steps in a full window at 1.5-2.2 Hz, steady steps "
          "(also CV <= 0.10), median cadence; and the calibration cadence (steps/min):")
    print(g.round(1).to_string())


def simulated(users: list[int], csv: Path | None = None) -> pd.DataFrame:
    from pdrlearn.sim import UserProfile, simulate, simulate_path
    from pdrlearn.sim.route import parse_route
    from pdrlearn.track.evaluate import evaluate_track

    rows = []
    for u in users:
        user = UserProfile.from_seed(u)
        cal60 = simulate("walk", u, "normal", rate_hz=100.0, seed=1, length_m=60.0)
        cal60_m = W.walked_between_contacts(cal60)
        cal20 = CS.walk(user, 1.0, u)
        tests = {sc: (simulate(sc, u, "normal", rate_hz=100.0), "60") for sc in "ABCD"}
        tests["pivot"] = (simulate_path(parse_route(PV.ROUTE), user, rate_hz=100.0, seed=u), "60")
        walkways = {f"walk {v} m/s": CS.walk(user, v, u + 1000) for v in CS.SPEEDS}
        for label, opts in CONFIGS.items():
            params = {}
            for key, (walk, dist) in {"60": (cal60, cal60_m), "20": (cal20, CS.TRUE_M)}.items():
                base, _ = resolve_params(walk, None)
                base.options = dict(opts)
                params[key] = calibrate([walk], PIPELINE, distances=[dist], params=base)
            for sc, (s, key) in tests.items():
                res = get_pipeline(PIPELINE)(s, params=params[key], **opts)
                rows.append({"user": u, "scenario": sc, "config": label,
                             "dist_err_pct": evaluate_track(res, s).get("distance_error_pct")})
            for sc, s in walkways.items():  # W211's measure: the summed lengths against the 20 m walkway
                res = get_pipeline(PIPELINE)(s, params=params["20"], **opts)
                d = float(res.steps["length_m"].abs().sum())
                rows.append({"user": u, "scenario": sc, "config": label,
                             "dist_err_pct": 100.0 * (d / CS.TRUE_M - 1.0)})
        if csv is not None:  # each user's rows as they come (a long run can be read part-way)
            pd.DataFrame(rows).to_csv(csv, index=False)
        print(f"user {u} done", file=sys.stderr, flush=True)
    return pd.DataFrame(rows)


def sim_table(sim: pd.DataFrame) -> None:
    g = R.change_table(sim, _candidate())
    print(f"\n(e) simulated users {sim.user.min()}-{sim.user.max()} ({sim.user.nunique()}), {PIPELINE} calibrated: "
          "median |distance error| (%):")
    print(g.round(3).to_string())


def main() -> None:
    ap = argparse.ArgumentParser()
    R.add_sim_real(ap, "5860-5919", W.ROOT / "datasets" / "external")
    ap.add_argument("--from-csv", type=Path, default=None, help="print (e) from rows written by --csv")
    ap.add_argument("--candidate", choices=sorted(CANDIDATES), default="law",
                    help="law: W240's cadence_law true; steady: W261's cadence_law \"steady\"")
    args = ap.parse_args()
    label, opts = CANDIDATES[args.candidate]
    CONFIGS.clear()
    CONFIGS.update({"defaults": {}, label: opts})
    logging.disable(logging.WARNING)
    pd.set_option("display.width", 220)
    if not args.no_real:
        real_tables(real(args.external))
    if args.from_csv is not None:
        sim_table(pd.read_csv(args.from_csv))
    elif not args.no_sim:
        sim_table(simulated(list(R.user_range(args.users)), args.csv))


if __name__ == "__main__":
    main()
