"""Session 42, implementer I2 (trial s41 T3 F6): path.png colours a track's ramp and stair strides and adds a
height-over-distance panel when the track has any (L592). The figure's line data is read, not its pixels."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.track.plots import DISTANCE_PANEL_XLABEL, climb_spans, path_figure, walked_distance

#: a 8 % ramp up, level, a stair flight up, level (user 11770: this file's one session)
ROUTE = "stand:2, straight:3, slope:8:8, straight:4, up:10, straight:4, stand:2"


@pytest.fixture(scope="module")
def tracked(tmp_path_factory):
    from pdrlearn.cli.track import track_session, track_settings

    d = tmp_path_factory.mktemp("l592") / "s"
    assert main(["simulate", "--route", ROUTE, "--user-seed", "11770", "--rate", "50", "--out", str(d)]) == 0
    return track_session(d, track_settings(altitude="fused", no_plot=True))


def _panel(fig):
    return next(ax for ax in fig.axes if ax.get_xlabel() == DISTANCE_PANEL_XLABEL)


def test_ramp_and_stair_strides_are_coloured_with_a_distance_panel_l592(tracked):
    from matplotlib import pyplot as plt

    result = tracked["result"]
    spans = climb_spans(result)
    kinds = [k for k, _, _ in spans]
    assert "ramp" in kinds and kinds[-1] == "stairs"  # the ramp, the flight last
    _, fig = path_figure({"track": result})
    try:
        ad = _panel(fig)
        tr = result.trajectory
        base = [ln for ln in ad.get_lines() if ln.get_label() == "track"][0]
        np.testing.assert_allclose(base.get_xdata(), walked_distance(tr["x"], tr["y"]))
        np.testing.assert_allclose(base.get_ydata(), tr["z"].to_numpy(float))
        dz = pd.to_numeric(result.steps["dz_m"], errors="coerce").to_numpy(float)
        coloured = [ln for ln in ad.get_lines() if ln.get_gid()]
        plan = [ln for ln in fig.axes[0].get_lines() if ln.get_gid()]
        assert len(coloured) == len(plan) == len(spans)
        for (kind, a, b), line, p in zip(spans, coloured, plan, strict=True):  # each stretch rises what it climbs
            z = line.get_ydata()
            assert line.get_gid() == p.get_gid() == kind
            assert z[-1] - z[0] == pytest.approx(dz[a:b + 1].sum())
            np.testing.assert_allclose(p.get_xdata(), tr["x"].to_numpy(float)[a:b + 2])
        assert 1.0 < z[-1] - z[0] < 2.5  # the flight climbs (10 stairs)
    finally:
        plt.close(fig)


def test_a_level_track_gets_no_distance_panel_l592(tracked):
    from matplotlib import pyplot as plt

    from pdrlearn.track.base import TrackResult

    result = tracked["result"]
    steps = result.steps.assign(dz_m=0.0)
    level = TrackResult(steps=steps, trajectory=result.trajectory.assign(z=0.0), info=dict(result.info))
    assert climb_spans(level) == []
    _, fig = path_figure({"track": level})
    try:
        assert all(ax.get_xlabel() != DISTANCE_PANEL_XLABEL for ax in fig.axes) and len(fig.axes) == 1
    finally:
        plt.close(fig)


def test_walked_distance_kernel_l592():
    np.testing.assert_allclose(walked_distance([0, 3, 3, np.nan], [0, 4, 4, 1]), [0, 5, 5, 5])
