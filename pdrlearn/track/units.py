"""Which body unit a track follows, and whether it covers the walk the session recorded (decisions B126, B127).

``track --units foot`` tracks the foot unit alone (the waist files left out, as ``pdrlearn run --units foot``,
E26; decision L634: the foot track still reads the waist barometer for its rides, through
:func:`with_left_out_units`), ``--units waist`` the lower back alone. A session holding both units whose tracked
unit starts or stops more than :data:`~pdrlearn.io.plasys.SPAN_TOLERANCE_S` inside the other's recording is refused
(B126): the other unit shows that the walk went on, and the track (and a ``--window``) would describe only part of it.
"""

from __future__ import annotations

import dataclasses

from pdrlearn.errors import DataError, shell_quote
from pdrlearn.io.sensors import PLACEMENTS as UNITS  # the units ``--units`` accepts (decision B127)
from pdrlearn.io.session import Session


def parse_units(text: str | None) -> tuple[str, ...] | None:
    """``"foot"``, ``"waist"`` or ``"foot,waist"`` -> the units (None: every unit the session has). One
    :class:`DataError` line for another name."""
    if text is None:
        return None
    units = tuple(dict.fromkeys(u.strip().lower() for u in str(text).split(",") if u.strip()))
    bad = [u for u in units if u not in UNITS]
    if bad or not units:
        raise DataError(f"--units {text!r}: expected foot, waist or foot,waist (the body units to track with)")
    return units


def keep_units(session: Session, units: tuple[str, ...] | None) -> Session:
    """Decision B127: the session with the sensor streams of ``units`` only (None: unchanged); one
    :class:`DataError` line when it has none of a unit asked for."""
    if units is None:
        return session
    missing = [u for u in units if not session.placement_streams(u)]
    if missing:
        has = ", ".join(session.placements) or "none"
        raise DataError(f"{session.where}: --units {','.join(units)}: the session has no {' or '.join(missing)} unit "
                        f"(it has: {has}); drop --units or name a unit it has")
    streams = {k: s for k, s in session.streams.items() if s.placement in units}
    left_out = {k: s for k, s in session.streams.items() if s.placement not in units}  # decision W253
    return dataclasses.replace(session, streams=streams, _left_out={**session._left_out, **left_out})


def without_streams(session: Session, names: tuple[str, ...]) -> Session:
    """The session without the sensor streams ``names`` (decision L657: ``track --compass off`` reads it as without
    wMagneticField.csv); not put back by :func:`with_left_out_units`. The session itself when it has none of them."""
    if not any(n in session.streams for n in names):
        return session
    return dataclasses.replace(session, streams={k: s for k, s in session.streams.items() if k not in names})


def with_left_out_units(session: Session) -> Session:
    """Decision W253: the session with the streams ``--units`` left out (:func:`keep_units`) put back, for the
    checks that read another unit's cues (W173's backward, L219's sideways warnings of a waist track); the session
    itself when nothing was left out."""
    if not session._left_out:
        return session
    return dataclasses.replace(session, streams={**session._left_out, **session.streams}, _left_out={})


def tracked_unit(pipeline: str) -> str:
    """The unit a pipeline tracks: the foot for plasys, the lower back for the waist pipelines."""
    return "foot" if pipeline == "plasys" else "waist"


def unit_span(session: Session, unit: str) -> tuple[float, float] | None:
    """The first and last sample (s) of ``unit``'s streams in the session (None: it has none)."""
    ts = [s for s in session.placement_streams(unit).values() if len(s)]
    if not ts:
        return None
    return min(float(s.t[0]) for s in ts), max(float(s.t[-1]) for s in ts)


