"""Decision L177's measurement: does the live Tracker's clock check (its early estimates included) stay quiet on
clean simulated sessions and warn when the waist clock is shifted by +0.3 s, and is its final estimate the offline
``align_units``' (L161's rule, on the runtime)?

    PYTHONPATH=. python experiments/live_clock_check_l177.py --users 2980-2999
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

from _results import add_users, user_range  # noqa: E402
from pdrlearn.runtime import Tracker, load_bundle  # noqa: E402
from pdrlearn.runtime.replay import replay_chunks  # noqa: E402
from pdrlearn.steps.align import align_units  # noqa: E402
from unit_offset_l161 import rule_met, sessions  # noqa: E402

BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"


def live(session, bundle, chunk_s: float):
    tr = Tracker(bundle)
    for push in replay_chunks({n: (st.t, st.values) for n, st in session.streams.items() if len(st)}, chunk_s):
        tr.push(push)
    tr.flush()
    return tr, [w for w in tr.warnings if "decision L161" in w]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    add_users(ap, "2980-2999", "first-last simulated user seeds")
    ap.add_argument("--shift", type=float, default=0.3, help="waist clock shift (s) of the warned sessions")
    ap.add_argument("--chunk-s", type=float, default=1.0, help="replay chunk (s), run's default")
    a = ap.parse_args()
    users = user_range(a.users)
    logging.disable(logging.WARNING)
    bundle = load_bundle(BUNDLE)
    warned = {"clean": 0, "shifted": 0}
    worst = 0.0
    for u, pair in sessions(users, a.shift):
        row = [f"user {u}"]
        for kind, sess in pair:
            offline, _ = align_units(sess)
            tr, lines = live(sess, bundle, a.chunk_s)
            est = tr.clock_offset
            fin = est["offset_s"] if est else float("nan")
            worst = max(worst, abs(fin - offline))
            warned[kind] += bool(lines)
            said = lines[0].split(" s from")[0].rsplit(" ", 1)[-1] if lines else "-"
            row.append(f"{kind} offline {offline:+.3f} live final {fin:+.3f} warned {int(bool(lines))} ({said})")
        print(" | ".join(row), flush=True)
    n = len(users)
    print(f"clean warned {warned['clean']}/{n}; +{a.shift:g} s warned {warned['shifted']}/{n}; "
          f"largest |live final - offline| {worst:.2e} s")
    print("L177 rule:", "ADOPTED (clock_check on by default)" if rule_met(warned, n)
          else "NOT adopted (clock_check stays off)")


if __name__ == "__main__":
    main()
