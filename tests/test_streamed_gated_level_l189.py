"""Decision L189: with ``gated_level_dz=True`` (an option, off by default: measured, not adopted by its rule; decision
L550: a keyword of ``track_plasys(streaming=True)`` and ``Tracker``, no module switch), ``track --streaming`` and the
runtime ``Tracker`` give an M3 stride whose terrain class the 0.95 gate
(L18) dropped L39's level rule, with offline's L184 function (``kernels.distance.unclassed_level_dz``).

The case is L184's (trial `audit`): user 5's DTW terrain model, whose probabilities stay far below 0.95, on scenario D
at fast speed: every terrain class is gated, so the flat strides kept their integrated heights streamed and live."""

from __future__ import annotations

from functools import partial

import numpy as np
import pytest

import pdrlearn.track.plasys as plasys
from pdrlearn.kernels.distance import LEVEL_DZ_M, unclassed_level_dz, unclassed_level_dz_one
from pdrlearn.sim import simulate
from pdrlearn.track.evaluate import evaluate_track
from tests.runtime_helpers import replay


def test_one_stride_call_is_the_array_function():
    dz = [0.05, -0.08, 0.17, -0.16, 0.0999, 0.1, -0.1]
    for classed in (True, False):
        want = unclassed_level_dz(np.array(dz), np.full(len(dz), classed))
        assert [unclassed_level_dz_one(d, classed) for d in dz] == want.tolist()
    assert unclassed_level_dz_one(0.0999, False) == 0.0 and unclassed_level_dz_one(LEVEL_DZ_M, False) == LEVEL_DZ_M


@pytest.fixture(scope="module")
def soft_terrain_case(tmp_path_factory):
    """User 5's DTW terrain model (probabilities below the gate), exported to a bundle, and scenario D fast: DTW
    with C4's gap temperature, as L189 measured it (C67's calibrated temperature passes more strides)."""
    from pdrlearn.export.from_model import export_model
    from tests.runtime_helpers import gap_dtw_terrain_case

    model, d = gap_dtw_terrain_case()
    root = tmp_path_factory.mktemp("l189")
    model.save(root / "model")
    export_model(root / "model", root / "bundle")
    return model, root / "bundle", d


def _live(bundle, d, on: bool):
    from pdrlearn.runtime import Tracker

    return replay(Tracker(bundle, gated_level_dz=on), d, 1.0)


@pytest.mark.slow
def test_gated_strides_streamed_and_live_get_the_level_height_as_offline(soft_terrain_case):
    model, bundle, d = soft_terrain_case
    res = plasys.track_plasys(d, method="M3", model=model, streaming=True, gated_level_dz=True)
    st = res.steps
    gated = st[[c for c in st.columns if c.startswith("p_terrain_")]].max(axis=1).to_numpy() < 0.95
    assert gated.mean() > 0.9  # the case: nearly every terrain class dropped by the gate
    dz = st["dz_m"].to_numpy()
    assert np.all((np.abs(dz[gated]) >= LEVEL_DZ_M) | (dz[gated] == 0.0))  # L39's rule, as offline (L184)
    assert (dz[gated] == 0.0).sum() >= 40
    ev = evaluate_track(res, d)
    ref = ev["altitude_change_ref_m"]
    offline = evaluate_track(plasys.track_plasys(d, method="M3", model=model), d)["altitude_change_m"]
    assert abs(ev["altitude_change_m"] - offline) < 0.25 and abs(ev["altitude_change_m"] - ref) < 0.3
    # the runtime: the same strides, the same heights (the one-stride call of the same function)
    live = _live(bundle, d, True)
    moved = [s for s in live if s.gap_s == 0.0]
    assert len(moved) == len(st)
    np.testing.assert_allclose([s.dz_m for s in moved], dz, atol=1e-9)
    assert live[-1].z == pytest.approx(res.trajectory["z"].iloc[-1], abs=1e-6)
    # without L189 the gated flat strides keep their integrated heights: streamed and live climb too high (the gap)
    before = plasys.track_plasys(d, method="M3", model=model, streaming=True)  # the default (L189 not adopted)
    assert evaluate_track(before, d)["altitude_change_m"] - ref > 0.4
    assert _live(bundle, d, False)[-1].z - ref > 0.4
    np.testing.assert_array_equal(before.steps["length_m"], st["length_m"])  # lengths untouched


def test_where_offline_and_streamed_agreed_nothing_changes():
    """A session where offline and streamed agreed before: scenario D (user 2) with the label classes (oracle: no
    probabilities, never gated) - the option changes no stride, and streamed still ends at offline's altitude."""
    d = simulate("D", user_seed=2, speed="normal")
    offline = evaluate_track(plasys.track_plasys(d, method="M3", model="oracle"), d)
    on = plasys.track_plasys(d, method="M3", model="oracle", streaming=True, gated_level_dz=True)
    off = plasys.track_plasys(d, method="M3", model="oracle", streaming=True)
    np.testing.assert_array_equal(on.steps["dz_m"], off.steps["dz_m"])
    np.testing.assert_array_equal(on.trajectory[["x", "y", "z"]], off.trajectory[["x", "y", "z"]])
    assert abs(evaluate_track(on, d)["altitude_change_m"] - offline["altitude_change_m"]) < 0.25


def test_a_soft_model_streamed_ends_where_offline_does():
    """The gap L189 closes, on a model whose every terrain class the gate drops (SVM trained on one session): scenario
    D (user 2, 3.80 m of stairs) streamed ends at 3.809 m with the option, 3.163 m without it; offline 3.859 m
    (printed when written)."""
    from pdrlearn.classify import train_user

    sim = partial(simulate, device_errors=True)
    model = train_user([sim("terrain", user_seed=2, speed="normal")], tasks=["terrain"], methods=["svm"],
                       units=["foot"], cv=2, distance_calibration=False)
    d = sim("D", user_seed=2, speed="normal")
    offline = evaluate_track(plasys.track_plasys(d, method="M3", model=model), d)["altitude_change_m"]
    on = evaluate_track(plasys.track_plasys(d, method="M3", model=model, streaming=True, gated_level_dz=True),
                        d)["altitude_change_m"]
    off = evaluate_track(plasys.track_plasys(d, method="M3", model=model, streaming=True), d)["altitude_change_m"]
    assert abs(on - offline) < 0.1 and abs(off - offline) > 0.5
