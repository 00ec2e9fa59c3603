"""Session 40, fixer FO: the fixes of review R3 (D41 stride speeds scaled with D39's lengths, W457 gait-all's
resolved ROOT, L555 ``known_step_lengths`` without a matrix, L556 ``--compass`` without a fused heading, D42
non-finite ``--gnss-time-offset`` and the outside-fixes advice, D43 a blank ``t`` cell, L557 finite inputs)."""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.aid import aid_track
from pdrlearn.aid.fixgen import gnss_fixes
from pdrlearn.io.session import Session
from pdrlearn.track.gait import add_gait_columns
from tests.test_gnss_s40 import ORIGIN, _legs, _pdr

REAL = Path(__file__).resolve().parents[1] / "datasets" / "real"


# --- D41 -------------------------------------------------------------------------------------------------
def test_aided_speed_is_scaled_with_the_length(tmp_path):
    steps, truth = _legs((900.0, 900.0))
    pdr = _pdr(steps, scale=0.8)  # T3's waist-only track: -19 %
    add_gait_columns(pdr.steps)  # the pipeline fills speed_mps from the PDR's lengths before aiding
    fx = gnss_fixes(truth, accuracy_m=5.0, origin=ORIGIN, seed=4)
    p = tmp_path / "fix.csv"
    fx[["t", "lat", "lon", "accuracy_m"]].to_csv(p, index=False)
    out = aid_track(pdr, Session(name="w"), gnss_path=p, start=ORIGIN)
    assert out.info["aid"]["gnss"]["distance_scaled"]
    st = out.steps
    ok = np.isfinite(st["speed_mps"].to_numpy(float))
    assert ok.sum() > 100
    np.testing.assert_allclose((st["speed_mps"] * st["stride_time_s"])[ok], st["length_m"].abs()[ok], rtol=1e-9)
    assert st["speed_mps"].median() == pytest.approx(0.75 / 0.55, rel=0.015)  # the true speed, not 0.8 x
