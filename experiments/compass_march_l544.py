"""Decision L544's adoption measurement (run once; the rule is in docs/decisions/localization.md): "today" (L182's
check fitting a hard-iron offset on every set of strides) against the candidate (no offset fitted where the headings'
resultant length exceeds L84's ``HARD_IRON_MAX_RESULTANT``; in L264's windows a heading offset that drifts
linearly) and clean-compass tracking (``compass_fallback=False``),
on fresh simulated users 10840-10851: (a) marches, (b) a disturbed compass, (c) short routes, (d) R1 x2 and L264's
shift at 3 uT. Offline, no model. Prints; changes nothing on disk but a temporary folder.

Since L545 (not adopted) L182's one fit is never gated; since L559 (L558's rule met) the windows always fit L544's
model from two windows on and there is no keyword left: a rerun tracks today's code as both "today" and "candidate"
(the measured "today" is in the decision log only).

Run: ``OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/compass_march_l544.py``
"""

from __future__ import annotations

import logging
import sys
import tempfile
from pathlib import Path

import numpy as np

import pdrlearn.track.plasys as P
from pdrlearn.io.plasys import read_session
from pdrlearn.track.evaluate import STOREY_HEIGHT_M

ROOT = Path(__file__).resolve().parents[1]
from compass_check_long import R1  # noqa: E402  the navigation trial's R1 (L226)
from compass_span_l280 import err, summarise  # noqa: E402  (L280's track summary and compass check)
from compass_window_shift import LOOP, ROUTE1, SHORT, fmt, simulate  # noqa: E402  (L264's routes, runner)

MARCH = "straight:1200:fast, slope:500:6, curve:90:50, straight:1000, slope:500:-6, straight:800:slow"


def track(s, config: str, sh: float, **kw) -> dict:
    """``config`` ("today" / "candidate") only names the result since L559: both track today's code."""
    return summarise(P.track_plasys(s, **kw), s, sh)


def run_part(tmp: Path, name: str, route: str, users, sh: float, extra=(), clean: bool = False) -> None:
    e, fired, worse = {"today": [], "candidate": [], "clean": []}, {"today": 0, "candidate": 0}, []
    for u in users:
        s = read_session(simulate(tmp / f"{''.join(c for c in name if c.isalnum())}_{u}", route, u, *extra))
        r = {k: track(s, k, sh) for k in ("today", "candidate")}
        if clean:
            r["clean"] = track(s, "candidate", sh, compass_fallback=False)
        for k in r:
            e[k].append(err(r[k]))
            if k in fired:
                fired[k] += r[k]["_fired"]
        worse += [u] if err(r["candidate"]) - err(r["today"]) > 2 * r["today"]["final_position_sigma_m"] else []
        print(f"{name} u{u}: " + "; ".join(f"{k} {fmt(r[k])}" for k in r), flush=True)
    print(f"{name}: median final error " + ", ".join(f"{k} {np.median(v):.3f} m" for k, v in e.items() if v)
          + "; check fires " + ", ".join(f"{k} {n}" for k, n in fired.items()) + f" of {len(users)}"
          + f"; candidate worse than today by more than today's 2 sigma: {worse}", flush=True)


def main(start: int = 0) -> None:
    """``start``: the first part to run (the first run stopped at part 8, "(c) short loop", on a folder name its
    parts shared; the rerun began there with the same users)."""
    logging.disable(logging.WARNING)
    tmp = Path(tempfile.mkdtemp(prefix="l544_"))
    r1x2 = ", ".join([R1] * 2)
    parts = []
    part = (lambda *a, **k: parts.append((a, k)))  # noqa: E731  collected, then run from ``start``
    part(tmp, "(a) march", MARCH, range(10840, 10844), STOREY_HEIGHT_M, clean=True)
    part(tmp, "(a) straight1000", "straight:1000", range(10844, 10846), STOREY_HEIGHT_M, clean=True)
    part(tmp, "(b) R1x2 30uT", r1x2, range(10846, 10852), 2.89, ("--mag-disturbance", "30"))
    part(tmp, "(b) loop 30uT", LOOP, range(10846, 10852), STOREY_HEIGHT_M, ("--mag-disturbance", "30"))
    part(tmp, "(b) straight300 30uT", "straight:300", range(10846, 10850), STOREY_HEIGHT_M,
         ("--mag-disturbance", "30"))
    part(tmp, "(b) shift route1 30uT", ROUTE1, range(10850, 10852), STOREY_HEIGHT_M, ("--mag-disturbance", "30"))
    part(tmp, "(c) short 0", SHORT[0], range(10846, 10852), STOREY_HEIGHT_M)
    part(tmp, "(c) short loop", SHORT[1], range(10846, 10852), STOREY_HEIGHT_M)
    part(tmp, "(d) R1x2 3uT", r1x2, range(10846, 10852), 2.89)
    part(tmp, "(d) shift route1", ROUTE1, range(10850, 10852), STOREY_HEIGHT_M, clean=True)
    for a, k in parts[start:]:
        run_part(*a, **k)


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 0)
