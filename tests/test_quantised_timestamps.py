"""Decision D7: quantised timestamps (204.8 Hz written as integer ms) keep the true sampling period."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.io import Stream, read_session
from pdrlearn.io.session import SENSORS
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.plasys import track_plasys


def _stream(t_s):
    t = np.asarray(t_s, float)
    return Stream(SENSORS["fAccelerometer"], t, np.zeros((len(t), 3)))


def test_period_of_integer_ms_at_204_8_hz_is_the_mean_interval():
    t = np.round(np.arange(4000) * 1000 / 204.8) / 1000  # 4 and 5 ms intervals, median 5 ms
    assert np.median(np.diff(t)) == pytest.approx(0.005)
    assert _stream(t).rate_hz == pytest.approx(204.8, rel=2e-4)
    gapped = np.concatenate([t[:2000], t[2000:] + 0.5])  # a 0.5 s dropout does not enter the mean
    assert _stream(gapped).rate_hz == pytest.approx(204.8, rel=2e-4)


def test_regular_timestamps_keep_the_median_exactly():
    t = np.arange(3000) / 204.8
    rng = np.random.default_rng(0)
    jittered = np.arange(3000) * 0.01 + rng.normal(0, 1e-4, 3000)  # 100 Hz with 0.1 ms jitter
    for tt in (t, np.sort(jittered)):
        assert _stream(tt).period_s == float(np.median(np.diff(tt)))


def test_integer_ms_recording_tracks_like_the_float_one(gaitmap_level_left, tmp_path):
    import shutil

    dst = tmp_path / "int_ms"
    shutil.copytree(gaitmap_level_left, dst)
    for f in ("fAccelerometer.csv", "fGyroscope.csv"):
        df = pd.read_csv(dst / f)
        df["timestamp"] = df["timestamp"].round().astype(int)
        df.to_csv(dst / f, index=False)
    a, b = read_session(gaitmap_level_left), read_session(dst)
    ma, mb = (evaluate_track(track_plasys(s, method="auto"), s) for s in (a, b))
    assert abs(mb["stride_length_mae_m"] - ma["stride_length_mae_m"]) < 0.003  # 0.061 vs 0.035 m before
    assert abs(mb["distance_error_pct"] - ma["distance_error_pct"]) < 0.5
