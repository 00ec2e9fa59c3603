"""Matplotlib figures: sessions with step labels, and :func:`new_figure`, how every pdrlearn figure is made."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from pdrlearn.atomic import atomic_file
from pdrlearn.errors import DataError
from pdrlearn.io.session import Session
from pdrlearn.mplconfig import ensure_config_dir

#: PNG text chunk (key, value) that marks a figure of ``pdrlearn plot`` (:func:`plot_session`), so that
#: ``plot --force`` replaces only such a figure (decision B26, ``cli.common.file_kind``).
PLOT_MARK = ("pdrlearn", "plot")
#: The same mark in a PDF or SVG figure (decision L70): its "Creator" metadata (matplotlib's PDF and SVG
#: backends take only their standard keys; PNG takes any text chunk).
PLOT_CREATOR = "pdrlearn plot"
#: The figure formats every figure writer takes, by file suffix (decision L70): matplotlib's Agg, PDF and SVG
#: backends, chosen by ``savefig`` from the suffix.
FIGURE_SUFFIXES = (".png", ".pdf", ".svg")
#: Resolution (dots per inch) of every figure written (``--dpi`` overrides it, decision L70); a vector
#: figure's (PDF, SVG) lines and text do not depend on it.
DEFAULT_DPI = 110
#: ``--dpi`` bounds (the CLI's ``min``/``max``): below 20 the text is unreadable; 600 dpi is print resolution,
#: and ``plot``'s 11 x 16.6 in figure of 8 streams is then 11 * 16.6 * 600^2 * 4 bytes = 263 MB of RGBA.
DPI_RANGE = (20, 600)

_TERRAIN_COLOURS = {"flat": "#9ecae1", "up": "#a1d99b", "down": "#fdae6b"}
#: decision L655: ``plot --shade travel``'s colours, one per steps.csv ``travel`` label (L412); forward as flat's
_TRAVEL_COLOURS = {"forward": "#9ecae1", "backward": "#fb6a4a", "left": "#74c476", "right": "#fdd0a2",
                   "side": "#c7e9c0", "turn": "#bcbddc"}
#: decision L655: the steps columns ``plot`` shades by (``--shade``) and their colours; terrain the default
SHADE_COLOURS = {"terrain": _TERRAIN_COLOURS, "travel": _TRAVEL_COLOURS}
#: decision W296: a track's transfers.csv rows drawn on ``plot``'s panels, by kind (the lying kinds, W245, as one)
_TRANSFER_COLOURS = {"sit-to-stand": "#2ca02c", "stand-to-sit": "#d62728", "lying": "#9467bd"}
#: decision E99: a ``plot`` window longer than this (s) is drawn for display: each stream's min/max envelope over
#: :data:`ENVELOPE_COLUMNS` time columns instead of every sample, and runs of steps of one colour (each starting
#: within :data:`SPAN_JOIN_S` of the last one's end: a walk's strides follow each other) shaded as one span; and a
#: one-line note suggests ``--start/--end``. At 10 min a 20 Hz stream has 12 000 samples and a walk ~500 strides,
#: more than the figure's ~1200 pixel columns: the strides' shading merges into solid bands either way
LONG_WINDOW_S = 600.0
#: decision E99: the envelope's time columns (plot's figure is 11 in wide: 1210 px at the default 110 dpi)
ENVELOPE_COLUMNS = 2000
#: decision E99: the largest pause (s) between two steps shaded as one span in a long window
SPAN_JOIN_S = 1.0


def new_figure(nrows: int = 1, ncols: int = 1, *, figsize=None, layout=None, **subplots):
    """Decision E88: ``(figure, axes)`` of a new figure drawn with matplotlib's object API (a
    ``matplotlib.figure.Figure`` on its own Agg canvas), as ``pyplot.subplots`` gives them (``subplots``: its
    ``sharex``, ``squeeze``, ``height_ratios`` ...), without ``matplotlib.use`` or pyplot: the user's backend (a
    notebook's inline one) is left as it was, and the figure is in no pyplot list (nothing to close)."""
    ensure_config_dir()  # decision B226: no matplotlib noise when the home folder cannot be written
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=figsize, layout=layout)
    FigureCanvasAgg(fig)
    return fig, fig.subplots(nrows, ncols, **subplots)


