"""Decision W337 (docs/decisions/waist.md): W336's `foot_rest_veto` off vs on, measured once (rule committed first).
(a) fresh simulated users 7190-7199, W218's routes + stairs, waist-pendulum and waist-pll: pooled F1, extra contacts,
summed |distance error|; (b) the same users standing in a vehicle ride (S71): contacts inside the ride, F1;
(c) the real recordings with both a foot and a lower-back unit (counted).

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_foot_rest_w337.py [W342|W548]
Writes experiments/results/waist_foot_rest_w337.md (with W342: waist_foot_rest_w342.md, decision W342's re-run; with
W548: waist_foot_rest_w548.md, W548's check on fresh users 15840-15849 with its part (d), race walkers).
"""

from __future__ import annotations

import contextlib
import io
import logging
import sys
import warnings
from pathlib import Path

import numpy as np

import waist_ic_classes as W  # noqa: E402 - f1
import waist_stand as S  # noqa: E402 - W218's routes, matched_truth
from pdrlearn.track.waist import track_waist
from waist_freeze_veto import simulate  # noqa: E402 - a route at a given gait

ROOT = Path(__file__).resolve().parents[1]
USERS = range(7190, 7200)  # the lead's fresh users for W337 (F4's range 7180-7209)
ROUTES = {**S.W218_ROUTES,
          "stairs": ("stand:3, straight:5, up:12, straight:3, down:12, straight:5, stand:3", {})}
RIDE = "stand:5, straight:15, vehicle:120, straight:15, stand:5"
PIPELINES = ("waist-pendulum", "waist-pll")


def _run(s, pipeline: str, on: bool) -> tuple[np.ndarray, float]:
    st = track_waist(s, pipeline=pipeline, foot_rest_veto=on).steps
    return st["event_s"].to_numpy(float), float(np.nansum(st["length_m"].to_numpy(float)))


def routes() -> bool:
    print("## (a) W218's routes + stairs, off -> on\n\n| route | pipeline | F1 off (TP/det/ref) | F1 on | extra off -> "
          "on | sum abs distance error m off -> on | met |\n|---|---|---|---|---|---|---|")
    ok = True
    for name, (route, kw, *gait) in ROUTES.items():
        sessions = [simulate(route.format(hz=3 + u % 6, acc=(7.0, 8.5, 10.0)[u % 3]), kw, u,
                             gait[0](u) if gait else None) for u in USERS]
        for pl in PIPELINES:
            n = {v: np.zeros(3, dtype=int) for v in (False, True)}
            derr = {v: 0.0 for v in n}
            for s in sessions:
                truth = s.extras["ics"]["ic_s"].to_numpy(float)
                walked = float(s.steps["length_m"].sum()) if s.steps is not None else 0.0
                for v in n:
                    ev, dist = _run(s, pl, v)
                    m = S.matched_truth(ev, truth)
                    n[v] += (int((m >= 0).sum()), ev.size, truth.size)
                    derr[v] += abs(dist - walked)
            f = {v: W.C.f1(*map(int, n[v])) for v in n}
            extra = {v: int(n[v][1] - n[v][0]) for v in n}
            good = (f[True] >= f[False] - 0.002 and extra[True] <= extra[False] + 0.002 * int(n[False][2])
                    and derr[True] <= derr[False] * 1.01 + 1e-9)
            ok &= good
            print(f"| {name} | {pl} | {f[False]:.4f} ({'/'.join(map(str, n[False]))}) | {f[True]:.4f} "
                  f"({'/'.join(map(str, n[True]))}) | {extra[False]} -> {extra[True]} | {derr[False]:.2f} -> "
                  f"{derr[True]:.2f} | {'yes' if good else 'NO'} |", flush=True)
    print(f"\n(a) {'met' if ok else 'NOT met'}\n")
    return ok


