"""Decision L184: offline M3 gives L39's level rule to a stride whose terrain class the 0.95 gate (L18) dropped.

The case of trial `audit` (session 26, finding 1): after C55 user 5's model chose `dtw/fused` for terrain, whose
probabilities stay far below 0.95, so every terrain class was gated and the flat strides of scenario D kept
their integrated heights (+1.09 m on user 5 fast, altitude 3.93 -> 4.86 m for 3.80 m)."""

from __future__ import annotations

import numpy as np
import pytest

import pdrlearn.track.plasys as plasys
from pdrlearn.kernels.distance import LEVEL_DZ_M, unclassed_level_dz
from pdrlearn.track.evaluate import evaluate_track


def test_unclassed_level_dz_levels_only_the_unclassed_strides():
    dz = np.array([0.05, -0.08, 0.17, 0.05, 0.16, -0.09])
    classed = np.array([True, True, True, False, False, False])
    out = unclassed_level_dz(dz, classed)
    # classed strides keep the height their class rule gave, unclassed ones under 0.10 m are level (L39)
    np.testing.assert_array_equal(out, [0.05, -0.08, 0.17, 0.0, 0.16, 0.0])
    assert out is not dz and dz[3] == 0.05


@pytest.fixture(scope="module")
def soft_terrain_case():
    """User 5's DTW terrain model (probabilities below the gate) and scenario D at fast speed, as the trial's: DTW
    with C4's gap temperature, as in session 26 (C67's calibrated temperature passes more strides through the gate)."""
    from tests.runtime_helpers import gap_dtw_terrain_case

    return gap_dtw_terrain_case()


@pytest.mark.slow
def test_gated_strides_are_levelled_and_the_altitude_holds(soft_terrain_case, monkeypatch):
    model, d = soft_terrain_case
    res = plasys.track_plasys(d, method="M3", model=model)
    st = res.steps
    pmax = st[[c for c in st.columns if c.startswith("p_terrain_")]].max(axis=1).to_numpy()
    gated = pmax < 0.95
    assert gated.mean() > 0.9  # the case: DTW's soft probabilities, nearly every class dropped by the gate
    dz = st["dz_m"].to_numpy()
    assert np.all((np.abs(dz[gated]) >= LEVEL_DZ_M) | (dz[gated] == 0.0))
    ev = evaluate_track(res, d)
    alt, ref = ev["altitude_change_m"], ev["altitude_change_ref_m"]
    assert abs(alt - ref) < 0.35, (alt, ref)  # L627's start tilt: 4.104 m for 3.800 (was within 0.25)
    assert not [w for w in res.info["warnings"] if "strides classed flat" in w]
    # without L184 the same strides keep their integrated heights and the track climbs too high (the bug)
    monkeypatch.setattr(plasys, "GATED_LEVEL_DZ", False)
    before = plasys.track_plasys(d, method="M3", model=model)
    assert evaluate_track(before, d)["altitude_change_m"] - ref > 0.4
    np.testing.assert_allclose(before.steps["length_m"], st["length_m"])  # lengths untouched