def walk_ends(ends: dict, clock: dict | None = None) -> tuple[float, float] | None:
    """Decision B273: the walk a session recorded, (first, last) s: the span of both units' recordings together
    (``ends``: :func:`~pdrlearn.io.plasys.unit_ends` as read, before any cut) when they start or stop over
    :data:`~pdrlearn.io.plasys.SPAN_TOLERANCE_S` apart (B83: a dead unit or drifting clocks - the unit that went on
    shows the walk went on), else the foot unit's (the waist's alone); ``clock``: a waist clock moved onto the
    foot's (``{"offset_s", "drift", "ref_s"}``, ``--clock-offset`` / ``--clock-drift-ppm`` / ``--align-units``,
    :func:`pdrlearn.track.plasys.move_waist_clock`'s formula) maps the waist's ends first. None: no unit."""
    from pdrlearn.io.plasys import SPAN_TOLERANCE_S

    if not ends:
        return None
    ends = dict(ends)
    if clock and "waist" in ends:  # t_foot = ref + (t_waist - offset - ref) / (1 + drift), move_waist_clock's
        ref, off, drift = float(clock.get("ref_s") or 0.0), float(clock["offset_s"]), float(clock.get("drift", 0.0))
        ends["waist"] = tuple(ref + (t - off - ref) / (1.0 + drift) for t in ends["waist"])
    if len(ends) < 2:
        return next(iter(ends.values()))
    (f0, f1), (w0, w1) = ends["foot"], ends["waist"]
    if max(abs(f0 - w0), abs(f1 - w1)) <= SPAN_TOLERANCE_S:
        return f0, f1
    return min(f0, w0), max(f1, w1)


def span_cut_s(uncut: dict | None, session: Session, unit: str, clock: dict | None = None) -> float:
    """Decisions B267, B273: the seconds of the walk the track of ``unit`` does not cover - :func:`walk_ends` of
    ``uncut`` (both units' ends as read, before any cut; ``clock`` a waist clock moved onto the foot's) less
    ``unit``'s span in ``session`` now: a cut to the common span (``--common-span``, B81 / B83; the overhang a
    moved waist clock leaves, L162) and the time the other unit recorded on after the tracked one stopped (the
    foot's battery dead at 200 s of a 336 s march: 135.6 s, where B267 counted only the tracked unit's own cut
    seconds, 0.0); 0.0 when nothing was lost."""
    now = unit_span(session, unit)
    walk = walk_ends(uncut, clock) if uncut else None
    if walk is None or now is None:
        return 0.0
    cut = (walk[1] - walk[0]) - (now[1] - now[0])
    return round(cut, 3) if cut > 1e-6 else 0.0


def units_apart_line(session: Session) -> str | None:
    """Decision B267 (``pdrlearn info``): one warning line when the session's foot and waist units start or stop
    over :data:`~pdrlearn.io.plasys.SPAN_TOLERANCE_S` apart - what ``track`` then refuses (B126, B21) or, with
    ``--common-span``, cuts (B83) - naming a clock offset (B243) or drift (B264) where the spans look like one, in
    the words of ``track``'s refusal (decision B269: :func:`~pdrlearn.io.plasys.clock_offset_fix` /
    :func:`~pdrlearn.io.plasys.clock_drift_fix`, so both name the same ``--clock-drift-ppm`` and ``--clock-offset``);
    None when they agree or the session has one unit."""
    from pdrlearn.io.plasys import (
        SPAN_TOLERANCE_S,
        clock_drift_fix,
        clock_offset_fix,
        waist_clock_drift,
        waist_clock_offset,
    )

    foot, waist = unit_span(session, "foot"), unit_span(session, "waist")
    if foot is None or waist is None:
        return None
    start, end = waist[0] - foot[0], waist[1] - foot[1]
    if max(abs(start), abs(end)) <= SPAN_TOLERANCE_S:
        return None
    offset, drift = waist_clock_offset(foot, waist), waist_clock_drift(foot, waist)
    command = f"pdrlearn track {shell_quote(session.folder) if session.folder is not None else 'SESSION'}"
    if offset is not None:  # B269: B243's words, as track's refusal (B126) and B21's
        why = f"{clock_offset_fix(offset, command)}, "
    elif drift is not None:  # B269: B264's words; the unit that stopped first, as B21's refusal names it
        why = f"{clock_drift_fix(*drift, command, 'foot' if end > 0 else 'waist')}, "
    else:
        why = "the waist unit " + " and ".join(
            f"{verb} {abs(v):.2f} s {'after' if v > 0 else 'before'} the foot unit"
            for verb, v in (("started", start), ("stopped", end)) if abs(v) > SPAN_TOLERANCE_S) + " -- "
    lo, hi = max(foot[0], waist[0]), min(foot[1], waist[1])
    walk = walk_ends({"foot": foot, "waist": waist})  # decision B273: span_cut_s's count after --common-span
    lost = (walk[1] - walk[0]) - (hi - lo)
    return (f"{session.where}: the foot unit covers {foot[0]:.2f}-{foot[1]:.2f} s and the waist unit "
            f"{waist[0]:.2f}-{waist[1]:.2f} s: {why}`pdrlearn track` refuses a track that needs the unit that "
            f"stopped short (B126, B21) and with --common-span tracks only the {lo:.2f}-{hi:.2f} s both cover "
            f"(B83; sessions.csv's common_span_cut_s then reads the {lost:.2f} s of the walk not tracked, decision "
            "B267 / B273)")


