"""Decision W111's measurement: ``pause_steps`` (a step longer than 1.5 local periods keeps one period's length)
off vs on, judged by the rule written before the run (docs/decisions/waist.md W111):
(a) simulated daily activities, fresh users 950-989: median |bout error| falls by >= 1.0 point;
(b) real Test11 HA001 / HA002 / MS001: median per-bout error vs Length and vs strides each rises <= 0.5 point;
(c) real Test5 pooled, calibrated and uncalibrated: median rises <= 0.5 point;
(d) simulator A-D users 1-3 (experiments/waist.py): median |distance error| rises <= 0.5 point.

Run: OMP_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python experiments/waist_pause_steps.py [--external datasets/external]
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import numpy as np
import pandas as pd

import waist as W  # noqa: E402
from pdrlearn.sim import UserProfile, simulate_path  # noqa: E402
from pdrlearn.sim.route import parse_route  # noqa: E402
from pdrlearn.track.evaluate import path_length  # noqa: E402
from pdrlearn.track.waist import track_waist  # noqa: E402
from pdrlearn.waist.calibration import calibrate  # noqa: E402
from pdrlearn.waist.evaluate import steps_in_interval  # noqa: E402
from pdrlearn.waist.params import resolve_params  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
USERS = range(950, 990)
ROUTE = ("stand:3, straight:6, turn:180, straight:4, stand:4, straight:3, turn:-90, straight:5, sit:10, straight:4, "
         "turn:-135, straight:4, stand:3")
BOUT_GAP_S = 2.5


def sim_bouts(session, gap_s: float = BOUT_GAP_S) -> list[tuple[float, float]]:
    """The simulated walking bouts: reference contacts split at gaps over ``gap_s``, first to last contact."""
    ic = np.sort(session.extras["ics"]["ic_s"].to_numpy(float))
    cut = np.flatnonzero(np.diff(ic) > gap_s)
    return [(ic[a], ic[b]) for a, b in zip(np.r_[0, cut + 1], np.r_[cut, ic.size - 1], strict=True) if b > a]


def sim_daily(pause: bool | str, users=USERS) -> pd.DataFrame:
    """Rule (a): per bout of each user's daily-activity route, the calibrated pendulum's error (%)."""
    rows = []
    for u in users:
        prof = UserProfile.from_seed(u)
        cal = simulate_path(parse_route("straight:20"), prof, rate_hz=100, seed=u + 5000)
        base, _ = resolve_params(cal, None)
        base.options = {"pause_steps": pause}
        params = calibrate([cal], "waist-pendulum", distances=[W.walked_between_contacts(cal)], params=base)
        s = simulate_path(parse_route(ROUTE), prof, rate_hz=100, seed=u)
        st = track_waist(s, pipeline="waist-pendulum", params=params, pause_steps=pause).steps
        tr = s.trajectory
        for a, b in sim_bouts(s):
            ref = path_length(tr[(tr["t"] >= a) & (tr["t"] <= b)])
            est = float(st["length_m"].abs().to_numpy(float)[steps_in_interval(st, a, b)].sum())
            rows.append({"user": u, "start_s": a, "ref_m": ref, "err_pct": 100 * (est / ref - 1)})
    return pd.DataFrame(rows)


def print_users_better(off: pd.DataFrame, on: pd.DataFrame) -> None:
    """The line of how many simulated users' median |bout error| (:func:`sim_daily`) fell / rose, off -> on."""
    per_user = off.assign(on=on.err_pct.abs(), off=lambda x: x.err_pct.abs()).groupby("user")[["off", "on"]].median()
    print(f"users whose median |bout error| fell / rose: {(per_user.on < per_user.off).sum()} / "
          f"{(per_user.on > per_user.off).sum()} of {len(per_user)}")


def real(ext: Path, pause: bool | str) -> tuple[pd.DataFrame, pd.DataFrame]:
    """Rules (b), (c): experiments/waist.py's calibrated and default rows of the offline pendulum."""
    bouts: list = []
    df = W.real(ext, W.external_runs(ext), configs=[("waist-pendulum", "waist-pendulum", {"pause_steps": pause})],
                bouts=bouts)
    b = pd.DataFrame(bouts)
    return b, W.pooled(df, b)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    ap.add_argument("--sim-users", type=int, default=3)
    args = ap.parse_args()
    logging.disable(logging.WARNING)
    res = {}
    for pause in (False, True):
        d = sim_daily(pause)
        b, pool = real(args.external, pause)
        t11 = b[b.test.str.startswith("Test11") & (b.params == "calibrated")].assign(
            a=lambda x: x.error_pct.abs(), s=lambda x: x.error_strides_pct.abs())
        t11 = t11.groupby("subject")[["a", "s"]].median()
        t5 = pool[pool.test == "Test5"].set_index("params")["bout_err_median_pct"]
        t11p = pool[(pool.test == "Test11") & (pool.params == "calibrated")].iloc[0]
        configs = [("waist-pendulum", "waist-pendulum", {"pause_steps": pause})]
        sim = W.summarize_sim(W.simulated(list(range(1, args.sim_users + 1)), configs=configs))
        res[pause] = {"sim_daily": float(d.err_pct.abs().median()), "users_better": d, "t11": t11,
                      "t5_cal": float(t5["calibrated"]), "t5_def": float(t5["defaults"]),
                      "t11_pooled": (float(t11p.bout_err_median_pct), float(t11p.bout_err_strides_median_pct)),
                      "ad": float(sim.dist_err_abs_median_pct.iloc[0])}
        r = res[pause]
        print(f"pause_steps={pause}: (a) simulated daily activities users 950-989, {len(d)} bouts: median |bout "
              f"error| {r['sim_daily']:.3f} %; (c) Test5 calibrated {r['t5_cal']:.3f} %, uncalibrated "
              f"{r['t5_def']:.3f} %; Test11 pooled vs Length / strides {r['t11_pooled'][0]:.3f} / "
              f"{r['t11_pooled'][1]:.3f} %; (d) A-D users 1-{args.sim_users} {r['ad']:.3f} %", flush=True)
        print("  (b) Test11 median per bout vs Length / vs strides: " + ", ".join(
            f"{k} {v.a:.3f} / {v.s:.3f} %" for k, v in t11.iterrows()), flush=True)
    off, on = res[False], res[True]
    print_users_better(off["users_better"], on["users_better"])
    rules = {"(a) simulated daily activities falls >= 1.0 point": on["sim_daily"] <= off["sim_daily"] - 1.0,
             "(b) no Test11 subject's median rises > 0.5 point": bool(
                 ((on["t11"] - off["t11"]) <= 0.5).to_numpy().all()),
             "(c) Test5 calibrated and uncalibrated rise <= 0.5 point": on["t5_cal"] <= off["t5_cal"] + 0.5
             and on["t5_def"] <= off["t5_def"] + 0.5,
             "(d) A-D rises <= 0.5 point": on["ad"] <= off["ad"] + 0.5}
    for k, v in rules.items():
        print(f"{k}: {'holds' if v else 'FAILS'}")
    print("W111: " + ("ADOPTED (all hold)" if all(rules.values()) else "not adopted (a rule fails)"))


if __name__ == "__main__":
    main()
