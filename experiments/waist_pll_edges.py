"""Decisions W345 / W356: where `waist-pll`'s extra contacts lie, and W356's edge lock measured (W357).

Diagnosis (W345, the default run): per route of W218 (`waist_stand.W218_ROUTES`), fresh simulated users, today's
defaults: the true contacts (`ics`), the detected ones, the one-to-one matches within 0.25 s
(`waist_stand.matched_truth`), the unmatched detected contacts ("extra") and, of those, the ones at a walking
sequence's edge (its first or last contact, `has_next`); for an extra at an edge: how far it lies before the
sequence's first / after its last true contact, in the user's step periods (median true step interval); and the
PLL's phase error at the peak that made it (:func:`pdrlearn.kernels.step_events.phase_error_deg`, computed by the
PLL kernel itself since W356 and read from its events' ``phase_err_deg``; the detected contact is matched to the
nearest kept PLL peak; seed 000 Sec. II-C: locked, the output's peak lies on the input's; 0 deg = in phase).

``--edge-lock`` (W356's measurement, once; W357 records it): each route tracked with the option ``pll_edge_lock`` off
and on on the same simulated sessions; ``--edge-lock trailing`` (W358's measurement, once, users 8160-8199; W366
records it): off and ``"trailing"`` (only a gated run's last peak judged); ``--edge-lock walk-end`` (W367's
measurement, once, users 8320-8359; W368 records it): off and ``"walk-end"`` (a run's last peak judged only where the
walk ends), recall's tolerance 0.005 (W367); ``--edge-lock walk-edges --baseline walk-end`` (W372's measurement,
once, users 8700-8739; W373 records it): ``"walk-end"`` against ``"walk-edges"`` (also a run's first peak judged, only
where the walk starts after it), W367's tolerances; the rule's (a) F1, (b) extra contacts,
(c) recall printed and judged; with ``--external DIR`` also (d): `experiments/waist.py`'s `real` on its
`external_runs` (mobgap), `waist-pll (A-HE)` off and on, every row's step F1.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/waist_pll_edges.py [FIRST_USER LAST_USER+1]
     [--edge-lock [trailing|walk-end|walk-edges] [--baseline walk-end] [--external datasets/external]]
"""

from __future__ import annotations

import argparse
import logging
import math
from pathlib import Path

import numpy as np

import pdrlearn.kernels.step_events as SE
from waist_freeze_veto import simulate
from waist_stand import W218_ROUTES, matched_truth, track_waist

USERS = range(7370, 7390)  # the lead's fresh users for W345 (session 33)
EDGE_USERS = range(7750, 7790)  # the lead's fresh users for W356 (session 34)
TRAILING_USERS = range(8160, 8200)  # the lead's fresh users for W358 (session 34)
WALK_END_USERS = range(8320, 8360)  # the lead's fresh users for W367 (session 35)
WALK_EDGES_USERS = range(8700, 8740)  # the lead's fresh users for W372 (session 35)
#: the decision of each measured mode's rule and its (c) recall tolerance (W356 / W358: 0.002; W367: 0.005)
RULES = {True: ("W356", 0.002), "trailing": ("W358", 0.002), "walk-end": ("W367", 0.005),
         "walk-edges": ("W372", 0.005)}
_PEAKS: list[tuple[float, float]] = []  # (PLL peak time, phase error deg) of every kept PLL peak of the current track


def _recording(fn):
    """``fn`` (the PLL kernel or its flush), unchanged, plus a side record of each kept peak's time and phase error."""
    def wrapped(*args):
        res = fn(*args)
        _PEAKS.extend((e[4]["pll_peak_s"], e[4]["phase_err_deg"]) for e in (res[0] if isinstance(res, tuple) else res))
        return res
    return wrapped


def _new() -> dict:
    return {"n_true": 0, "n_det": 0, "n_tp": 0, "n_extra": 0, "n_edge": 0, "n_bouts": 0, "lead": [], "lag": [],
            "ph_edge": [], "ph_true": [], "ph_lead": [], "ph_lag": []}


