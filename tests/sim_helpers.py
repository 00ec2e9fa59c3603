"""Simulator test helpers (review R2, session 33): the whole 500 Hz grid and its parts of 1000 samples."""

from __future__ import annotations

import importlib

import numpy as np

from pdrlearn.sim import simulate_path


def whole_and_parts(monkeypatch, route, user, rate_hz: float, seed: int):
    """Decision S44: the session of ``route`` simulated on the whole fine grid at once and in parts of 1000 samples
    (``FINE_CHUNK``), after checking that every stream is the same in both; ``(whole, parts)``."""
    sim_module = importlib.import_module("pdrlearn.sim.simulate")
    monkeypatch.setattr(sim_module, "FINE_CHUNK", 10**9)
    whole = simulate_path(route, user, rate_hz=rate_hz, seed=seed)
    monkeypatch.setattr(sim_module, "FINE_CHUNK", 1000)
    parts = simulate_path(route, user, rate_hz=rate_hz, seed=seed)
    for k in whole.streams:
        assert np.array_equal(whole.streams[k].values, parts.streams[k].values), k
    return whole, parts


def straight_walk(root, uid: int, metres: float = 40.0):
    """A fresh simulated user ``uid`` walking ``metres`` between two 3 s stands at 100 Hz (pendulum bounce), written
    to ``root / f"u{uid}"``; returns ``root`` (the steady-trim tests of session 34)."""
    from pdrlearn.io import write_session
    from pdrlearn.sim import Stand, Straight, UserProfile

    s = simulate_path([Stand(3), Straight(metres), Stand(3)], UserProfile.from_seed(uid), speed="normal",
                      rate_hz=100, seed=uid, bounce="pendulum", name=f"u{uid}")
    write_session(s, root / f"u{uid}")
    return root


def quiet_walk(route: str, uid: int, seed: int, rate_hz: float = 100.0):
    """A simulated ``route`` (``"straight:12"``) of user ``uid`` at ``rate_hz``, its warnings silenced (the import
    tests' module fixtures; review R2, session 35)."""
    import logging

    from pdrlearn.sim import UserProfile
    from pdrlearn.sim.route import parse_route

    logging.disable(logging.WARNING)
    try:
        return simulate_path(parse_route(route), UserProfile.from_seed(uid), rate_hz=rate_hz, seed=seed,
                             scenario="route")
    finally:
        logging.disable(logging.NOTSET)


def lab_columns(walk, origin_s: float = 0.0, *, time="time_s", acc="acc_{}", gyr="gyr_{}", g_units: bool = False):
    """The foot unit of ``walk`` as a lab export's table: ``time`` (s from ``origin_s``), three ``acc`` and three
    ``gyr`` columns (``{}`` is x, y, z), in m/s^2 and rad/s or, ``g_units``, in g and deg/s (review R2, session 35)."""
    import pandas as pd

    a, g = walk["fAccelerometer"], walk["fGyroscope"]
    av, gv = (a.values / 9.80665, np.degrees(g.values)) if g_units else (a.values, g.values)
    df = pd.DataFrame({time: a.t - a.t[0] + origin_s})
    for k, c in enumerate("xyz"):
        df[acc.format(c)] = av[:, k]
    for k, c in enumerate("xyz"):
        df[gyr.format(c)] = gv[:, k]
    return df


def terrain_cohort(root, users, main):
    """A cohort of simulated ``users`` with a terrain exercise each in ``train/`` (seed 0) and ``test/`` (seed 7),
    trained by ``train-all --methods heuristic,svm --cv 3``; ``(cohort, models)`` (decisions C92, C97)."""
    from pdrlearn.io import write_session
    from pdrlearn.sim import simulate

    for u in users:
        write_session(simulate("terrain", user_seed=u), root / f"u{u}" / "train" / "terrain")
        write_session(simulate("terrain", user_seed=u, seed=7), root / f"u{u}" / "test" / "terrain")
    models = root.parent / f"{root.name}_models"
    assert main(["train-all", str(root), "--out", str(models), "--serial", "--methods", "heuristic,svm",
                 "--cv", "3"]) == 0
    return root, models


def evaluate_per_method(models, cohort, out, main):
    """``evaluate-all MODELS COHORT --out OUT --serial --per-method``; cohort_methods.csv as a DataFrame."""
    import pandas as pd

    assert main(["evaluate-all", str(models), str(cohort), "--out", str(out), "--serial", "--per-method"]) == 0
    return pd.read_csv(out / "cohort_methods.csv")


def session_digest(s) -> str:
    """SHA-256 of a session's streams, ground truth and meta (values rounded to 1e-9; decision S27's pinned
    default sessions, tests/test_sim.py)."""
    import hashlib
    import json

    h = hashlib.sha256()
    for name in sorted(s.streams):
        st = s.streams[name]
        h.update(name.encode())
        h.update(np.round(st.t, 9).tobytes())
        h.update(np.round(st.values, 9).tobytes())
    for df in (s.trajectory, s.steps, s.extras["ics"], s.extras["foot_trajectory"]):
        for c in df.columns:
            v = df[c].to_numpy()
            h.update(str(c).encode())
            num = v.dtype.kind in "fiub"
            h.update(np.round(v.astype(float), 9).tobytes() if num else "|".join(map(str, v)).encode())
    h.update(json.dumps(s.meta, sort_keys=True, default=str).encode())
    return h.hexdigest()
