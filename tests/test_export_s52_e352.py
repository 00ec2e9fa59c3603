"""Decision E352: a live per-step position radius. :func:`pdrlearn.kernels.position_sigma.stride_radius` is the one
kernel behind the offline ``pos_sigma_m`` (:func:`pdrlearn.track.position_sigma.sigma_per_row`) and the live waist
tracker's ``LiveStep.pos_sigma_m``; the radius after a stride reads no later stride, so the live value (the kernel over
the steps so far) equals the whole track's. The live == `run` trajectory.csv equality on a simulated stairs walk is
pinned in ``tests/test_runtime_waist.py::test_the_waist_runtime_gives_the_offline_barometric_altitude_and_floors``."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.kernels.position_sigma import SIGMA_PARAMS, rest_clock, stride_radius
from pdrlearn.track.position_sigma import sigma_per_row


def _walk(n=60):
    rng = np.random.default_rng(52)
    start = np.cumsum(rng.uniform(0.5, 0.7, n)) + 2.0
    start[30:] += 90.0  # a 90 s rest after the 30th step (L297's clock skips it when given)
    end = start + 0.55
    return pd.DataFrame({"start_s": start, "end_s": end, "length_m": rng.uniform(0.4, 0.8, n),
                         "heading_rad": np.cumsum(rng.normal(0, 0.2, n))})


def test_the_radius_of_each_prefix_is_the_whole_track_s_and_sigma_per_row_s():
    steps = _walk()
    p = SIGMA_PARAMS["waist"]
    L, h, e, s = (steps[c].to_numpy(float) for c in ("length_m", "heading_rad", "end_s", "start_s"))
    full, _ = stride_radius(L, h, e, 0.0, p)
    rows = sigma_per_row(steps, np.concatenate([[0.0], e]), p)
    np.testing.assert_allclose(rows[1:], full, atol=1e-12, rtol=0)
    live = [stride_radius(L[:k + 1], h[:k + 1], e[:k + 1], 0.0, p)[0][-1] for k in range(len(L))]
    np.testing.assert_allclose(live, full, atol=1e-12, rtol=0)
    assert np.all(np.diff(full) >= 0) and full[-1] > full[0] > 0
    rests = [(float(e[29]), float(s[30]))]  # L306: the rest L296 corrected
    clock = rest_clock(s, e, 0.0, 60.0, rests)
    assert clock[30] == e[30] - (s[30] - e[29])
    skipped = [stride_radius(L[:k + 1], h[:k + 1], clock[:k + 1], 0.0, p)[0][-1] for k in range(len(L))]
    np.testing.assert_allclose(skipped, sigma_per_row(steps, np.concatenate([[0.0], e]), p, 60.0, rests)[1:],
                               atol=1e-12, rtol=0)
    assert skipped[-1] < full[-1]  # the bias term's clock skipped the rest
