"""A small synthetic two-unit session with labelled stance-to-stance steps (for export/runtime tests).

Not a gait model: each stride is a 0.4 s stance (still foot) and a 0.6 s swing whose foot pitch rate,
forward and vertical accelerations depend on the step's terrain / direction / length class, so every
task is learnable. 20 Hz like the PLASYS firmware (thesis ch.4.2.3).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.io import THESIS_FOOT_FRAME, THESIS_WAIST_FRAME, Session, Stream

G = 9.80665
TERRAIN = ("flat", "up", "down")
DIRECTION = ("forward", "backward")
LENGTH = ("short", "normal", "long")


def synthetic_session(
    n_steps: int = 90,
    *,
    seed: int = 0,
    rate_hz: float = 20.0,
    name: str = "synth",
    turn_rad_per_step: float = 0.0,
) -> Session:
    rng = np.random.default_rng(seed)
    stance, swing = 0.4, 0.6
    n_st, n_sw = int(round(stance * rate_hz)), int(round(swing * rate_hz))
    fa, fg, wa, wg = [], [], [], []
    t = 0.0
    dt = 1.0 / rate_hz
    labels = [(TERRAIN[i % 3], DIRECTION[(i // 3) % 2], LENGTH[(i // 6) % 3]) for i in range(n_steps)]
    rng.shuffle(labels)
    mids = []
    for ter, dirn, ln in labels:
        # stance: foot still (thesis foot frame: y up), small noise
        a_st = np.tile([0.0, G, 0.0], (n_st, 1)) + rng.normal(0, 0.03, (n_st, 3))
        g_st = rng.normal(0, 0.02, (n_st, 3))
        mids.append(t + (n_st // 2) * dt)
        u = np.linspace(0, 1, n_sw)
        amp = {"short": 1.5, "normal": 2.5, "long": 3.5}[ln] * (1 if dirn == "forward" else -1)
        vert = {"flat": 0.0, "up": 2.0, "down": -2.0}[ter]
        fwd = amp * np.sin(2 * np.pi * u) * (1 + rng.normal(0, 0.05))
        up = vert * np.sin(np.pi * u) + 1.0 * np.sin(2 * np.pi * u)
        pitch = -(3.0 + abs(amp)) * np.sin(2 * np.pi * u) + (0.8 * vert) * np.sin(np.pi * u)
        a_sw = np.column_stack([fwd, G + up, rng.normal(0, 0.05, n_sw)]) + rng.normal(0, 0.05, (n_sw, 3))
        g_sw = np.column_stack(
            [
                rng.normal(0, 0.05, n_sw),
                turn_rad_per_step / swing + rng.normal(0, 0.01, n_sw),
                pitch + rng.normal(0, 0.05, n_sw),
            ]
        )
        fa += [a_st, a_sw]
        fg += [g_st, g_sw]
        n = n_st + n_sw
        uu = np.linspace(0, 2 * np.pi, n)
        # waist (thesis waist frame: x left, y up, z forward)
        wa.append(
            np.column_stack(
                [
                    0.3 * np.sin(uu),
                    G + 0.5 * vert * np.sin(uu / 2) + 0.8 * np.sin(2 * uu),
                    0.5 * amp * np.sin(uu),
                ]
            )
            + rng.normal(0, 0.05, (n, 3))
        )
        wg.append(
            np.column_stack(
                [
                    rng.normal(0, 0.05, n),
                    (0.3 if dirn == "forward" else -0.3) * np.sin(uu)
                    + 0.2 * amp * np.cos(uu)
                    + turn_rad_per_step / (n * dt),
                    rng.normal(0, 0.05, n),
                ]
            )
        )
        t += n * dt
    # final stance so the last step ends in a rest
    fa.append(np.tile([0.0, G, 0.0], (n_st, 1)))
    fg.append(np.zeros((n_st, 3)))
    wa.append(np.tile([0.0, G, 0.0], (n_st, 1)))
    wg.append(np.zeros((n_st, 3)))
    mids.append(t + (n_st // 2) * dt)
    fa, fg, wa, wg = map(np.vstack, (fa, fg, wa, wg))
    ts = np.arange(len(fa)) * dt
    still = np.linalg.norm(fg, axis=1) < 0.5
    heel = np.where(still, 400.0, 0.0) + rng.normal(0, 2.0, len(ts)).clip(0)
    toe = np.roll(heel, 2)
    baro = 1013.0 + rng.normal(0, 0.01, len(ts))
    steps = pd.DataFrame(
        {
            "start_s": mids[:-1],
            "end_s": mids[1:],
            "terrain": [lab[0] for lab in labels],
            "direction": [lab[1] for lab in labels],
            "length_class": [lab[2] for lab in labels],
        }
    )
    streams = {
        "fAccelerometer": Stream("fAccelerometer", ts, fa),
        "fGyroscope": Stream("fGyroscope", ts, fg),
        "wAccelerometer": Stream("wAccelerometer", ts, wa),
        "wGyroscope": Stream("wGyroscope", ts, wg),
        "fForceA": Stream("fForceA", ts, heel),
        "fForceB": Stream("fForceB", ts, toe),
        "wBarometer": Stream("wBarometer", ts, baro),
    }
    return Session(
        name=name,
        streams=streams,
        steps=steps,
        # the waist signal is not a walk's (its forward/vertical phase reads as backward, W2): since D23 amended only
        # a foot's reversed forward is refused, so the declared waist frame is kept with D10's warning, no override
        meta={"user": "synthetic"},
        frames={"foot": THESIS_FOOT_FRAME, "waist": THESIS_WAIST_FRAME},
    )


_CACHE: dict = {}

#: the synthetic user's stride-length class bounds, recorded in the models of :func:`trained_dirs` /
#: :func:`rest_dirs` (their training session has no ``length_m``): the thesis step bounds x 2 that every bundle
#: carried before decision L59 (docs/decisions/localization.md), so the runtime tests keep their length rule
SYNTHETIC_BOUNDS = {"short": [0.0, 0.60], "normal": [0.60, 0.90], "long": [0.92, 20.0]}


def _with_bounds(model):
    model.data_summary["length_bounds_m"] = SYNTHETIC_BOUNDS
    return model

#: every method of issue 5, exported by the "bundle_all" bundle
ALL_METHODS = ["heuristic", "fusion", "dtw", "svm", "nn"]
#: every unit: body units, the soft vote (decision C7) and the combined feature vector (decision C22)
ALL_UNITS = ("foot", "waist", "fused", "combined")


def made_once(tmp_path_factory, name: str, make) -> Path:
    """The folder ``name`` that ``make(folder)`` fills, made once per test run (session 40): under pytest-xdist every
    worker of the run shares it, the first one to take the file lock makes it and the others wait for it and read it
    (pytest-xdist's documented pattern: a lock beside ``tmp_path_factory.getbasetemp().parent``, the run's folder);
    a serial run (no worker) makes it in its own temporary folder, as before. ``NAME.done`` beside it marks a
    finished folder: a worker that failed half-way leaves none, and the next one starts again from an empty folder.
    Callers read it and never write into it (every test that edits a bundle copies it first)."""
    import os
    import shutil

    if not os.environ.get("PYTEST_XDIST_WORKER"):  # serial: the parent is shared by every run of the user
        folder = tmp_path_factory.mktemp(name)
        make(folder)
        return folder
    from filelock import FileLock

    folder = tmp_path_factory.getbasetemp().parent / name
    done = folder.with_name(f"{name}.done")
    with FileLock(str(folder) + ".lock"):
        if not done.is_file():
            shutil.rmtree(folder, ignore_errors=True)
            folder.mkdir()
            make(folder)
            done.touch()
    return folder


def trained_dirs(tmp_path_factory) -> dict:
    """Train once per test run (:func:`made_once`: one xdist worker trains, the others read its folder): a two-unit
    model (all methods), its bundles (all methods; default = chosen), and a foot-only model + bundle (for the
    Bluetooth protocol). Returns their paths."""
    if "root" not in _CACHE:
        _CACHE.update(root=made_once(tmp_path_factory, "trained", _train_two_unit))
    return _CACHE


def _train_two_unit(root: Path) -> None:
    """:func:`trained_dirs`'s models and bundles, into ``root``."""
    from pdrlearn.classify import train_user
    from pdrlearn.export.from_model import export_model

    train = synthetic_session(90, seed=0)
    # every unit named: the soft votes (fused) beside the combined models, which replace the svm/nn soft votes
    # by default (decision C23), so that the bundles hold both kinds
    _with_bounds(train_user([train], cv=2, seed=0, units=list(ALL_UNITS))).save(root / "model")
    export_model(root / "model", root / "bundle_all", methods=ALL_METHODS)
    export_model(root / "model", root / "bundle")
    foot = train.copy()
    for name in ("wAccelerometer", "wGyroscope", "wBarometer"):
        del foot.streams[name]
    _with_bounds(train_user([foot], cv=2, seed=0, units=["foot"], methods=["svm", "dtw"])).save(root / "model_foot")
    export_model(root / "model_foot", root / "bundle_foot")


