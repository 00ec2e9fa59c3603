"""Steps decision 97 (session 53, FG; trial s53t3 F1): the RMS envelope ``event_power`` (not adopted: an option) keeps
an up-sampled real walk's contacts where |acc| low-passed moves them, and the fallback line ``contact_rate_warning``
of a ``--toe-off`` track whose IMU-only contacts were dated outside 90-300 Hz."""

from __future__ import annotations

import json
import logging
import math

import numpy as np
import pandas as pd
import pytest

from pdrlearn.io import read_session
from pdrlearn.kernels import contact as C
from pdrlearn.steps.detectors import AccelStepDetector
from pdrlearn.track.evaluate import summary_warnings
from pdrlearn.track.toeoff import contact_rate_warning


@pytest.fixture(scope="module")
def level_left_pair(real_dir, tmp_path_factory):
    """gaitmap level left's 20.5-30.5 s (204.8 Hz) and its band-limited copy at 399.36 Hz (scipy resample_poly 39 / 20,
    trial s53t3's resample.py): the window holds the three strides whose contacts moved 28.7-33.0 ms (steps 97)."""
    from scipy.signal import resample_poly

    src = real_dir / "gaitmap_level_left"
    meta = json.loads((src / "meta.json").read_text())
    out = {}
    for rate, (up, down) in ((204.8, (1, 1)), (399.36, (39, 20))):
        d = tmp_path_factory.mktemp(f"ll{rate:g}")
        for name in ("fAccelerometer.csv", "fGyroscope.csv"):
            x = pd.read_csv(src / name)
            x = x[(x["timestamp"] >= 20500) & (x["timestamp"] < 30500)]
            v = resample_poly(x[["x", "y", "z"]].to_numpy(float), up, down, axis=0, padtype="line")
            t = float(x["timestamp"].iloc[0]) + np.arange(len(v)) * 1000.0 / rate
            pd.DataFrame({"timestamp": t, "x": v[:, 0], "y": v[:, 1], "z": v[:, 2]}).to_csv(d / name, index=False)
        (d / "meta.json").write_text(json.dumps({**meta, "rate_hz": rate, "n_samples": len(t)}))
        out[rate] = read_session(d)
    return out


def _moved(pair, **kw) -> tuple[int, int]:
    logging.disable(logging.WARNING)
    try:
        a, b = (np.sort(AccelStepDetector(**kw).detect(pair[r])["event_s"].to_numpy(float)) for r in (204.8, 399.36))
    finally:
        logging.disable(logging.NOTSET)
    return len(a), int(sum(np.min(np.abs(b - x)) > 0.010 for x in a))


def test_the_rms_envelope_keeps_an_up_sampled_walks_contacts(level_left_pair):
    n, before = _moved(level_left_pair)
    assert n >= 8 and before == 3  # |acc| low-passed: 3 contacts 28.7-33.0 ms later at 399.36 Hz
    assert _moved(level_left_pair, event_power=True) == (n, 0)
    assert AccelStepDetector().event_power is False  # not adopted (steps 97): the default is before


def test_the_envelope_is_the_root_of_the_low_passed_power_and_the_streamed_ic_reads_it():
    fs = 200.0
    b, a = C.butter2(8.0, fs)
    rng = np.random.default_rng(97)
    m = 9.8 + np.abs(rng.normal(0, 3, 400))
    np.testing.assert_allclose(C.event_envelope(m, b, a, True), np.sqrt(C.lowpass2(m * m, b, a)))
    np.testing.assert_array_equal(C.event_envelope(m, b, a), C.lowpass2(m, b, a))
    # a swing, an impact bump and a ringing tail on one axis: the envelope dates the impact differently from |acc|
    t = np.arange(0, 1.2, 1 / fs)
    z = 9.81 + 12 * np.exp(-((t - 0.45) / 0.05) ** 2) + 25 * np.exp(-((t - 0.8) / 0.012) ** 2) * np.cos(
        2 * math.pi * 60 * (t - 0.8))
    acc = np.column_stack([np.zeros_like(t), np.zeros_like(t), z])
    plain, power = C.impact_time(t, acc), C.impact_time(t, acc, power=True)
    assert math.isfinite(plain) and math.isfinite(power) and plain != power
    assert power == C.impact_peak(t, np.abs(z), C.GRAVITY, C.PEAK_FRAC, C.EVENT_CUTOFF_HZ, C.SUBSAMPLE,
                                  power=True)[0]


@pytest.mark.parametrize("rate, said", [(25.0, "25 Hz"), (1024.0, "ringing"), (100.0, None), (204.8, None)])
def test_a_toe_off_tracks_contacts_outside_90_to_300_hz_get_one_line(rate, said):
    summary = {"rate_hz": rate, "median_stance_time_s": 0.62, "info": {"stance_source": "imu"}}
    line = contact_rate_warning(summary)
    if said is None:
        assert line is None
        return
    assert said in line and "steps.md 89, 97" in line and "90-300 Hz" in line
    assert [w for w in summary_warnings(summary) if "move with the rate" in w] == [line]  # track / run print it
    assert contact_rate_warning({**summary, "info": {"stance_source": "force"}}) is None  # insoles' contacts
    assert contact_rate_warning({"rate_hz": rate}) is None  # no --toe-off: no stance times