def _figure(nrows: int, height: float = 2.0):
    ensure_config_dir()  # decision B226
    import matplotlib.pyplot as plt

    # constrained layout: the title and a figure legend take the room they need above the panels (a fixed
    # top margin left a blank band over 8 panels and drew the legend over the title, decision L57)
    fig, axes = new_figure(nrows, 1, figsize=(11, height * nrows + 0.6), sharex=True, squeeze=False,
                           layout="constrained")
    return plt, fig, axes[:, 0]


def save_atomic(fig, path: Path, metadata: dict[str, str] | None = None, *, dpi: float | None = None) -> None:
    """Save a figure via a temporary file so an interrupted run leaves no half-written figure. The format
    follows the suffix of ``path`` (:data:`FIGURE_SUFFIXES`; anything else is PNG, as before); ``metadata``:
    extra PNG text chunks (a PDF or SVG gets "Creator" :data:`PLOT_CREATOR` instead when ``metadata`` is
    :data:`PLOT_MARK`); ``dpi``: default :data:`DEFAULT_DPI` (decision L70). The figure is closed afterwards, saved
    or not (decision B151)."""
    path = Path(path)
    fmt = path.suffix.lower().lstrip(".")
    if "." + fmt not in FIGURE_SUFFIXES:
        fmt = "png"
    if fmt != "png" and metadata:  # PDF/SVG take only their standard keys (decision L70)
        metadata = {"Creator": PLOT_CREATOR} if metadata == dict([PLOT_MARK]) else None
    try:
        with atomic_file(path, suffix="." + fmt) as tmp:
            fig.savefig(tmp, format=fmt, dpi=DEFAULT_DPI if dpi is None else float(dpi), bbox_inches="tight",
                        metadata=metadata)
    finally:  # decision B151: closed even when saving fails (a full disk leaked one figure per session)
        if getattr(fig.canvas, "manager", None) is not None:  # a pyplot figure (E88: ours are in no pyplot list)
            import matplotlib.pyplot as plt

            plt.close(fig)


def is_plot_figure(path: Path) -> bool:
    """True when ``path`` is a figure of ``pdrlearn plot`` (:data:`PLOT_MARK` in a PNG, "Creator"
    :data:`PLOT_CREATOR` in a PDF or SVG; decisions B26, L70)."""
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix == ".png":
        from pdrlearn.cli.common import png_text

        return png_text(path).get(PLOT_MARK[0]) == PLOT_MARK[1]
    if suffix == ".pdf":
        data = path.read_bytes()
        return data[:5] == b"%PDF-" and f"/Creator ({PLOT_CREATOR})".encode() in data
    if suffix == ".svg":
        with open(path, "rb") as f:
            head = f.read(4096)  # matplotlib writes the metadata before the drawing
        return b"<svg" in head and f"<dc:title>{PLOT_CREATOR}</dc:title>".encode() in head
    return False


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
    reversed_ = f"{where}: --end {hi:g} s is not after --start {lo:g} s; swap or fix them"
    if start is not None and end is not None and hi <= lo:  # decision B210: both given, reversed is said first
        raise DataError(reversed_)  # (start 100, end 50 had been "outside the session")
    if lo >= duration_s or hi <= 0:
        raise DataError(f"{where}: --start {lo:g} s .. --end {hi:g} s is outside the session "
                        f"(0 to {duration_s:.1f} s); pick a window inside it")
    if hi <= lo:
        raise DataError(reversed_)
    return lo, hi


def plot_session(session: Session, out: Path, *, start: float | None = None, end: float | None = None,
                 steps=None, steps_what: str | None = None, dpi: float | None = None, transfers=None,
                 shade: str = "terrain") -> Path:
    """One panel per sensor stream; steps shaded by terrain (``shade``, decision L655: or by travel; alternately
    when unknown): the labelled ones, or ``steps`` (arguments of :func:`session_figure`; ``transfers`` too). The
    format follows the suffix of ``out`` (PNG, PDF or SVG; ``dpi`` default :data:`DEFAULT_DPI`, decision L70)."""
    _, fig = session_figure(session, start=start, end=end, steps=steps, steps_what=steps_what, transfers=transfers,
                            shade=shade)
    save_atomic(fig, Path(out), metadata=dict([PLOT_MARK]), dpi=dpi)
    return Path(out)


