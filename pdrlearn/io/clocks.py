"""Per-unit clocks of a session folder (decision B115 in docs/decisions/bad-input.md): ``meta.json`` may give each
body unit its own sampling rate and clock offset::

    {"clocks": {"foot": {"rate_hz": 200},
                "waist": {"rate_hz": 100, "clock_offset_s": 0.25}}}

``rate_hz`` is what the session-wide ``rate_hz`` is, for that unit's files only (sample-counter timestamps, B31 /
B98; the declared-rate check, B32); ``timestamp`` what ``"units": {"timestamp": ...}`` is, for that unit only (e.g.
``"samples"`` for a unit whose files count samples while the session declares ms); ``clock_offset_s`` is added to
that unit's timestamps when the session is read (the unit's clock + offset = the session's clock, on which the
labels are). The key is ``"clocks"``, keyed by
placement like ``"frames"``, not ``"units"``: ``"units"`` already holds the files' measurement units.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from pdrlearn.errors import DataError
from pdrlearn.io.sensors import SENSORS

UNITS = ("foot", "waist")
FIELDS = ("rate_hz", "clock_offset_s", "timestamp")
EXAMPLE = '"clocks": {"foot": {"rate_hz": 200}, "waist": {"rate_hz": 100, "clock_offset_s": 0.25}}'


def _number(v) -> bool:
    return not isinstance(v, bool) and isinstance(v, int | float) and math.isfinite(v)


def unit_clocks(meta: dict, meta_path: Path) -> dict[str, dict[str, float]]:
    """meta.json's ``"clocks"`` checked: unit -> ``{"rate_hz": Hz or None, "clock_offset_s": s}`` (empty when
    absent). A unit other than foot / waist, another field, a rate that is not a positive number of Hz or an offset
    that is not a number of seconds is one :class:`DataError` line naming meta.json and the fix. Per-unit entries
    under ``"units"`` (the measurement units' key) are refused, naming ``"clocks"``."""
    units = meta.get("units")
    if isinstance(units, dict):
        misplaced = [u for u in UNITS if isinstance(units.get(u), dict)]
        if misplaced:
            raise DataError(f"{meta_path}: \"units\".\"{misplaced[0]}\" is an object, but \"units\" holds the files' "
                            "measurement units; give a unit's sampling rate and clock offset under \"clocks\": "
                            f"{{{EXAMPLE}}} (decision B115)")
    raw = meta.get("clocks")
    if raw is None:
        return {}
    if not isinstance(raw, dict):
        raise DataError(f"{meta_path}: \"clocks\" must be an object keyed by unit, e.g. {{{EXAMPLE}}}")
    out = {}
    for unit, spec in raw.items():
        if unit not in UNITS:
            raise DataError(f"{meta_path}: clocks.{unit}: unknown unit; the units are {' and '.join(UNITS)} "
                            f"(rename or remove the entry, decision B115)")
        if not isinstance(spec, dict):
            raise DataError(f"{meta_path}: clocks.{unit} must be an object such as {{\"rate_hz\": 100, "
                            "\"clock_offset_s\": 0.25}")
        extra = [k for k in spec if k not in FIELDS]
        if extra:
            raise DataError(f"{meta_path}: clocks.{unit}.{extra[0]}: unknown field; a unit's clock has "
                            f"{' and '.join(FIELDS)} (decision B115)")
        rate = spec.get("rate_hz")
        if rate is not None and not (_number(rate) and rate > 0):
            raise DataError(f"{meta_path}: clocks.{unit}.rate_hz {rate!r} is not a positive number of Hz; give the "
                            f"{unit} unit's sampling rate, e.g. 100, or remove the field")
        off = spec.get("clock_offset_s", 0.0)
        if not _number(off):
            raise DataError(f"{meta_path}: clocks.{unit}.clock_offset_s {off!r} is not a number of seconds; give "
                            f"the seconds added to the {unit} unit's timestamps (e.g. 0.25 or -1.5), or remove it")
        ts = spec.get("timestamp")
        if ts is not None and not isinstance(ts, str):
            raise DataError(f"{meta_path}: clocks.{unit}.timestamp {ts!r} is not a unit; write e.g. \"samples\" or "
                            "\"ms since the first sample\", or remove it")
        out[unit] = {"rate_hz": None if rate is None else float(rate), "clock_offset_s": float(off),
                     "timestamp": ts}
    return out


def unit_groups(raw: dict, clocks: dict, rate_hz: float | None,
                meta: dict) -> list[tuple[list[str], float | None, dict]]:
    """The sensor files that share a clock, each with its rate (Hz, or None) and the meta.json its timestamp unit
    is read from: one group of every file without ``clocks`` (the session-wide ``rate_hz`` and ``units``), else
    one per unit, foot first (its ``clocks`` rate and timestamp unit, else the session's)."""
    if not clocks:
        return [(list(raw), rate_hz, meta)]
    groups = []
    for unit in UNITS:
        names = [n for n in raw if SENSORS[n].placement == unit]
        if names:
            c = clocks.get(unit, {})
            r = c.get("rate_hz")
            m = meta
            if c.get("timestamp") is not None:  # the unit's own timestamp unit
                units = meta.get("units") if isinstance(meta.get("units"), dict) else {}
                m = {**meta, "units": {**units, "timestamp": c["timestamp"]}}
            groups.append((names, r if r is not None else rate_hz, m))
    return groups


def apply_offsets(streams: dict, clocks: dict, meta_path: Path) -> None:
    """In place: each unit's ``clock_offset_s`` added to its streams' timestamps. An offset longer than the unit's
    recording is refused (one line): the units would not overlap at all, which is a mistaken unit (ms for s)
    or sign rather than a clock offset."""
    from pdrlearn.io.session import Stream

    for unit, spec in clocks.items():
        off = spec["clock_offset_s"]
        names = [n for n, s in streams.items() if s.placement == unit and len(s)]
        if not off or not names:
            continue
        span = max(float(streams[n].t[-1]) for n in names) - min(float(streams[n].t[0]) for n in names)
        if abs(off) >= span:
            raise DataError(f"{meta_path}: clocks.{unit}.clock_offset_s {off:g} s is longer than the {unit} unit's "
                            f"recording ({span:.2f} s), so it could not overlap the other unit; give the offset in "
                            f"seconds (the {unit} unit's clock + clock_offset_s = the session's clock, decision B115)")
        for n in names:
            s = streams[n]
            streams[n] = Stream(n, np.asarray(s.t, dtype=float) + off, s.values)


def one_unit_counting(raw: dict, folder: Path, meta_path: Path) -> None:
    """Decision B116: without ``clocks``, a session whose accelerometer/gyroscope files of one unit are sample
    counters (B98's consecutive integers) while the other unit's are not is refused, one line: the session-wide
    ``rate_hz`` and timestamp unit cannot say which files count samples (read as ms, a 100 Hz counter made a 27 s
    foot recording 2.7 s long beside its 27 s waist, and ``track`` exited 0 with 0.59 m)."""
    from pdrlearn.io.validate import sample_numbers

    counting = {}
    for unit in UNITS:
        imu = [n for n in raw if SENSORS[n].placement == unit and SENSORS[n].kind in ("accelerometer", "gyroscope")]
        if imu:
            counting[unit] = (imu[0], all(sample_numbers(raw[n][:, 0]) for n in imu))
    if len(counting) == 2 and counting["foot"][1] != counting["waist"][1]:
        unit = "foot" if counting["foot"][1] else "waist"
        other = "waist" if unit == "foot" else "foot"
        name = counting[unit][0]
        t = raw[name][:, 0]
        raise DataError(f"{folder / SENSORS[name].filename}: the {unit} unit's timestamps are consecutive integers "
                        f"({t[0]:.0f}-{t[-1]:.0f}), the {other} unit's are not: sample counters on one unit; give that "
                        f"unit's clock in {meta_path.name}: \"clocks\": {{\"{unit}\": {{\"rate_hz\": <Hz>, "
                        "\"timestamp\": \"samples\"}} (\"rate_hz\": 1000, \"timestamp\": \"ms\" if they are ms; "
                        "decisions B115, B116)")