def trained_dirs_and_walk(tmp_path_factory, name: str = "cli") -> dict:
    """:func:`trained_dirs` plus ``walk``: a 20-stride synthetic session written to a new folder (seed 9), and
    ``tmp``: that folder's parent (for the CLI tests of export and run)."""
    from pdrlearn.io import write_session

    d = dict(trained_dirs(tmp_path_factory))
    root = tmp_path_factory.mktemp(name)
    write_session(synthetic_session(20, seed=9, name="walk"), root / "walk")
    d["walk"] = root / "walk"
    d["tmp"] = root
    return d


#: methods of the rest-boundary model: the ensemble (decision C14) and its members
REST_METHODS = ["nn", "svm", "dtw", "ensemble"]


def rest_dirs(tmp_path_factory) -> dict:
    """A foot-only model trained on rest-to-rest windows (``boundaries="rest"``, decision 13) with the
    ``ensemble`` method, and its bundle with every method (once per test run, :func:`made_once`)."""
    if "rest_root" not in _CACHE:
        _CACHE.update(rest_root=made_once(tmp_path_factory, "trained_rest", _train_rest))
    return _CACHE


def _train_rest(root: Path) -> None:
    """:func:`rest_dirs`'s model and bundle, into ``root``."""
    from pdrlearn.classify import train_user
    from pdrlearn.export.from_model import export_model

    foot = synthetic_session(90, seed=0)
    for name in ("wAccelerometer", "wGyroscope", "wBarometer"):
        del foot.streams[name]
    _with_bounds(train_user([foot], cv=2, seed=0, units=["foot"], methods=REST_METHODS, boundaries="rest")).save(
        root / "model")
    export_model(root / "model", root / "bundle", methods=REST_METHODS)


