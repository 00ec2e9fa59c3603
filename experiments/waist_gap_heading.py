"""Decision E114 (docs/decisions/export.md): a stride across a waist gap over 1 s headed by the foot (heading auto),
against main's kernel (the waist gyroscope interpolated across the gap), on fresh simulated walks.

Users 4042-4059 (fresh), 20 Hz, normal speed, seed 4, the trial's loop R1 (session 28); every waist stream removed
for 30 s from 100 + 3 (u - 4042) s. `track --streaming` without a model (the kernel `run` shares), final position
error (m, `evaluate_track`) per arm; each walk's copy without a gap must give identical steps in both arms.
E114 is the kernel's rule (W413 removed its module switch, commit d3ffb129 holds it): main's arm stands in the
kernel's ``waist_heads`` with :func:`before_e114` for its tracks.

Run: PYTHONPATH=. .venv/bin/python experiments/waist_gap_heading.py [--users 4042-4059]
"""

from __future__ import annotations

import argparse
import logging
from unittest import mock

import numpy as np

import _repo  # noqa: F401  (the repository root at the end of sys.path, for tests.*: E301)
from pdrlearn.kernels import stride as SK
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.plasys import track_plasys
from tests.runtime_helpers import without

#: the trial's loop (session 28, trial_nav.md "R1")
R1 = ("stand:5, straight:20, turn:90, straight:15, up:17, turn:180, up:17, straight:10, turn:-90, straight:25, "
      "backward:4, stand:20, turn:180, straight:25, turn:90, straight:10, down:17, turn:180, down:17, straight:15, "
      "turn:-90, straight:20, turn:180")
GAP_S = 30.0
ARMS = ("main", "E114")


def before_e114(levelled) -> bool:
    """The kernel's ``waist_heads`` before E114 (main's arm): a levelled waist gyroscope heads every stride, gap or
    not."""
    return "waist" in levelled and levelled["waist"][2] is not None


def run(session, arm: str):
    if arm == "E114":
        return track_plasys(session, streaming=True)
    with mock.patch.object(SK, "waist_heads", before_e114):
        return track_plasys(session, streaming=True)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--users", default="4042-4059")
    a = p.parse_args()
    logging.getLogger("pdrlearn").setLevel(logging.ERROR)
    lo, _, hi = a.users.partition("-")
    errs, same = [], 0
    users = range(int(lo), int(hi or lo) + 1)
    for u in users:
        ses = simulate_path(parse_route(R1), UserProfile.from_seed(u), speed="normal", rate_hz=20.0, seed=4,
                            name=f"waistgap_u{u}", scenario="route")
        t0 = 100.0 + 3.0 * (u - 4042)
        gs = without(ses, t0, t0 + GAP_S, [n for n in ses.streams if n.startswith("w")])
        e = [evaluate_track(run(gs, arm), gs)["final_position_error_m"] for arm in ARMS]
        clean = [run(ses, arm).steps for arm in ARMS]
        ok = clean[0].equals(clean[1])
        same += ok
        errs.append(e)
        print(f"u{u} gap {t0:.0f}-{t0 + GAP_S:.0f} s: final position error main {e[0]:.2f} m, E114 {e[1]:.2f} m "
              f"({e[1] - e[0]:+.2f}); no-gap steps identical: {ok}", flush=True)
    m = np.array(errs)
    d = m[:, 1] - m[:, 0]
    print(f"mean final position error: main {m[:, 0].mean():.2f} m, E114 {m[:, 1].mean():.2f} m; worst change "
          f"{d.max():+.2f} m; walks better {int((d < 0).sum())}/{len(d)}; no-gap identical {same}/{len(users)}")


if __name__ == "__main__":
    main()
