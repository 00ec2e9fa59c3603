"""Decision B79 (docs/decisions/bad-input.md): the waist axis test reads the step frequency in 1.2-3.0 Hz; a
walk faster than 180 steps/min (running) is not tested, instead of its lateral axis being called forward and a
right declared frame "contradicted" (the trial's stairs at 220 steps/min)."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.track.frame_inference import FrameInferenceError, infer_waist_frame

G = 9.80665


def _waist(cadence_spm: float, fs: float = 100.0, seconds: float = 40.0, seed: int = 0) -> np.ndarray:
    """Sensor x = left, y = up, z = forward (the simulator's waist frame): vertical bounce and forward surge at
    step frequency (forward leading by 45 deg, W2), medio-lateral sway at stride frequency, noise."""
    rng = np.random.default_rng(seed)
    t = np.arange(0.0, seconds, 1.0 / fs)
    f = cadence_spm / 60.0
    up = G + 2.5 * np.sin(2 * np.pi * f * t)
    fwd = 1.5 * np.sin(2 * np.pi * f * t + np.pi / 4)
    left = 1.4 * np.sin(np.pi * f * t)
    return np.column_stack([left, up, fwd]) + rng.normal(0, 0.2, (len(t), 3))


def test_walking_waist_frame_is_inferred():
    got = infer_waist_frame(_waist(110.0), np.zeros((4000, 3)), 100.0)
    assert got.frame.z == "forward" and got.frame.y == "up"


def test_running_cadence_is_not_tested():
    with pytest.raises(FrameInferenceError, match=r"peaks above 3 Hz \(over 180 steps/min\) in \d+ of \d+ walking "
                                                  r"windows.*running is not supported"):
        infer_waist_frame(_waist(220.0), np.zeros((4000, 3)), 100.0)