def _add(a: dict, s, edge_lock: bool | str) -> None:
    """Track the simulated session ``s`` with waist-pll (``pll_edge_lock=edge_lock``) and add its counts to ``a``."""
    _PEAKS.clear()
    truth = np.sort(s.extras["ics"]["ic_s"].to_numpy(float))
    st = track_waist(s, pipeline="waist-pll", pll_edge_lock=edge_lock).steps
    ev, hn = st["event_s"].to_numpy(float), st["has_next"].to_numpy(bool)
    m = matched_truth(ev, truth)
    used = np.zeros(ev.size, bool)
    used[m[m >= 0]] = True
    first, last = np.r_[True, ~hn[:-1]], ~hn
    period = float(np.median(np.diff(truth))) if truth.size > 1 else math.nan
    peaks = np.array(_PEAKS) if _PEAKS else np.zeros((0, 2))
    phase = peaks[np.abs(peaks[:, 0][None, :] - ev[:, None]).argmin(1), 1] if len(peaks) else ev * np.nan
    a["n_true"] += truth.size
    a["n_det"] += ev.size
    a["n_tp"] += int(used.sum())
    a["n_extra"] += int((~used).sum())
    a["n_bouts"] += int(first.sum())
    edge = ~used & (first | last)
    a["n_edge"] += int(edge.sum())
    a["ph_edge"] += phase[edge].tolist()
    a["ph_true"] += phase[used].tolist()
    for j in np.flatnonzero(edge):  # the sequence's true contacts: those matched inside it
        seq_end = j + int(np.argmax(~hn[j:])) if first[j] else j
        seq_start = j if first[j] else j - int(np.argmax(first[j::-1]))
        inside = truth[(m >= seq_start) & (m <= seq_end)]
        if not inside.size:
            continue
        if first[j] and ev[j] < inside[0]:
            a["lead"].append((inside[0] - ev[j]) / period)
            a["ph_lead"].append(phase[j])
        if last[j] and ev[j] > inside[-1]:
            a["lag"].append((ev[j] - inside[-1]) / period)
            a["ph_lag"].append(phase[j])


def _scores(a: dict) -> tuple[float, float]:
    """(F1, recall) of the counts ``a``."""
    prec, rec = a["n_tp"] / max(a["n_det"], 1), a["n_tp"] / max(a["n_true"], 1)
    return 2 * prec * rec / max(prec + rec, 1e-12), rec


def _line(name: str, n_users: int, a: dict) -> str:
    def locked(x):
        return f"{np.mean(np.abs(x) < 45):.2f}" if len(x) else "-"

    def q(x):
        return np.round(np.percentile(x, [10, 50, 90]), 2).tolist() if len(x) else "-"

    return (f"{name}: {n_users} users, true {a['n_true']}, detected {a['n_det']}, matched {a['n_tp']}, F1 "
            f"{_scores(a)[0]:.4f}; extra {a['n_extra']}, at a sequence edge {a['n_edge']} ({a['n_bouts']} sequences); "
            f"edge extras before the first true contact {len(a['lead'])} (lead in step periods p10/50/90 "
            f"{q(a['lead'])}), after the last {len(a['lag'])} (lag {q(a['lag'])}); |phase error| < 45 deg: matched "
            f"{locked(a['ph_true'])}, edge extras {locked(a['ph_edge'])} (leading {locked(a['ph_lead'])}, trailing "
            f"{locked(a['ph_lag'])})")


def route_table(users=USERS, locks=(False,)) -> dict[str, list[dict]]:
    """Per route of W218: the counts of each ``pll_edge_lock`` value of ``locks`` on the same simulated sessions
    (one line each printed); returns route -> [counts per lock]."""
    kern, flush = SE.pll_kernel, SE.pll_flush
    SE.pll_kernel, SE.pll_flush = _recording(kern), _recording(flush)
    out = {}
    try:
        for name, (route, kw, *gait) in W218_ROUTES.items():
            acc = [_new() for _ in locks]
            for u in users:
                s = simulate(route.format(hz=3 + u % 6, acc=(7.0, 8.5, 10.0)[u % 3]), kw, u,
                             gait[0](u) if gait else None)
                for a, lock in zip(acc, locks, strict=True):
                    _add(a, s, lock)
            for a, lock in zip(acc, locks, strict=True):
                print(_line(name + (f" (pll_edge_lock {_label(lock)})" if len(locks) > 1 else ""),
                            len(users), a), flush=True)
            out[name] = acc
    finally:
        SE.pll_kernel, SE.pll_flush = kern, flush
    return out


def _label(lock: bool | str) -> str:
    return lock if isinstance(lock, str) else ("on" if lock else "off")


