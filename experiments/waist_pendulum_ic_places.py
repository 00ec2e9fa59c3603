"""Decision W374's diagnosis: where the default offline `waist-pendulum` misses true contacts and adds extra ones on
fresh simulated users (issue 4/8; no behaviour change).

Per route of W218 (`waist_stand.W218_ROUTES`: walk, walk-turn, tug, daily, tug-pendulum, freeze, shuffle; the gait of
each user as `waist_pll_edges.route_table` draws it), the contacts of `track_waist(session, pipeline="waist-pendulum")`
(today's defaults) are matched one-to-one within 0.25 s to the simulator's true contacts (`ics`,
`waist_stand.matched_truth`). The true contacts are cut into bouts where two follow each other more than 1.5 s apart
(W47's walking-sequence gap). Every error goes to the FIRST place it meets:

- missed true contact: "closing step" (the simulator's `kind == "close"`: the foot brought beside the other at a
  bout's end), "bout start" (the bout's first or second contact), "bout end" (its last or second-last), "turn"
  (`kind == "turn"`), "slow / short" (mean interval to its bout neighbours > 0.75 s, < 80 steps/min), "straight";
  its cause: "timing" (an unmatched detected contact 0.25-0.5 s away: seen, dated too far), else read in the
  detector's own signal (the vertical acceleration low-passed as seed 003 sec. 3.1 does, its maxima at least 0.25 s
  apart; the step's maximum the first one -0.05 to +0.45 s from the true contact): "no maximum", "gate closed" (the
  offline motion gate, W4 / W76's relative threshold on the centred 2 s SD, is closed at the maximum), "low" (under
  the detector's 0.1 m/s^2) or "rules" (the sequence rules or a veto dropped it);
- extra detected contact: "timing" (an unmatched true contact 0.25-0.5 s away), "outside walking" (over 1 s from
  every true contact: standing, sitting, a transfer, a freeze), "before a bout" / "after a bout" (before its first /
  after its last true contact, within 1 s), "in a turn" (between two true contacts one of which is a turn step;
  how many of them lie between two contacts of the SAME foot is printed beside, W376),
  "within a straight" (between two true contacts of a straight).

``--turn-bridge`` (W374's rule, measured once, users 8780-8799; W375 records it): each route tracked with the option
``turn_bridge`` off and on on the same simulated sessions; (a) F1, (b) total errors (missed + extra), (c) recall
printed and judged; with ``--external DIR`` also (d): `experiments/waist.py`'s `real` on its `external_runs` (mobgap),
the offline `waist-pendulum` configuration off and on, every row's (calibrated and defaults) step F1.

``--bridge-side`` (W384's rule, measured once, users 8930-8949; W385 records it): the same, ``turn_bridge`` off against
``"side"`` (the bridge's added contacts only where their W20 side is decided and alternates).

``--with-bridge`` (W376, a read-out): the table with ``turn_bridge`` on, where its added extras lie.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/waist_pendulum_ic_places.py [FIRST LAST+1]
     [--turn-bridge [--external datasets/external] | --bridge-side [--external datasets/external] | --with-bridge]
Writes its table to stdout (W374: experiments/results/waist_pendulum_ic_places_w374.txt; W375:
experiments/results/waist_pendulum_turn_bridge_w375.txt).
"""

from __future__ import annotations

import argparse
import logging
from collections import Counter
from pathlib import Path

import numpy as np

from pdrlearn.kernels import waist as K  # noqa: E402
from pdrlearn.kernels.dsp import find_peaks  # noqa: E402
from pdrlearn.track.waist import track_waist  # noqa: E402
from pdrlearn.waist.ahrs import waist_imu  # noqa: E402
from pdrlearn.waist.events import gate_threshold  # noqa: E402
from waist_freeze_veto import simulate  # noqa: E402
from waist_pll_edges import mobgap_check  # noqa: E402
from waist_stand import TOL_S, W218_ROUTES, matched_truth  # noqa: E402

USERS = range(8760, 8780)  # the lead's fresh users for W374's diagnosis (session 36)
RULE_USERS = range(8780, 8800)  # the lead's fresh users for W374's rule (session 36)
SIDE_USERS = range(8930, 8950)  # the lead's fresh users for W384's rule (session 36; 8910-8929 for its diagnosis)
BOUT_GAP_S = 1.5  # W47: a step to the next contact within 1.5 s chains a walking sequence
SLOW_S = 0.75  # < 80 steps/min (waist_ic_classes.py's slow class)
NEAR_S = 1.0  # an extra over 1 s from every true contact lies outside walking
MISS_PLACES = ("closing step", "bout start", "bout end", "turn", "slow / short", "straight")
EXTRA_PLACES = ("timing", "outside walking", "before a bout", "after a bout", "in a turn", "within a straight")
SAME_FOOT = ", same-foot pair"  # W376: an extra in a turn between two true contacts of one foot


