"""Trial T2 (session 44) finding F1: decision E286, E272's waist gyroscope bias is also read on the rest before the
first stride (the docs' "stand still 10 s before a walk"; before, ``stop_yaw_bias`` returned None without a stride
before the stop and the live Tracker trimmed that rest to ``buffer_s``)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
G = 9.80665


def test_the_rest_before_the_first_stride_gives_the_stop_bias_e286():
    """With no stride before (``prev_end`` None) a 15 s rest from the recording's start is read (before: None); a rest
    under ``STOP_MIN_S`` still gives none, as between strides."""
    from pdrlearn.kernels.stop_bias import stop_yaw_bias

    t = np.round(np.arange(0.0, 15.0, 0.01), 6)
    acc = np.tile([0.0, 0.0, G], (len(t), 1))
    gyr = np.tile([0.0, 0.0, 0.004], (len(t), 1))
    got = stop_yaw_bias({"wAccelerometer": (t, acc), "wGyroscope": (t, gyr)}.__getitem__, None, 15.0)
    assert got == pytest.approx(0.004, abs=1e-4)
    short = {"wAccelerometer": (t[t < 8], acc[t < 8]), "wGyroscope": (t[t < 8], gyr[t < 8])}
    assert stop_yaw_bias(short.__getitem__, None, 8.0) is None


def test_the_live_tracker_reads_the_first_stand_e286(tmp_path):
    """The live Tracker in 0.1 s pushes keeps the waist's first 12 s stand and reads E272's bias on it at the first
    stride (main: no stop read, ``n_stops`` 0: the only stop of 10 s or more is the first stand)."""
    from pdrlearn.cli import main
    from pdrlearn.runtime import Tracker, load_bundle
    from pdrlearn.runtime.replay import read_streams, replay_chunks

    walk = tmp_path / "walk"
    assert main(["simulate", "--route", "straight:4, stand:2.5, straight:4", "--stand", "12", "--user-seed", "12503",
                 "--rate", "100", "--out", str(walk)]) == 0
    bundle = load_bundle(ROOT / "models" / "plasys-sim-default")
    tracker = Tracker(bundle)
    streams, _ = read_streams(walk, bundle)
    steps = [s for chunk in replay_chunks(streams, 0.1) for s in tracker.push(chunk)] + list(tracker.flush())
    assert len(steps) > 4
    assert tracker._stop_bias.n_stops == 1
    assert abs(tracker._stop_bias.rps) < 0.01  # the simulator's waist bias (rad/s), not a turn
