"""The batched step-window path (pdrlearn.features.batch) equals the per-step kernel."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.features import step_windows
from pdrlearn.features.batch import gravity_rotation_batch, resample_rows
from pdrlearn.io import read_session
from pdrlearn.signal import gravity_rotation


def _same(a, b):
    assert np.array_equal(np.isnan(a.X), np.isnan(b.X))
    np.testing.assert_allclose(np.nan_to_num(a.X), np.nan_to_num(b.X), rtol=1e-9, atol=1e-9)


def test_batch_equals_per_step_on_two_unit_20hz():
    sim = pytest.importorskip("pdrlearn.sim")
    s = sim.simulate("D", user_seed=2, speed="slow")
    _same(step_windows(s, batch=True), step_windows(s, batch=False))


@pytest.mark.parametrize("name", ["gaitmap_level_right", "mobgap_HA001_Test5_Trial1"])
def test_batch_equals_per_step_on_real_fast_streams(real_dir, name):
    """204.8 Hz foot / 100 Hz waist: the anti-alias box filter and the rest-mean window are active."""
    s = read_session(real_dir / name)
    if s.steps is None or not len(s.steps):
        pytest.skip("no labelled steps")
    steps = s.steps.iloc[:40]
    a, b = step_windows(s, steps, batch=True), step_windows(s, steps, batch=False)
    assert np.isfinite(a.X[:, 1]).all() or np.isfinite(a.X).any()
    _same(a, b)


def test_gravity_rotation_batch_matches_single():
    rng = np.random.default_rng(0)
    g = np.vstack([rng.normal(size=(20, 3)) * 5, [[0, 0, 9.8], [0, 0, -9.8]]])
    r = gravity_rotation_batch(g)
    for gi, ri in zip(g, r, strict=True):
        np.testing.assert_allclose(ri, gravity_rotation(gi), atol=1e-12)
        np.testing.assert_allclose(ri @ gi, [0, 0, np.linalg.norm(gi)], atol=1e-9)
    with pytest.raises(DataError, match="gravity"):
        gravity_rotation_batch(np.zeros((1, 3)))


def test_resample_rows_matches_np_interp_with_clamped_ends():
    rng = np.random.default_rng(1)
    t = np.sort(rng.uniform(0, 1, size=(5, 12)), axis=1)
    v = rng.normal(size=(5, 12, 2))
    tn = np.linspace(-0.2, 1.2, 30)[None, :].repeat(5, axis=0)  # upsampling: no box filter
    out = resample_rows(tn, t, v)
    for b in range(5):
        for k in range(2):
            np.testing.assert_allclose(out[b, k], np.interp(tn[b], t[b], v[b, :, k]), atol=1e-12)
