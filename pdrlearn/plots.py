"""Matplotlib figures (Agg backend): sessions with step labels."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from pdrlearn.atomic import atomic_file
from pdrlearn.errors import DataError
from pdrlearn.io.session import Session

#: PNG text chunk (key, value) that marks a figure of ``pdrlearn plot`` (:func:`plot_session`), so that
#: ``plot --force`` replaces only such a figure (decision B26, ``cli.common.file_kind``).
PLOT_MARK = ("pdrlearn", "plot")

_TERRAIN_COLOURS = {"flat": "#9ecae1", "up": "#a1d99b", "down": "#fdae6b"}


def _figure(nrows: int, height: float = 2.0):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    # constrained layout: the title and a figure legend take the room they need above the panels (a fixed
    # top margin left a blank band over 8 panels and drew the legend over the title, decision L57)
    fig, axes = plt.subplots(nrows, 1, figsize=(11, height * nrows + 0.6), sharex=True, squeeze=False,
                             layout="constrained")
    return plt, fig, axes[:, 0]


def save_atomic(fig, path: Path, metadata: dict[str, str] | None = None) -> None:
    """Save a figure via a temporary file so an interrupted run leaves no half-written PNG (``metadata``:
    extra PNG text chunks)."""
    with atomic_file(path, suffix=".png") as tmp:
        fig.savefig(tmp, dpi=110, bbox_inches="tight", metadata=metadata)


def relative_luminance(rgb) -> float:
    """WCAG 2.x relative luminance of an sRGB colour (components 0-1; alpha ignored)."""
    c = np.asarray(rgb, dtype=float)[:3]
    lin = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)  # WCAG 2.x sRGB linearisation
    return float(lin @ np.array([0.2126, 0.7152, 0.0722]))


def contrast_ratio(a, b) -> float:
    """WCAG 2.x contrast ratio (1-21) of two colours: (L1 + 0.05) / (L2 + 0.05), L1 the lighter."""
    la, lb = sorted((relative_luminance(a), relative_luminance(b)), reverse=True)
    return (la + 0.05) / (lb + 0.05)


def text_colour_on(rgb) -> str:
    """"black" or "white", whichever contrasts more with a cell of colour ``rgb`` (the numbers of a
    confusion matrix: black on the dark end of "Blues" was unreadable, decision L57)."""
    black, white = (0.0, 0.0, 0.0), (1.0, 1.0, 1.0)
    return "white" if contrast_ratio(rgb, white) > contrast_ratio(rgb, black) else "black"


def check_window(start: float | None, end: float | None, duration_s: float, where: str) -> tuple[float, float]:
    """Validate a time window (s since the session start) against a session of ``duration_s`` seconds.

    ``None`` means the session's start / end. Returns ``(start, end)``; a window that is reversed, not
    finite or entirely outside the session is a :class:`DataError` (an empty plot would hide the mistake).
    """
    lo = 0.0 if start is None else float(start)
    hi = duration_s if end is None else float(end)
    if not (np.isfinite(lo) and np.isfinite(hi)):
        raise DataError(f"{where}: --start {lo:g} / --end {hi:g} must be finite seconds")
    if lo >= duration_s or hi <= 0:
        raise DataError(f"{where}: --start {lo:g} s .. --end {hi:g} s is outside the session "
                        f"(0 to {duration_s:.1f} s); pick a window inside it")
    if hi <= lo:
        raise DataError(f"{where}: --end {hi:g} s is not after --start {lo:g} s; swap or fix them")
    return lo, hi


def plot_session(session: Session, out: Path, *, start: float | None = None, end: float | None = None) -> Path:
    """One panel per sensor stream; labelled steps shaded by terrain (or alternately when unknown)."""
    plt, fig = session_figure(session, start=start, end=end)
    save_atomic(fig, Path(out), metadata=dict([PLOT_MARK]))
    plt.close(fig)
    return Path(out)


def session_figure(session: Session, *, start: float | None = None, end: float | None = None):
    """The figure of :func:`plot_session` (not saved): ``(pyplot, figure)``."""
    names = list(session.streams)
    t0 = session.t_start
    start, end = check_window(start, end, session.t_end - t0, session.name)
    lo, hi = t0 + start, t0 + end
    plt, fig, axes = _figure(len(names))
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
        fig.legend(handles, list(_TERRAIN_COLOURS), loc="outside lower center", ncol=3, fontsize=8,
                   title="labelled steps", title_fontsize=8)
    fig.suptitle(f"{session.name}: {len(names)} stream(s), "
                 f"{0 if session.steps is None else len(session.steps)} labelled step(s)")
    return plt, fig

