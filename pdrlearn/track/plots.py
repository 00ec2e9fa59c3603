"""Figures of tracked paths (Agg backend)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from pdrlearn.io.session import Session
from pdrlearn.plots import save_atomic
from pdrlearn.track.base import TrackResult


def plot_paths(paths: dict[str, TrackResult], out: Path, *, session: Session | None = None,
               title: str = "") -> Path:
    """Plan view (x east, y north, m) of one or more tracks, with the ground truth when the session has one.

    The ground truth is shifted so that it starts where the tracks start (its position at the first
    track's start time).
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 6))
    t0 = None
    for name, r in paths.items():
        tr = r.trajectory
        ax.plot(tr["x"], tr["y"], "-", lw=1.4, marker=".", ms=3, label=f"{name} ({r.distance_m:.1f} m)")
        t0 = float(tr["t"].iloc[0]) if t0 is None and len(tr) else t0
    if session is not None and session.trajectory is not None and len(session.trajectory) > 1:
        g = session.trajectory
        gt = g["t"].to_numpy(float)
        ref_t = gt[0] if t0 is None else t0
        x0, y0 = np.interp(ref_t, gt, g["x"].to_numpy(float)), np.interp(ref_t, gt, g["y"].to_numpy(float))
        ax.plot(g["x"] - x0, g["y"] - y0, "k--", lw=1.0, label="ground truth")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("east [m]")
    ax.set_ylabel("north [m]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(title or (session.name if session is not None else "track"))
    save_atomic(fig, Path(out))
    plt.close(fig)
    return Path(out)
