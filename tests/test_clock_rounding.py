"""Decision E35: results do not depend on the rounding of the clock (a shift of 1e-13 s, ms / 1000 vs ms * 1e-3).

Two new-user trials found the streamed track of the same session differ by centimetres between a session built
in memory and the same session written and read back (clock values differing by 1.4e-14 s): stride windows and
stance windows whose length is an exact multiple of the sample interval held one sample more or less by
rounding. Comparisons against window edges and limits now count differences within ``TIE_S`` as equal.
"""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.io import Session, Stream
from pdrlearn.kernels.stride import StanceSegmenter
from pdrlearn.kernels.window import TIE_S, cover
from pdrlearn.sim import simulate
from pdrlearn.track import get_pipeline


def _shifted(s: Session, eps: float) -> Session:
    return Session(s.name, {n: Stream(n, st.t + eps, st.values) for n, st in s.streams.items()},
                   extras=s.extras, meta=s.meta)


@pytest.mark.parametrize("t0", [0.1, 0.1 + 1e-15, 0.1 - 1e-15, 0.30000000000000004])
def test_cover_puts_a_sample_within_tie_of_an_edge_on_it(t0):
    t = np.arange(12) * 0.05  # 0.1 and 0.3 are samples 2 and 6 up to rounding
    i0, _ = cover(t, t0, 0.5)
    assert t[i0] == pytest.approx(round(t0 / 0.05) * 0.05, abs=TIE_S)
    _, i1 = cover(t, 0.0, t0)
    assert t[i1 - 1] == pytest.approx(round(t0 / 0.05) * 0.05, abs=TIE_S)


def test_stance_segmenter_ignores_clock_rounding():
    """Fixed rule (E7): a stance of exactly min_stance_s (3 still samples at 20 Hz, 0.1 s) is one whatever
    the clock's rounding; strides of 22 samples from t = 7.3 s (s1 - s0 is 0.1 - 1e-15 s there before E35)."""
    fs = 20.0
    n = 22 * 40
    k = np.arange(n)
    t = 7.3 + k / fs
    w = np.where(k % 22 < 3, 0.1, 3.0)  # 3 still samples per 1.1 s stride
    gyr = np.column_stack([np.zeros(n), w, np.zeros(n)])
    fixed = {"stance_floor_factor": 0.0, "stance_mean_min_s": 0.0, "stance_gap_s": 0.0}
    ref = StanceSegmenter(**fixed).update(t - 7.3 + 100.0, gyr)
    assert len(ref) == 39
    for t_ in (t, t + 1e-13, t - 1e-13, t * (1 + 1e-16)):
        got = StanceSegmenter(**fixed).update(t_, gyr)
        assert len(got) == len(ref), len(got)


def test_streamed_track_is_the_same_on_a_clock_shifted_by_rounding():
    logging.getLogger("pdrlearn").setLevel(logging.ERROR)
    try:
        d = simulate("D", user_seed=1)
        ref = get_pipeline("plasys")(d, method="auto", streaming=True).trajectory[["x", "y", "z"]].to_numpy()
        for eps in (1e-13, 1e-12):
            got = get_pipeline("plasys")(_shifted(d, eps), method="auto", streaming=True)
            np.testing.assert_allclose(got.trajectory[["x", "y", "z"]].to_numpy(), ref, atol=1e-9)
    finally:
        logging.getLogger("pdrlearn").setLevel(logging.NOTSET)
