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


_MADE: dict = {}

#: ``train``'s options of :func:`terrain_cv_model` (decisions C143, C150)
TERRAIN_CV_TRAIN = ["--tasks", "terrain", "--methods", "svm,heuristic", "--cv", "3", "--cv-groups", "user",
                    "--no-distance-calibration"]
TERRAIN_CV_USERS = (9660, 9661, 9662)


def terrain_cv_model(tmp_path_factory):
    """Users 9660-9662's terrain exercises (``root / "u9660"`` ...) trained by ``train --report`` into
    ``root / "model"`` and ``root / "rep"``, train's console text (stdout, piped: not a terminal) in
    ``root / "console.txt"``, and ``pdrlearn report root/model --out root/R``: made once per test run
    (``runtime_helpers.made_once``) for the tests of decisions C143 and C150, which built the same model each
    (testing decision D51). Read-only: a test that writes copies it first."""
    if "terrain_cv" not in _MADE:
        from tests.runtime_helpers import made_once

        _MADE["terrain_cv"] = made_once(tmp_path_factory, "terrain_cv_model", _train_terrain_cv)
    return _MADE["terrain_cv"]


def _train_terrain_cv(root) -> None:
    import contextlib
    import io

    from pdrlearn.cli import main
    from pdrlearn.io import write_session
    from pdrlearn.sim import simulate

    dirs = [str(write_session(simulate("terrain", user_seed=u), root / f"u{u}")) for u in TERRAIN_CV_USERS]
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        code = main(["train", *dirs, "--out", str(root / "model"), *TERRAIN_CV_TRAIN, "--report", str(root / "rep")])
    assert code == 0
    (root / "console.txt").write_text(buf.getvalue(), encoding="utf-8")
    with contextlib.redirect_stdout(io.StringIO()):
        assert main(["report", str(root / "model"), "--out", str(root / "R")]) == 0


#: the users of :func:`shared_terrain_cohort` (decision C92's test's)
TERRAIN_COHORT_USERS = (8660, 8661)


def shared_terrain_cohort(tmp_path_factory):
    """:func:`terrain_cohort` of users 8660 and 8661 and its ``evaluate-all --per-method`` output
    (:func:`evaluate_per_method` into ``eval``), made once per test run (``runtime_helpers.made_once``) for the tests
    of decisions C92 and C97, which built and evaluated the same kind of cohort each (testing decision D51):
    ``(cohort, models, eval)``. Read-only."""
    if "terrain_cohort" not in _MADE:
        from tests.runtime_helpers import made_once

        _MADE["terrain_cohort"] = made_once(tmp_path_factory, "terrain_cohort", _make_terrain_cohort)
    root = _MADE["terrain_cohort"]
    return root / "cohort", root / "cohort_models", root / "eval"


def _make_terrain_cohort(root) -> None:
    import contextlib
    import io

    from pdrlearn.cli import main

    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        cohort, models = terrain_cohort(root / "cohort", TERRAIN_COHORT_USERS, main)
        evaluate_per_method(models, cohort, root / "eval", main)
