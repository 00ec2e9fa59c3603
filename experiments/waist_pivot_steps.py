"""Decision W150's adoption rule for the pivot-step candidate (option ``pivot_steps``), defaults vs candidate.

Prints, for ``waist-pendulum`` (deciding) and ``waist-pll`` (information):
(a) pooled Test11 (mobgap HA001, HA002, MS001; 15 bouts): median |bout error| vs INDIP ``Length`` and vs the bouts'
    strides, calibrated on each subject's Test5 walks (experiments/waist.py's protocol);
(b) the same bouts with meta.json defaults (no calibration);
(c) Test5 straight walks, each trial calibrated on the other (6 runs): the distance error of each run;
(d) fresh simulated users (default 2760-2819, 100 Hz, each calibrated on its simulated 60 m walk as
    experiments/waist.py): the median |distance error| of scenarios A-D and of the S41 turning route
    ``straight:6, pivot:180, straight:6, pivot:-90, straight:4`` (waist-pendulum only);
and the demo row (HA001 Test11 calibrated on Test5 Trial1 only).

Run: PYTHONPATH=. .venv/bin/python experiments/waist_pivot_steps.py [--external datasets/external]
     [--users 2760-2819] [--no-sim] [--no-real] [--csv rows.csv]
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import numpy as np
import pandas as pd

import _results as R  # noqa: E402  (the shared options and tables, E294)
import waist as W  # noqa: E402
from pdrlearn.io import read_session  # noqa: E402
from pdrlearn.track import get_pipeline  # noqa: E402
from pdrlearn.waist.calibration import calibrate  # noqa: E402
from pdrlearn.waist.evaluate import distance_metrics  # noqa: E402
from pdrlearn.waist.params import resolve_params  # noqa: E402

CONFIGS = {"defaults": {}, "pivot_steps": {"pivot_steps": True}}
PIPELINES = ("waist-pendulum", "waist-pll")
ROUTE = "straight:6, pivot:180, straight:6, pivot:-90, straight:4"  # decision S41's turning route


def _track(pipeline: str, opts: dict, test, cal=None, distances=None):
    params = None
    if cal is not None:
        base, _ = resolve_params(cal[0], None)
        base.options = dict(opts)
        params = calibrate(cal, pipeline, params=base, distances=distances)
    return get_pipeline(pipeline)(test, params=params, **opts)


def tracked_runs(ext: Path, pipelines, configs: dict):
    """W150's real protocol (experiments/waist.py's runs of ``ext``): per pipeline, config (label, options), run and
    calibration (a Test11 run calibrated on its subject's Test5 walks and not; a Test5 run on the other trial),
    ``(pipeline, label, cal_names, name, calibrated, result, distance_metrics)``; each recording read once."""
    runs = W.external_runs(ext)
    cache: dict[str, object] = {}

    def sess(n):
        if n not in cache:
            cache[n] = read_session(ext / n)
        return cache[n]

    for pipeline in pipelines:
        for label, opts in configs.items():
            for cal_names, name in runs:
                test = sess(name)
                for calibrated in (True, False) if "_Test11_" in name else (True,):
                    res = _track(pipeline, opts, test, [sess(c) for c in cal_names] if calibrated else None)
                    yield pipeline, label, cal_names, name, calibrated, res, distance_metrics(res.steps, test)


def real(ext: Path) -> pd.DataFrame:
    """One row per (pipeline, config, run, calibrated?) with its bouts' errors."""
    rows = []
    for pipeline, label, cal_names, name, calibrated, _, d in tracked_runs(ext, PIPELINES, CONFIGS):
        for b in d["bouts"]:
            rows.append({"pipeline": pipeline, "config": label, "test": name, "cal": "+".join(cal_names),
                         "calibrated": calibrated, "run_error_pct": d["distance_error_pct"],
                         "err_L": b["error_pct"], "err_strides": b.get("error_strides_pct", np.nan)})
    return pd.DataFrame(rows)


def real_tables(df: pd.DataFrame) -> None:
    t11 = df[df.test.str.contains("_Test11_")]
    g = t11.assign(aL=t11.err_L.abs(), aS=t11.err_strides.abs()).groupby(["pipeline", "calibrated", "config"])
    print("(a)/(b) pooled Test11, median |bout error| vs Length / vs the bouts' strides (%), bouts:")
    print(pd.DataFrame({"vs_Length": g.aL.median(), "vs_strides": g.aS.median(), "bouts": g.size()}).round(2)
          .to_string())
    t5 = df[df.test.str.contains("_Test5_") & df.calibrated]
    runs = t5.groupby(["pipeline", "config", "cal", "test"], sort=False).run_error_pct.first().unstack("config")
    runs["change"] = runs["pivot_steps"] - runs["defaults"]
    print("\n(c) Test5, each trial calibrated on the other: distance error per run (%):")
    print(runs.round(3).to_string())


def demo(ext: Path) -> None:
    test = read_session(ext / "mobgap_HA001_Test11_Trial1")
    cal = [read_session(ext / "mobgap_HA001_Test5_Trial1")]
    for label, opts in CONFIGS.items():
        d = distance_metrics(_track("waist-pendulum", opts, test, cal).steps, test)
        print(f"demo HA001 Test11 (calibrated on Test5 Trial1), {label}: total {d['distance_error_pct']:.2f} %, "
              f"median per bout {d['bout_distance_error_median_pct']:.2f} %")


def simulated(users: list[int], csv: Path | None = None) -> pd.DataFrame:
    from pdrlearn.sim import UserProfile, simulate, simulate_path
    from pdrlearn.sim.route import parse_route
    from pdrlearn.track.evaluate import evaluate_track

    rows = []
    for u in users:
        cal = simulate("walk", u, "normal", rate_hz=100.0, seed=1, length_m=60.0)
        cal_m = W.walked_between_contacts(cal)
        tests = {sc: simulate(sc, u, "normal", rate_hz=100.0) for sc in "ABCD"}
        tests["pivot"] = simulate_path(parse_route(ROUTE), UserProfile.from_seed(u), rate_hz=100.0, seed=u)
        for label, opts in CONFIGS.items():
            base, _ = resolve_params(cal, None)
            base.options = dict(opts)
            params = calibrate([cal], "waist-pendulum", distances=[cal_m], params=base)
            for sc, s in tests.items():
                res = get_pipeline("waist-pendulum")(s, params=params, **opts)
                rows.append({"user": u, "scenario": sc, "config": label, "k": params.k,
                             "dist_err_pct": evaluate_track(res, s).get("distance_error_pct")})
        if csv is not None:  # each user's rows as they come (a long run can be read part-way)
            pd.DataFrame(rows).to_csv(csv, index=False)
    return pd.DataFrame(rows)


def sim_table(sim: pd.DataFrame) -> None:
    g = R.change_table(sim, "pivot_steps")
    n = sim.user.nunique()
    print(f"\n(d) simulated users {sim.user.min()}-{sim.user.max()} ({n}), waist-pendulum calibrated: median "
          "|distance error| (%):")
    print(g.round(3).to_string())


def main() -> None:
    ap = argparse.ArgumentParser()
    R.add_sim_real(ap, "2760-2819", W.ROOT / "datasets" / "external")
    args = ap.parse_args()
    logging.basicConfig(level=logging.ERROR)
    pd.set_option("display.width", 220)
    if not args.no_real:
        real_tables(real(args.external))
        demo(args.external)
    if not args.no_sim:
        sim_table(simulated(list(R.user_range(args.users)), args.csv))


if __name__ == "__main__":
    main()
