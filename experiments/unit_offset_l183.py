"""Decision L183's measurement: does the clock check's lock test (``pdrlearn.kernels.align.offset_locked``) keep
L161's warning on clean / +0.3 s shifted scenario D sessions as it was (clean quiet, shifted warned) and silence it on
queue sessions (start-stop shuffles, 1-2 strides a bout)? Offline (``unit_offset_line``, what ``track`` / ``run``
warn with) and, with ``--live``, the live ``Tracker``'s L177 check (any estimate, 1 s chunks).

    PYTHONPATH=. python experiments/unit_offset_l183.py --users 3040-3069 --queue-users 3040-3049 \
        --queue-dirs /tmp/tb/queue [--live]
"""

from __future__ import annotations

import argparse
import logging
import tempfile
from pathlib import Path

from live_clock_check_l177 import BUNDLE, live
from pdrlearn.io import read_session
from pdrlearn.kernels.align import offset_locked, unit_offset_message
from pdrlearn.sim import simulate
from pdrlearn.steps.align import align_estimate
from unit_offset_l161 import shifted

QUEUE = ", ".join(["stand:4, straight:0.5"] * 12)  # the trial's queue route (session 26, finding 10)


def judge(session, bundle=None) -> dict:
    """Offline: the estimate, warned before L183 (offset alone) and with it; live (``bundle``): the same pair."""
    try:
        est = align_estimate(session)
    except Exception:  # too few events: no estimate, no line (as unit_offset_line)
        est = None
    old = est is not None and unit_offset_message(est["offset_s"], est["drift"]) is not None
    new = est is not None and unit_offset_message(est["offset_s"], est["drift"], estimate=est) is not None
    out = {"est": est, "old": old, "new": new}
    if bundle is not None:
        tr, _ = live(session, bundle, 1.0)
        out["live_new"] = bool([w for w in tr.warnings if "decision L161" in w])
    return out


def fmt(name: str, r: dict) -> str:
    e = r["est"]
    if e is None:
        return f"{name}: no estimate"
    s = (f"{name}: offset {e['offset_s']:+.3f} s, matched {e['matched']}/{e['foot_events']}, residual SD "
         f"{e['residual_sd_s']:.4f} s, locked {int(offset_locked(e))}, warned before {int(r['old'])} "
         f"now {int(r['new'])}")
    return s + (f", live now {int(r['live_new'])}" if "live_new" in r else "")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--users", default="3040-3069")
    ap.add_argument("--queue-users", default="3040-3049")
    ap.add_argument("--queue-dirs", nargs="*", default=[])
    ap.add_argument("--live", action="store_true")
    a = ap.parse_args()
    logging.disable(logging.WARNING)
    from pdrlearn.cli import main as cli
    from pdrlearn.runtime import load_bundle

    bundle = load_bundle(BUNDLE) if a.live else None
    lo, hi = (int(v) for v in a.users.split("-"))
    n = {"clean": 0, "shifted_old": 0, "shifted_new": 0, "lost": 0, "queue": 0, "queue_n": 0, "live_clean": 0,
         "live_shifted": 0, "live_queue": 0}
    for u in range(lo, hi + 1):
        s = simulate("D", u, rate_hz=100.0)
        c, sh = judge(s, bundle), judge(shifted(s, 0.3), bundle)
        n["clean"] += c["new"]
        n["shifted_old"] += sh["old"]
        n["shifted_new"] += sh["new"]
        n["lost"] += sh["old"] and not sh["new"]
        n["live_clean"] += c.get("live_new", 0)
        n["live_shifted"] += sh.get("live_new", 0)
        print(fmt(f"D {u} clean", c), "|", fmt("+0.3 s", sh), flush=True)
    queues = [(d, read_session(d)) for d in a.queue_dirs]
    qlo, qhi = (int(v) for v in a.queue_users.split("-"))
    with tempfile.TemporaryDirectory() as tmp:
        for u in range(qlo, qhi + 1):
            d = Path(tmp) / f"queue_{u}"
            rc = cli(["simulate", "--route", QUEUE, "--step-length", "0.2", "--step-time", "0.7", "--user-seed",
                      str(u), "--out", str(d)])
            assert rc == 0
            queues.append((f"queue user {u}", read_session(d)))
        for name, s in queues:
            r = judge(s, bundle)
            n["queue"] += r["new"]
            n["queue_n"] += 1
            n["live_queue"] += r.get("live_new", 0)
            print(fmt(str(name), r), flush=True)
    users = hi - lo + 1
    print(f"clean warned {n['clean']}/{users}; +0.3 s warned {n['shifted_new']}/{users} (before L183 "
          f"{n['shifted_old']}/{users}, silenced {n['lost']}); queue warned {n['queue']}/{n['queue_n']}")
    if a.live:
        print(f"live: clean warned {n['live_clean']}/{users}; +0.3 s warned {n['live_shifted']}/{users}; queue warned "
              f"{n['live_queue']}/{n['queue_n']}")
    ok = n["clean"] == 0 and n["lost"] == 0 and n["queue"] == 0  # the rule (offline); live reported beside it
    print("L183 rule:", "ADOPTED" if ok else "NOT adopted")


if __name__ == "__main__":
    main()