def edge_lock_rule(users, external: Path | None, mode: bool | str = True, baseline: bool | str = False) -> bool:
    """W356's rule (``mode`` True), W358's (``mode`` "trailing"), W367's ("walk-end") or W372's ("walk-edges",
    ``baseline`` "walk-end"): ``baseline`` (the option off unless given) against ``mode``, (a)-(c) on the simulated
    routes, (d) on the mobgap recordings when ``external`` is given. "off" / "on" below: ``baseline`` / ``mode``."""
    decision, rec_tol = RULES[mode]
    print(f"{decision}: off = pll_edge_lock {_label(baseline)}, on = pll_edge_lock {_label(mode)}", flush=True)
    res = route_table(users, locks=(baseline, mode))
    ok_a = ok_c = True
    extra = [0, 0]
    for name, (off, on) in res.items():
        (f0, r0), (f1, r1) = _scores(off), _scores(on)
        ok_a &= f1 >= f0 - 0.002
        ok_c &= r1 >= r0 - rec_tol
        extra[0] += off["n_extra"]
        extra[1] += on["n_extra"]
        print(f"{name}: F1 off {f0:.4f} on {f1:.4f} ({f1 - f0:+.4f}); recall off {r0:.4f} on {r1:.4f} "
              f"({r1 - r0:+.4f}); extra off {off['n_extra']} on {on['n_extra']}", flush=True)
    ok_b = extra[1] < extra[0]
    print(f"(a) F1 not lower by more than 0.002 on any route: {'met' if ok_a else 'NOT met'}; (b) extra contacts "
          f"off {extra[0]} on {extra[1]}: {'met' if ok_b else 'NOT met'}; (c) recall not lower by more than "
          f"{rec_tol} on any route: {'met' if ok_c else 'NOT met'}", flush=True)
    ok_d = True
    if external is not None:
        ok_d = mobgap_check(external, ("waist-pll (A-HE)", "waist-pll"), {"pll_edge_lock": baseline},
                            {"pll_edge_lock": mode})
    adopted = ok_a and ok_b and ok_c and ok_d and external is not None
    print(f"{decision} ({_label(mode)}): {'adopted' if adopted else 'not adopted'}")
    return adopted


def mobgap_check(external: Path, config: tuple[str, str], off: dict, on: dict, tol: float = 0.005) -> bool:
    """The (d) of W356-W372's and W374's rules: `experiments/waist.py`'s `real` on its `external_runs` (mobgap) with the
    configuration ``config`` (label, pipeline) under the options ``off`` and ``on``; every row's step F1 printed; True
    iff none is lower by more than ``tol``."""
    from waist import external_runs, real

    runs = external_runs(external)
    dfs = [real(external, runs, configs=[(*config, opts)]) for opts in (off, on)]
    ok = True
    for (_, r0), (_, r1) in zip(dfs[0].iterrows(), dfs[1].iterrows(), strict=True):
        d = r1.step_f1 - r0.step_f1
        ok &= bool(d >= -tol)
        print(f"mobgap {r0.subject} {r0.test} ({r0.params}, calibrated on {r0.calibrated_on}): step F1 off "
              f"{r0.step_f1:.4f} on {r1.step_f1:.4f} ({d:+.4f}); detected off {r0.n_detected} on {r1.n_detected}",
              flush=True)
    print(f"(d) mobgap {config[1]} step F1 not lower by more than {tol} on any row: {'met' if ok else 'NOT met'}")
    return ok


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("users", nargs="*", type=int, help="FIRST_USER LAST_USER+1")
    ap.add_argument("--edge-lock", nargs="?", const=True, default=None,
                    choices=[True, "trailing", "walk-end", "walk-edges"],
                    help="W356's rule: pll_edge_lock off and on (W357); 'trailing': W358's rule (W366); 'walk-end': "
                         "W367's rule (W368); 'walk-edges': W372's rule (W373, with --baseline walk-end)")
    ap.add_argument("--baseline", default=False, choices=[False, "walk-end"],
                    help="the pll_edge_lock compared against (default off; W372: walk-end)")
    ap.add_argument("--external", type=Path, default=None, help="the mobgap folder for W356's (d)")
    args = ap.parse_args()
    logging.basicConfig(level=logging.ERROR)
    default = {None: USERS, True: EDGE_USERS, "trailing": TRAILING_USERS, "walk-end": WALK_END_USERS,
               "walk-edges": WALK_EDGES_USERS}[args.edge_lock]
    users = range(args.users[0], args.users[1]) if len(args.users) > 1 else default
    if args.edge_lock is not None:
        edge_lock_rule(users, args.external, args.edge_lock, args.baseline)
    else:
        route_table(users)
