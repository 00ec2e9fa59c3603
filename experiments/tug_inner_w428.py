"""Decision W428's measurement (docs/decisions/waist.md): a two-unit foot track's TUG outputs with W418's inner
waist work cut to what the TUG reads (``trunk_events``, new) against the whole waist-pendulum track (old), on fresh
simulated two-unit TUGs with different stand / turn / pace settings, and the CPU time of both.

Run: PYTHONPATH=. .venv/bin/python experiments/tug_inner_w428.py [--users 10432-10439] [--walk DIR] [--out DIR]

``--walk``: a two-unit session (e.g. ``pdrlearn simulate --route "stand:3, straight:380, stand:3" --user-seed 10430
--rate 100``) whose ``pdrlearn track`` CPU time is measured in both arms too.
"""

from __future__ import annotations

import argparse
import contextlib
import filecmp
import io
import json
import statistics
import tempfile
import time
from pathlib import Path

#: (route, stand_s, sit_start_s, sit_end_s, speed, bounce) per user, in turn: the T1 TUG, longer stands, a curved turn,
#: a 5 m walk, a normal pace, a 360 deg turn to sit
SETTINGS = [
    ("straight:3, turn:180, straight:3, turn:180", 0.5, 3.0, 3.0, "slow", "pendulum"),
    ("straight:3, turn:180, straight:3, turn:180", 2.0, 3.0, 3.0, "slow", "pendulum"),
    ("straight:3, curve:180:0.6, straight:3, turn:180", 1.0, 4.0, 3.0, "slow", "pendulum"),
    ("straight:5, turn:180, straight:5, turn:180", 0.5, 3.0, 5.0, "normal", "constant"),
    ("straight:3, turn:180, straight:3, turn:180", 3.0, 5.0, 3.0, "normal", "pendulum"),
    ("straight:3, turn:-180, straight:3, turn:-180", 0.5, 3.0, 3.0, "slow", "pendulum"),
    ("straight:3, turn:180, straight:3, turn:360", 1.0, 3.0, 3.0, "slow", "pendulum"),
    ("straight:4, turn:180, straight:4, turn:180", 0.5, 2.0, 2.0, "fast", "pendulum"),
]


def make(uid: int, setting: tuple, out: Path) -> None:
    """One simulated two-unit TUG session written to ``out``."""
    from pdrlearn import write_session
    from pdrlearn.sim.route import parse_route
    from pdrlearn.sim.simulate import simulate_path
    from pdrlearn.sim.user import UserProfile

    route, stand, sit0, sit1, speed, bounce = setting
    s = simulate_path(parse_route(route), UserProfile.from_seed(uid), speed=speed, rate_hz=100, seed=0,
                      scenario="route", sit_start_s=sit0, sit_end_s=sit1, stand_s=stand, bounce=bounce)
    write_session(s, out, overwrite=True)


@contextlib.contextmanager
def old_path():
    """W418's inner work as it was: the whole waist-pendulum track."""
    import pdrlearn.track.waist as W
    from pdrlearn.track.base import get_pipeline

    new = W.trunk_events
    W.trunk_events = get_pipeline("waist-pendulum")
    try:
        yield
    finally:
        W.trunk_events = new


def track(folder: Path, out: Path, old: bool) -> tuple[float, float]:
    """``pdrlearn track folder`` (old or new inner path): its CPU time and the inner work's (s)."""
    import pdrlearn.track.plasys as P
    from pdrlearn.cli import main

    spent = [0.0]
    inner = P.add_trunk_transfers

    def timed(*a, **k):
        t = time.process_time()
        try:
            return inner(*a, **k)
        finally:
            spent[0] += time.process_time() - t

    P.add_trunk_transfers = timed
    try:
        with old_path() if old else contextlib.nullcontext():
            t0 = time.process_time()
            with contextlib.redirect_stdout(io.StringIO()):  # the track's own lines are not the measurement's
                assert main(["track", str(folder), "--out", str(out), "--force"]) == 0
            return time.process_time() - t0, spent[0]
    finally:
        P.add_trunk_transfers = inner


def same_outputs(a: Path, b: Path) -> list[str]:
    """The output files of two track folders that differ (run.json's and path.png's times and pixels left out)."""
    names = sorted(({p.name for p in a.iterdir()} | {p.name for p in b.iterdir()}) - {"run.json", "path.png"})
    return [n for n in names
            if not (a / n).is_file() or not (b / n).is_file() or not filecmp.cmp(a / n, b / n, shallow=False)]


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--users", default="10432-10439")
    ap.add_argument("--walk", default=None)
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--out", default=None)
    a = ap.parse_args()
    lo, hi = (int(x) for x in a.users.split("-"))
    root = Path(a.out or tempfile.mkdtemp(prefix="w428_"))
    n_same = 0
    for k, uid in enumerate(range(lo, hi + 1)):
        setting = SETTINGS[k % len(SETTINGS)]
        make(uid, setting, root / f"tug_{uid}")
        cpu = {}
        for arm in ("old", "new"):
            cpu[arm] = track(root / f"tug_{uid}", root / f"tug_{uid}_{arm}", arm == "old")
        diff = same_outputs(root / f"tug_{uid}_old", root / f"tug_{uid}_new")
        n_same += not diff
        s = json.loads((root / f"tug_{uid}_new" / "summary.json").read_text())
        print(f"user {uid} ({setting[0]}; stand {setting[1]:g} s, {setting[4]}): tug_time_s {s['tug_time_s']}, "
              f"n_tug_trials {s['n_tug_trials']}, transfers {s['n_sit_to_stand']}/{s['n_stand_to_sit']}; "
              f"outputs {'identical' if not diff else 'DIFFER: ' + ', '.join(diff)}; inner work cpu "
              f"{cpu['old'][1]:.2f} -> {cpu['new'][1]:.2f} s")
    print(f"identical outputs: {n_same} of {hi - lo + 1} users")
    if a.walk:
        runs = {"old": [], "new": []}
        for _ in range(a.reps):
            for arm in ("old", "new"):
                runs[arm].append(track(Path(a.walk), root / f"walk_{arm}", arm == "old"))
        diff = same_outputs(root / "walk_old", root / "walk_new")
        for arm in ("old", "new"):
            print(f"walk {arm}: track cpu median {statistics.median(r[0] for r in runs[arm]):.2f} s, inner work "
                  f"median {statistics.median(r[1] for r in runs[arm]):.2f} s (of {a.reps})")
        print(f"walk outputs {'identical' if not diff else 'DIFFER: ' + ', '.join(diff)}")


if __name__ == "__main__":
    main()
