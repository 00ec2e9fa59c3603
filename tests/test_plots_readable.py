"""New-user trial (session 14): figures that can be read.

- L57: `pdrlearn plot` drew the flat/up/down legend over the title, and an 8-stream session's figure had a
  blank band (~1.9 in) between the title and the first panel; confusion matrices printed black numbers on
  navy cells.
- L55: path.png of a multi-floor walk had no altitude: the storeys overlapped in the plan view; its axes said
  east / north for a track whose heading is relative to its start.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.plots import contrast_ratio, relative_luminance, session_figure, text_colour_on
from pdrlearn.track.base import TrackResult
from pdrlearn.track.plots import ALTITUDE_PANEL_M, path_figure


@pytest.fixture(scope="module")
def sim_a():
    from pdrlearn.sim import simulate

    return simulate("A", user_seed=1, speed="normal")  # 8 streams, terrain labels, a waist magnetometer


def _boxes(fig):
    fig.canvas.draw()
    r = fig.canvas.get_renderer()
    return r, fig.dpi


def test_session_figure_title_legend_and_panels_do_not_overlap_or_gap(sim_a):
    assert len(sim_a.streams) == 8 and "terrain" in sim_a.steps
    plt, fig = session_figure(sim_a)
    try:
        r, dpi = _boxes(fig)
        title = fig._suptitle.get_window_extent(r)
        (legend,) = fig.legends
        leg = legend.get_window_extent(r)
        top = fig.axes[0].get_tightbbox(r)
        assert not title.overlaps(leg), (title, leg)
        assert not top.overlaps(title) and not top.overlaps(leg)
        # no blank band: the first panel (with its tick labels) starts within 0.4 in below the title
        assert title.y0 - top.y1 < 0.4 * dpi, (title.y0 - top.y1) / dpi
        for ax in fig.axes:  # the legend hides no panel
            assert not ax.get_window_extent(r).overlaps(leg)
    finally:
        plt.close(fig)


def test_wcag_luminance_and_contrast_hand_values():
    assert relative_luminance((1, 1, 1)) == pytest.approx(1.0)
    assert relative_luminance((0, 0, 0)) == 0.0
    assert contrast_ratio((1, 1, 1), (0, 0, 0)) == pytest.approx(21.0)
    assert relative_luminance((0.5, 0.5, 0.5)) == pytest.approx(0.2140, abs=1e-4)  # ((0.555/1.055)^2.4)
    assert text_colour_on((0.031, 0.188, 0.420)) == "white"  # "Blues" at its dark end (#08306b)
    assert text_colour_on((0.969, 0.984, 1.0)) == "black"  # its light end (#f7fbff)


def test_confusion_numbers_contrast_with_their_cells(monkeypatch, tmp_path):
    """Every number of a confusion matrix reaches WCAG's 4.5:1 against its cell (black on the navy cells was
    about 2:1 and failed)."""
    import matplotlib.axes
    import matplotlib.colors

    from pdrlearn.classify.evaluation import plot_confusions

    cm = [[40, 3, 0], [5, 22, 1], [0, 9, 14]]
    res = {"classes": ["flat", "up", "down"], "n_steps": 94,
           "methods": {"svm": {"units": {"foot": {"confusion": cm, "accuracy": 0.8}}}}}
    cells = []
    orig_text, orig_imshow = matplotlib.axes.Axes.text, matplotlib.axes.Axes.imshow
    images = []

    def imshow(self, *a, **kw):
        images.append(orig_imshow(self, *a, **kw))
        return images[-1]

    def text(self, x, y, s, *a, **kw):
        cells.append((int(y), int(x), kw.get("color")))
        return orig_text(self, x, y, s, *a, **kw)

    monkeypatch.setattr(matplotlib.axes.Axes, "imshow", imshow)
    monkeypatch.setattr(matplotlib.axes.Axes, "text", text)
    plot_confusions("terrain", res, tmp_path / "c.png")
    assert (tmp_path / "c.png").is_file() and len(cells) == 9
    im = images[0]
    for i, j, colour in cells:
        cell = im.cmap(im.norm(cm[i][j]))
        fg = matplotlib.colors.to_rgb(colour or "black")
        assert contrast_ratio(fg, cell) >= 4.5, (i, j, colour, cell)


def _track(z, info, t0=0.0):
    n = len(z)
    tr = pd.DataFrame({"t": t0 + np.arange(n, dtype=float), "x": np.arange(n) * 0.7, "y": np.zeros(n),
                       "z": np.asarray(z, float)})
    return TrackResult(steps=pd.DataFrame(), trajectory=tr, info=info)


def test_path_figure_gets_an_altitude_panel_when_the_track_climbs(sim_a):
    from matplotlib import pyplot as plt

    climbing = _track(np.repeat([0.0, 3.0, 6.0], 6), {"pipeline": "runtime"})
    plt_, fig = path_figure({"run": climbing})
    try:
        assert len(fig.axes) == 2
        assert fig.axes[1].get_ylabel() == "height z [m]" and fig.axes[1].get_xlabel() == "time [s]"
        (line,) = fig.axes[1].get_lines()
        np.testing.assert_array_equal(line.get_ydata(), climbing.trajectory["z"])
    finally:
        plt.close(fig)
    # level (less than ALTITUDE_PANEL_M of height change): the plan view alone
    _, fig = path_figure({"run": _track(np.full(18, 0.9 * ALTITUDE_PANEL_M) * np.r_[np.zeros(9), np.ones(9)],
                                        {"pipeline": "runtime"})})
    assert len(fig.axes) == 1
    plt.close(fig)
    # the ground truth's height counts too (a level track on a walk whose truth climbs 3 m), drawn from the
    # track's start height
    s = sim_a.copy()
    g = s.trajectory
    s.trajectory = g.assign(z=g["z"] + np.linspace(0.0, 3.0, len(g)))
    t0 = float(g["t"].iloc[5])
    _, fig = path_figure({"run": _track(np.full(10, 12.5), {"pipeline": "runtime"}, t0=t0)}, session=s)
    try:
        assert len(fig.axes) == 2
        truth = [ln for ln in fig.axes[1].get_lines() if ln.get_label().startswith("ground truth")][0]
        t, z = truth.get_xdata(), truth.get_ydata()
        assert np.interp(t0, t, z) == pytest.approx(12.5)
    finally:
        plt.close(fig)


@pytest.mark.parametrize(("info", "absolute"), [
    ({"pipeline": "runtime"}, False),  # the runtime: gyroscope headings from 0 at the start
    ({"pipeline": "plasys", "heading_source": "foot"}, False),  # the foot's integrated yaw
    ({"pipeline": "plasys", "heading_source": "fused"}, True),  # aligned to the waist compass: north-referenced
])
def test_plan_axes_name_the_frame(sim_a, info, absolute):
    from matplotlib import pyplot as plt

    _, fig = path_figure({"t": _track(np.zeros(8), info)}, session=sim_a)
    try:
        ax = fig.axes[0]
        if absolute:
            assert (ax.get_xlabel(), ax.get_ylabel()) == ("east [m]", "north [m]")
        else:
            assert ax.get_xlabel().startswith("x [m]") and "not east" in ax.get_xlabel()
            assert ax.get_ylabel().startswith("y [m]") and "not north" in ax.get_ylabel()
    finally:
        plt.close(fig)
