"""Decision L264's adoption measurement (run once; the rule is in docs/decisions/localization.md): today's L182 check
and L226 fallback against the candidate (L264's windowed check + L266's drifting fallback offset) on fresh simulated
users 5170-5199 - the session-29 trial's shift routes (route1, route2, route1 with 3 % foot drops), clean-compass
tracking (L17's fused heading, ``compass_fallback=False``) as the reference; L226's R1 x2 and L182's loop at 30 uT
(does the check still fire); short routes and R1 x2 at 3 uT - and the real gaitmap recordings. Offline, no model.
Prints; changes nothing on disk but a temporary folder.

Run: ``OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/compass_window_shift.py``
"""

from __future__ import annotations

import logging
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

import pdrlearn.track.plasys as P
from pdrlearn.io.plasys import read_session
from pdrlearn.track.evaluate import STOREY_HEIGHT_M, track_summary

ROOT = Path(__file__).resolve().parents[1]
from compass_check_long import R1  # noqa: E402  the navigation trial's R1 (L226)

# the session-29 trial's shift routes (/tmp/occ/route1.txt; route2 = route1 + 3 flights up / down, trolley, curve)
ROUTE1 = ("stand:30, straight:30, turn:90, straight:15, stand:10, side:2, straight:10, turn:-90, trolley:40, stand:30, "
          "up:17, straight:3, up:17, straight:10, sit:300, straight:10, lift:-6, straight:20, stand:60, straight:8, "
          "turn:180, straight:8, stand:120, straight:5, turn:90, straight:5, turn:90, straight:5, turn:90, straight:5, "
          "stand:20, trolley:60, turn:180, trolley:60, sit:400, straight:25, down:17, straight:3, down:17, "
          "straight:40, stand:200, straight:12, pivot:90, straight:12, pivot:-90, straight:12, stand:15, straight:30")
LOOP = ", ".join(["straight:15, curve:-90:1"] * 8)  # L182's level loop
SHORT = ("straight:30, turn:90, straight:30", LOOP)


def simulate(out: Path, route: str, u: int, *extra: str) -> Path:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    subprocess.run([sys.executable, "-m", "pdrlearn", "simulate", "--route", route, "--user-seed", str(u), "--seed",
                    str(u), *extra, "--out", str(out)], check=True, capture_output=True, env=env)
    return out


def track(s, candidate: bool, sh: float, **kw) -> dict:
    P.COMPASS_CHECK_WINDOWED = P.FALLBACK_DRIFT = candidate
    P.COMPASS_SPAN_GATES = False  # L265's measurement was before L280's gates (L281)
    r = P.track_plasys(s, **kw)
    out = track_summary(r, s, storey_height_m=sh)
    cc = r.info.get("compass_check") or {}
    out["_median"], out["_fired"] = cc.get("median_deg"), bool(cc.get("median_deg", 0) > P.COMPASS_DISAGREE_DEG)
    return out


def three(folder: Path, sh: float = STOREY_HEIGHT_M) -> tuple[dict, dict, dict]:
    s = read_session(folder)
    return track(s, False, sh), track(s, True, sh), track(s, False, sh, compass_fallback=False)


def fmt(d: dict) -> str:
    med = "-" if d["_median"] is None else f"{d['_median']:.1f}"
    return f"{d['final_position_error_m']:.2f} m (2 sigma {2 * d['final_position_sigma_m']:.2f}, check {med} deg)"


def main() -> None:
    logging.disable(logging.WARNING)
    tmp = Path(tempfile.mkdtemp(prefix="l264_"))
    route2 = ROUTE1 + (", stand:60, up:17, straight:3, up:17, straight:3, up:17, straight:20, turn:180, straight:20, "
                       "down:17, straight:3, down:17, straight:3, down:17, trolley:80, stand:300, straight:50, "
                       "curve:90:3, straight:30, stand:60, straight:40")  # /tmp/occ/route2.txt
    shift = [("route1", ROUTE1, u, ()) for u in range(5170, 5182)] + \
        [("route2", route2, u, ()) for u in range(5182, 5188)] + \
        [("route1 drops 3 %", ROUTE1, u, ("--drop-rate", "0.03")) for u in range(5188, 5194)]
    today, cand, clean, worse = [], [], [], []
    for name, route, u, extra in shift:
        a, b, c = three(simulate(tmp / f"shift_{u}", route, u, *extra))
        today.append(a["final_position_error_m"])
        cand.append(b["final_position_error_m"])
        clean.append(c["final_position_error_m"])
        worse += [u] if b["final_position_error_m"] - c["final_position_error_m"] > 2 * c["final_position_sigma_m"] \
            else []
        print(f"{name} u{u}: today {fmt(a)}; candidate {fmt(b)}; clean-compass {fmt(c)}", flush=True)
    print(f"SHIFT median final error: today {np.median(today):.2f} m, candidate {np.median(cand):.2f} m, clean-compass "
          f"{np.median(clean):.2f} m; candidate worse than clean by more than its 2 sigma: {worse}", flush=True)
    for name, route, users, sh in (("R1x2 30 uT", ", ".join([R1] * 2), range(5170, 5190), 2.89),
                                   ("loop 30 uT", LOOP, range(5190, 5200), STOREY_HEIGHT_M)):
        fa = fb = 0
        ea, eb = [], []
        for u in users:
            a, b, _ = three(simulate(tmp / f"{name[:4]}30_{u}", route, u, "--mag-disturbance", "30"), sh)
            fa, fb = fa + a["_fired"], fb + b["_fired"]
            ea.append(a["final_position_error_m"])
            eb.append(b["final_position_error_m"])
            print(f"{name} u{u}: today {fmt(a)}; candidate {fmt(b)}", flush=True)
        print(f"{name}: check fires today {fa} of {len(users)}, candidate {fb}; median final error today "
              f"{np.median(ea):.2f} m, candidate {np.median(eb):.2f} m", flush=True)
    for name, route, users, sh in (("short 0", SHORT[0], range(5170, 5180), STOREY_HEIGHT_M),
                                   ("short 1", SHORT[1], range(5170, 5180), STOREY_HEIGHT_M),
                                   ("R1x2 3 uT", ", ".join([R1] * 2), range(5170, 5190), 2.89)):
        ea, eb, fa, fb = [], [], 0, 0
        for u in users:
            a, b, _ = three(simulate(tmp / f"{name.replace(' ', '')}_{u}", route, u), sh)
            ea.append(a["final_position_error_m"])
            eb.append(b["final_position_error_m"])
            fa, fb = fa + a["_fired"], fb + b["_fired"]
            if a["final_position_error_m"] != b["final_position_error_m"]:
                print(f"{name} u{u}: today {fmt(a)}; candidate {fmt(b)}", flush=True)
        print(f"{name}: median final error today {np.median(ea):.3f} m, candidate {np.median(eb):.3f} m; check fires "
              f"today {fa} of {len(users)}, candidate {fb}", flush=True)
    for d in sorted((ROOT / "datasets" / "real").glob("gaitmap_*")):
        s = read_session(d)
        a, b = track(s, False, STOREY_HEIGHT_M), track(s, True, STOREY_HEIGHT_M)
        print(f"real {d.name}: distance error today {a.get('distance_error_pct')} %, candidate "
              f"{b.get('distance_error_pct')} %, check {a['_median']} / {b['_median']}", flush=True)


if __name__ == "__main__":
    main()