def _extra_line(extra: Counter) -> str:
    """One line: each place's extras (a turn's: its count between two same-foot contacts beside)."""
    def one(p):
        n = extra[p] + extra[p + SAME_FOOT]
        return f"{p} {n}" + (f" (between two same-foot true contacts {extra[p + SAME_FOOT]})" if p == "in a turn"
                             else "")
    return "; ".join(one(p) for p in EXTRA_PLACES)


def sessions(name: str, users) -> list:
    """The route ``name`` of W218 simulated for each user (the gait and freeze drawn as waist_pll_edges draws them)."""
    route, kw, *gait = W218_ROUTES[name]
    return [simulate(route.format(hz=3 + u % 6, acc=(7.0, 8.5, 10.0)[u % 3]), kw, u, gait[0](u) if gait else None)
            for u in users]


def maxima(session) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The detector's vertical maxima: (times s, filtered height m/s^2, motion gate open) (module docstring)."""
    imu = waist_imu(session)
    thr, sigma, _ = gate_threshold(imu)
    vf = K.fir_zero_lag(imu.acc_v - imu.acc_v.mean(), K.fir_taps(2.5, imu.fs, int(round(0.3 * imu.fs))))
    cand = find_peaks(vf, height=0.0, distance=max(1, int(round(0.25 * imu.fs))))
    return imu.t[cand], vf[cand], K.motion_state(sigma, walk_threshold=thr)[cand] > 0


def _cause(t: float, mx) -> str:
    tc, h, open_ = mx
    near = np.flatnonzero((tc > t - 0.05) & (tc < t + 0.45))
    if not near.size:
        return "no maximum"
    k = near[0]
    return "gate closed" if not open_[k] else ("low" if h[k] < 0.1 else "rules")


def places(ev: np.ndarray, ics, mx=None) -> tuple[list[tuple[str, str]], list[str], int]:
    """(place, cause) of each missed true contact, place of each extra detected one, the number matched; ``mx``:
    :func:`maxima` of the session (None: the causes other than timing are "not detected")."""
    truth = ics["ic_s"].to_numpy(float)
    order = np.argsort(truth)
    truth, kind, foot = truth[order], ics["kind"].to_numpy(str)[order], ics["foot"].to_numpy(str)[order]
    m = matched_truth(ev, truth)
    used = np.zeros(ev.size, bool)
    used[m[m >= 0]] = True
    bout = np.r_[0, np.cumsum(np.diff(truth) > BOUT_GAP_S)] if truth.size else np.zeros(0, int)
    misses = []
    for i in np.flatnonzero(m < 0):
        members = np.flatnonzero(bout == bout[i])
        k = int(np.searchsorted(members, i))
        gaps = np.diff(truth[members])
        local = gaps[max(k - 1, 0):k + 1]
        if kind[i] == "close":
            place = "closing step"
        elif k <= 1:
            place = "bout start"
        elif k >= members.size - 2:
            place = "bout end"
        elif kind[i] == "turn":
            place = "turn"
        elif local.size and local.mean() > SLOW_S:
            place = "slow / short"
        else:
            place = "straight"
        d = np.abs(ev[~used] - truth[i])
        timing = d.size and d.min() <= 2 * TOL_S
        misses.append((place, "timing" if timing else ("not detected" if mx is None else _cause(truth[i], mx))))
    extras = []
    free_truth = truth[m < 0]
    for j in np.flatnonzero(~used):
        if free_truth.size and np.abs(free_truth - ev[j]).min() <= 2 * TOL_S:
            extras.append("timing")
            continue
        if not truth.size or np.abs(truth - ev[j]).min() > NEAR_S:
            extras.append("outside walking")
            continue
        after = int(np.searchsorted(truth, ev[j]))
        if after == 0 or (after < truth.size and bout[after] != bout[after - 1] and truth[after] - ev[j] <
                          ev[j] - truth[after - 1]):
            extras.append("before a bout")
        elif after == truth.size or bout[after] != bout[after - 1]:
            extras.append("after a bout")
        elif "turn" in (kind[after - 1], kind[after]):
            extras.append("in a turn" + (SAME_FOOT if foot[after - 1] == foot[after] else ""))
        else:
            extras.append("within a straight")
    return misses, extras, int(used.sum())


def _missed(miss: Counter) -> str:
    """One line: each place's misses and their causes."""
    def one(p):
        causes = ", ".join(f"{c} {v}" for (q, c), v in sorted(miss.items()) if q == p)
        return f"{p} {sum(v for (q, _), v in miss.items() if q == p)}" + (f" ({causes})" if causes else "")
    return "; ".join(one(p) for p in MISS_PLACES)


