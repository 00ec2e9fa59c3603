"""Decision E71: the live input checks' per-push work (``FrozenWatch`` vectorised on the run splitting of
``kernels.units.identical_runs``, one ``FrozenWatch.push`` per tracker push) warns about the same frozen runs as
the offline ``kernels.units`` result, whatever the push size."""

from __future__ import annotations

import re

import numpy as np
import pytest

from pdrlearn.kernels.units import FROZEN_PARTNER, frozen_spans, identical_runs, moving_samples
from pdrlearn.runtime.guard import WATCHED, FrozenWatch


def _streams(seed: int) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """60 s at 100 Hz of a foot and a waist unit that move, with runs of one repeated sample of 0.5-4 s (some over
    :data:`FROZEN_S`, one at the very start, one to the very end, two back to back) in every stream."""
    rng = np.random.default_rng(seed)
    t = np.round(np.arange(6000) * 0.01, 9)
    out = {}
    for j, name in enumerate(WATCHED):
        base = {"Gyroscope": 0.0, "Accelerometer": 9.81, "MagneticField": 40.0}[name[1:]]
        v = base + rng.normal(0, 2.0, (len(t), 3))
        spans = [(0, 250), (1200 + 100 * j, 1350 + 100 * j), (2500, 2700), (2700, 2950), (4000 + 50 * j, 4180),
                 (5650, 6000)]
        for a, b in spans:
            v[a:b] = v[a] if a != 2700 else v[a] + 1.0  # the two back-to-back runs hold different values
        if seed % 2 and name == "fGyroscope":
            v[1500:2600] = rng.normal(0, 0.01, (1100, 3))  # the foot rests: its accelerometer's runs are not frozen
        out[name] = (t, v)
    return out


def _offline(streams) -> set[tuple[str, str]]:
    """(stream, first time) of each run ``io.plasys.warn_frozen`` warns about, from ``kernels.units``."""
    out = set()
    for name, (t, v) in streams.items():
        pt, pv = streams[FROZEN_PARTNER[name]]
        moved = pt[moving_samples(FROZEN_PARTNER[name], pv)]
        out |= {(name, f"{a:.2f}") for a, b, _ in frozen_spans(t, v) if np.any((moved >= a) & (moved <= b))}
    return out


@pytest.mark.parametrize("seed", [0, 1, 2])
@pytest.mark.parametrize("chunk", [1, 7, 1000])
def test_live_frozen_warnings_are_the_offline_runs_whatever_the_push_size(seed, chunk):
    streams = _streams(seed)
    want = _offline(streams)
    assert len(want) >= 10  # the runs are there (and some are not frozen: under 2 s, or at rest)
    w, got = FrozenWatch(), []
    n = len(streams["fGyroscope"][0])
    for i in range(0, n, chunk):
        if chunk == 1:  # the tracker's one-sample path on Python floats (E17)
            got += w.push({}, {k: (float(t[i]), v[i].tolist()) for k, (t, v) in streams.items()})
        else:
            got += w.push({k: (t[i:i + chunk], v[i:i + chunk]) for k, (t, v) in streams.items()})
    # a run still going at the push's end: "since 12.00 s (2.3 s so far)"; one ended in it: "for 2.5 s (12.00-14.49 s)"
    seen = [(m.split(":")[0], next(g for g in re.search(r"since (\d+\.\d\d) s|\((\d+\.\d\d)-", m).groups() if g))
            for m in got]
    assert len(seen) == len(set(seen))  # each run warned about once
    assert set(seen) == want


def test_identical_runs_cover_every_row_once():
    v = np.array([[1, 1], [1, 1], [2, 1], [2, 2], [2, 2], [2, 2], [3, 3]])
    starts, ends = identical_runs(v)
    assert starts.tolist() == [0, 2, 3, 6] and ends.tolist() == [1, 2, 5, 6]
    t = np.arange(7.0)
    assert frozen_spans(t, v, 1.0) == [(0.0, 1.0, 2), (3.0, 5.0, 3)]
    assert frozen_spans(t, v, 0.0) == frozen_spans(t, v, 1.0)  # a row unlike both neighbours is no span
