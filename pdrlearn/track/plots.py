"""Figures of tracked paths (drawn without touching the matplotlib backend, decision E88)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from pdrlearn.io.session import Session
from pdrlearn.plots import save_atomic
from pdrlearn.track.base import TrackResult

#: decision L55: path.png gets an altitude-vs-time panel when a drawn path's height spans at least this (m):
#: the threshold of the track evaluation's altitude error (``altitude_error_pct``, evaluate.py)
ALTITUDE_PANEL_M = 0.5
#: decision L592: the colours of a track's ramp strides (ramps.csv, L301) and stair-flight strides (stairs.csv,
#: L432) in path.png's plan view and its elevation-vs-distance panel
CLIMB_COLOURS = {"ramp": "tab:orange", "stairs": "tab:purple"}
#: decision L592: their line widths: a ramp's is drawn narrower over a flight on the same strides (a stride can be in
#: both tables: stairs.csv lists a steep ramp's 0.10 m strides as a flight too)
CLIMB_WIDTHS = {"ramp": 2.0, "stairs": 4.0}
#: decision L592: the x label that names the elevation-vs-distance panel
DISTANCE_PANEL_XLABEL = "distance along the path [m]"
#: decision L655: path.png's markers at the end of a foot track's backward and side strides (steps.csv travel,
#: L412), coloured as ``plot --shade travel`` shades them: (travel labels, marker, colour, legend label)
TRAVEL_MARKERS = ((("backward",), "v", "#de2d26", "backward strides (steps.csv travel)"),
                  (("left", "right", "side"), "D", "#31a354", "side strides (steps.csv travel left / right / side)"))


def plot_paths(paths: dict[str, TrackResult], out: Path, *, session: Session | None = None,
               title: str = "", dpi: float | None = None) -> Path:
    """Plan view of one or more tracks, with the ground truth when the session has one; below it the height
    ``z`` against time when a track or the ground truth changes height by :data:`ALTITUDE_PANEL_M` or more
    (the storeys of a multi-floor walk overlap in the plan view, decision L55). ``dpi``: as
    :func:`pdrlearn.plots.save_atomic` (default 110, ``--dpi`` of track and run, decision L70).

    The ground truth is shifted so that it starts where the tracks start (its position at the first
    track's start time onto the first track's first point: the origin, or for ``track --window`` the
    position at the window's start). When the first track's heading is relative to its start (0 = east, unless
    ``initial_heading`` says otherwise; :func:`heading_is_absolute`), the ground truth is also rotated to set
    off in that track's direction (:func:`initial_bearing`); the legend says so, and the axes are ``x`` (heading
    0 at the start) / ``y`` instead of east / north (L55). A track with ``pos_sigma_m`` gets a shaded circle of
    twice its last value about its end (decision L128); the view covers the paths, never the circle (decision L694,
    L175's rule for every circle): a circle reaching beyond the paths is clipped, drawn as its outline, and its legend
    says so. Decision L592: a track's
    ramp and stair strides are coloured (:data:`CLIMB_COLOURS`, :func:`climb_spans`) and, when a track has any, a
    last panel draws its height against the distance walked along it.
    """
    _, fig = path_figure(paths, session=session, title=title)
    save_atomic(fig, Path(out), dpi=dpi)
    return Path(out)


def path_figure(paths: dict[str, TrackResult], *, session: Session | None = None, title: str = ""):
    """The figure of :func:`plot_paths` (not saved): ``(pyplot, figure)``; its axes: the plan view, then the
    altitude panel when there is one. The figure is a :func:`pdrlearn.plots.new_figure` (decision E88: the
    matplotlib backend, e.g. a notebook's, is left as it was; the figure shows itself in a notebook cell)."""
    from pdrlearn.mplconfig import ensure_config_dir

    ensure_config_dir()  # decision B226: no matplotlib noise when the home folder cannot be written
    import matplotlib.pyplot as plt
    from matplotlib.patches import Circle

    from pdrlearn.plots import new_figure

    t0, first, first_info = None, None, {}
    lines = []  # (label, t, x, y, z, style)
    for name, r in paths.items():
        tr = r.trajectory
        lines.append((f"{name} ({r.distance_m:.1f} m)", *(tr[c].to_numpy(float) for c in ("t", "x", "y", "z")),
                      {"ls": "-", "lw": 1.4, "marker": ".", "ms": 3}))
        t0 = float(tr["t"].iloc[0]) if t0 is None and len(tr) else t0
        if first is None and len(tr):
            first, first_info = tr, r.info or {}
    absolute = first is None or session is None or heading_is_absolute(first_info, session)
    if session is not None and session.trajectory is not None and len(session.trajectory) > 1:
        g = session.trajectory
        gt = g["t"].to_numpy(float)
        ref_t = gt[0] if t0 is None else t0
        x0, y0, z0 = (np.interp(ref_t, gt, g[c].to_numpy(float)) for c in ("x", "y", "z"))
        gx, gy = g["x"].to_numpy(float) - x0, g["y"].to_numpy(float) - y0
        gz = g["z"].to_numpy(float) - z0 + (float(first["z"].iloc[0]) if first is not None else 0.0)
        label = "ground truth"
        if first is not None and not absolute:
            rot = rotated_to_track(gx, gy, gt >= ref_t, first["x"].to_numpy(float), first["y"].to_numpy(float))
            if rot is not None:
                gx, gy = rot
                label = "ground truth (rotated to the track's initial direction: relative heading)"
        if first is not None:  # L105: a windowed track starts where the walk was then, not at the origin
            gx, gy = gx + float(first["x"].iloc[0]), gy + float(first["y"].iloc[0])
        lines.append((label, gt, gx, gy, gz, {"ls": "--", "lw": 1.0, "color": "k"}))
    climbs = any(len(z) and np.nanmax(z) - np.nanmin(z) >= ALTITUDE_PANEL_M for *_, z, _ in lines)
    spans = {name: climb_spans(r) for name, r in paths.items()}  # decision L592
    ratios = (3, *((1.1,) if climbs else ()), *((1.1,) if any(spans.values()) else ()))
    fig, axes = new_figure(len(ratios), 1, figsize=(7, 6 + 2.6 * (len(ratios) - 1)), layout="constrained",
                           **({"height_ratios": ratios} if len(ratios) > 1 else {}))
    axes = list(np.atleast_1d(axes))
    ax, az = axes[0], axes[1] if climbs else None
    rides = {f"{name} ({r.distance_m:.1f} m)": ride_rows(r) for name, r in paths.items()}  # decision L623
    for label, _, x, y, _, style in lines:
        ax.plot(*broken_at(x, y, rides.get(label)), label=label, **style)
    draw_rides(ax, lines, rides)
    draw_travel(ax, paths)  # decision L655
    if any(spans.values()):
        draw_climbs(ax, axes[-1], paths, spans)
    box = path_box([(x, y) for _, _, x, y, _, _ in lines])
    for r in paths.values():  # decision L128: the 2-sigma circle of the position uncertainty at the track's end
        tr = r.trajectory
        if "pos_sigma_m" in tr and len(tr) and float(tr["pos_sigma_m"].iloc[-1]) > 0:
            radius = 2.0 * float(tr["pos_sigma_m"].iloc[-1])
            end = (float(tr["x"].iloc[-1]), float(tr["y"].iloc[-1]))
            # decisions L175 / L694: the circle never widens the view (add_artist does not update the data
            # limits), which covers the paths: a small figure is not a squiggle inside a 4 m disc; a circle reaching
            # beyond the paths is clipped and drawn as its outline only (no wash over the whole figure)
            inside = box is None or (box[0] <= end[0] - radius and end[0] + radius <= box[1]
                                     and box[2] <= end[1] - radius and end[1] + radius <= box[3])
            look = {"alpha": 0.15} if inside else {"fill": False, "ls": "--", "lw": 1.0, "alpha": 0.6}
            ax.add_artist(Circle(end, radius, **look, label=(
                f"end position, 2-sigma radius {radius:.1f} m (model, not a guarantee"
                + (")" if inside else "; reaches beyond the paths: outline, clipped, L694)"))))
    ax.set_aspect("equal", adjustable="datalim")
    if absolute:
        ax.set_xlabel("east [m]")
        ax.set_ylabel("north [m]")
    else:  # a heading relative to the start: the axes are not east / north (decision L55)
        ax.set_xlabel("x [m] (heading 0 at the start, not east: relative heading)")
        ax.set_ylabel("y [m] (90 deg left of x, not north)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(title or (session.name if session is not None else "track"))
    if climbs:
        for label, t, _, _, z, style in lines:
            az.plot(t, z, label=label, **{**style, "ms": 2})
        az.set_xlabel("time [s]")
        az.set_ylabel("height z [m]")
        az.grid(alpha=0.3)
        az.set_title("height over time", fontsize=9)
    return plt, fig


def ride_rows(result: TrackResult) -> np.ndarray:
    """Decision L623: the trajectory rows whose line from the row before crosses a ride of ``info["rides"]``
    (:func:`pdrlearn.track.rides.trajectory_rides`: not walked); none without rides."""
    from pdrlearn.track.rides import trajectory_rides

    tr = result.trajectory
    if not (result.info or {}).get("rides") or not len(tr):
        return np.zeros(0, dtype=int)
    return np.flatnonzero(trajectory_rides(tr, result.info["rides"]).notna().to_numpy())


def broken_at(x: np.ndarray, y: np.ndarray, rows) -> tuple[np.ndarray, np.ndarray]:
    """Decision L623: ``x``, ``y`` with a NaN put before each of ``rows`` (a line plot draws no line into them)."""
    if rows is None or not len(rows):
        return x, y
    return np.insert(np.asarray(x, float), rows, np.nan), np.insert(np.asarray(y, float), rows, np.nan)


def draw_rides(ax, lines, rides: dict) -> None:
    """Decision L623: each ride's line (the row before to the row after, ``rides``: per track label the rows of
    :func:`ride_rows`) thin, grey and dotted, one legend entry: not a walked path."""
    label = "ride (rides.csv): not walked; its travel is not in the track (L623)"
    for name, _, x, y, _, _ in lines:
        for i in rides.get(name, ()):
            ax.plot(x[i - 1:i + 1], y[i - 1:i + 1], ls=":", lw=1.0, color="0.5", label=label)
            label = None


def draw_travel(ax, paths: dict[str, TrackResult]) -> None:
    """Decision L655: a marker (:data:`TRAVEL_MARKERS`) at the end of each backward and each side stride of every
    drawn foot track (its steps' travel labels, L412's :func:`pdrlearn.track.travel.travel_labels`), at the
    trajectory's position at the stride's ``end_s``; one legend entry per kind drawn. Nothing for a lower-back
    track or a walk of forward strides only."""
    from pdrlearn.track.travel import travel_labels

    labelled = set()
    for r in paths.values():
        st, tr = r.steps, r.trajectory
        if st is None or not len(st) or "end_s" not in st or tr is None or len(tr) < 2:
            continue
        travel = travel_labels(st)  # L412, idempotent: the offline tracker's left / right kept
        if travel is None:
            continue
        t = tr["t"].to_numpy(float)
        for kinds, marker, colour, label in TRAVEL_MARKERS:
            rows = np.isin(travel, kinds)
            if not rows.any():
                continue
            end = st["end_s"].to_numpy(float)[rows]
            x, y = (np.interp(end, t, tr[c].to_numpy(float)) for c in ("x", "y"))
            ax.plot(x, y, ls="none", marker=marker, ms=5, color=colour, zorder=3,
                    label=None if label in labelled else label)
            labelled.add(label)


def climb_spans(result: TrackResult) -> list[tuple[str, int, int]]:
    """Decision L592: ``(kind, first, last)`` rows of ``result.steps`` of its ramps (``"ramp"``: ramps.csv's,
    :func:`pdrlearn.track.grade.track_ramps` under the track's ``--stair-grade``) and, on a foot track off a declared
    inclined belt, its stair flights (``"stairs"``: stairs.csv's, :func:`pdrlearn.track.stair_flights.flight_spans`;
    none on the lower back, L440, or for rows not in ``start_s`` order), sorted by first row (a flight before a
    ramp on the same row); none when the trajectory is not one row per stride after its start row."""
    from pdrlearn.track.clinical import _is_lower_back
    from pdrlearn.track.grade import info_stair_grade, table_ramps
    from pdrlearn.track.stair_flights import flight_spans

    st, info = result.steps, result.info or {}
    if not len(st) or "dz_m" not in st or "start_s" not in st or len(result.trajectory) != len(st) + 1:
        return []
    with info_stair_grade(info):
        out = [("ramp", int(r["first"]), int(r["last"])) for r in table_ramps(st, info)]
    if (not _is_lower_back(st) and info.get("belt_incline_pct") is None
            and st["start_s"].is_monotonic_increasing):
        out += [("stairs", int(a), int(b) - 1) for a, b, _ in flight_spans(st.reset_index(drop=True))]
    return sorted(out, key=lambda s: (s[1], s[0] == "ramp"))


def walked_distance(x, y) -> np.ndarray:
    """Decision L592: the horizontal distance walked along a path to each of its points (m, 0 at the first; a
    non-finite step counts 0). A pure kernel."""
    d = np.hypot(np.diff(np.asarray(x, float)), np.diff(np.asarray(y, float)))
    return np.concatenate([[0.0], np.cumsum(np.nan_to_num(d))])


def draw_climbs(ax, ad, paths: dict[str, TrackResult], spans: dict) -> None:
    """Decision L592: each track's ramp and stair strides (``spans``, :func:`climb_spans`) coloured over its path in
    the plan view ``ax`` (trajectory rows ``first`` to ``last + 1``: a stride ends at the row after its start row),
    and in ``ad`` the tracks' heights ``z`` against :func:`walked_distance`, the same strides coloured (each
    coloured line's ``gid`` is its kind)."""
    named = set()
    for name, r in paths.items():
        tr = r.trajectory
        x, y, z = (tr[c].to_numpy(float) for c in ("x", "y", "z"))
        dist = walked_distance(x, y)
        ad.plot(dist, z, label=name, lw=1.2, color="0.4")
        for kind, a, b in spans[name]:
            label = f"{kind} strides ({'ramps' if kind == 'ramp' else 'stairs'}.csv)"
            style = {"color": CLIMB_COLOURS[kind], "lw": CLIMB_WIDTHS[kind], "gid": kind,
                     "label": label if label not in named else "_" + label}
            named.add(label)
            ax.plot(x[a:b + 2], y[a:b + 2], **style)
            ad.plot(dist[a:b + 2], z[a:b + 2], **style)
    ad.set_xlabel(DISTANCE_PANEL_XLABEL)
    ad.set_ylabel("height z [m]")
    ad.grid(alpha=0.3)
    ad.legend(fontsize=7)
    ad.set_title("height over the distance walked (ramps and stairs coloured)", fontsize=9)


def path_box(paths: list[tuple[np.ndarray, np.ndarray]]) -> tuple[float, float, float, float] | None:
    """``(xmin, xmax, ymin, ymax)`` of the finite points of ``paths`` (``(x, y)`` arrays); None when there are
    none. Decision L175: path.png's plan view covers the paths, so that a 2-sigma circle far wider than a long
    track does not shrink the track to a dot."""
    x = np.concatenate([np.asarray(p[0], float) for p in paths]) if paths else np.zeros(0)
    y = np.concatenate([np.asarray(p[1], float) for p in paths]) if paths else np.zeros(0)
    ok = np.isfinite(x) & np.isfinite(y)
    if not ok.any():
        return None
    return float(x[ok].min()), float(x[ok].max()), float(y[ok].min()), float(y[ok].max())


def initial_bearing(x: np.ndarray, y: np.ndarray, *, min_dist_m: float = 2.0) -> float | None:
    """ENU bearing (rad, 0 = east) from a path's first point to its first point at least ``min_dist_m`` away
    (about two strides: past the start's sway, before the first turn of a corridor walk); None when the path
    never gets that far."""
    d = np.hypot(x - x[0], y - y[0]) if len(x) else np.zeros(0)
    far = np.flatnonzero(d >= min_dist_m)
    if not len(far):
        return None
    i = int(far[0])
    return float(np.arctan2(y[i] - y[0], x[i] - x[0]))


def rotated_to_track(gx: np.ndarray, gy: np.ndarray, after: np.ndarray, tx: np.ndarray, ty: np.ndarray
                     ) -> tuple[np.ndarray, np.ndarray] | None:
    """The ground truth ``(gx, gy)`` (start-shifted) rotated about the start so that its path from the
    track's start (``after``) sets off in the track's initial direction; None when either is too short."""
    a_tr, a_gt = initial_bearing(tx, ty), initial_bearing(gx[after], gy[after])
    if a_tr is None or a_gt is None:
        return None
    c, s = np.cos(a_tr - a_gt), np.sin(a_tr - a_gt)
    return c * gx - s * gy, s * gx + c * gy


def heading_is_absolute(info: dict, session: Session) -> bool:
    """True when a track's heading is referenced to north, from its ``info``: aided by position fixes; given its
    start direction (``initial_heading_rad``, ``track --initial-heading``, decision L98); the
    offline plasys waist or fused heading on a session with a waist magnetometer (the waist filter's compass), unless
    D25's mounting check dropped the compass (``info.compass_mount.fallback``: the foot gyroscope's own heading,
    relative, decision L511).
    Relative (heading 0 = the start's direction): ``--streaming`` (gyroscopes only), the foot's integrated yaw,
    the lower-back pipelines (their heading starts at the unit's initial facing, docs/waist.md, W5), a
    magnetometer in the session or not. A track without a pipeline in its ``info``: absolute when the session
    has a magnetometer."""
    has_compass = any("Magnetic" in k for k in session.streams)
    if info.get("aid") or info.get("initial_heading_rad") is not None:  # L98: the user gave the start direction
        return True
    if "pipeline" not in info:
        return has_compass
    mount_fallback = bool((info.get("compass_mount") or {}).get("fallback"))  # decision L511: D25's foot heading
    return (info["pipeline"] == "plasys" and not info.get("streaming")
            and info.get("heading_source") in ("waist", "fused") and has_compass and not mount_fallback)
