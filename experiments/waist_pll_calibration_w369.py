"""Decision W369 (amending W368): why waist-pll's simulated distance error rose when W368 made
``pll_edge_lock: "walk-end"`` the default (experiments/waist.py, users 1-3, median |error| 4.99 -> 5.91 %).
Analysis, no rule: nothing is adopted from it (review R1 item 3 wrote the first version, /tmp/r1/cal.py).

Per user, experiments/waist.py's protocol (calibrated on a 60 m walk measured from the first to the last reference
initial contact, W21; tracks of scenarios A-D): the calibration walk's contacts and counted steps under
``pll_edge_lock`` false and "walk-end", and the A-D distance errors (vs the reference strides, evaluate_track) of
  off/off        calibrated and tracked with false (before session 35),
  off/walk-end   calibrated with false, tracked with "walk-end" (a PARAMS.json made before session 35, now),
  walk-end/walk-end  both "walk-end" (a calibration made now).

Run: PYTHONPATH=$PWD python experiments/waist_pll_calibration_w369.py   (about a minute)
"""

from __future__ import annotations

import logging

import numpy as np

from pdrlearn.sim import simulate  # noqa: E402
from pdrlearn.track.evaluate import evaluate_track  # noqa: E402
from pdrlearn.track.waist import track_waist  # noqa: E402
from pdrlearn.waist.calibration import calibrate  # noqa: E402
from pdrlearn.waist.params import resolve_params  # noqa: E402
from waist import walked_between_contacts  # noqa: E402  (experiments/waist.py's calibration distance)

USERS = (1, 2, 3)  # experiments/waist.py's simulated users
CONFIGS = (("off/off", False, False), ("off/walk-end", False, "walk-end"), ("walk-end/walk-end", "walk-end",
                                                                              "walk-end"))


def calibrated(cal, mode, cal_m: float):
    """waist-pll calibrated on ``cal`` under pll_edge_lock ``mode``, and that walk's contacts and counted steps."""
    base, _ = resolve_params(cal, None)
    base.options = {"pll_edge_lock": mode}
    st = track_waist(cal, pipeline="waist-pll", params=base).steps
    return calibrate([cal], "waist-pll", distances=[cal_m], params=base), st


def main() -> None:
    logging.disable(logging.WARNING)
    errs = {c[0]: [] for c in CONFIGS}
    for u in USERS:
        cal = simulate("walk", u, "normal", rate_hz=100.0, seed=1, length_m=60.0)
        cal_m = walked_between_contacts(cal)
        ics = cal.extras["ics"]["ic_s"].to_numpy(float)
        params = {}
        for mode in (False, "walk-end"):
            params[mode], st = calibrated(cal, mode, cal_m)
            ev = st["event_s"].to_numpy(float)
            print(f"user {u} calibration walk ({cal_m:.2f} m), pll_edge_lock {mode!s:8}: {len(ev)} contacts "
                  f"(reference {len(ics)}), {int(st['has_next'].sum())} steps counted; first / last contact "
                  f"{ev[0]:.2f} / {ev[-1]:.2f} s (reference {ics[0]:.2f} / {ics[-1]:.2f} s)")
        tests = {sc: simulate(sc, u, "normal", rate_hz=100.0) for sc in "ABCD"}
        for name, cal_mode, track_mode in CONFIGS:
            row = []
            for s in tests.values():
                res = track_waist(s, pipeline="waist-pll", params=params[cal_mode], pll_edge_lock=track_mode)
                row.append(evaluate_track(res, s)["distance_error_pct"])
                errs[name].append(row[-1])
            print(f"user {u} {name:18} distance error A-D %: " + ", ".join(f"{e:+.2f}" for e in row))
    for name, e in errs.items():
        a = np.abs(np.asarray(e, float))
        print(f"{name:18} 12 runs: median |err| {np.median(a):.2f} %, mean |err| {a.mean():.2f} %, max "
              f"{a.max():.2f} %, signed mean {np.mean(e):+.2f} %")


if __name__ == "__main__":
    main()
