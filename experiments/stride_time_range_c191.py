"""Decision C191: where the stride-time check flags a walk. User 14420 trained as in length_contradiction_c191.py;
a straight route at its own gait and at 0.45 / 0.68 / 0.75 / 0.8 s steps (its own step length), tracked with the model.

    PYTHONPATH=. .venv/bin/python experiments/stride_time_range_c191.py
"""
import dataclasses
import logging

import numpy as np

from pdrlearn.classify import train_user
from pdrlearn.sim import simulate
from pdrlearn.sim.route import parse_route
from pdrlearn.sim.simulate import simulate_path
from pdrlearn.sim.user import SPEED_FACTORS, UserProfile
from pdrlearn.track import plasys


def main():
    """The experiment (run as a script only: importing it, as the E301 check does, runs nothing; decision D51)."""
    logging.getLogger("pdrlearn").setLevel(logging.ERROR)
    u = 14420
    model = train_user([simulate(ex, user_seed=u, seed=0) for ex in ("terrain", "direction", "length")], seed=0)
    cal = model.data_summary["distance_calibration"]
    print("speed_range_mps", cal["speed_range_mps"], "stride_time_range_s", cal["stride_time_range_s"])
    user = UserProfile.from_seed(u)
    f_len, f_time = SPEED_FACTORS["normal"]
    R = "stand:3, straight:10, turn:180, straight:10, stand:3"
    for name, t in (("own", None), ("waltz 0.68 s", 0.68), ("0.75 s", 0.75), ("0.8 s", 0.8), ("0.45 s", 0.45)):
        w = user if t is None else dataclasses.replace(user, step_time_s=t / f_time)
        s = simulate_path(parse_route(R), w, seed=1)
        res = plasys.track_plasys(s, method="M3", model=model)
        st = res.steps
        print(name, "median stride_time_s", round(float(np.nanmedian(st["stride_time_s"])), 3),
              "flagged", int(st["stride_time_out_of_range"].sum()), "of", len(st),
              "speed flagged", int(st["speed_out_of_range"].sum()))
        print([w_ for w_ in res.info.get("warnings", []) if "C191" in w_])


if __name__ == "__main__":
    main()
