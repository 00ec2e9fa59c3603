"""Decision B470 (session 48, FE, trial T1 finding F1): the offline foot track sets B454's ``clip_noise`` when the foot
accelerometer clips, with one line; the user's ``params`` win, M1's integration is left alone, and an unclipped file
is tracked exactly as before. Kernel-level (the track itself: tests/test_clipping_s46_b453_b454_l688.py)."""
from __future__ import annotations

import numpy as np

from pdrlearn.track.accel_clip import clip_noise_default
from pdrlearn.warning_lines import warning_code

G = 9.80665


def _acc(clip_g: float | None) -> np.ndarray:
    """A foot's accelerometer (n, 3): impacts of 6 g every 50 samples over gravity, flat at +-``clip_g`` g."""
    rng = np.random.default_rng(0)
    a = rng.normal(0.0, 2.0, (3000, 3)) + [0.0, 0.0, G]
    a[::50, 2] += 6 * G
    return a if clip_g is None else np.clip(a, -clip_g * G, clip_g * G)


def test_b470_a_clipped_foot_accelerometer_gets_clip_noise_with_one_line():
    kw = {"integrator": "kalman", "zupt_end": True}
    out, line = clip_noise_default(kw, None, _acc(4.0))
    assert out == {**kw, "clip_noise": True} and kw == {"integrator": "kalman", "zupt_end": True}
    assert "+-4 g in 60 of 3000 samples" in line and "'{\"clip_noise\": false}' turns it off" in line
    assert warning_code(line) == "B470"


def test_b470_the_user_s_params_m1_and_an_unclipped_file_are_left_alone():
    kw = {"integrator": "kalman"}
    assert clip_noise_default(kw, {"clip_noise": False}, _acc(4.0)) == (kw, None)  # the user's word wins
    assert clip_noise_default(kw, {"clip_noise": True}, _acc(4.0)) == (kw, None)  # set by the user: no line
    m1 = {"integrator": "integration"}
    assert clip_noise_default(m1, None, _acc(4.0)) == (m1, None)  # M1: no end ZUPT to attribute
    assert clip_noise_default(kw, None, _acc(None)) == (kw, None)  # nothing clipped: as before


def test_b471_the_16_g_line_s_race_walk_figures_are_the_experiment_s():
    """The +-16 g foot line's race-walk cost (B471) is the median experiments/clip_default_s48.py printed (its rows are
    committed), with and without B470's default."""
    from pathlib import Path

    import pandas as pd

    from pdrlearn.kernels.clipping import FOOT_ACCEL_RACE_WALK_16G

    rows = Path(__file__).resolve().parents[1] / "experiments" / "results"
    df = pd.concat([pd.read_csv(p) for p in sorted(rows.glob("clip_default_s48_part*.csv"))])
    race = df[df.kind == "racewalk"]
    assert len(race) == 24 and (race.clipped_samples > 0).all()
    got = (race.distance_error_pct_off.median(), race.distance_error_pct_cand.median())
    assert np.allclose(FOOT_ACCEL_RACE_WALK_16G, got, atol=0.005)
