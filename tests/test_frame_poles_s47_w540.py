"""Trial T2 (session 47) F3, decision W540: Nordic-walking pole jolts (a vertical 8 m/s^2 half-sine of 40 ms and a
4 m/s^2 forward push of 0.2 s, 80 ms after each heel strike) turn the lower back's W2 forward lead past the forward
half, so the default inference reads a forward walker as backward (the limit, kept: W540 not adopted); the option
``push_lead_deg=PUSH_LEAD_DEG`` refuses such a lead instead. User 15090 (fixer FF's range)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.track.frame_inference import PUSH_LEAD_DEG, FrameInferenceError, infer_waist_frame


def _add_pole_jolts(folder, amp: float = 8.0, offset_s: float = 0.08) -> None:
    """The trial's poles.py without its random jitter: waist frame x left, y up, z forward (the simulator's)."""
    acc = pd.read_csv(folder / "wAccelerometer.csv")
    t = acc["timestamp"].to_numpy(float) / 1000.0
    for ic in np.sort(pd.read_csv(folder / "ics.csv")["ic_ms"].to_numpy(float) / 1000.0):
        t0 = ic + offset_s
        m = (t >= t0) & (t < t0 + 0.04)
        acc.loc[m, "y"] += amp * np.sin(np.pi * (t[m] - t0) / 0.04)
        m = (t >= t0) & (t < t0 + 0.2)
        acc.loc[m, "z"] += amp / 2 * np.sin(np.pi * (t[m] - t0) / 0.2)
    acc.to_csv(folder / "wAccelerometer.csv", index=False)


@pytest.fixture(scope="module")
def poles(tmp_path_factory):
    sim = tmp_path_factory.mktemp("poles") / "nw"
    assert main(["simulate", "--route", "stand:3, straight:90, stand:3", "--step-length", "0.9", "--step-time", "0.5",
                 "--bounce", "population", "--rate", "100", "--user-seed", "15090", "--out", str(sim)]) == 0
    _add_pole_jolts(sim)
    s = read_session(sim)
    acc, gyr = s.streams["wAccelerometer"], s.streams["wGyroscope"]
    return np.asarray(acc.values), np.asarray(gyr.values), 1.0 / float(np.median(np.diff(acc.t)))


def test_pole_jolts_flip_the_default_waist_inference_the_known_limit_w540(poles):
    f = infer_waist_frame(*poles)
    assert f.frame.z == "backward", f.frame  # trial T2 F3's flip: W540 not adopted (a side shuffle reads there too)
    lead = float(f.evidence["forward lead"].split(" deg")[0])
    assert PUSH_LEAD_DEG[0] <= lead <= PUSH_LEAD_DEG[1], lead


def test_the_push_lead_option_refuses_the_pole_walkers_lead_w540(poles):
    with pytest.raises(FrameInferenceError, match="decision W540"):
        infer_waist_frame(*poles, push_lead_deg=PUSH_LEAD_DEG)
