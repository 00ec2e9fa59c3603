"""Decision W309 (session 32, review 2 finding 1): W277's walking test without the contacts inside a trunk-flexion
window, on waist-pll chair tests. Measured once, no tuning (the rule is W309's text).

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/w309_pll_chair.py   # fresh users 6820-6849
Output: experiments/results/w309_pll_chair.txt (the printed lines).

Session 41 (decision W467): W309 is the code (W310 adopted it); the "today" arm stands in W309's
``flexion_free_walking`` leaving the walking contacts as they are (:func:`before_w309`), no module switch.
"""
import contextlib
import logging
from unittest import mock

from pdrlearn.io import read_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.waist import track_waist
from pdrlearn.waist import transfers
from pdrlearn.waist.transfers import transfer_summary

USERS = range(6820, 6850)
STS5, TUG = "sit:1, sit:1, sit:1, sit:1", "straight:3, turn:180, straight:3, turn:180"
REAL = "datasets/real/mobgap_HA001_Test11_Trial1"
PIPES = ("waist-pll", "waist-pendulum")


def session(u: int):
    if u % 2 == 0:
        return simulate_path(parse_route(STS5), UserProfile.from_seed(u), seed=u, sit_start_s=3.0, sit_end_s=5.0)
    return simulate_path(parse_route(TUG), UserProfile.from_seed(u), seed=u, sit_start_s=5.0, sit_end_s=5.0)


def before_w309():
    """W277's walking test before W309: the contacts inside a flexion window are counted (a stand-in for the
    "today" arm, decision W467)."""
    return mock.patch.object(transfers, "flexion_free_walking", lambda walking, flexed: walking)


def read(s, pipeline: str, on: bool):
    with contextlib.nullcontext() if on else before_w309():
        res = track_waist(s, pipeline=pipeline)
    tr = res.info.get("transfers")
    summ = transfer_summary(tr, res.steps)
    rows = [] if tr is None else [(r["kind"], round(float(r["start_s"]), 2), round(float(r["end_s"]), 2))
                                  for r in (tr.to_dict("records") if hasattr(tr, "to_dict") else tr)]
    return (summ["n_sit_to_stand"], summ["n_stand_to_sit"]), summ["tug_time_s"] is not None, rows


def main() -> None:
    agree = {(k, on): 0 for k in ("sts5", "tug") for on in (False, True)}
    sts5_tug, tug_changed, pend_changed = 0, 0, 0
    for u in USERS:
        s = session(u)
        kind = "sts5" if u % 2 == 0 else "tug"
        got = {(p, on): read(s, p, on) for p in PIPES for on in (False, True)}
        for on in (False, True):
            agree[(kind, on)] += got[("waist-pll", on)][0] == got[("waist-pendulum", on)][0]
        sts5_tug += kind == "sts5" and got[("waist-pll", True)][1]
        tug_changed += kind == "tug" and got[("waist-pll", True)][1] != got[("waist-pll", False)][1]
        pend_changed += got[("waist-pendulum", True)][:2] != got[("waist-pendulum", False)][:2]
        print(f"user {u} {kind}: " + "; ".join(f"{p} {'candidate' if on else 'today'} rise/sit {v[0][0]}/{v[0][1]}"
                                               f" tug {'yes' if v[1] else 'no'}" for (p, on), v in got.items()),
              flush=True)
    real = read_session(REAL)
    real_same = {}
    for p in PIPES:
        a, b = read(real, p, False), read(real, p, True)
        real_same[p] = a[2] == b[2]
        print(f"real {REAL} {p}: today {a[0][0]}/{a[0][1]} rows {a[2]}; candidate {b[0][0]}/{b[0][1]} rows {b[2]}")
    print(f"(a) chair tests agreeing pll vs pendulum: today {agree[('sts5', False)]}/15, candidate "
          f"{agree[('sts5', True)]}/15")
    print(f"(b) chair tests with a waist-pll tug_time_s (candidate): {sts5_tug}/15")
    print(f"(c) TUGs agreeing: today {agree[('tug', False)]}/15, candidate {agree[('tug', True)]}/15; "
          f"tug_time_s presence changed on {tug_changed}/15")
    print(f"(d) waist-pendulum changed on {pend_changed}/30")
    print("(e) real Test11 rows unchanged: " + ", ".join(f"{p} {v}" for p, v in real_same.items()))
    met = (agree[("sts5", True)] >= 12 and agree[("sts5", True)] > agree[("sts5", False)] and sts5_tug == 0
           and agree[("tug", True)] >= agree[("tug", False)] and tug_changed == 0 and pend_changed == 0
           and all(real_same.values()))
    print(f"rule met: {bool(met)}")


if __name__ == "__main__":
    logging.disable(logging.WARNING)
    main()