def envelope(t: np.ndarray, y: np.ndarray, n_cols: int = ENVELOPE_COLUMNS) -> tuple[np.ndarray, np.ndarray]:
    """Decision E99: the min/max envelope of ``y`` (samples at sorted times ``t``) over ``n_cols`` equal time
    columns: per non-empty column its centre twice, with the column's minimum then its maximum (NaN ignored;
    a column of NaN only gives NaN). Every peak and trough of the signal stays on the figure."""
    t, y = np.asarray(t, float), np.asarray(y, float)
    if len(t) <= 2 * n_cols or not (t[-1] > t[0]):
        return t, y
    col = np.minimum(((t - t[0]) / (t[-1] - t[0]) * n_cols).astype(np.int64), n_cols - 1)
    starts = np.flatnonzero(np.diff(np.concatenate([[-1], col])))
    with np.errstate(invalid="ignore"):
        lo, hi = np.fmin.reduceat(y, starts), np.fmax.reduceat(y, starts)
    centre = t[0] + (col[starts] + 0.5) * (t[-1] - t[0]) / n_cols
    return np.repeat(centre, 2), np.column_stack([lo, hi]).ravel()


def joined_spans(starts: np.ndarray, ends: np.ndarray, keys: list) -> list[tuple[float, float, object]]:
    """Decision E99: ``(start, end, key)`` of each run of consecutive steps with the same ``key`` (terrain)
    where each starts within :data:`SPAN_JOIN_S` of the previous one's end."""
    out: list[list] = []
    for a, b, k in zip(starts, ends, keys, strict=True):
        if out and out[-1][2] == k and a - out[-1][1] <= SPAN_JOIN_S:
            out[-1][1] = max(out[-1][1], b)
        else:
            out.append([a, b, k])
    return [tuple(x) for x in out]


def steps_in_window(steps, lo: float, hi: float):
    """The rows of a steps table (``start_s``, ``end_s`` on the session's clock) that overlap ``[lo, hi]``
    (s), and how many of them the window cuts (start before ``lo`` or end after ``hi``)."""
    if steps is None or not len(steps):
        return steps, 0
    s, e = steps["start_s"].to_numpy(float), steps["end_s"].to_numpy(float)
    keep = (e >= lo) & (s <= hi)
    cut = int((keep & ((s < lo) | (e > hi))).sum())
    return steps[keep], cut


