"""Decision W186 (session 28): does an uncalibrated waist-pll track that reads far longer than the pendulum model on
the same session warn, on TUGs, and stay silent on plain walks and the real recordings? Run once after W186's rule
was committed; nothing tuned.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/waist_pll_excess.py sim   # users 3640-3679
     ... experiments/waist_pll_excess.py real   # datasets/external and /work/shared/data mobgap_*
Output: experiments/results/waist_pll_excess_sim.txt, waist_pll_excess_real.txt (the printed lines)
"""
import logging
import sys
from pathlib import Path

from pdrlearn.io import read_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.waist import track_waist

logging.disable(logging.WARNING)

USERS = range(3640, 3680)
TUG = "straight:3, turn:180, straight:3"
PLAIN = "stand:3, straight:20, stand:3"


def judged(session) -> tuple[float, float | None, bool, bool]:
    """(pll distance, pll / pendulum ratio, W186 line, W139 line) of the uncalibrated waist-pll track."""
    res = track_waist(session, pipeline="waist-pll", pll_check=True, sit_veto=False)  # as measured, before W185
    w = res.info["warnings"]
    return (float(res.steps["length_m"].sum()), res.info["pll_pendulum_ratio"], any("W186" in x for x in w),
            any("W139" in x for x in w))


def sim() -> None:
    tug_long = tug_long_warned = tug_warned = 0
    plain_warned = n_plain = 0
    for u in USERS:
        speed = "slow" if u % 2 else "normal"
        s = simulate_path(parse_route(TUG), UserProfile.from_seed(u), speed=speed, seed=u, rate_hz=100.0,
                          sit_start_s=3.0, sit_end_s=3.0)
        truth = float(s.meta["distance_m"])
        d, ratio, line, w139 = judged(s)
        err = 100.0 * (d / truth - 1.0)
        long_ = err > 50.0
        tug_long += long_
        tug_long_warned += long_ and line
        tug_warned += line
        r = "None" if ratio is None else f"{ratio:.2f}"
        print(f"TUG user {u} {speed}: waist-pll {d:.2f} m ({err:+.1f} %), pll/pendulum {r}, W186 {line}, "
              f"W139 {w139}", flush=True)
    for u in USERS:
        for speed in ("slow", "normal", "fast"):
            s = simulate_path(parse_route(PLAIN), UserProfile.from_seed(u), speed=speed, seed=u, rate_hz=100.0)
            d, ratio, line, w139 = judged(s)
            n_plain += 1
            plain_warned += line
            r = "None" if ratio is None else f"{ratio:.2f}"
            err = 100.0 * (d / float(s.meta["distance_m"]) - 1.0)
            print(f"plain user {u} {speed}: waist-pll {d:.2f} m ({err:+.1f} %), pll/pendulum "
                  f"{r}, W186 {line}, W139 {w139}", flush=True)
    print(f"\n(a) TUG tracks read > +50 % long: {tug_long}; of them warned (W186): {tug_long_warned}")
    print(f"    TUG tracks warned in all: {tug_warned} of {len(USERS)}")
    print(f"(b) plain walks warned (W186): {plain_warned} of {n_plain}")


def real() -> None:
    n = warned = 0
    for base in (Path("datasets/external"), Path("/work/shared/data")):
        for d in sorted(base.glob("mobgap_*")):
            dist, ratio, line, w139 = judged(read_session(d))
            n += 1
            warned += line
            r = "None" if ratio is None else f"{ratio:.2f}"
            print(f"{base.name}/{d.name}: waist-pll {dist:.2f} m, pll/pendulum {r}, W186 {line}, W139 {w139}",
                  flush=True)
    print(f"\n(c) real recordings warned (W186): {warned} of {n}")


if __name__ == "__main__":
    {"sim": sim, "real": real}[sys.argv[1]]()
