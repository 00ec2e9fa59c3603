"""Decision L332: L332's adoption rule (docs/decisions/localization.md) for ``pdrlearn evaluate``'s L95 line - the
sessions :func:`pdrlearn.classify.gait_range.out_of_range_sessions` flags by their labelled strides.

(a) every real / external recording with a steps.csv; (b) fresh simulated users' ``--scenario direction`` sessions
at normal, fast and slow speed; (c) the trial's ``slowback`` (slow, 0.3 m steps, backward) for other fresh users.
Simulated in memory at 20 Hz (PLASYS' rate): the labels do not depend on the rate.

Usage::

    PYTHONPATH=. OMP_NUM_THREADS=1 .venv/bin/python experiments/evaluate_range_l332.py
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from pdrlearn.classify.gait_range import labelled_gait, out_of_range_sessions  # noqa: E402
from pdrlearn.cli.simulate import _custom_gait  # noqa: E402  (--step-length as `pdrlearn simulate` sets it, S30)
from pdrlearn.io import read_session  # noqa: E402
from pdrlearn.sim import UserProfile, simulate, simulate_path  # noqa: E402
from pdrlearn.sim.route import parse_route  # noqa: E402
from pdrlearn.track.gait import _judged  # noqa: E402

SLOWBACK = "stand:2, backward:20, stand:2"  # trial 31's `slowback`, with --speed slow --step-length 0.3


def _users(text: str) -> list[int]:
    a, b = (int(v) for v in text.split("-"))
    return list(range(a, b + 1))


def _row(session, flagged: set[str]) -> str:
    cad, speed, what = _judged(labelled_gait(session))
    figs = f"cadence {cad:.0f} steps/min" if cad is not None else "no cadence"
    figs += f", {what} {speed:.2f} m/s" if speed is not None else ", no speed"
    return f"  {session.name:44s} {figs:58s} {'FLAGGED' if session.name in flagged else 'in range'}"


def _report(title: str, sessions: list) -> int:
    flagged = {f["session"] for f in out_of_range_sessions(sessions)}
    print(f"{title}: {len(flagged)} of {len(sessions)} flagged")
    for s in sessions:
        print(_row(s, flagged))
    return len(flagged)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", default="6500-6509", help="users of (b)")
    ap.add_argument("--back-users", default="6510-6514", help="users of (c)")
    args = ap.parse_args()
    real = sorted({p.parent for base in ("datasets/real", "datasets/external")
                   for p in (ROOT / base).glob("*/steps.csv")})
    n_a = _report("(a) real / external recordings with steps.csv", [read_session(d) for d in real])
    n_b = 0
    for speed in ("normal", "fast", "slow"):
        n_b += _report(f"(b) --scenario direction, {speed}",
                       [simulate("direction", UserProfile.from_seed(u), speed=speed, rate_hz=20.0, seed=u)
                        for u in _users(args.users)])
    back = [simulate_path(parse_route(SLOWBACK), _custom_gait(UserProfile.from_seed(u), "slow", 0.3, None, SLOWBACK),
                          speed="slow", rate_hz=20.0, seed=u, scenario="route", name=f"slowback_u{u}")
            for u in _users(args.back_users)]
    n_c = _report("(c) slowback (slow, 0.3 m steps)", back)
    ok = n_a == 0 and n_b == 0 and n_c == len(back)
    print(f"rule: (a) {n_a} flagged (need 0), (b) {n_b} flagged (need 0), (c) {n_c} of {len(back)} flagged "
          f"(need all): {'ADOPT' if ok else 'NOT ADOPTED'}")


if __name__ == "__main__":
    main()