def svm_user_walk(root, user: int, walk: str = "D"):
    """A simulated user's SVM on the fused units (L38's parity model) saved under ``root / "model"``, its bundle
    (``root / "bundle"``, loaded) and ``walk`` (seed 3): (model, bundle, session)."""
    from pdrlearn.classify import train_user
    from pdrlearn.export import export_model
    from pdrlearn.runtime import load_bundle
    from pdrlearn.sim import simulate

    cal = [simulate(e, user_seed=user, seed=0) for e in ("terrain", "direction", "length")]
    model = train_user(cal, methods=("svm",), units=("fused",), cv=3, user=f"u{user}")
    model.save(root / "model")
    export_model(root / "model", root / "bundle")
    return model, load_bundle(root / "bundle"), simulate(walk, user_seed=user, seed=3)


def replay(tracker, session, chunk_s: float = 0.5, used_only: bool = False) -> list:
    """Push ``session`` into ``tracker`` in ``chunk_s`` chunks, then flush; the emitted steps. ``used_only``: only
    the streams the tracker uses (``tracker.used_sensors``), from t = 0 to the last sample of any of them."""
    streams = {n: st for n, st in session.streams.items() if not used_only or n in tracker.used_sensors}
    if used_only:
        start, end = 0.0, max(st.t[-1] for st in streams.values())
    else:
        t = session.streams["fAccelerometer"].t
        start, end = t[0], t[-1]
    steps = []
    for t0 in np.arange(start, end + chunk_s, chunk_s):
        steps += tracker.push({n: (st.t[(st.t >= t0) & (st.t < t0 + chunk_s)],
                                   st.values[(st.t >= t0) & (st.t < t0 + chunk_s)])
                               for n, st in streams.items()})
    return steps + tracker.flush()