def table(users=USERS, **options) -> None:
    """The module docstring's table for ``users``; ``options``: track options (W376: ``turn_bridge=True``)."""
    miss_all, extra_all = Counter(), Counter()
    for name in W218_ROUTES:
        miss, extra = Counter(), Counter()
        n_true = n_det = n_tp = 0
        for s in sessions(name, users):
            ev = track_waist(s, pipeline="waist-pendulum", **options).steps["event_s"].to_numpy(float)
            mi, ex, tp = places(ev, s.extras["ics"], maxima(s))
            miss.update(mi)
            extra.update(ex)
            n_true, n_det, n_tp = n_true + len(s.extras["ics"]), n_det + ev.size, n_tp + tp
        f1 = 2 * n_tp / max(n_true + n_det, 1)
        print(f"\n{name}: {len(users)} users, true {n_true}, detected {n_det}, matched {n_tp}, F1 {f1:.4f}, "
              f"recall {n_tp / max(n_true, 1):.4f}; missed {n_true - n_tp}, extra {n_det - n_tp}")
        print("  missed: " + _missed(miss))
        print("  extra: " + _extra_line(extra))
        miss_all.update(miss)
        extra_all.update(extra)
    print(f"\nall routes: missed {sum(miss_all.values())}, extra {sum(extra_all.values())}")
    print("  missed: " + _missed(miss_all))
    print("  extra: " + _extra_line(extra_all))


def _counts(ev: np.ndarray, ics) -> np.ndarray:
    """(true, detected, matched) of one track."""
    truth = ics["ic_s"].to_numpy(float)
    return np.array([truth.size, ev.size, int((matched_truth(ev, np.sort(truth)) >= 0).sum())])


def turn_bridge_rule(users=RULE_USERS, external: Path | None = None, on=True, decision: str = "W374") -> bool:
    """W374's rule: ``turn_bridge`` off against ``on`` (W384: ``"side"``), (a)-(c) per route of W218, (d) on the mobgap
    recordings."""
    ok_a = ok_c = True
    err = np.zeros(2, dtype=int)
    for name in W218_ROUTES:
        c = np.zeros((2, 3), dtype=int)
        for s in sessions(name, users):
            for k, value in enumerate((False, on)):
                ev = track_waist(s, pipeline="waist-pendulum", turn_bridge=value).steps["event_s"].to_numpy(float)
                c[k] += _counts(ev, s.extras["ics"])
        f1 = 2 * c[:, 2] / np.maximum(c[:, 0] + c[:, 1], 1)
        rec = c[:, 2] / np.maximum(c[:, 0], 1)
        e = c[:, 0] + c[:, 1] - 2 * c[:, 2]
        err += e
        ok_a &= bool(f1[1] >= f1[0] - 0.002)
        ok_c &= bool(rec[1] >= rec[0] - 0.005)
        print(f"{name}: F1 off {f1[0]:.4f} on {f1[1]:.4f} ({f1[1] - f1[0]:+.4f}); recall off {rec[0]:.4f} on "
              f"{rec[1]:.4f} ({rec[1] - rec[0]:+.4f}); missed off {c[0, 0] - c[0, 2]} on {c[1, 0] - c[1, 2]}; extra "
              f"off {c[0, 1] - c[0, 2]} on {c[1, 1] - c[1, 2]}", flush=True)
    ok_b = bool(err[1] < err[0])
    print(f"(a) F1 not lower by more than 0.002 on any route: {'met' if ok_a else 'NOT met'}; (b) errors (missed + "
          f"extra) off {err[0]} on {err[1]}: {'met' if ok_b else 'NOT met'}; (c) recall not lower by more than 0.005 "
          f"on any route: {'met' if ok_c else 'NOT met'}", flush=True)
    ok_d = external is not None and mobgap_check(external, ("waist-pendulum", "waist-pendulum"),
                                                 {"turn_bridge": False}, {"turn_bridge": on})
    adopted = ok_a and ok_b and ok_c and ok_d and external is not None
    print(f"{decision} (turn_bridge={on}): {'adopted' if adopted else 'not adopted'}")
    return adopted


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("users", nargs="*", type=int, help="FIRST_USER LAST_USER+1")
    ap.add_argument("--turn-bridge", action="store_true", help="W374's rule: turn_bridge off and on (W375)")
    ap.add_argument("--external", type=Path, default=None, help="the mobgap folder for W374's (d)")
    ap.add_argument("--with-bridge", action="store_true", help="the table with turn_bridge on (W376)")
    ap.add_argument("--bridge-side", action="store_true", help="W384's rule: turn_bridge off and \"side\" (W385)")
    args = ap.parse_args()
    logging.disable(logging.WARNING)
    if args.bridge_side:
        turn_bridge_rule(range(args.users[0], args.users[1]) if len(args.users) > 1 else SIDE_USERS, args.external,
                         on="side", decision="W384")
    elif args.turn_bridge:
        turn_bridge_rule(range(args.users[0], args.users[1]) if len(args.users) > 1 else RULE_USERS, args.external)
    else:
        table(range(args.users[0], args.users[1]) if len(args.users) > 1 else USERS,
              **({"turn_bridge": True} if args.with_bridge else {}))
