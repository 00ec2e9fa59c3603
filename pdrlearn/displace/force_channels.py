"""Steps decisions 74 / 75: dead force channels and a session with one force channel.

A channel is dead when it carries no stance/swing modulation: the spread between its 5th and 95th percentiles is 0
(flat), or, with two channels, below ``FORCE_OFF_FRAC`` of the other channel's spread (the accel-force detector's
swing level, thesis ch.5.2). :func:`live_force` drops a dead channel from a session with one line naming it; the
remaining channel is the force (steps 75: the combined force of the thesis' rule is that channel).
"""

from __future__ import annotations

import copy

import numpy as np

from pdrlearn.kernels.contact import FORCE_OFF_FRAC

FORCE_NAMES = ("fForceA", "fForceB")
_WHAT = {"fForceA": "heel", "fForceB": "forefoot"}

#: steps decision 75 (measured): the forefoot alone times the contact 0.045 s later than both channels (the heel
#: strikes first), so a lone fForceB is not the force; a lone fForceA (heel or total) is
LONE_FORCE = ("fForceA",)

#: steps decision 75: why a lone fForceB is not the force (the reason half of :data:`LONE_FOREFOOT`)
LONE_FOREFOOT_WHY = ("fForceB.csv (forefoot) alone times the initial contact late (+0.045 s against both channels, "
                     "steps decision 75)")
LONE_FOREFOOT = (f"{LONE_FOREFOOT_WHY}: stance from the accelerometer/gyroscope detector; import the heel or a total "
                 "force as --heel to use it")

#: steps decision 77: what a weak (not flat) channel may be; a toe walker's heel is light, not broken
_WEAK_MEANS = {"fForceA": "a toe walker's heel, or a dead channel",
               "fForceB": "a foot that does not roll onto its forefoot, or a dead channel"}

def modulation(f: np.ndarray) -> tuple[float, float, float]:
    """Pure kernel: (5th percentile, 95th percentile, their spread) of one force channel's readings."""
    lo, hi = (float(v) for v in np.percentile(np.asarray(f, dtype=float), [5, 95]))
    return lo, hi, hi - lo


def dead_channels(values: dict[str, np.ndarray], *, frac: float = FORCE_OFF_FRAC) -> dict[str, str]:
    """Pure kernel (steps 74): channel name -> why it is dead ("flat" or "weak"), for the channels in ``values``
    (name -> readings) whose 5-95 % spread is 0, or below ``frac`` (``FORCE_OFF_FRAC``, thesis ch.5.2) of another
    live channel's spread."""
    spread = {n: modulation(v)[2] for n, v in values.items() if len(v)}
    out = {n: "flat" for n, s in spread.items() if not s > 0}
    best = max(spread.values(), default=0.0)
    for n, s in spread.items():
        if n not in out and s < frac * best:
            out[n] = "weak"
    return out


def _unit(session, name: str) -> str:
    """The channel's unit word for a line: "counts" when meta.json's units say so, else "N"."""
    u = (session.meta.get("units") or {}).get(name) if isinstance(session.meta.get("units"), dict) else None
    return "counts" if isinstance(u, str) and u.strip().lower().startswith("count") else "N"


def dead_why(session, dead: dict[str, str], live: list[str]) -> str:
    """Steps 74 / 77: each dropped channel named with its readings and why (flat: dead; weak: barely loaded)."""
    parts = []
    for n, why in dead.items():
        lo, hi, _ = modulation(session.streams[n].values[:, 0])
        u = _unit(session, n)
        if why == "flat":
            parts.append(f"{n}.csv ({_WHAT[n]}) is flat at {hi:.4g} {u}: a dead channel")
        else:  # steps decision 77: a light heel of a toe walker is weak too; not called broken
            parts.append(f"{n}.csv ({_WHAT[n]}) is barely loaded ({lo:.3g}-{hi:.3g} {u}, under {FORCE_OFF_FRAC:.0%} "
                         f"of {live[0]}.csv's stance/swing swing, thesis ch.5.2: {_WEAK_MEANS[n]})")
    return "; ".join(parts) + " (steps decision 74)"


def dead_line(session, dead: dict[str, str], live: list[str]) -> str:
    """Steps 74's line: each dead channel named with its readings, and what the force is now."""
    rest = (f"the force is {live[0]}.csv alone" if live and live[0] in LONE_FORCE else LONE_FOREFOOT if live else
            "no force channel is left: stance from the accelerometer/gyroscope detector")
    fix = ("check the insole's wiring, or drop the dead file to silence this" if "flat" in dead.values() else
           "check the insole's wiring if this foot loads it, or drop the file to silence this")  # steps 77
    return f"{dead_why(session, dead, live)}; {rest} - {fix}"

