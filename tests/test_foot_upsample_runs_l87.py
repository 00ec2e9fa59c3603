"""Decision L87: the 20 Hz block means upsampled run by run between dropped samples."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.displace import _kernels as K
from pdrlearn.io import read_session
from pdrlearn.io.plasys import write_session
from pdrlearn.sim.simulate import simulate
from pdrlearn.track.plasys import track_plasys

FS = 20.0


def _signal(t):
    return np.sin(2 * np.pi * t) + 0.5 * np.sin(6 * np.pi * t)


def _block_means(t):
    """Exact means of :func:`_signal` over each sample's period (the firmware's 20 Hz block means)."""
    F = lambda u: -np.cos(2 * np.pi * u) / (2 * np.pi) - np.cos(6 * np.pi * u) / (12 * np.pi)  # noqa: E731
    return ((F(t + 0.5 / FS) - F(t - 0.5 / FS)) * FS)[:, None]


def test_runs_keep_their_blocks_and_reconstruct_across_a_gap():
    t = np.arange(80) / FS
    keep = np.ones(len(t), dtype=bool)
    keep[[30, 50, 51, 62, 64]] = False  # one, two in a row, and a run of one sample (63) between two drops
    tk, xk = t[keep], _block_means(t)[keep]
    tf, xf = K.upsample_runs(tk, xk, 5, 1 / FS)
    assert len(tf) == 5 * len(tk) and np.all(np.diff(tf) > 0)
    # every sample's five fine samples stay inside its own period (no block widened across a drop)
    assert np.all(np.abs(tf.reshape(-1, 5) - tk[:, None]) < 0.5 / FS)
    assert np.allclose(xf.reshape(-1, 5, 1).mean(axis=1), xk, atol=0.01)  # block means kept (midpoint rule)
    i63 = int(np.flatnonzero(tk == t[63])[0])
    assert np.all(xf[5 * i63:5 * i63 + 5] == xk[i63])  # a run of one sample is held over its period
    err_runs = np.abs(xf[:, 0] - _signal(tf))
    tw, xw = K.upsample_block_means(tk, xk, 5)
    err_whole = np.abs(xw[:, 0] - _signal(tw))
    near = np.abs(tf - t[50]) < 0.2  # around the two-sample drop
    assert err_runs[near].max() < 0.05 < 0.2 < err_whole[np.abs(tw - t[50]) < 0.2].max()


def test_a_clock_without_drops_is_upsampled_bit_for_bit_as_before():
    t = np.arange(60) / FS
    x = _block_means(t)
    a, b = K.upsample_runs(t, x, 5, 1 / FS), K.upsample_block_means(t, x, 5)
    assert np.array_equal(a[0], b[0]) and np.array_equal(a[1], b[1])


def test_short_walk_with_drops_end_to_end(tmp_path):
    out = {}
    for drop in (0.0, 0.03):
        sim = simulate("walk", 2, rate_hz=FS, seed=0, length_m=10.0, drop_rate=drop)
        s = read_session(write_session(sim, tmp_path / f"d{drop:g}"))
        truth = float(sim.steps["length_m"].sum())
        out[drop] = {k: track_plasys(s, params=p) for k, p in
                     (("fixed", {}), ("runs", {"timestamps": True, "upsample_runs": True}))}
    clean, dropped = out[0.0], out[0.03]
    assert clean["runs"].distance_m == clean["fixed"].distance_m  # one run: as before, bit for bit
    assert clean["runs"].trajectory.equals(clean["fixed"].trajectory)
    assert dropped["runs"].distance_m == pytest.approx(clean["runs"].distance_m, abs=0.015 * truth)  # L87's 1.5 pp
    assert (clean["fixed"].distance_m - dropped["fixed"].distance_m) / truth > 0.03  # the default loses the drops
