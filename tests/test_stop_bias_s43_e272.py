"""Decision E272 (session 43, FH, trial T2 finding F2): the streamed two-unit heading (``Tracker``, ``pdrlearn run``,
the lean command; ``track --streaming`` by the same kernel) reads the waist gyroscope's vertical bias at each stop of
10 s or more and removes it from the strides after. A clean simulated walk with a stop, and the same walk with a known
bias step added to the waist gyroscope's up axis from the stop on: after E272 the strides after the stop turn as the
clean walk's; before it they turned by the bias times the walking time (0.01 rad/s x ~17 s = ~10 deg)."""

from __future__ import annotations

import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from pdrlearn.cli import main

ROOT = Path(__file__).resolve().parents[1]
SHIPPED = ROOT / "models" / "plasys-sim-default"
BIAS_RPS = 0.01  # 0.57 deg/s on the waist's up axis (meta.json frames: waist y = up)


@pytest.fixture(scope="module")
def walks(tmp_path_factory):
    root = tmp_path_factory.mktemp("e272")
    clean = root / "clean"
    assert main(["simulate", "--route", "straight:20, stand:25, straight:20, turn:90, straight:10", "-u", "12076",
                 "--no-noise", "-o", str(clean)]) == 0
    steps = np.genfromtxt(clean / "steps.csv", delimiter=",", names=True)
    ends = np.sort(steps[steps.dtype.names[1]]) / 1000.0
    stop_at = float(ends[np.argmax(np.diff(ends))])  # the last step before the longest pause: the stand
    biased = root / "biased"
    shutil.copytree(clean, biased)
    lines = (biased / "wGyroscope.csv").read_text().splitlines()
    out = [lines[0]]
    for line in lines[1:]:
        t, x, y, z = (float(v) for v in line.split(","))
        out.append(f"{t:.17g},{x:.17g},{y + (BIAS_RPS if t / 1000.0 >= stop_at else 0.0):.17g},{z:.17g}")
    (biased / "wGyroscope.csv").write_text("\n".join(out) + "\n")
    return clean, biased, stop_at


def _after_stop(session, stop_at):
    from pdrlearn.runtime.__main__ import replay

    tracker, steps = replay(SHIPPED, session)
    h = np.array([s.heading_rad for s in steps])
    t = np.array([s.start_s for s in steps])
    return h[t > stop_at + 10.0] - h[t <= stop_at][-1], tracker


def test_a_bias_read_at_a_stop_is_removed_after_it_e272(walks):
    clean, biased, stop_at = walks
    want, _ = _after_stop(clean, stop_at)
    got, tracker = _after_stop(biased, stop_at)
    assert len(got) == len(want) > 10
    err = np.degrees(np.abs(np.angle(np.exp(1j * (got - want)))))
    assert err.max() < 1.5, err.max()  # before E272: ~29 deg off (0.01 rad/s over the 25 s stop and the walk after)
    assert tracker._stop_bias.n_stops >= 1
    assert abs(tracker._stop_bias.rps - BIAS_RPS) < 0.002  # the up axis' bias, read at the stand


def test_track_streaming_removes_the_same_bias_e272(walks):
    from pdrlearn.io import read_session
    from pdrlearn.runtime.__main__ import replay
    from pdrlearn.track.plasys import track_streaming

    _, biased, _ = walks
    _, steps = replay(SHIPPED, biased)
    res = track_streaming(read_session(biased), model=SHIPPED / "models" if (SHIPPED / "models").is_dir() else None,
                          method="M2")
    off = res.steps["heading_rad"].to_numpy(float)
    live = np.array([s.heading_rad for s in steps])
    n = min(len(off), len(live))
    assert n > 20
    assert np.degrees(np.abs(np.angle(np.exp(1j * (off[-1] - live[-1]))))) < 1.0
    assert math.isfinite(float(off[-1]))
