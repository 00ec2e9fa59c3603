"""Decisions E124 / E125: side steps (simulator decision S49) in the streamed foot tracks (``track --streaming``:
``plasys`` with ``streaming=True``, its defaults, no model) and ``pdrlearn run`` (the shipped bundle
``models/plasys-sim-default``, every unit of the session, the CLI in this process). Fresh simulated users, seed 1,
20 Hz, the two routes of L218 (``straight:10, side:3, straight:10`` and ``side:-4``); per route and path the
final position error (m) per user and its median (min..max). ``--controls`` prints, for scenarios A, C, D,
``straight:5, backward:6, straight:5`` and ``straight:23``, how many tracks are identical (distance and end point
within 1e-9 m) with E124's rule off and on. ``--candidate`` prints the side routes with the rule off and on.
E124 is the rule of both paths (adopted in E125; decision E234 removed its module switch ``STREAMED_SIDE_TRAVEL``):
the "off" arm stands in :class:`~pdrlearn.kernels.sideways.SideRun`'s angle with 0 (:func:`before_e124`).

    PYTHONPATH=. OMP_NUM_THREADS=1 .venv/bin/python experiments/side_steps_streamed.py --users 4160-4169
    PYTHONPATH=. OMP_NUM_THREADS=1 .venv/bin/python experiments/side_steps_streamed.py --users 4170-4179 --candidate
    PYTHONPATH=. OMP_NUM_THREADS=1 .venv/bin/python experiments/side_steps_streamed.py --users 4170-4179 --controls
"""

from __future__ import annotations

import contextlib
import io
import json
import logging
import sys
import tempfile
from pathlib import Path
from unittest import mock

import numpy as np

from pdrlearn.cli import main as cli
from pdrlearn.io import write_session
from pdrlearn.kernels import sideways as KS
from pdrlearn.sim import UserProfile, simulate, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline
from pdrlearn.track.evaluate import evaluate_track

ROOT = Path(__file__).resolve().parents[1]
BUNDLE = ROOT / "models" / "plasys-sim-default"
ROUTES = ("straight:10, side:3, straight:10", "side:-4")
CONTROLS = ("A", "C", "D", "straight:5, backward:6, straight:5", "straight:23")
PATHS = ("streamed", "run")


def session(route: str, user: int):
    if len(route) == 1:
        return simulate(route, user, rate_hz=20.0, seed=1)
    return simulate_path(parse_route(route), UserProfile.from_seed(user), rate_hz=20.0, seed=1, scenario="route")


def track(s, path: str, tmp: Path) -> dict:
    """Final position error, distance and end point of one path's track of ``s``."""
    if path == "streamed":
        res = get_pipeline("plasys")(s, streaming=True)
        ev = evaluate_track(res, s)
        return {"err": ev.get("final_position_error_m", np.nan), "dist": ev["distance_m"],
                "end": res.trajectory[["x", "y"]].to_numpy(float)[-1]}
    src, out = tmp / "session", tmp / "run"
    if not src.exists():
        write_session(s, src)
    with contextlib.redirect_stdout(io.StringIO()):  # run's summary lines
        assert cli(["run", str(BUNDLE), str(src), "--out", str(out), "--force"]) == 0
    summ = json.loads((out / "summary.json").read_text())
    traj = np.loadtxt(out / "trajectory.csv", delimiter=",", skiprows=1, usecols=(1, 2))
    return {"err": summ.get("final_position_error_m", np.nan), "dist": summ["distance_m"], "end": traj[-1]}


@contextlib.contextmanager
def before_e124():
    """The streamed tracks before E124 (decision E234: no switch, a stand-in for the arm): every
    :meth:`SideRun.stride <pdrlearn.kernels.sideways.SideRun.stride>` still runs (L243's ``sideways`` rows read its
    state) but adds 0 to the stride's direction, in ``track --streaming`` and the runtime alike."""
    real = KS.SideRun.stride

    def no_angle(self, *args, **kwargs) -> float:
        real(self, *args, **kwargs)
        return 0.0

    with mock.patch.object(KS.SideRun, "stride", no_angle):
        yield


def measure(route: str, path: str, user: int, on: bool) -> dict:
    with tempfile.TemporaryDirectory() as d, contextlib.nullcontext() if on else before_e124():
        return track(session(route, user), path, Path(d))


def main(users: range, mode: str) -> None:
    logging.disable(logging.WARNING)
    print(f"users {users.start}-{users.stop - 1}, seed 1, 20 Hz", flush=True)
    if mode == "controls":
        for route in CONTROLS:
            for p in PATHS:
                same = 0
                for u in users:
                    a, b = measure(route, p, u, False), measure(route, p, u, True)
                    same += abs(a["dist"] - b["dist"]) <= 1e-9 and bool(np.all(np.abs(a["end"] - b["end"]) <= 1e-9))
                print(f"{route!r} {p}: identical with E124's rule on in {same} of {len(users)} tracks", flush=True)
        return
    for route in ROUTES:
        for p in PATHS:
            for on in ((False, True) if mode == "candidate" else (True,)):
                e = np.array([measure(route, p, u, on)["err"] for u in users])
                print(f"{route!r} {p} (E124's rule {'on' if on else 'off'}): final_position_error_m median "
                      f"{np.median(e):.2f} ({e.min():.2f}..{e.max():.2f}); per user "
                      + " ".join(f"{x:.2f}" for x in e), flush=True)


if __name__ == "__main__":
    args = sys.argv[1:]
    a, b = (int(x) for x in args[args.index("--users") + 1].split("-")) if "--users" in args else (4160, 4169)
    main(range(a, b + 1), "controls" if "--controls" in args else "candidate" if "--candidate" in args else "table")