def holed_chunks(session, chunk_s: float, hole=None, sensors=None):
    """``{sensor: (t, values)}`` per ``chunk_s`` slice of ``session`` (from the foot accelerometer's first time),
    without the samples strictly inside ``hole`` = ``(a, b)`` s of ``sensors`` (None: of every stream); a stream with
    no sample in a slice is left out of it (a link that lost packets: decisions L674, E299)."""
    t = session.streams["fAccelerometer"].t
    for a in np.arange(t[0], t[-1] + chunk_s, chunk_s):
        chunk = {}
        for n, st in session.streams.items():
            keep = (st.t >= a) & (st.t < a + chunk_s)
            if hole is not None and (sensors is None or n in sensors):
                keep &= ~((st.t > hole[0]) & (st.t < hole[1]))
            if keep.any():
                chunk[n] = (st.t[keep], st.values[keep])
        yield chunk


def gait_replay(bundle, seed: int, route: str, *, rate_hz: float = 50.0, keep=lambda name: name.startswith("f")):
    """Decisions E320 / E326: a simulated walk (user ``seed``, ``route`` at ``rate_hz``) with only the foot streams
    ``keep`` takes, replayed in 1 s chunks through a foot-only ``Tracker(contacts=True, gait=True)`` of ``bundle``
    (warnings silenced): ``(session, tracker, steps)``."""
    import logging

    from pdrlearn.runtime import Tracker
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    s = simulate_path(parse_route(route), UserProfile.from_seed(seed), speed="normal", rate_hz=rate_hz, seed=1,
                      scenario="route")
    s.streams = {n: st for n, st in s.streams.items() if keep(n)}
    logging.disable(logging.WARNING)
    try:
        tr = Tracker(bundle, units=("foot",), sensors=list(s.streams), contacts=True, gait=True,
                     input_rates_hz={n: rate_hz for n in s.streams})
        steps = replay(tr, s, chunk_s=1.0)
    finally:
        logging.disable(logging.NOTSET)
    return s, tr, steps


def time_chunks(session, chunk_s: float, prefix: str = ""):
    """``(t0, {sensor: (t, values)})`` per ``chunk_s`` slice of ``session`` (slices of whole sample indices from the
    foot accelerometer's first time: no sample in two slices), the streams whose name starts with ``prefix``."""
    t = session.streams["fAccelerometer"].t
    edges = t[0] + chunk_s * np.arange(int((t[-1] - t[0]) / chunk_s) + 2)
    for a, b in zip(edges[:-1], edges[1:], strict=True):
        yield float(a), {n: (st.t[(st.t >= a) & (st.t < b)], st.values[(st.t >= a) & (st.t < b)])
                         for n, st in session.streams.items() if n.startswith(prefix)}