def session_figure(session: Session, *, start: float | None = None, end: float | None = None, steps=None,
                   steps_what: str | None = None, transfers=None, shade: str = "terrain"):
    """The figure of :func:`plot_session` (not saved): ``(pyplot, figure)``, a figure of :func:`new_figure`
    (decision E88: the backend left alone; ``pyplot.close`` of it is a no-op, the first item is kept for callers
    that close it).

    ``steps``: a table with ``start_s``, ``end_s`` (s, the session's clock) and optionally ``terrain`` to
    shade instead of the session's labelled steps, ``steps_what`` what they are ("detected stride(s) (accel)");
    default the labelled steps. The time axis is the window ``[start, end]`` exactly (default the session),
    a step it cuts is shaded inside it only, and the title counts the steps shaded (decision L70).

    ``transfers`` (decision W296): a track's transfers.csv (``kind``, ``start_s``, ``end_s``) drawn as hatched spans
    over the steps, coloured by kind, with a legend; the title counts those in the window.

    ``shade`` (decision L655): the steps column the shading follows, a key of :data:`SHADE_COLOURS` - ``terrain``
    (flat / up / down) or ``travel`` (a foot track's forward / backward / left / right / side / turn, L412).
    """
    if shade not in SHADE_COLOURS:
        raise ValueError(f"session_figure: shade must be one of {', '.join(SHADE_COLOURS)}, not {shade!r}")
    palette = SHADE_COLOURS[shade]
    names = list(session.streams)
    t0 = session.t_start
    start, end = check_window(start, end, session.t_end - t0, session.name)
    lo, hi = t0 + start, t0 + end
    if steps is None:
        steps, steps_what = session.steps, "labelled step(s)"
    steps_what = steps_what or "step(s)"
    shown, cut = steps_in_window(steps, lo, hi)
    ensure_config_dir()  # decision E261 (B226): before this function's first matplotlib import, not only new_figure's
    from matplotlib.patches import Rectangle

    long = end - start > LONG_WINDOW_S  # decision E99: drawn for display, with a note
    if long:
        import logging

        logging.getLogger("pdrlearn.plots").warning(
            "%s: the window is %.0f s long (over %.0f s): each stream is drawn as its min/max envelope and the "
            "steps as joined spans, so single steps cannot be told apart; pick a stretch with --start/--end (e.g. "
            "--start %.0f --end %.0f) to see them (decision E99)", session.name, end - start, LONG_WINDOW_S, start,
            start + 120.0)
    spans = []
    if shown is not None:
        for i, row in enumerate(shown.itertuples()):
            value = getattr(row, shade, None)  # decision L655: terrain or travel
            colour = palette.get(value if isinstance(value, str) else None,
                                 "#dddddd" if (i % 2 and not long) else "#f0f0f0")
            # decision L70: clipped to the window (a stride it cuts widened the axis before)
            spans.append((max(row.start_s, lo) - t0, min(row.end_s, hi) - t0, colour))
        if long:
            spans = joined_spans(*(np.array([x[j] for x in spans]) for j in (0, 1)), [x[2] for x in spans])
    moves, kinds = transfer_spans(transfers, lo, hi, t0)
    plt, fig, axes = _figure(len(names))
    for ax, name in zip(axes, names, strict=True):
        s = session.streams[name].slice(lo, hi + 1e-9)
        for j, col in enumerate(s.spec.columns):
            ax.plot(*(envelope(s.t - t0, s.values[:, j]) if long else (s.t - t0, s.values[:, j])), lw=0.8,
                    label=col)
        ax.set_ylabel(f"{name}\n[{s.unit}]", fontsize=8)
        ax.legend(loc="upper right", fontsize=7, ncol=3)
        for a, b, colour in spans:
            ax.axvspan(a, b, color=colour, alpha=0.35, lw=0)
        for a, b, colour in moves:  # decision W296: the transfers over the steps
            ax.axvspan(a, b, facecolor=colour, edgecolor=colour, alpha=0.3, hatch="//", lw=1.0)
    axes[-1].set_xlim(start, end)  # decision L70: the window exactly (shared by every panel)
    axes[-1].set_xlabel("time since session start [s]")
    if shown is not None and shade in shown and shown[shade].isin(list(palette)).any():
        handles = [Rectangle((0, 0), 1, 1, color=c, alpha=0.5) for c in palette.values()]
        fig.legend(handles, list(palette), loc="outside lower center", ncol=len(palette), fontsize=8,
                   title=steps_what.replace("(s)", "s") + ("" if shade == "terrain" else f" by {shade}"),
                   title_fontsize=8)
    if kinds:  # decision W296
        handles = [Rectangle((0, 0), 1, 1, facecolor=_TRANSFER_COLOURS[k], alpha=0.4, hatch="//") for k in kinds]
        fig.legend(handles, kinds, loc="outside upper left", ncol=len(kinds), fontsize=8,
                   title="transfers (transfers.csv)", title_fontsize=8)
    whole = start <= 0 and end >= session.t_end - t0
    n = 0 if shown is None else len(shown)
    window = "" if whole else f", {start:g}-{end:g} s of {session.t_end - t0:.1f} s"
    cuts = f" ({cut} cut by the window)" if cut else ""
    moved = f", {len(moves)} transfer(s)" if transfers is not None else ""
    fig.suptitle(f"{session.name}: {len(names)} stream(s){window}, {n} {steps_what}"
                 f"{' in the window' if not whole else ''}{cuts}{moved}")
    return plt, fig


def transfer_spans(transfers, lo: float, hi: float, t0: float) -> tuple[list[tuple[float, float, str]], list[str]]:
    """Decision W296: ``(spans, kinds)`` of a transfers.csv table's rows that overlap ``[lo, hi]`` (s, the session's
    clock): each ``(start, end, colour)`` since ``t0`` clipped to the window, and the kinds drawn (legend order)."""
    if transfers is None or not len(transfers):
        return [], []
    shown, _ = steps_in_window(transfers, lo, hi)
    spans, kinds = [], []
    for row in shown.itertuples():
        kind = row.kind if row.kind in ("sit-to-stand", "stand-to-sit") else "lying"
        spans.append((max(row.start_s, lo) - t0, min(row.end_s, hi) - t0, _TRANSFER_COLOURS[kind]))
        kinds.append(kind)
    return spans, [k for k in _TRANSFER_COLOURS if k in kinds]
