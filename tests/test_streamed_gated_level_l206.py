"""Decision L206: ``gated_level_dz="summed"`` (decision L550: a keyword, no module switch) - L39's level rule on the
summed dz of a run of gated M3 strides (``summed_level_step``), one kernel for ``track --streaming`` and the runtime
``Tracker``."""

from __future__ import annotations

import numpy as np
import pytest

import pdrlearn.track.plasys as plasys
from pdrlearn.kernels.distance import LEVEL_DZ_M, streamed_gated_level_dz, summed_level_step
from tests.runtime_helpers import replay
from tests.test_streamed_gated_level_l189 import soft_terrain_case  # noqa: F401 (the fixture)


def test_a_run_is_levelled_while_its_summed_dz_stays_under_the_level_threshold():
    dz = np.array([0.06, 0.03, 0.02, -0.05, 0.30, 0.04, -0.09, 0.08, 0.05, 0.07])
    classed = np.array([False] * 4 + [False, False, False, True, False, False])
    out = streamed_gated_level_dz(dz, classed, "summed")
    # run 1: sums 0.06, 0.09 levelled; 0.11 kept; 0.06 levelled. 0.30 (>= 0.10) kept, ends the run. run 2: 0.04,
    # -0.05 levelled; 0.08 is classed (kept, ends the run); run 3: 0.05 levelled, 0.12 kept
    np.testing.assert_allclose(out, [0.0, 0.0, 0.02, 0.0, 0.30, 0.0, 0.0, 0.08, 0.0, 0.07])
    # per stride (L189) levels every gated stride under 0.10 m: the summed rule levels a subset of those
    per = streamed_gated_level_dz(dz, classed, True)
    assert np.all((out == 0.0) <= (per == 0.0)) and (per == 0.0).sum() > (out == 0.0).sum()
    np.testing.assert_array_equal(streamed_gated_level_dz(dz, classed, False), dz)
    with pytest.raises(ValueError, match="L206"):  # L550: one DataError line (a ValueError)
        streamed_gated_level_dz(dz, classed, "sum")


def test_the_one_stride_step_carries_the_run_as_the_array_does():
    rng = np.random.default_rng(0)
    dz, classed = rng.normal(0.0, 0.07, 200), rng.random(200) < 0.3
    run, got = 0.0, []
    for d, c in zip(dz.tolist(), classed.tolist(), strict=True):
        o, run = summed_level_step(d, c, run)
        got.append(o)
    assert got == streamed_gated_level_dz(dz, classed, "summed").tolist()
    assert summed_level_step(LEVEL_DZ_M, False, 0.0) == (LEVEL_DZ_M, 0.0)  # L39's own threshold ends the run


@pytest.mark.slow
def test_summed_streamed_and_live_give_the_same_heights(soft_terrain_case):  # noqa: F811
    """User 5's DTW terrain model on D fast (nearly every terrain class gated): with "summed" the streamed strides'
    heights follow the kernel, and the runtime's per-stride dz equal the streamed ones."""
    from pdrlearn.runtime import Tracker

    model, bundle, d = soft_terrain_case
    raw = plasys.track_plasys(d, method="M3", model=model, streaming=True).steps
    st = plasys.track_plasys(d, method="M3", model=model, streaming=True, gated_level_dz="summed").steps
    classed = st[[c for c in st.columns if c.startswith("p_terrain_")]].max(axis=1).to_numpy() >= 0.95
    want = streamed_gated_level_dz(raw["dz_m"].to_numpy(), classed, "summed")
    np.testing.assert_allclose(st["dz_m"], want, atol=1e-12)
    assert (st["dz_m"].to_numpy() == 0.0).sum() > (raw["dz_m"].to_numpy() == 0.0).sum()
    live = [s for s in replay(Tracker(bundle, gated_level_dz="summed"), d, 1.0) if s.gap_s == 0.0]
    assert len(live) == len(st)
    np.testing.assert_allclose([s.dz_m for s in live], st["dz_m"], atol=1e-9)
    np.testing.assert_array_equal(raw["length_m"], st["length_m"])  # lengths untouched
