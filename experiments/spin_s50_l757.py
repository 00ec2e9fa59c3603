"""Decision L757 (session 50): L742's spin tilt limit at 0.6 rad/s re-measured on fresh users at 20, 50 and 100 Hz, by
the rule written in docs/decisions/localization.md before measuring.

Users 17210-17229: a spin without a step, alone and inside a walk, at 20, 50 and 100 Hz; users 17230-17249: slow
patients (0.25-0.35 m steps at the simulator's slow speed) stepping turns at 20, 50 and 100 Hz. Each session is
tracked in-process offline (plasys), streamed, and by the runtime ``Tracker`` (BUNDLE: one bundle, trained on user
17210's calibration exercises at 100 Hz), with the kernel's limit at each LIMIT (0 = L742's rule off).

``PYTHONPATH=. python experiments/spin_s50_l757.py BUNDLE spin|patient|report [LIMIT ...]``
"""
from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.kernels import spin
from pdrlearn.runtime import Tracker, load_bundle
from pdrlearn.runtime.replay import replay_chunks
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.base import get_pipeline

SPIN_USERS = range(17210, 17230)
PATIENT_USERS = range(17230, 17250)
RATES = (20, 50, 100)
WORK = Path("/tmp/i4_l757")
SPINS = ("spin:180:2", "spin:-270:4", "spin:360:6", "spin:360:3, stand:2, spin:360:3", "spin:-180:5", "spin:270:3")
PATIENT_ROUTE = ("stand:2, straight:6, turn:180, straight:6, turn:90, straight:4, turn:-45, straight:4, stand:2, "
                 "turn:-180, stand:2")
STEPS_M = (0.25, 0.30, 0.35)  # a 0.3-0.45 m/s patient, tests/test_clinical_summary.py's recipe


def windows(steps) -> np.ndarray:
    if isinstance(steps, pd.DataFrame):
        return steps[["start_s", "end_s"]].to_numpy(float).reshape(-1, 2)
    return np.array([[x.start_s, x.end_s] for x in steps], dtype=float).reshape(-1, 2)


def inside(w: np.ndarray, spins: np.ndarray) -> int:
    mid = w.mean(axis=1)
    return int(sum(((mid > a) & (mid < b)).sum() for a, b in spins))


def tracked(s, bundle, limit: float) -> dict:
    """Strides (windows) of each path with the kernel limit at ``limit``; None when a path found none."""
    spin.SPIN_TILT_MAX_RAD_S = limit  # the measurement's knob only: the package's value is not changed
    out = {}
    for path in ("track", "stream"):
        try:
            out[path] = windows(get_pipeline("plasys")(s, streaming=path == "stream").steps)
        except Exception as e:  # noqa: BLE001 - a spin alone has no stride: L742's one line
            out[path] = np.zeros((0, 2))
            out[path + "_error"] = str(e)[:80]
    tr = Tracker(bundle)
    st = []
    for chunk in replay_chunks({n: (x.t, x.values) for n, x in s.streams.items()}, 1.0):
        st += tr.push(chunk)
    out["run"] = windows(st + tr.flush())
    return out


def kernel_view(s, w: np.ndarray) -> np.ndarray:
    """L742's peak tilt rate of each window ``w`` over the foot's samples."""
    a, g = s.streams["fAccelerometer"], s.streams["fGyroscope"]
    return np.array([spin.turn_rates(a.t, a.values, g.t, g.values, x, y)[0] for x, y in w])


