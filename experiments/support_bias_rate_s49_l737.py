"""Decision L737 (session 49, FA, review R1 F2): does L730's two-term insole caveat (measured at 100 Hz) hold at a
foot rate of 50 and 20 Hz?

Usage:
    PYTHONPATH=.:experiments .venv/bin/python experiments/support_bias_rate_s49_l737.py [FIRST_USER N_USERS [RATE ...]]

Users 16500-16519 (fresh, session 49), L728's route, paces and walker (experiments/support_bias_s48_l728.py), force
insoles, both feet of one walk simulated at each ``rate_hz`` (default 100, 50, 20). Per walk: the median IC and
toe-off errors (ms, L728's matching), the tracked - true double support (points) and L730's double-support range at
the walk's cycle (:func:`pdrlearn.track.support_bias.stance_bias_ms`, ``200 b / c``). Prints one row per walk and, per
rate, how many walks lie within L730's range widened by 1 point on each side (L737's rule: at least 90 %); writes
nothing.
"""

from __future__ import annotations

import logging
import sys

import numpy as np

from pdrlearn.sim.route import parse_route
from pdrlearn.sim.simulate import simulate_path
from pdrlearn.track.bilateral import bilateral_gait, label_steps
from pdrlearn.track.plasys import track_plasys
from pdrlearn.track.support_bias import stance_bias_ms
from support_bias_s48_l728 import ROUTE, errors_ms, walker

WIDEN = 1.0  # L730's check: the range widened by 1 point on each side
SHARE = 0.9  # L737's rule: at least 90 % of the walks (L730's 27 of 30)


def ds_range(cycle_s: float) -> tuple[float, float]:
    """L730's double-support range (points) at a gait cycle of ``cycle_s`` s: twice the stance bias's share."""
    lo, hi = stance_bias_ms("force", cycle_s)
    return 200.0 * lo / 1000.0 / cycle_s, 200.0 * hi / 1000.0 / cycle_s


def walk_row(u: int, pace: str, rate: float) -> tuple:
    user, speed = walker(u, pace)
    sessions = [simulate_path(parse_route(ROUTE), user, speed=speed, rate_hz=rate, seed=u, instrumented_foot=f)
                for f in ("left", "right")]
    labels = [label_steps(s) for s in sessions]
    truth = bilateral_gait(*labels)["walk"]
    tracks = [track_plasys(s, toe_off=True, transfers=False) for s in sessions]
    res = bilateral_gait(*(t.steps for t in tracks), contact_source="force")["walk"]
    pairs = list(zip(tracks, labels, strict=True))
    ic = np.concatenate([errors_ms(t.steps["event_s"], lab["ic_s"]) for t, lab in pairs])
    to = np.concatenate([errors_ms(t.steps["tc_s"], lab["tc_s"]) for t, lab in pairs])
    cyc = 0.5 * (truth["stride_time_s_left"] + truth["stride_time_s_right"])
    ds = res["double_support_pct"]
    diff = np.nan if ds is None else ds - truth["double_support_pct"]
    lo, hi = ds_range(cyc)
    inside = bool(lo - WIDEN <= diff <= hi + WIDEN)
    return (u, pace, rate, cyc, float(np.median(ic)) if len(ic) else np.nan,
            float(np.median(to)) if len(to) else np.nan, diff, lo, hi, inside)


def main() -> None:
    logging.disable(logging.WARNING)
    first, n = (int(sys.argv[1]), int(sys.argv[2])) if len(sys.argv) > 2 else (16500, 20)
    rates = [float(r) for r in sys.argv[3:]] or [100.0, 50.0, 20.0]
    print("rate Hz | user | pace | cycle s | IC err ms | TO err ms | DS tracked-true | L730 range | within +-1")
    rows = []
    for rate in rates:
        for u in range(first, first + n):
            for pace in ("normal", "fast", "race"):
                r = walk_row(u, pace, rate)
                rows.append(r)
                print(f"{rate:g} | {u} | {pace} | {r[3]:.3f} | {r[4]:+.1f} | {r[5]:+.1f} | {r[6]:+.1f} | "
                      f"{r[7]:+.1f}..{r[8]:+.1f} | {'yes' if r[9] else 'no'}", flush=True)
    print("per rate and pace: median cycle s | IC err ms | TO err ms | DS diff (min..max) | within")
    for rate in rates:
        for pace in ("normal", "fast", "race"):
            r = np.array([x[3:9] for x in rows if x[2] == rate and x[1] == pace], float)
            k = sum(x[9] for x in rows if x[2] == rate and x[1] == pace)
            print(f"{rate:g} Hz {pace}: {np.median(r[:, 0]):.3f} | {np.median(r[:, 1]):+.1f} | "
                  f"{np.median(r[:, 2]):+.1f} | {np.nanmedian(r[:, 3]):+.1f} ({np.nanmin(r[:, 3]):+.1f}.."
                  f"{np.nanmax(r[:, 3]):+.1f}) | {k} of {len(r)}")
        k = sum(x[9] for x in rows if x[2] == rate)
        m = sum(1 for x in rows if x[2] == rate)
        print(f"{rate:g} Hz: within L730's range +-{WIDEN:g} point on {k} of {m} walks: "
              f"{'holds' if k >= SHARE * m else 'fails'} (rule: at least {SHARE:.0%})")


if __name__ == "__main__":
    main()
