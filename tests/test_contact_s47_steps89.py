"""Steps decision 89 (session 47, FG, trial T3 F1): the foot's impact peaks grouped into bumps by a prominence in
m/s^2 (``AccelStepDetector(peak_prominence=...)``, not adopted as the default) keep a real recording's ICs when it
is up-sampled; 0 is every local maximum in samples, as before."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pdrlearn.kernels.contact import bump_peaks, impact_time
from tests.conftest import REAL


def test_bump_peaks_merges_a_shallow_ripple_and_keeps_every_peak_at_zero():
    values = [30.0, 41.9, 38.9, 20.0]
    dips = [math.inf, 12.0, 38.85, 15.0]  # 41.9 -> 38.9 dips 0.05 only: a ripple of the 41.9 bump
    assert bump_peaks(values, dips, 1.0) == [0, 1, 3]
    assert bump_peaks(values, dips, 0.0) == [0, 1, 2, 3]
    assert bump_peaks([40.0, 40.5], [math.inf, 39.9], 1.0) == [1]  # the bump keeps its higher maximum


def _resampled(session, up: int):
    from scipy.signal import resample_poly

    from pdrlearn.io.session import Stream

    acc = session["fAccelerometer"]
    fs = 1.0 / float(np.median(np.diff(acc.t)))
    v = resample_poly(acc.values, up, 1, axis=0, padtype="line")
    out = session.copy()
    out.streams = {"fAccelerometer": Stream("fAccelerometer", acc.t[0] + np.arange(len(v)) / (fs * up), v)}
    return out


@pytest.mark.slow
def test_upsampled_gaitmap_walk_keeps_its_ics_with_the_option():
    from pdrlearn.io import read_session
    from pdrlearn.steps import AccelStepDetector

    native = read_session(REAL / "gaitmap_level_left")
    up = _resampled(native, 5)  # 204.8 -> 1024 Hz, band-limited

    def moved(h):
        e0 = AccelStepDetector(peak_prominence=h).detect(native).event_s.to_numpy()
        e1 = AccelStepDetector(peak_prominence=h).detect(up).event_s.to_numpy()
        return np.array([np.min(np.abs(e1 - x)) for x in e0])

    before = moved(0.0)
    assert (before > 0.004).sum() >= 5  # T3 F1: 8 of 29 ICs moved +4.3 to +33.3 ms
    assert moved(1.7).max() < 0.0025

    # the streamed IC (E49's impact_time) groups the same way: the stride whose IC T3 saw move +21.5 ms
    st = AccelStepDetector().detect(native)
    row = st.iloc[int(np.argmin(np.abs(st.event_s.to_numpy() - 9.574)))]
    acc = up["fAccelerometer"]
    w = (acc.t >= row.start_s) & (acc.t <= row.end_s)
    rippled, bumped = (impact_time(acc.t[w], acc.values[w], prominence=h) for h in (0.0, 1.7))
    assert rippled - row.event_s > 0.015 and abs(bumped - row.event_s) < 0.003
