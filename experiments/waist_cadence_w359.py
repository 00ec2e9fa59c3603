"""Decision W359: the lower back's median stride time / cadence as a grouped-data median of the whole-sample times,
against its adoption rule (written in docs/decisions/waist.md before this ran).

Fresh users 7900-7909, stand 3 s, straight 60 m, stand 3 s, pendulum bounce; "single" (speed normal, variability
1.0) and "dual" (speed slow, variability 2.5) as trial T1; simulated at 20 Hz and 100 Hz; waist-pendulum and waist-pll
(uncalibrated). Truth: 120 / the median true stride time of the steady strides (the simulator's ``ic_s``). Each
track's |median_cadence_spm - truth| with the plain median (before) and the grouped median (after): both summaries
of the same track.

W359 was adopted; decision L595 removed its switch ``gait.WAIST_GROUPED_MEDIAN``: the plain arm is
:func:`plain_median` (the old off branch: no contact grid), a stand-in for that arm only.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_cadence_w359.py [--users 7900-7909]
"""

from __future__ import annotations

import argparse
import logging
from contextlib import contextmanager, nullcontext
from unittest import mock

import numpy as np

import pdrlearn.track.gait as gait
from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.track.gait import gait_summary
from pdrlearn.track.waist import track_waist

CONDITIONS = (("single", "normal", 1.0), ("dual", "slow", 2.5))  # trial T1's two conditions


def true_cadence(session) -> float:
    """120 / the median true stride time of the steady strides (trial T1's truth)."""
    st = session.steps
    stride = np.diff(st["ic_s"].to_numpy(float))
    return float(120.0 / np.median(stride[st["steady"].to_numpy(bool)[1:]]))


@contextmanager
def plain_median():
    """The plain median, as before W359: no contact grid (what ``WAIST_GROUPED_MEDIAN = False`` did)."""
    with mock.patch.object(gait, "_contact_grid", lambda start_s: None):
        yield


def cadences(steps) -> tuple[float, float]:
    """(plain, grouped) median cadence of one lower-back steps table."""
    out = []
    for on in (False, True):
        with nullcontext() if on else plain_median():
            out.append(float(gait_summary(steps)["median_cadence_spm"]))
    return out[0], out[1]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", default="7900-7909")
    a, b = ap.parse_args().users.split("-")
    logging.getLogger("pdrlearn").setLevel(logging.ERROR)
    rows = []
    for uid in range(int(a), int(b) + 1):
        user = UserProfile.from_seed(uid)
        for cond, speed, var in CONDITIONS:
            for rate in (20, 100):
                s = simulate_path([Stand(3), Straight(60), Stand(3)], user, speed=speed, rate_hz=rate, seed=uid,
                                  variability=var, bounce="pendulum")
                truth = true_cadence(s)
                for pipe in ("pendulum", "pll"):
                    before, after = cadences(track_waist(s, pipeline=f"waist-{pipe}").steps)
                    rows.append((uid, cond, rate, pipe, truth, before, after))
                    print(f"{uid} {cond:6s} {rate:3d} Hz waist-{pipe:8s} truth {truth:7.2f}  plain {before:7.2f} "
                          f"({before - truth:+6.2f})  grouped {after:7.2f} ({after - truth:+6.2f})", flush=True)
    for rate in (20, 100):
        r = [x for x in rows if x[2] == rate]
        eb = np.abs([x[5] - x[4] for x in r])
        ea = np.abs([x[6] - x[4] for x in r])
        print(f"{rate} Hz, {len(r)} tracks: |cadence error| steps/min median {np.median(eb):.3f} -> "
              f"{np.median(ea):.3f}, largest {eb.max():.3f} -> {ea.max():.3f}")


if __name__ == "__main__":
    main()
