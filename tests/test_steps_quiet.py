"""Foot accelerometer detector: the still (foot-flat) time that ends a swing adapts to the walker's own
rests (docs/decisions/steps.md 14). Hand-made |acc| profiles: short foot-flats of a fast/pathological
gait must count, a quiet-looking slow swing must not split a stride."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.io.session import Session, Stream
from pdrlearn.signal.conditioning import G
from pdrlearn.steps import AccelStepDetector

OLD = {"still_window_s": 0.15, "min_quiet_s": 0.2, "max_quiet_s": 0.2, "quiet_frac": 0.0}  # before decision 14


def _session(fs: float, pieces: list[tuple[float, float]], n: int, *, lead_s: float = 0.0,
             seed: int = 0) -> tuple[Session, int]:
    """Foot session whose |acc| - g repeats ``pieces`` (duration s, plateau level m/s^2) n times."""
    prof = [np.zeros(int(round(lead_s * fs)))]
    for _ in range(n):
        for dur, lvl in pieces:
            k = int(round(dur * fs))
            edge = np.minimum(np.arange(k) + 0.5, k - np.arange(k) - 0.5) / fs  # s from the piece's ends
            prof.append(lvl * np.clip(edge / 0.02, 0.0, 1.0))  # plateau with 20 ms ramps
    prof.append(np.zeros(int(round(1.0 * fs))))
    m = G + np.concatenate(prof) + np.random.default_rng(seed).normal(0, 0.05, sum(len(p) for p in prof))
    t = np.arange(m.size) / fs
    acc = np.column_stack([np.zeros_like(m), np.zeros_like(m), m])
    return Session("hand-made", {"fAccelerometer": Stream("fAccelerometer", t, acc)}), n


# fast / MS-like stride (0.92 s): foot-flat of only 0.13 s, push-off, swing, impact
FAST = [(0.13, 0.0), (0.25, 6.0), (0.45, 3.0), (0.05, 25.0), (0.04, 2.0)]
# slow stride (1.58 s): long rest, push-off, 0.14 s of quiet mid-swing, late swing, impact
SLOW = [(0.5, 0.0), (0.4, 4.0), (0.14, 0.0), (0.45, -3.0), (0.05, 25.0), (0.04, 2.0)]


@pytest.mark.parametrize("fs", [102.4, 204.8])
def test_short_foot_flats_count_as_rests(fs):
    s, n = _session(fs, FAST, 12)
    assert abs(len(AccelStepDetector().detect(s)) - n) <= 1
    assert len(AccelStepDetector(**OLD).detect(s)) < n // 2  # 0.2 s of quiet required: strides merge


@pytest.mark.parametrize("fs", [100.0, 204.8])
def test_quiet_mid_swing_of_slow_walking_does_not_split_strides(fs):
    s, n = _session(fs, SLOW, 10, lead_s=2.0)  # standing first, as every recording starts
    assert len(AccelStepDetector().detect(s)) == n
    fixed = AccelStepDetector(quiet_frac=0.0).detect(s)  # a fixed 0.1 s rest splits the slow swings
    assert len(fixed) > n + 3


def test_rate_of_20hz_unchanged():
    # at 20 Hz the still window keeps 3 samples and the still run 2 samples, whatever the quiet time
    det = AccelStepDetector()
    proc = det._make_processor(20.0)
    assert proc.w == 3 and proc.params.min_still_n == proc.params.max_still_n == 2
