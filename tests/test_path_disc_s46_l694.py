"""Decision L694 (session 46, FK, trial T2 finding F9): path.png's 2-sigma circle about the end never sets the plan
view's axes; the view covers the paths. A circle reaching beyond them is clipped and drawn as its outline only (a
7.5 m dance figure was a small squiggle inside a shaded 4.2 m disc); one inside the paths stays a shaded disc."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest


def _figure(radius_m: float):
    """A 3 m x 1.5 m box figure ending inside it at (1.5, 0.75), its final 2-sigma radius ``radius_m``."""
    from pdrlearn.track.base import TrackResult
    from pdrlearn.track.plots import path_figure

    x = np.array([0.0, 3.0, 3.0, 0.0, 0.0, 1.5])
    y = np.array([0.0, 0.0, 1.5, 1.5, 0.0, 0.75])
    traj = pd.DataFrame({"t": np.arange(len(x), dtype=float), "x": x, "y": y, "z": 0.0, "heading_rad": 0.0,
                         "pos_sigma_m": np.linspace(0.0, radius_m / 2.0, len(x))})
    return path_figure({"box": TrackResult(steps=pd.DataFrame(), trajectory=traj, info={})})


@pytest.mark.parametrize("radius_m, inside", [(4.2, False), (0.5, True)])
def test_the_circle_does_not_set_the_view_l694(radius_m, inside):
    from matplotlib.patches import Circle

    plt, fig = _figure(radius_m)
    try:
        ax = fig.axes[0]
        fig.canvas.draw()
        (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
        assert x0 > 1.5 - radius_m and x1 < 1.5 + radius_m or inside  # main: the 8.4 m disc set the view
        assert max(x1 - x0, y1 - y0) < 4.0  # the 3 m x 1.5 m figure fills the view (equal aspect)
        circles = [a for a in ax.get_children() if isinstance(a, Circle)]
        assert len(circles) == 1 and circles[0].get_fill() == inside
        label = [lb for lb in ax.get_legend_handles_labels()[1] if "2-sigma radius" in lb]
        assert len(label) == 1 and ("L694" in label[0]) == (not inside)
    finally:
        plt.close(fig)
