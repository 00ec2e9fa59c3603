"""Decisions W581 / W582: W173's backward line on a forward low-swing shuffle (trial s50 T3 finding F3).
Fresh simulated users 17620-17649, waist-pendulum at 20 Hz, both units; each track's W173 lines read with W173's
push-off cue alone (``max_travel_deg=None``) and with W581's travel cue (135 deg): shuffles (``--swing-height 0.06``,
0.3 m steps in 0.8 s: a 10 m straight walk and W111's daily route), the same daily route at the user's own swing, and
W173's backward-only and forward / backward / forward routes. Prints counts (tracks with a line, lines).

    PYTHONPATH=. OMP_NUM_THREADS=1 .venv/bin/python experiments/waist_backward_w581.py [FIRST LAST]  (17621 17649)
"""

from __future__ import annotations

import dataclasses
import logging
import sys

import waist_backward  # a sibling script, imported by bare name (E301)
from pdrlearn.cli.simulate import with_swing_and_sway
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.backward import backward_runs, backward_steps, backward_warnings


def routes(user: int) -> dict:
    """The measured sessions of one user (name -> session)."""
    own = UserProfile.from_seed(user)
    slow = dataclasses.replace(own, step_length_m=0.3, step_time_s=0.8)
    shuffler = with_swing_and_sway(slow, 0.06, None)
    def sim(route, u):
        return simulate_path(parse_route(route), u, rate_hz=20.0, seed=1, scenario="route")
    return {"shuffle-straight": sim("stand:3, straight:10, stand:3", shuffler),
            "shuffle-daily": sim(waist_backward.DAILY, shuffler),
            "slow-daily": sim(waist_backward.DAILY, slow),
            "own-daily": sim(waist_backward.DAILY, own),
            **{k: sim(r, own) for k, r in waist_backward.BACKWARD.items()}}


def main(first: int = 17621, last: int = 17649) -> None:
    logging.disable(logging.WARNING)
    rules = {"W173 push-off alone": None, "W581 + travel > 135 deg": 135.0}
    count: dict = {}
    for user in range(first, last + 1):
        for name, s in routes(user).items():
            steps = track_waist(s, pipeline="waist-pendulum").steps
            for rule, deg in rules.items():
                n = len(backward_warnings(steps, s, max_travel_deg=deg))
                runs = backward_runs(backward_steps(steps, s, max_travel_deg=deg), steps["has_next"].to_numpy(bool))
                c = count.setdefault((name, rule), [0, 0, 0])
                c[0] += n > 0
                c[1] += n
                c[2] += len(runs)
        print(f"user {user} done", flush=True)
    n_users = last - first + 1
    for (name, rule), (tracks, lines, runs) in count.items():
        print(f"{name:17s} {rule:24s} tracks with a line {tracks} of {n_users}, lines {lines} (W582), "
              f"stretches {runs} (W173's lines before W582)")


if __name__ == "__main__":
    main(*(int(a) for a in sys.argv[1:3]))
