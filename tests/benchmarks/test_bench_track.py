"""Benchmark: tracking one hour of two-unit (foot + waist) data end to end with PLASYS M3
(steps, classes, displacement, heading, position). Run with ``pytest -m bench --benchmark-enable``."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.io.session import Session, Stream


def tile_session(s: Session, hours: float = 1.0) -> Session:
    """Repeat a session end to end (times shifted) until it lasts ``hours``."""
    dur = s.duration_s + 1.0
    n = int(np.ceil(hours * 3600.0 / dur))
    streams = {}
    for name, st in s.streams.items():
        t = np.concatenate([st.t + k * dur for k in range(n)])
        streams[name] = Stream(name, t, np.tile(st.values, (n, 1)))
    steps = None
    if s.steps is not None:
        parts = []
        for k in range(n):
            p = s.steps.copy()
            for c in p.columns:
                if c.endswith("_s"):
                    p[c] = p[c] + k * dur
            parts.append(p)
        steps = pd.concat(parts, ignore_index=True)
    return Session(name=f"{s.name}_x{n}", streams=streams, steps=steps, meta=dict(s.meta),
                   frames=dict(s.frames))


@pytest.fixture(scope="module")
def hour_session():
    sim = pytest.importorskip("pdrlearn.sim")
    s = sim.simulate("C", user_seed=1, speed="normal")
    return tile_session(s, 1.0)


@pytest.mark.bench
def test_bench_track_one_hour_m3(benchmark, hour_session):
    from pdrlearn.track.plasys import track_plasys

    model = "oracle"
    try:  # a trained model makes the classification part of the timing
        from pdrlearn.classify import train_user
        from pdrlearn.sim import simulate

        model = train_user([simulate(e, user_seed=1) for e in ("terrain", "direction", "length")],
                           methods=("svm",), cv=3)
    except (ImportError, AttributeError):
        pass
    res = benchmark.pedantic(track_plasys, args=(hour_session,), kwargs={"method": "M3", "model": model},
                             rounds=3, iterations=1)
    assert len(res.steps) > 1000


@pytest.mark.bench
def test_bench_track_one_hour_m1(benchmark, hour_session):
    from pdrlearn.track.plasys import track_plasys

    res = benchmark.pedantic(track_plasys, args=(hour_session,), kwargs={"method": "M1"}, rounds=3,
                             iterations=1)
    assert len(res.steps) > 1000
