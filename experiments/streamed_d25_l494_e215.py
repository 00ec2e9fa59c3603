"""Decision E215 (docs/decisions/export.md): D25 and L494 on the streamed track (``track --streaming``, the runtime).

Prints, final position error (m) of ``track_plasys(streaming=True, method="M2")``:

* D25: users 9880-9884, two units (heading auto: the waist gyroscope), the waist normal, turned on the belt
  (``waist_mount_deg`` z 90 and z 180, as ``simulate --waist-mount``) and mirrored (x and y columns of the waist
  accelerometer, gyroscope and magnetometer swapped, the belt frame kept: D26's ``--meta keep``);
* L494: users 9885-9889, heading foot, the foot unit yawed on the shoe by 0, +20, -30 deg (L494's remount about the
  simulator foot frame's y, frame kept), ``track_plasys(..., first_walk=...)`` (decision E222's keyword; E215's
  flag then) off (old) and on (new); and the same users' two-unit tracks (heading auto), old and new;
* the real foot recordings of datasets/real, heading foot, old and new: distance and final position (error where the
  recording has a reference).

    PYTHONPATH=. python experiments/streamed_d25_l494_e215.py
"""

from __future__ import annotations

import logging
from pathlib import Path

import numpy as np
from scipy.spatial.transform import Rotation

from pdrlearn.io import read_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.frame_inference import remount
from pdrlearn.track.plasys import track_plasys

ROUTE = "stand:3, straight:20, turn:90, straight:10, turn:-90, straight:15, stand:3"  # D25's / L494's route
REAL = Path(__file__).resolve().parents[1] / "datasets" / "real"
SWAP = np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])  # x <-> y columns


def _walk(user: int, **knobs):
    return simulate_path(parse_route(ROUTE), UserProfile.from_seed(user), rate_hz=100.0, seed=user, scenario="route",
                         **knobs)


def _final_error(session, result) -> float:
    true = session.trajectory[["x", "y"]].to_numpy(float)
    est = result.trajectory[["x", "y"]].to_numpy(float)
    return float(np.hypot(*((est[-1] - est[0]) - (true[-1] - true[0]))))


def _kept(session, placement: str, rotation: np.ndarray):
    s = remount(session, placement, rotation)
    s.frames[placement] = session.frames[placement]  # the nearest-axis / belt declaration kept
    return s


def _streamed(session, heading: str, first_walk: bool):
    return track_plasys(session, streaming=True, method="M2", heading=heading, first_walk=first_walk)


def d25() -> None:
    print("D25 (two units, heading auto; first-walk flag as shipped): final error, normal / z:90 / z:180 / mirrored")
    for u in range(9880, 9885):
        normal = _walk(u)
        cases = [normal, _walk(u, waist_mount_deg=(0.0, 0.0, 90.0)), _walk(u, waist_mount_deg=(0.0, 0.0, 180.0)),
                 _kept(normal, "waist", SWAP)]
        errs = [_final_error(s, track_plasys(s, streaming=True, method="M2", heading="auto")) for s in cases]
        print(f"  user {u}: " + " / ".join(f"{e:.3f}" for e in errs)
              + f"  (largest change from normal {max(abs(e - errs[0]) for e in errs[1:]):.3f} m)", flush=True)


def l494() -> None:
    print("L494 (heading foot): final error old -> new, yaw 0 / +20 / -30; two units (auto) old -> new")
    yawed_old, yawed_new = [], []
    for u in range(9885, 9890):
        w = _walk(u)
        row = []
        for deg in (0.0, 20.0, -30.0):
            s = w if not deg else _kept(w, "foot", Rotation.from_euler("y", deg, degrees=True).as_matrix().T)
            old, new = (_final_error(s, _streamed(s, "foot", f)) for f in (False, True))
            row.append(f"{old:.3f} -> {new:.3f}")
            if deg:
                yawed_old.append(old)
                yawed_new.append(new)
        two = [_streamed(w, "auto", f).trajectory[["x", "y"]].to_numpy(float) for f in (False, True)]
        same = two[0].shape == two[1].shape and np.array_equal(two[0], two[1])
        print(f"  user {u}: " + " / ".join(row) + f"; two units {_final_error(w, _streamed(w, 'auto', False)):.3f}"
              f" identical: {same}", flush=True)
    print(f"  mean over the yawed mounts: {np.mean(yawed_old):.3f} -> {np.mean(yawed_new):.3f} m "
          f"({100 * (np.mean(yawed_new) / np.mean(yawed_old) - 1):+.0f} %)")


def real() -> None:
    print("real foot recordings (heading foot): distance, final position (x, y), final error where known; old -> new")
    for d in sorted(REAL.glob("gaitmap_*")):
        s = read_session(d)
        out = []
        for f in (False, True):
            r = _streamed(s, "foot", f)
            ev = evaluate_track(r, s)
            xy = r.trajectory[["x", "y"]].to_numpy(float)[-1]
            fe = ev.get("final_position_error_m")
            out.append(f"{ev.get('distance_m'):.4f} m ({xy[0]:.2f}, {xy[1]:.2f})"
                       + (f" err {fe:.3f}" if fe is not None else ""))
        print(f"  {d.name}: " + " -> ".join(out), flush=True)


if __name__ == "__main__":
    logging.disable(logging.WARNING)
    d25()
    l494()
    real()
