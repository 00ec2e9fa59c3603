"""Decision L198's measurement: does the clock estimate (``pdrlearn.kernels.align.align_events``, fitted about the
matched foot events' mean) give the same offset whatever the clocks' origin (0, device uptime, epoch), keep L161 /
L183's check (clean quiet, +0.3 s warned), and what did the old fit (read at t = 0) say?

    PYTHONPATH=. python experiments/clock_origin_l198.py --users 3500-3529 [--live]
"""

from __future__ import annotations

import argparse
import logging

from live_clock_check_l177 import BUNDLE, live
from pdrlearn.io.session import Stream
from pdrlearn.kernels.align import unit_offset_message
from pdrlearn.sim import simulate
from pdrlearn.steps.align import align_estimate
from unit_offset_l161 import shifted

#: the clock origins (s): the simulator's 0, one hour of device uptime, an epoch clock (2024)
ORIGINS = (0.0, 3600.0, 1.7e9)


def moved(session, origin: float):
    """The session with every stream's clock (foot and waist alike) starting at ``origin`` s."""
    s = session.copy()
    for n, st in list(s.streams.items()):
        s.streams[n] = Stream(n, st.t + origin, st.values)
    return s


def judge(session, bundle=None) -> dict:
    """The estimate, whether L161's line warns (L183's lock included) now and with the old fit (read at t = 0)."""
    est = align_estimate(session)
    old = est["offset_s"] - est["drift"] * est["ref_s"]  # the same line read at the clock's 0 (before L198)
    out = {"offset": est["offset_s"], "old": old,
           "warn": unit_offset_message(est["offset_s"], est["drift"], estimate=est) is not None,
           "warn_old": unit_offset_message(old, est["drift"], estimate=est) is not None}
    if bundle is not None:
        tr, lines = live(session, bundle, 1.0)
        out["live_warn"] = bool(lines)
        out["live_offset"] = tr.clock_offset["offset_s"] if tr.clock_offset else float("nan")
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--users", default="3500-3529")
    ap.add_argument("--live", action="store_true", help="also the live Tracker's check (1 s chunks)")
    a = ap.parse_args()
    logging.disable(logging.WARNING)
    from pdrlearn.runtime import load_bundle

    bundle = load_bundle(BUNDLE) if a.live else None
    lo, hi = (int(v) for v in a.users.split("-"))
    n = {k: [0] * len(ORIGINS) for k in ("clean", "clean_old", "shifted", "shifted_old", "live_clean",
                                         "live_shifted")}
    spread = live_gap = 0.0
    for u in range(lo, hi + 1):
        s = simulate("D", u, rate_hz=100.0)
        row = [f"D {u}"]
        for kind, base in (("clean", s), ("shifted", shifted(s, 0.3))):
            offs = []
            for i, origin in enumerate(ORIGINS):
                r = judge(moved(base, origin), bundle)
                offs.append(r["offset"])
                n[kind][i] += r["warn"]
                n[kind + "_old"][i] += r["warn_old"]
                if bundle is not None:
                    n["live_" + kind][i] += r["live_warn"]
                    live_gap = max(live_gap, abs(r["live_offset"] - r["offset"]))
                row.append(f"{kind} @{origin:g} {r['offset']:+.4f} (old {r['old']:+.2f}) warned {int(r['warn'])}"
                           + (f" live {int(r['live_warn'])}" if bundle is not None else ""))
            spread = max(spread, max(offs) - min(offs))
        print(" | ".join(row), flush=True)
    users = hi - lo + 1
    for i, origin in enumerate(ORIGINS):
        print(f"origin {origin:g} s: clean warned {n['clean'][i]}/{users} (old fit {n['clean_old'][i]}); +0.3 s "
              f"warned {n['shifted'][i]}/{users} (old fit {n['shifted_old'][i]})"
              + (f"; live clean {n['live_clean'][i]}, +0.3 s {n['live_shifted'][i]}" if bundle is not None else ""))
    print(f"largest offset spread over the origins {spread * 1e3:.3f} ms"
          + (f"; largest |live final - offline| {live_gap:.2e} s" if bundle is not None else ""))
    ok = (all(c == 0 for c in n["clean"]) and all(c == users for c in n["shifted"]) and spread <= 1e-3)
    print("L198 rule (a-c):", "KEPT" if ok else "NOT kept")


if __name__ == "__main__":
    main()