def main(bundle_dir: str, mode: str, *limits: str) -> None:
    bundle = load_bundle(Path(bundle_dir))
    lims = [float(x) for x in limits] or [0.6]
    rows, kern = [], []
    if mode == "spin":
        for k, u in enumerate(SPIN_USERS):
            sp = SPINS[k % len(SPINS)]
            for rate in RATES:
                for where, route in (("alone", f"stand:3, {sp}, stand:3"),
                                     ("walk", f"stand:2, straight:4, stand:2, {sp}, stand:2, straight:4, stand:2")):
                    s = simulate_path(parse_route(route), UserProfile.from_seed(u), rate_hz=rate, seed=5,
                                      name=f"spin_u{u}_{rate}_{where}")
                    true = 0 if s.steps is None else len(s.steps)  # a spin alone has no stride
                    spins = s.extras["spins"][["start_s", "end_s"]].to_numpy(float)
                    kern += [{"kind": "spin", "rate": rate, "user": u, "tilt": v} for v in kernel_view(s, spins)]
                    for lim in lims:
                        res = tracked(s, bundle, lim)
                        for path in ("run", "stream", "track"):
                            rows.append({"user": u, "rate": rate, "where": where, "spin": sp, "limit": lim,
                                         "path": path, "strides": len(res[path]), "true": true,
                                         "in_spin": inside(res[path], spins)})
                    print(pd.DataFrame(rows[-3 * len(lims):]).to_string(header=len(rows) <= 3 * len(lims)),
                          flush=True)
    elif mode == "patient":
        for k, u in enumerate(PATIENT_USERS):
            step = STEPS_M[k % len(STEPS_M)]
            prof = dataclasses.replace(UserProfile.from_seed(u), step_length_m=step / 0.85, step_time_s=0.75 / 1.2)
            for rate in RATES:
                s = simulate_path(parse_route(PATIENT_ROUTE), prof, speed="slow", rate_hz=rate, seed=5,
                                  bounce="pendulum", name=f"patient_u{u}_{rate}")
                truth = s.steps
                tw = windows(truth)
                turn = (truth["kind"] == "turn").to_numpy() if "kind" in truth else np.zeros(len(truth), bool)
                for v, t in zip(kernel_view(s, tw), turn, strict=True):
                    kern.append({"kind": "turn step" if t else "stride", "rate": rate, "user": u, "tilt": v})
                for lim in lims:
                    res = tracked(s, bundle, lim)
                    for path in ("run", "stream", "track"):
                        rows.append({"user": u, "rate": rate, "step_m": step, "limit": lim, "path": path,
                                     "strides": len(res[path]), "true": len(truth)})
                print(pd.DataFrame(rows[-3 * len(lims):]).to_string(header=len(rows) <= 3 * len(lims)), flush=True)
    else:
        report()
        return
    pd.DataFrame(rows).to_csv(WORK / f"rows_{mode}.csv", index=False)
    pd.DataFrame(kern).to_csv(WORK / f"kernel_{mode}.csv", index=False)


def report() -> None:
    pd.set_option("display.width", 250)
    kern = pd.concat([pd.read_csv(p) for p in sorted(WORK.glob("kernel_*.csv"))])
    for (kind, rate), g in kern.groupby(["kind", "rate"]):
        print(f"kernel {kind:9s} {rate:3d} Hz: n {len(g)} peak tilt rate min {g['tilt'].min():.3f} "
              f"max {g['tilt'].max():.3f} rad/s")
    if (WORK / "rows_spin.csv").exists():
        sp = pd.read_csv(WORK / "rows_spin.csv")
        for (lim, path, rate), g in sp.groupby(["limit", "path", "rate"]):
            walk = g[g["where"] == "walk"]
            print(f"spin    limit {lim:.2f} {path:6s} {rate:3d} Hz: strides inside a spin window "
                  f"{int(g['in_spin'].sum())} (sessions with one {int((g['in_spin'] > 0).sum())} of {len(g)}); "
                  f"walk sessions strides - true {(walk['strides'] - walk['true']).tolist()}")
    if (WORK / "rows_patient.csv").exists():
        pa = pd.read_csv(WORK / "rows_patient.csv")
        off = pa[pa["limit"] == 0].set_index(["user", "rate", "path"])["strides"]
        for (lim, path, rate), g in pa.groupby(["limit", "path", "rate"]):
            g = g.set_index(["user", "rate", "path"])
            d = g["strides"] - off.reindex(g.index)
            print(f"patient limit {lim:.2f} {path:6s} {rate:3d} Hz: strides - rule off {d.tolist()}; "
                  f"strides - true {(g['strides'] - g['true']).tolist()}")


if __name__ == "__main__":
    main(*sys.argv[1:])
