"""Decision L280's adoption measurement (run once; the rule is in docs/decisions/localization.md): L264's protocol
(``compass_window_shift.py``, parts a-d) on fresh simulated users 5420-5449 with three configurations - pre-L264
(L182's one fit + L226's one constant), today (L264's windows + L266's line, adopted in L265) and the candidate
(today + L280's span gates: L182's one fit also judges a walk up to ``COMPASS_ONE_FIT_MAX_S``; L266's line only on a
stretch of ``FALLBACK_DRIFT_MIN_S``) - and clean-compass tracking (L17's fused heading, ``compass_fallback=False``)
on the shift routes. Offline, no model. Prints; changes nothing on disk but a temporary folder.

Run: ``OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/compass_span_l280.py``
"""

from __future__ import annotations

import logging
import tempfile
from pathlib import Path

import numpy as np

import pdrlearn.track.plasys as P
from pdrlearn.io.plasys import read_session
from pdrlearn.track.evaluate import STOREY_HEIGHT_M, track_summary

ROOT = Path(__file__).resolve().parents[1]
from compass_check_long import R1  # noqa: E402  the navigation trial's R1 (L226)
from compass_window_shift import LOOP, ROUTE1, SHORT, fmt, simulate  # noqa: E402  (L264's routes, runner)

#: (windowed check, drifting line, L280's span gates) per configuration
CONFIGS = {"pre-L264": (False, False, False), "today": (True, True, False), "candidate": (True, True, True)}
ROUTE2 = ROUTE1 + (", stand:60, up:17, straight:3, up:17, straight:3, up:17, straight:20, turn:180, straight:20, "
                   "down:17, straight:3, down:17, straight:3, down:17, trolley:80, stand:300, straight:50, "
                   "curve:90:3, straight:30, stand:60, straight:40")  # L264's route2


def track(s, config: str, sh: float, **kw) -> dict:
    P.COMPASS_CHECK_WINDOWED, P.FALLBACK_DRIFT, P.COMPASS_SPAN_GATES = CONFIGS[config]
    return summarise(P.track_plasys(s, **kw), s, sh)


def summarise(r, s, sh: float) -> dict:
    """A track's summary with the compass check's median disagreement and whether it fired (also L544's / L558's)."""
    out = track_summary(r, s, storey_height_m=sh)
    cc = r.info.get("compass_check") or {}
    out["_median"], out["_fired"] = cc.get("median_deg"), bool(cc.get("median_deg", 0) > P.COMPASS_DISAGREE_DEG)
    return out


def err(d: dict) -> float:
    return d["final_position_error_m"]


def main() -> None:
    logging.disable(logging.WARNING)
    tmp = Path(tempfile.mkdtemp(prefix="l280_"))
    shift = [("route1", ROUTE1, u, ()) for u in range(5420, 5432)] + \
        [("route2", ROUTE2, u, ()) for u in range(5432, 5438)] + \
        [("route1 drops 3 %", ROUTE1, u, ("--drop-rate", "0.03")) for u in range(5438, 5444)]
    today, cand, clean, worse = [], [], [], []
    for name, route, u, extra in shift:
        s = read_session(simulate(tmp / f"shift_{u}", route, u, *extra))
        a, b = track(s, "today", STOREY_HEIGHT_M), track(s, "candidate", STOREY_HEIGHT_M)
        c = track(s, "today", STOREY_HEIGHT_M, compass_fallback=False)
        today.append(err(a))
        cand.append(err(b))
        clean.append(err(c))
        worse += [u] if err(b) - err(c) > 2 * c["final_position_sigma_m"] else []
        print(f"{name} u{u}: today {fmt(a)}; candidate {fmt(b)}; clean-compass {fmt(c)}", flush=True)
    print(f"(a) SHIFT median final error: today {np.median(today):.2f} m, candidate {np.median(cand):.2f} m, "
          f"clean-compass {np.median(clean):.2f} m; candidate worse than clean by more than its 2 sigma: {worse}",
          flush=True)
    parts = (("(b) R1x2 30 uT", ", ".join([R1] * 2), range(5420, 5440), 2.89, ("--mag-disturbance", "30")),
             ("(b) loop 30 uT", LOOP, range(5440, 5450), STOREY_HEIGHT_M, ("--mag-disturbance", "30")),
             ("(c) short 0", SHORT[0], range(5420, 5430), STOREY_HEIGHT_M, ()),
             ("(c) short 1", SHORT[1], range(5420, 5430), STOREY_HEIGHT_M, ()),
             ("(d) R1x2 3 uT", ", ".join([R1] * 2), range(5420, 5440), 2.89, ()))
    for name, route, users, sh, extra in parts:
        e = {k: [] for k in CONFIGS}
        fired = {k: 0 for k in CONFIGS}
        one_fit, worse = [], []
        for u in users:
            s = read_session(simulate(tmp / f"{name[4:].replace(' ', '')}_{u}", route, u, *extra))
            r = {k: track(s, k, sh) for k in CONFIGS}
            for k in CONFIGS:
                e[k].append(err(r[k]))
                fired[k] += r[k]["_fired"]
            one_fit += [u] if r["pre-L264"]["_fired"] else []
            worse += [u] if err(r["candidate"]) - err(r["today"]) > 2 * r["today"]["final_position_sigma_m"] else []
            if len({round(err(r[k]), 6) for k in CONFIGS}) > 1 or extra:
                print(f"{name} u{u}: " + "; ".join(f"{k} {fmt(r[k])}" for k in CONFIGS), flush=True)
        idx = [list(users).index(u) for u in one_fit]
        on_one = ", ".join(f"{k} {np.median(np.array(e[k])[idx]):.2f} m" for k in CONFIGS) if idx else "none"
        print(f"{name}: median final error " + ", ".join(f"{k} {np.median(e[k]):.3f} m" for k in CONFIGS)
              + "; check fires " + ", ".join(f"{k} {fired[k]}" for k in CONFIGS) + f" of {len(users)}"
              + f"; on the {len(one_fit)} sessions pre-L264's one fit fires ({one_fit}): {on_one}"
              + f"; candidate worse than today by more than today's 2 sigma: {worse}", flush=True)
    for d in sorted((ROOT / "datasets" / "real").glob("gaitmap_*")):
        s = read_session(d)
        r = {k: track(s, k, STOREY_HEIGHT_M) for k in CONFIGS}
        print(f"real {d.name}: distance error " + ", ".join(f"{k} {r[k].get('distance_error_pct')} %"
                                                           for k in CONFIGS)
              + f"; check {r['candidate']['_median']}", flush=True)


if __name__ == "__main__":
    main()