def check_tracked_span(session: Session, unit: str, command: str | None = None, *,
                       alone: str | None = None) -> None:
    """Decision B126: refuse, one line, a session whose tracked ``unit`` starts or stops more than
    :data:`~pdrlearn.io.plasys.SPAN_TOLERANCE_S` inside the other unit's recording (a foot unit whose battery ran
    out at 180 s while the waist went on to 385 s was tracked "ok", 198.91 of the 425.7 m walked). The mirror
    case, the other unit stopping early, is refused where a method needs it to cover the tracked one (B21, B83);
    both name the same two ways out: ``--common-span`` (the time both cover, B83) or ``--units`` (one unit).
    ``command``: the command line the fixes name (``pdrlearn track FOLDER`` when None; ``pdrlearn run BUNDLE
    SESSION``, which shares the whole check beside its own cover check B21, decisions B274, B278); ``alone``: the
    unit the ``--units`` fix names (the other unit when None; ``run``'s runtime needs the foot, so it names
    ``--units foot``)."""
    from pdrlearn.io.plasys import (
        SPAN_TOLERANCE_S,
        clock_drift_fix,
        clock_offset_fix,
        waist_clock_drift,
        waist_clock_offset,
    )

    other = "waist" if unit == "foot" else "foot"
    mine, theirs = unit_span(session, unit), unit_span(session, other)
    if mine is None or theirs is None:
        return
    late, early = mine[0] - theirs[0], theirs[1] - mine[1]
    if max(late, early) <= SPAN_TOLERANCE_S:
        return
    drift = waist_clock_drift(mine, theirs) if unit == "foot" else None
    what = " and ".join(p for p, v in ((f"started {late:.2f} s after", late), (f"stopped {early:.2f} s before", early))
                        if v > SPAN_TOLERANCE_S)
    folder = shell_quote(session.folder) if session.folder is not None else "SESSION"
    command = command or f"pdrlearn track {folder}"
    lo, hi = max(mine[0], theirs[0]), min(mine[1], theirs[1])
    head = (f"{session.where}: the tracked {unit} unit covers {mine[0]:.2f}-{mine[1]:.2f} s but the {other} "
            f"unit {theirs[0]:.2f}-{theirs[1]:.2f} s")
    cut = (f"track the {lo:.2f}-{hi:.2f} s both cover with `{command} --common-span` (decision B83), "
           f"or the {alone or other} unit alone with --units {alone or other}")
    offset = waist_clock_offset(mine, theirs) if unit == "foot" else None
    if offset is not None:  # decision B243: a shifted clock - the fix that keeps the whole walk
        raise DataError(f"{head}: {clock_offset_fix(offset, command)}, {cut} (decision B126)")
    if drift is not None:  # decision B264: clocks drifting apart - the drift named first, as B243's offset
        raise DataError(f"{head}: {clock_drift_fix(*drift, command)}, {cut} (decision B126)")
    raise DataError(f"{head}: it {what} the {other} unit, so the track would describe only part of the walk -- "
                    f"{cut}, or restore the {unit} files (decision B126)")
