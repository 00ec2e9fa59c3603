"""Decisions W348/W349: the waist pendulum's vertical excursion h at 20 Hz (the thesis waist phone's rate) with and
without W348's band-limited upsampling to 100 Hz before the double integration.

Prints (a) fresh simulated normal walkers (population bounce, ``straight:40``) at 20 and 100 Hz: the median
|h / truth - 1| over the steady steps (truth: the waist unit's height, peak to peak between two contacts, of the same
walk simulated at 100 Hz) and the median uncalibrated distance ratio; (b) whether the 100 Hz steps are byte-identical;
(c) the mobgap Test5 / Test11 recordings resampled to 20 Hz: the median |bout distance error| (and at 100 Hz);
(d) calibrated users (one walk, seed 0) tested on another walk (seed 1) at 20 Hz: the median |distance error|.

    PYTHONPATH=. python experiments/excursion_rate.py --external datasets/external [--users 7510-7524 --cal 7525-7529]
"""

from __future__ import annotations

import argparse
import contextlib
import functools
import logging
from pathlib import Path

import numpy as np

from pdrlearn.kernels import waist as K


@contextlib.contextmanager
def excursion_rate(min_rate_hz: float):
    """Every caller of :func:`~pdrlearn.kernels.waist.vertical_excursion` with ``min_rate_hz`` (0: W348 off)."""
    base = K.vertical_excursion
    K.vertical_excursion = functools.partial(base, min_rate_hz=min_rate_hz)
    try:
        yield
    finally:
        K.vertical_excursion = base


def _walk(user: int, rate: float, seed: int = 0):
    from pdrlearn.sim.path import Stand, Straight
    from pdrlearn.sim.simulate import simulate_path
    from pdrlearn.sim.user import UserProfile

    return simulate_path([Stand(3), Straight(40), Stand(3)], UserProfile.from_seed(user), speed="normal", seed=seed,
                         rate_hz=rate, bounce="population")


def truth_h(ses) -> tuple[np.ndarray, np.ndarray]:
    """The steady contacts (not the first or last three) and the truth h between each two."""
    tr = ses.trajectory
    t, z = tr["t"].to_numpy(float), tr["z"].to_numpy(float)
    inner = np.sort(ses.extras["ics"]["ic_s"].to_numpy(float))[3:-3]
    return inner, np.array([np.ptp(z[(t >= a) & (t <= b)]) for a, b in zip(inner[:-1], inner[1:], strict=True)])


def tracked(ses):
    from pdrlearn.track.waist import track_waist
    from pdrlearn.waist.params import resolve_params

    p, _ = resolve_params(ses, None)
    return track_waist(ses, pipeline="waist-pendulum", params=p)


def walked_m(ses) -> float:
    xy = ses.trajectory[["x", "y"]].to_numpy(float)
    return float(np.sum(np.linalg.norm(np.diff(xy, axis=0), axis=1)))


def sim_part(users: range) -> None:
    rows = {}
    for u in users:
        inner, h_true = truth_h(_walk(u, 100.0))
        ht = float(np.median(h_true))
        for rate in (20.0, 100.0):
            ses = _walk(u, rate)
            for rule in (0.0, K.EXCURSION_MIN_RATE_HZ):
                with excursion_rate(rule):
                    res = tracked(ses)
                st = res.steps[res.steps["has_next"]]
                mid = 0.5 * (st["start_s"].to_numpy(float) + st["end_s"].to_numpy(float))
                h = st["h_m"].to_numpy(float)[(mid > inner[0]) & (mid < inner[-1])]
                rows.setdefault((rate, rule), []).append((float(np.median(np.abs(h / ht - 1.0))),
                                                          res.distance_m / walked_m(ses), st))
    for (rate, rule), r in rows.items():
        print(f"(a) users {users.start}-{users.stop - 1} {rate:g} Hz W348 {'on ' if rule else 'off'}: "
              "median |h/truth-1|"
              f" {np.median([x[0] for x in r]):.4f}  median ratio {np.median([x[1] for x in r]):.4f}", flush=True)
    same = all(a[2].equals(b[2]) for a, b in zip(rows[(100.0, 0.0)], rows[(100.0, K.EXCURSION_MIN_RATE_HZ)],
                                                   strict=True))
    print(f"(b) 100 Hz steps identical with W348 on and off: {same}", flush=True)


def real_part(external: Path) -> None:
    from pdrlearn.io.plasys import read_session
    from pdrlearn.io.resample import resample_session
    from pdrlearn.waist.evaluate import distance_metrics

    for folder in sorted(list(external.glob("mobgap_*_Test5_*")) + list(external.glob("mobgap_*_Test11_*"))):
        ses = read_session(folder)
        line = f"(c) {folder.name}:"
        native = distance_metrics(tracked(ses).steps, ses)
        if not native:
            print(line, "no reference bouts")
            continue
        line += f" 100 Hz {native['bout_distance_error_median_pct']:.2f} %"
        low = resample_session(ses, {n: 20.0 for n in ses.streams if n.startswith("w")})
        for rule in (0.0, K.EXCURSION_MIN_RATE_HZ):
            with excursion_rate(rule):
                m = distance_metrics(tracked(low).steps, low)
            line += f" | 20 Hz W348 {'on' if rule else 'off'} {m['bout_distance_error_median_pct']:.2f} %"
        print(line, flush=True)


def calibrated_part(users: range) -> None:
    from pdrlearn.track.waist import track_waist
    from pdrlearn.waist.calibration import calibrate

    for rule in (0.0, K.EXCURSION_MIN_RATE_HZ):
        errs = []
        with excursion_rate(rule):
            for u in users:
                cal = calibrate([_walk(u, 20.0, 0)], "waist-pendulum", distances=[40.0])
                test = _walk(u, 20.0, 1)
                res = track_waist(test, pipeline="waist-pendulum", params=cal)
                errs.append(100.0 * (res.distance_m / walked_m(test) - 1.0))
        print(f"(d) users {users.start}-{users.stop - 1} 20 Hz calibrated W348 {'on ' if rule else 'off'}: median "
              f"|distance error| {np.median(np.abs(errs)):.2f} %  ({', '.join(f'{e:+.2f}' for e in errs)})", flush=True)


def _range(text: str) -> range:
    lo, hi = (int(v) for v in text.split("-"))
    return range(lo, hi + 1)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--external", default="datasets/external")
    ap.add_argument("--users", default="7510-7524")
    ap.add_argument("--cal", default="7525-7529")
    a = ap.parse_args()
    logging.getLogger("pdrlearn").setLevel(logging.ERROR)
    sim_part(_range(a.users))
    real_part(Path(a.external))
    calibrated_part(_range(a.cal))


if __name__ == "__main__":
    main()