def rides() -> bool:
    print(f"## (b) vehicle ride `{RIDE}`, off -> on\n\n| pipeline | contacts in rides off -> on | F1 off -> on | "
          "distance m off -> on (walked) | met |\n|---|---|---|---|---|")
    sessions = [simulate(RIDE, {}, u) for u in USERS]
    ok = True
    for pl in PIPELINES:
        inside, dist = {False: 0, True: 0}, {False: 0.0, True: 0.0}
        n = {v: np.zeros(3, dtype=int) for v in (False, True)}
        walked = 0.0
        for s in sessions:
            truth = s.extras["ics"]["ic_s"].to_numpy(float)
            row = s.extras["rides"].iloc[0]
            walked += float(s.steps["length_m"].sum())
            for v in n:
                ev, d = _run(s, pl, v)
                inside[v] += int(((ev > row.start_s) & (ev < row.end_s)).sum())
                m = S.matched_truth(ev, truth)
                n[v] += (int((m >= 0).sum()), ev.size, truth.size)
                dist[v] += d
        f = {v: W.C.f1(*map(int, n[v])) for v in n}
        good = inside[True] <= 0.1 * inside[False] and f[True] > f[False]
        ok &= good
        print(f"| {pl} | {inside[False]} -> {inside[True]} | {f[False]:.4f} -> {f[True]:.4f} | {dist[False]:.1f} -> "
              f"{dist[True]:.1f} ({walked:.1f}) | {'yes' if good else 'NO'} |", flush=True)
    print(f"\n(b) {'met' if ok else 'NOT met'}\n")
    return ok


def real() -> bool:
    from pdrlearn.io import read_session

    both = 0
    dirs = [p.parent for root in (ROOT / "datasets" / "external", Path("/work/shared/data")) if root.exists()
            for p in root.rglob("meta.json")]
    for d in dirs:
        try:
            s = read_session(d)
        except Exception:  # noqa: BLE001 - counting only
            continue
        both += bool(s.placement_streams("foot")) and bool(s.placement_streams("waist"))
    print(f"## (c) real sessions with both a foot and a lower-back unit: {both} of {len(dirs)}\n")
    return True


def verdict(decision: str, title: str, parts: dict, out_name: str, yes: str = "ADOPT", no: str = "not adopted"
            ) -> None:
    """Run each part (name -> callable returning met), print and write experiments/results/OUT_NAME with the
    verdict line (shared by W339's script)."""
    warnings.filterwarnings("ignore")
    logging.disable(logging.WARNING)
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        print(f"# {decision}: {title} (rule committed before this run)\n")
        ok = {k: f() for k, f in parts.items()}
        print(f"{decision} " + ", ".join(f"({k}) {'met' if v else 'NOT met'}" for k, v in ok.items())
              + f": {yes if all(ok.values()) else no}")
    (ROOT / "experiments" / "results" / out_name).write_text(buf.getvalue())
    print(buf.getvalue())


def race() -> bool:
    """Decision W548 (d): race walkers (W549's race gait and route, the foot unit present): the veto drops nothing."""
    from race_walk_s48_w549 import gait_session

    print("## (d) race walkers, waist-pendulum: contacts off -> on\n\n| user | off | on |\n|---|---|---|")
    ok = True
    for u in USERS:
        s = gait_session(u, "race")
        n = {v: _run(s, "waist-pendulum", v)[0].size for v in (False, True)}
        ok &= n[True] == n[False]
        print(f"| {u} | {n[False]} | {n[True]} |", flush=True)
    print(f"\n(d) {'met' if ok else 'NOT met'}\n")
    return ok


if __name__ == "__main__":
    # W342 re-ran W337's rule unchanged after the stride fix: `python experiments/waist_foot_rest_w337.py W342`
    name = sys.argv[1] if len(sys.argv) > 1 else "W337"
    parts = {"a": routes, "b": rides, "c": real}
    if name == "W548":  # decision W548's check: fresh users, and race walkers
        USERS = range(15840, 15850)
        parts["d"] = race
    verdict(name, "foot_rest_veto, off -> on", parts, f"waist_foot_rest_{name.lower()}.md",
            yes="met: W548 kept" if name == "W548" else "ADOPT")