def calibrated_length_model(root, scenario_speed: str = "normal"):
    """A length model of simulated user 2 trained with ``distance_calibration=True``, saved in ``root/model``
    and exported to ``root/bundle``, and scenario A of the same user at ``scenario_speed`` (same unit: S22
    per-device scale errors): ``(root, model, session)``."""
    from pdrlearn.classify import train_user
    from pdrlearn.export.from_model import export_model
    from pdrlearn.sim import simulate

    cal = simulate("length", user_seed=2, speed="normal")
    model = train_user([cal], tasks=["length"], methods=["svm"], units=["foot"], cv=2, distance_calibration=True)
    model.length_bounds_m = cal.meta["length_class_bounds_m"]
    model.save(root / "model")
    export_model(root / "model", root / "bundle")
    return root, model, simulate("A", user_seed=2, speed=scenario_speed)


def scaled_foot_acc(s: Session, k: float) -> Session:
    """The session as recorded by a foot accelerometer with scale factor ``k`` on every axis."""
    acc = s.streams["fAccelerometer"]
    streams = {**s.streams, "fAccelerometer": Stream("fAccelerometer", acc.t, acc.values * k)}
    return Session(name=s.name, streams=streams, steps=s.steps, trajectory=s.trajectory, extras=s.extras,
                   meta=s.meta, frames=s.frames)


def per_timestamp(s: Session) -> list[dict]:
    """One push per sample time, every sensor that has a sample then (a live stream, sample by sample)."""
    times = np.unique(np.concatenate([st.t for st in s.streams.values()]))
    idx = {n: np.searchsorted(st.t, times) for n, st in s.streams.items()}
    return [{n: (st.t[i:i + 1], st.values[i:i + 1]) for n, st in s.streams.items()
             if (i := int(idx[n][k])) < len(st.t) and st.t[i] == when} for k, when in enumerate(times)]


def without(s: Session, a: float, b: float, names=None) -> Session:
    """``s`` without the samples of ``names`` (default: every stream) in ``[a, b)`` s."""
    c = s.copy()
    for n, st in s.streams.items():
        if names is None or n in names:
            m = ~((st.t >= a) & (st.t < b))
            c.streams[n] = Stream(n, st.t[m], st.values[m])
    return c


def push_waist(tr, s, chunks) -> list:
    """Push ``s``'s waist samples into the waist tracker ``tr`` in pieces of ``chunks`` sizes (the rest at once),
    then flush; the reported steps (``pdrlearn.waist.WaistTracker`` and ``pdrlearn.runtime.WaistTracker``)."""
    a, g = s["wAccelerometer"], s["wGyroscope"]
    out, i = [], 0
    for c in chunks:
        if i >= len(a.t):
            break
        out += tr.push(a.t[i:i + c], a.values[i:i + c], g.values[i:i + c])
        i += c
    if i < len(a.t):
        out += tr.push(a.t[i:], a.values[i:], g.values[i:])
    return out + tr.flush()


def gap_dtw_terrain_case():
    """User 5's foot DTW terrain model trained with C4's gap temperature (its probabilities stay under L18's 0.95
    gate, the case L184 and L189 were measured on; C67's calibrated default passes more strides) and scenario D at
    fast speed, both simulated with device errors as experiments/localization.py does."""
    from functools import partial

    import pdrlearn.classify.training as training
    from pdrlearn.classify import train_user
    from pdrlearn.sim import simulate

    sim = partial(simulate, device_errors=True)
    kept, training.DTW_CALIBRATION = training.DTW_CALIBRATION, "gap"
    try:
        model = train_user([sim("terrain", user_seed=5, speed="normal")], tasks=["terrain"], methods=["dtw"],
                           units=["foot"], cv=2, distance_calibration=False)
    finally:
        training.DTW_CALIBRATION = kept
    return model, sim("D", user_seed=5, speed="fast")


def written_route(folder: Path, route: str, seed: int) -> Path:
    """Simulated user ``seed`` walking ``route`` (``pdrlearn simulate --route``'s grammar), written as a PLASYS
    session folder ``folder`` (what ``pdrlearn run`` and the lean command read); returns ``folder``."""
    from pdrlearn.io import write_session
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    s = simulate_path(parse_route(route), UserProfile.from_seed(seed), seed=seed, scenario="route")
    write_session(s, folder)
    return folder
