"""Matplotlib figures (Agg backend): sessions with step labels."""

from __future__ import annotations

from pathlib import Path

from pdrlearn.io.session import Session

_TERRAIN_COLOURS = {"flat": "#9ecae1", "up": "#a1d99b", "down": "#fdae6b"}


def _figure(nrows: int, height: float = 2.0):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(nrows, 1, figsize=(11, height * nrows + 0.6), sharex=True, squeeze=False)
    return plt, fig, axes[:, 0]


def save_atomic(fig, path: Path) -> None:
    """Save a figure via a temporary file so an interrupted run leaves no half-written PNG."""
    path = Path(path)
    tmp = path.with_name(f".{path.name}.tmp.png")
    fig.savefig(tmp, dpi=110, bbox_inches="tight")
    tmp.replace(path)


def plot_session(session: Session, out: Path, *, start: float | None = None, end: float | None = None) -> Path:
    """One panel per sensor stream; labelled steps shaded by terrain (or alternately when unknown)."""
    names = list(session.streams)
    plt, fig, axes = _figure(len(names))
    t0 = session.t_start
    lo = t0 + (start or 0.0)
    hi = session.t_end if end is None else t0 + end
    for ax, name in zip(axes, names, strict=True):
        s = session.streams[name].slice(lo, hi + 1e-9)
        for j, col in enumerate(s.spec.columns):
            ax.plot(s.t - t0, s.values[:, j], lw=0.8, label=col)
        ax.set_ylabel(f"{name}\n[{s.unit}]", fontsize=8)
        ax.legend(loc="upper right", fontsize=7, ncol=3)
        if session.steps is not None:
            for i, row in enumerate(session.steps.itertuples()):
                if row.end_s < lo or row.start_s > hi:
                    continue
                colour = _TERRAIN_COLOURS.get(getattr(row, "terrain", None), "#dddddd" if i % 2 else "#f0f0f0")
                ax.axvspan(row.start_s - t0, row.end_s - t0, color=colour, alpha=0.35, lw=0)
    axes[-1].set_xlabel("time since session start [s]")
    if session.steps is not None and "terrain" in session.steps:
        handles = [plt.Rectangle((0, 0), 1, 1, color=c, alpha=0.5) for c in _TERRAIN_COLOURS.values()]
        fig.legend(handles, list(_TERRAIN_COLOURS), loc="upper center", ncol=3, fontsize=8)
    fig.suptitle(f"{session.name}: {len(names)} stream(s), "
                 f"{0 if session.steps is None else len(session.steps)} labelled step(s)", y=1.0)
    save_atomic(fig, Path(out))
    plt.close(fig)
    return Path(out)

