"""Decision W165's measurement: W134's ``pause_steps="standing"`` in the realtime detector and the live trackers
(the candidate) against the realtime track before W165 (``pause_steps=False``, what ``--realtime`` applied), judged
by the rule written before the run (docs/decisions/waist.md W165):
(a) fresh simulated users 3260-3299 (W111's daily-activity route, W134's protocol: calibrated on a 20 m straight
    walk of seed user + 5000, 100 Hz, seed = user), realtime ``waist-pendulum``: pooled contact F1 (``score_events``,
    0.25 s, every contact vs ``ics.csv``) at most 0.002 lower and the median |bout error| at most 0.3 point higher;
(b) real Test11 (HA001, HA002, MS001; experiments/waist.py's external protocol, realtime rows): pooled F1 not lower
    and the pooled bout distance-error medians (vs ``Length`` and vs the strides, calibrated and defaults) not higher;
(c) real Test5: the pooled F1 and bout medians (calibrated and defaults) unchanged.
(d) (a test, not this script) the live ``WaistTracker`` equals the realtime replay on HA001 Test11.

Decision W166 runs the same rule for W131's ``contact_shift`` inside W31's decision window (``--option
contact_shift``: false against true, both with the realtime default of W165).

Run: OMP_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python experiments/waist_live_pause_steps.py [--external DIR]
[--option contact_shift]
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import numpy as np
import pandas as pd

import waist as W  # noqa: E402
import waist_pause_steps as P  # noqa: E402
from pdrlearn.sim import UserProfile, simulate_path  # noqa: E402
from pdrlearn.sim.route import parse_route  # noqa: E402
from pdrlearn.steps.evaluate import score_events  # noqa: E402
from pdrlearn.track.evaluate import path_length  # noqa: E402
from pdrlearn.track.waist import track_waist  # noqa: E402
from pdrlearn.waist.calibration import calibrate  # noqa: E402
from pdrlearn.waist.evaluate import steps_in_interval  # noqa: E402
from pdrlearn.waist.params import resolve_params  # noqa: E402

USERS = range(3260, 3300)
#: option -> (decision, value before, candidate)
CANDIDATES = {"pause_steps": ("W165", False, "standing"), "contact_shift": ("W166", False, True)}


def simulated(opt: dict, users=USERS) -> tuple[dict, pd.DataFrame]:
    """Rule (a): pooled contact counts and the per-bout errors of the calibrated realtime pendulum."""
    rows, tp, det, ref = [], 0, 0, 0
    for u in users:
        prof = UserProfile.from_seed(u)
        cal = simulate_path(parse_route("straight:20"), prof, rate_hz=100, seed=u + 5000)
        base, _ = resolve_params(cal, None)
        base.options = {**opt, "realtime": True}
        params = calibrate([cal], "waist-pendulum", distances=[W.walked_between_contacts(cal)], params=base)
        s = simulate_path(parse_route(P.ROUTE), prof, rate_hz=100, seed=u)
        st = track_waist(s, pipeline="waist-pendulum", params=params, realtime=True, **opt).steps
        sc = score_events(st["event_s"].to_numpy(float), s.extras["ics"]["ic_s"].to_numpy(float), tolerance_s=0.25)
        tp, det, ref = tp + sc["true_positives"], det + sc["count"], ref + sc["reference_count"]
        tr = s.trajectory
        for a, b in P.sim_bouts(s):
            r = path_length(tr[(tr["t"] >= a) & (tr["t"] <= b)])
            est = float(st["length_m"].abs().to_numpy(float)[steps_in_interval(st, a, b)].sum())
            rows.append({"user": u, "start_s": a, "ref_m": r, "err_pct": 100 * (est / r - 1)})
    d = pd.DataFrame(rows)
    return {"f1": 2 * tp / (det + ref), "tp": tp, "det": det, "ref": ref,
            "median": float(d.err_pct.abs().median()), "bouts": len(d)}, d


def real(ext: Path, opt: dict) -> pd.DataFrame:
    """Rules (b), (c): experiments/waist.py's pooled realtime rows (calibrated and defaults)."""
    bouts: list = []
    cfg = [("waist-pendulum realtime", "waist-pendulum", {"realtime": True, **opt})]
    df = W.real(ext, W.external_runs(ext), configs=cfg, bouts=bouts)
    return W.pooled(df, pd.DataFrame(bouts)).set_index(["test", "params"])


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--external", type=Path, default=P.ROOT / "datasets" / "external")
    ap.add_argument("--option", choices=sorted(CANDIDATES), default="pause_steps")
    args = ap.parse_args()
    decision, before, candidate = CANDIDATES[args.option]
    logging.disable(logging.WARNING)
    res = {}
    for value in (before, candidate):
        sim, d = simulated({args.option: value})
        pool = real(args.external, {args.option: value})
        res[value] = (sim, d, pool)
        print(f"{args.option}={value!r} realtime: (a) users {USERS.start}-{USERS.stop - 1}: pooled F1 {sim['f1']:.4f} "
              f"({sim['tp']}/{sim['det']}/{sim['ref']}), median |bout error| {sim['median']:.3f} % over "
              f"{sim['bouts']} bouts", flush=True)
        for (test, params), r in pool.iterrows():
            print(f"  {test} {params}: pooled F1 {r.step_f1:.4f}, bout median vs Length {r.bout_err_median_pct:.3f} "
                  f"%, vs strides {r.bout_err_strides_median_pct:.3f} % ({r.bouts} bouts)", flush=True)
    (s0, d0, p0), (s1, d1, p1) = res[before], res[candidate]
    P.print_users_better(d0, d1)
    cols = ["step_f1", "bout_err_median_pct", "bout_err_strides_median_pct"]
    t11 = [k for k in p0.index if k[0] == "Test11"]
    t5 = [k for k in p0.index if k[0] == "Test5"]
    rules = {
        "(a) simulated F1 at most 0.002 lower": s1["f1"] >= s0["f1"] - 0.002,
        "(a) simulated median |bout error| at most 0.3 point higher": s1["median"] <= s0["median"] + 0.3,
        "(b) Test11 pooled F1 not lower": all(p1.loc[k, "step_f1"] >= p0.loc[k, "step_f1"] for k in t11),
        "(b) Test11 pooled bout medians not higher": all(
            p1.loc[k, c] <= p0.loc[k, c] for k in t11 for c in cols[1:]),
        "(c) Test5 unchanged": all(np.isclose(p1.loc[k, c], p0.loc[k, c], rtol=0, atol=1e-9)
                                   for k in t5 for c in cols)}
    for k, v in rules.items():
        print(f"{k}: {'holds' if v else 'FAILS'}")
    print(f"{decision}: " + ("ADOPT (all hold)" if all(rules.values()) else "NOT adopted (a rule fails)"), flush=True)


if __name__ == "__main__":
    main()
