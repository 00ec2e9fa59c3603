"""Why the offline first-stride heading differs from the streamed one (decision L84's diagnosis).

Offline `track` (M3 engine, no model) takes its absolute heading from the waist compass ("fused", L17);
the streamed path starts at `initial_heading` (0 rad, the simulator's default `heading0_deg`) and integrates
the gyroscopes. This script splits the waist compass' mean error over each simulated walk into the parts the
simulator put there: the hard-iron offset (sensor_errors in meta.json), the waist unit's mounting yaw
(user.waist_misalignment_deg, a rotation vector in the body FLU frame: its z part is the yaw), and the rest
(the indoor field disturbances, noise, pelvis rotation). It prints, per session, the first stride's heading
offline / streamed / true, the final position errors, and the same offline track with the compass' hard-iron
offset removed (an oracle: the simulator's value) and with neither hard iron nor mounting yaw.

    PYTHONPATH=. .venv/bin/python experiments/heading0_diagnosis.py [SCENARIO USER SEED ...]
"""

from __future__ import annotations

import copy
import logging
import sys

import numpy as np

from pdrlearn.orient import _kernels as OK
from pdrlearn.orient.filters import WaistHeading, unit_data
from pdrlearn.signal import lowpass
from pdrlearn.sim.simulate import simulate
from pdrlearn.track import get_pipeline
from pdrlearn.track.evaluate import evaluate_track

logging.getLogger("pdrlearn").setLevel(logging.ERROR)


def _circmean(a: np.ndarray) -> float:
    return float(np.arctan2(np.mean(np.sin(a)), np.mean(np.cos(a))))


def _true_heading(session, t0: float, t1: float) -> float:
    gt = session.trajectory
    x = np.interp([t0, t1], gt["t"], gt["x"])
    y = np.interp([t0, t1], gt["t"], gt["y"])
    return float(np.arctan2(y[1] - y[0], x[1] - x[0]))


def run(scenario: str, user: int, seed: int) -> dict:
    plasys = get_pipeline("plasys")
    ses = simulate(scenario, user, "normal", seed=seed)
    off = plasys(ses)
    stm = plasys(ses, streaming=True)
    e_off = evaluate_track(off, ses)["final_position_error_m"]
    e_stm = evaluate_track(stm, ses)["final_position_error_m"]
    r0 = off.steps.iloc[0]
    h_true = _true_heading(ses, float(r0["start_s"]), float(r0["end_s"]))
    # the waist compass and filtered heading against the true pelvis yaw, over the whole walk
    u = unit_data(ses, "waist")
    wh = WaistHeading().estimate(u.t, u.acc, u.gyr, u.mag, fs=u.fs)
    gt = ses.trajectory
    yaw = np.interp(u.t, gt["t"], np.unwrap(gt["heading_rad"].to_numpy(float)))
    comp_err = _circmean(wh.compass_ - yaw)
    filt_err = _circmean(wh.heading_ - yaw)
    ses_hi = copy.deepcopy(ses)
    _strip_hard_iron(ses_hi)
    u2 = unit_data(ses_hi, "waist")
    comp_nohi = OK.tilt_compensated_heading(lowpass(u2.acc, 1.0, u2.fs), u2.mag)
    comp_nohi_err = _circmean(comp_nohi - yaw)
    mis_yaw = float(np.radians(ses.meta["user"]["waist_misalignment_deg"][2]))
    off_hi = plasys(ses_hi)
    e_off_hi = evaluate_track(off_hi, ses_hi)["final_position_error_m"]
    return {"sc": scenario, "user": user, "seed": seed, "h_true": h_true,
            "h_off": float(r0["heading_rad"]), "h_stm": float(stm.steps.iloc[0]["heading_rad"]),
            "compass_err": comp_err, "filtered_err": filt_err, "hard_iron_part": comp_err - comp_nohi_err,
            "mount_yaw": mis_yaw, "rest": comp_nohi_err - mis_yaw,
            "e_off": e_off, "e_stm": e_stm, "e_off_no_hard_iron": e_off_hi,
            "hard_iron_ut": ses.meta["sensor_errors"]["wMagneticField"]["hard_iron_ut"]}


def _strip_hard_iron(ses) -> None:
    hi = np.asarray(ses.meta["sensor_errors"]["wMagneticField"]["hard_iron_ut"], float)
    m = ses.streams["wMagneticField"]
    m.values = m.values - hi


def main(argv: list[str]) -> None:
    jobs = [(argv[i], int(argv[i + 1]), int(argv[i + 2])) for i in range(0, len(argv), 3)] or \
        [("A", u, 0) for u in range(1, 9)]
    print("| walk | true h1 | offline h1 | streamed h1 | compass err | filtered err | = hard iron | + mount yaw"
          " | + rest | hard iron (uT, x=left y=up z=fwd) | final err offline | streamed | offline, hard iron removed |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for sc, u, s in jobs:
        r = run(sc, u, s)
        print(f"| {sc} u{u} s{s} | {r['h_true']:+.3f} | {r['h_off']:+.3f} | {r['h_stm']:+.3f} | "
              f"{r['compass_err']:+.3f} | {r['filtered_err']:+.3f} | {r['hard_iron_part']:+.3f} | "
              f"{r['mount_yaw']:+.3f} | {r['rest']:+.3f} | {', '.join(f'{v:+.2f}' for v in r['hard_iron_ut'])} | "
              f"{r['e_off']:.2f} | {r['e_stm']:.2f} | {r['e_off_no_hard_iron']:.2f} |", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