def present(session) -> list[str]:
    """The session's force streams with at least two samples."""
    return [n for n in FORCE_NAMES if n in session.streams and len(session.streams[n]) >= 2]


def _dropped(session) -> tuple[dict[str, str], list[str], list[str]]:
    """Steps 74 / 75: (dead channels -> why, live channels, channels to drop: the dead and a lone forefoot)."""
    names = present(session)
    dead = dead_channels({n: session.streams[n].values[:, 0] for n in names})
    live = [n for n in names if n not in dead]
    return dead, live, [*dead, *(live if len(live) == 1 and live[0] not in LONE_FORCE else [])]


def live_force(session):
    """Steps 74 / 75: ``session`` without its dead force channels, and without a lone channel the detector does not
    run on (a shallow copy; the same session when nothing is dropped) and the line saying so (None without)."""
    dead, live, drop = _dropped(session)
    if not drop:
        return session, None
    out = copy.copy(session)
    out.streams = {k: v for k, v in session.streams.items() if k not in drop}
    return out, dead_line(session, dead, live) if dead else LONE_FOREFOOT


def no_force_left(session, what: str) -> str | None:
    """Decision B409 / steps 77: the one error line when ``what`` (a detector chosen by name, that reads the force)
    is left with no force channel once steps 74 / 75 drop theirs; None when a force channel is left."""
    dead, live, drop = _dropped(session)
    if not drop or set(live) - set(drop):
        return None
    why = "; ".join(w for w in (dead and dead_why(session, dead, live),
                                live and LONE_FOREFOOT_WHY) if w)
    return (f"{session.where}: {what} reads the force sensors, and none is usable: {why}; count on the IMU with "
            "--detector accel, or import the heel or a total force as --heel (decision B409)")

def one_channel_filled(session):
    """Steps 75: a session whose one force channel is fForceA (heel or total) gets fForceB as 0 N on its clock (the
    thesis' combined force, ch.5.2, is then that one channel); any other session is returned as it is."""
    names = present(session)
    if len(names) != 1 or names[0] not in LONE_FORCE:
        return session
    s = session.streams[names[0]]
    other = next(n for n in FORCE_NAMES if n != names[0])
    out = copy.copy(session)
    out.streams = {**session.streams, other: type(s)(other, s.t, np.zeros_like(s.values))}
    return out


#: decision B399: words in an unused column's name that mark a further force channel (a midfoot / arch sensor)
EXTRA_FORCE_WORDS = ("midfoot", "midsole", "arch", "force", "fsr")


def extra_force_line(unused: list[str]) -> str | None:
    """Decision B399: one line when an unused column of an import looks like a further force channel (a midfoot
    sensor): pdrlearn reads two channels and its detectors use their sum, so say where to add it."""
    hit = [c for c in unused if any(w in "".join(ch for ch in c.lower() if ch.isalnum()) for w in EXTRA_FORCE_WORDS)]
    if not hit:
        return None
    return (f"{', '.join(hit)}: a further force channel? pdrlearn reads two, heel (--heel, fForceA.csv) and forefoot "
            "(--toe, fForceB.csv), and its force detectors use their sum (thesis ch.5.2); add a midfoot column into "
            "the forefoot column before importing (the heel alone times the contact, steps decision 75), or import "
            "a total force as --heel alone (docs/data.md, Force insoles; decision B399)")


def lone_heel_rejected(session, foot, what: str) -> str | None:
    """Steps decision 78: the one error line when ``what`` (a detector chosen by name that reads the force) would
    run on a lone fForceA (steps 75) that decision L365's per-stride check rejects for the whole session (loaded
    outside the foot IMU's rests or not in them); None otherwise (two channels, or the check passes). ``foot``: the
    foot unit's :class:`~pdrlearn.orient.UnitData`."""
    from pdrlearn.displace.foot import inertial_stance
    from pdrlearn.displace.force_check import _disagreement

    if present(session) != list(LONE_FORCE):
        return None
    _, chk = _disagreement(session, foot, inertial_stance(foot.acc, foot.gyr, foot.fs))
    if not chk.session:
        return None
    why = ", ".join(sorted(set(chk.reasons)))
    return (f"{session.where}: {what} reads fForceA.csv (heel) alone as the force (steps decision 75), and it "
            f"disagrees with the foot IMU in {chk.n_bad} of {chk.n_strides} strides ({why}; decision L365): a toe "
            "walker's heel, or an unloaded insole; count on the IMU with --detector accel (steps decision 78)")
