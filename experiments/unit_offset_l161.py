"""Decision L161's measurement: does the unaligned two-unit track's clock-offset warning stay quiet on clean
simulated sessions and warn when the waist clock is shifted by +0.3 s?

    PYTHONPATH=. python experiments/unit_offset_l161.py --users 1790-1809
"""

from __future__ import annotations

import argparse
import logging

from _results import add_users, user_range  # noqa: E402
from pdrlearn.io.session import Stream  # noqa: E402
from pdrlearn.sim import simulate  # noqa: E402
from pdrlearn.steps.align import align_units  # noqa: E402
from pdrlearn.track.plasys import UNIT_OFFSET_WARN_S, track_plasys  # noqa: E402


def shifted(session, dt: float):
    """The session with every waist stream's clock read ``dt`` s later (``t_w + dt``)."""
    s = session.copy()
    for n, st in list(s.streams.items()):
        if st.placement == "waist":
            s.streams[n] = Stream(n, st.t + dt, st.values)
    return s


def sessions(users: range, shift: float):
    """Per user of ``users``: ``(u, (("clean", s), ("shifted", s')))``, s scenario D at 100 Hz (seed = user) and s'
    its copy with the waist clock ``shift`` s late (L161's and L177's protocol)."""
    for u in users:
        s = simulate("D", u, rate_hz=100.0)
        yield u, (("clean", s), ("shifted", shifted(s, shift)))


def rule_met(warned: dict, n: int) -> bool:
    """L161's adoption rule (L177's too): no clean session of ``n`` warned and at least 15 of 20 shifted ones."""
    return warned["clean"] == 0 and warned["shifted"] >= 15 * n / 20


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    add_users(ap, "1790-1809", "first-last simulated user seeds")
    ap.add_argument("--shift", type=float, default=0.3, help="waist clock shift (s) of the warned sessions")
    a = ap.parse_args()
    users = user_range(a.users)
    logging.disable(logging.WARNING)
    warned = {"clean": 0, "shifted": 0}
    for u, pair in sessions(users, a.shift):
        row = [f"user {u}"]
        for kind, sess in pair:
            offset, _ = align_units(sess)
            r = track_plasys(sess, method="M2")
            w = any("decision L161" in line for line in r.info["warnings"])
            warned[kind] += w
            row.append(f"{kind} offset {offset:+.3f} s warn {int(w)}")
        print(" | ".join(row), flush=True)
    n = len(users)
    print(f"clean warned {warned['clean']}/{n}; +{a.shift:g} s warned {warned['shifted']}/{n} "
          f"(threshold {UNIT_OFFSET_WARN_S:g} s)")
    print("L161 rule:", "ADOPTED" if rule_met(warned, n) else "NOT adopted")


if __name__ == "__main__":
    main()
