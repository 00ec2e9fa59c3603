"""In-memory data model: :class:`Stream` (one sensor) and :class:`Session` (one recording).

Units: timestamps in seconds (float64); values in SI units (m/s^2, rad/s, uT, hPa, force in N or
normalised). Label tables use seconds too (``start_s``, ``end_s``, ``ic_s`` ...); on disk they are
milliseconds (``start_ms`` ...), see :mod:`pdrlearn.io.plasys`.
"""

from __future__ import annotations

import copy
import functools
import json
import logging
import os
from contextvars import ContextVar
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError, MissingSensorError, NotASessionError
from pdrlearn.io.frames import THESIS_FOOT_FRAME, THESIS_WAIST_FRAME, AxisFrame
from pdrlearn.io.sensors import SENSORS, UNIT_IMU, SensorSpec
from pdrlearn.kernels.clock import MAX_JITTER, jitter_gap_limit_s, nominal_period_s, stamp_jitter_s

#: The thesis mounting of each unit: the example of the missing-frame error (:meth:`Session.require_frame`).
EXAMPLE_FRAMES: dict[str, AxisFrame] = {"foot": THESIS_FOOT_FRAME, "waist": THESIS_WAIST_FRAME}

log = logging.getLogger(__name__)

#: Canonical columns of a steps table (seconds). Other columns are kept as they are.
STEP_COLUMNS = ("start_s", "end_s")
STEP_OPTIONAL = ("ic_s", "terrain", "direction", "length_m", "length_class")
TERRAIN_CLASSES = ("flat", "up", "down")  # thesis ch.6.1
DIRECTION_CLASSES = ("forward", "backward")  # thesis ch.6.2
LENGTH_CLASSES = ("short", "normal", "long")  # thesis ch.6.3

#: decision B64: an interval of dropped samples up to this long (s) is bridged when a session is read
#: (:meth:`Stream.bridged`): one lost sample at PLASYS' 20 Hz, a tenth of a stride, under a stance phase;
#: longer ones are left as they are (warned; over 1 s they are B11's gaps)
MAX_BRIDGED_S = 0.1


@dataclass
class Gap:
    """An interval between two consecutive samples longer than 1.5 nominal periods."""

    start_s: float
    duration_s: float


@dataclass
class Stream:
    """One sensor's time series.

    Parameters
    ----------
    name : PLASYS sensor name (``fAccelerometer`` ...), see :data:`pdrlearn.io.sensors.SENSORS`.
    t : (n,) float64 timestamps in seconds, strictly increasing.
    values : (n, k) float64 values in the sensor's SI unit.
    """

    name: str
    t: np.ndarray
    values: np.ndarray

    def __post_init__(self) -> None:
        """Decision B50: a known sensor name, and :func:`pdrlearn.io.validate.check_samples` (shape, finite,
        strictly increasing timestamps); the units and the clock are checked per session at the entry points
        (B49: :func:`session_entry`)."""
        from pdrlearn.io.validate import check_samples

        if isinstance(self.name, SensorSpec):  # Stream(SENSORS["fAccelerometer"], ...) means that sensor
            self.name = self.name.name
        if not isinstance(self.name, str) or self.name not in SENSORS:
            raise DataError(f"Stream {self.name!r}: unknown sensor name; use one of {', '.join(SENSORS)} "
                            "(pdrlearn.io.SENSORS: the name says the unit, placement and columns)")
        try:
            self.t = np.asarray(self.t, dtype=np.float64)
            v = np.asarray(self.values, dtype=np.float64)
        except (TypeError, ValueError):
            raise DataError(f"Stream '{self.name}': t and values must be numbers (arrays of float); convert "
                            "them first, e.g. np.asarray(x, dtype=float)") from None
        self.values = v.reshape(-1, 1) if v.ndim == 1 and self.spec.n_axes == 1 else v
        check_samples(self.name, self.t, self.values, f"Stream '{self.name}'")

    @property
    def spec(self) -> SensorSpec:
        return SENSORS[self.name] if self.name in SENSORS else SensorSpec(self.name, "", "", self.values.shape[1], "")

    @property
    def placement(self) -> str:
        return self.spec.placement

    @property
    def kind(self) -> str:
        return self.spec.kind

    @property
    def unit(self) -> str:
        return self.spec.unit

    def __repr__(self) -> str:
        """Decision B181: one line (samples, rate, duration, unit), not the arrays."""
        return (f"Stream({self.name!r}, {len(self)} samples, {self.rate_hz:.4g} Hz, {self.duration_s:.2f} s, "
                f"{self.spec.unit})")

    def __len__(self) -> int:
        return int(self.t.shape[0])

    @property
    def period_s(self) -> float:
        """Nominal sampling period (s): :func:`pdrlearn.kernels.clock.nominal_period_s` of the timestamps (the median
        interval, or the mean of the regular ones for a quantised or jittered clock; decisions D7, B33)."""
        return nominal_period_s(self.t)  # decisions D7, B33 (one rule with the lean runtime's replay, E76)

    @property
    def jitter(self) -> float:
        """Sampling jitter: the standard deviation of the regular sample intervals (0.5-1.5 medians, gaps left
        out) over the nominal period; 0 for a uniform clock and for a quantised one (its regular intervals take
        at most two values, D7's 4 and 5 ms). Decision B33: +-4 ms at 100 Hz gives 0.33."""
        if len(self) < 10:
            return 0.0
        d = np.diff(self.t)
        med = float(np.median(d))
        reg = d[(d >= 0.5 * med) & (d <= 1.5 * med)]
        if reg.size < 9 or np.unique(np.round(reg, 9)).size <= 2:
            return 0.0
        return float(np.std(reg) / self.period_s)

    @property
    def jittered(self) -> bool:
        """Sampling jitter above :data:`MAX_JITTER` (decision B33)."""
        return self.jitter > MAX_JITTER

    def on_uniform_clock(self, period_s: float | None = None, bridge_s: float | None = None) -> Stream:
        """The stream linearly interpolated onto a uniform clock at its nominal period from its first sample
        (decision B33: the pipelines integrate with ``dt = 1 / rate``, so samples taken at irregular true times
        are put where that assumes them). No sample is made up inside an interval longer than two periods:
        such gaps stay gaps (B11); a shorter one is bridged, as jitter cannot be told from one dropped sample.
        The period is :attr:`period_s` (for a jittered stream the sample count over the span, B182).
        ``period_s`` / ``bridge_s``: another period, and the longest interval bridged (decision B457: a stream
        whose rate changed goes onto its fastest stretch's period, bridging up to two of its slowest periods)."""
        d = np.diff(self.t)
        p = self.period_s if period_s is None else period_s
        n = int(np.floor((self.t[-1] - self.t[0]) / p + 1e-9)) + 1
        grid = self.t[0] + p * np.arange(n)
        i = np.clip(np.searchsorted(self.t, grid, side="right") - 1, 0, len(self) - 2)
        keep = (d[i] <= (2.0 * p if bridge_s is None else bridge_s)) | (grid <= self.t[i] + 1e-12)
        grid = grid[keep]
        values = np.column_stack([np.interp(grid, self.t, self.values[:, j]) for j in range(self.values.shape[1])])
        return Stream(self.name, grid, values)

    @property
    def rate_hz(self) -> float:
        """Native rate (Hz): 1 / :attr:`period_s` (decision B182: the sample count over the span on a jittered
        clock)."""
        p = self.period_s
        return float(1.0 / p) if p > 0 else float("nan")

    @property
    def duration_s(self) -> float:
        return float(self.t[-1] - self.t[0]) if len(self) else 0.0

    def _gap_limit(self, factor: float = 1.5) -> float:
        """The interval (s) over which :meth:`gaps` counts a gap."""
        p = self.period_s
        limit = factor * p
        if self.jittered:  # B33: +-4 ms at 100 Hz puts 7 % of the intervals over 1.5 periods, no sample missing
            # B182: sorted receive stamps (+-12 ms at 104 Hz) make intervals up to 3.3 periods
            limit = max(limit, p * (1.0 + 4.0 * self.jitter), jitter_gap_limit_s(p, stamp_jitter_s(self.t)))
        return limit

    def gaps(self, factor: float = 1.5) -> list[Gap]:
        """Intervals longer than ``factor`` nominal periods (dropped samples)."""
        if len(self) < 3:
            return []
        dt = np.diff(self.t)
        idx = np.flatnonzero(dt > self._gap_limit(factor))
        return [Gap(float(self.t[i]), float(dt[i])) for i in idx]

    def bridged(self, max_s: float = MAX_BRIDGED_S) -> Stream:
        """Decision B64: each interval of dropped samples (a :meth:`gaps` interval) at most ``max_s`` long gets
        round(interval / period) - 1 samples at equal spacing inside it, linearly interpolated between its two
        recorded samples (the pipelines integrate with ``dt = 1 / rate``, B33, so a missing sample took one
        period out of its stride). The recorded samples are kept as they are; longer intervals stay. ``self``
        (the same object) when no interval is bridged."""
        if len(self) < 3:
            return self
        d = np.diff(self.t)
        idx = np.flatnonzero((d > self._gap_limit()) & (d <= max_s * (1.0 + 1e-9)))
        if not idx.size:
            return self
        k = np.maximum(np.rint(d[idx] / self.period_s).astype(np.int64) - 1, 1)  # samples missing in each
        i = np.repeat(idx, k)
        frac = np.concatenate([np.arange(1, m + 1) / (m + 1) for m in k])
        t_new = self.t[i] + frac * d[i]
        v_new = self.values[i] + frac[:, None] * (self.values[i + 1] - self.values[i])
        return Stream(self.name, np.insert(self.t, i + 1, t_new), np.insert(self.values, i + 1, v_new, axis=0))

    def slice(self, t0: float, t1: float) -> Stream:
        """Samples with ``t0 <= t < t1``."""
        m = (self.t >= t0) & (self.t < t1)
        return Stream(self.name, self.t[m], self.values[m])

    def norm(self) -> np.ndarray:
        """Euclidean norm of each sample (n,)."""
        return np.linalg.norm(self.values, axis=1)

    def copy(self) -> Stream:
        return Stream(self.name, self.t.copy(), self.values.copy())


@dataclass
class Session:
    """One recording: named sensor streams plus labels and metadata.

    Attributes
    ----------
    name : session name (folder name on disk)
    streams : sensor name -> :class:`Stream`; any may be missing
    steps : steps table (``start_s``, ``end_s`` and, where known, ``ic_s``, ``terrain``, ``direction``,
        ``length_m``, ``length_class`` ...) or ``None``
    trajectory : ground-truth trajectory (``t``, ``x``, ``y``, ``z``; seconds and metres) or ``None``
    extras : other label tables (``ics``, ``bouts``, ``turns`` ...) with times in seconds
    meta : contents of ``meta.json``
    frames : placement -> declared :class:`AxisFrame` (absent when not declared)
    folder : the folder it was read from (:func:`pdrlearn.io.read_session`), ``None`` for one built in memory;
        errors about ``meta.json`` name ``folder / "meta.json"``
    infer_frames : when a unit's frame is not declared, :meth:`require_frame` infers it from the data with a
        warning (decision D8 in docs/decisions.md); ``False`` restores the plain missing-frame error
    check_units : the public entry points (step detectors' ``detect``, the tracking pipelines, step windows and
        so ``train_user``/evaluation) refuse values in implausible units (decision B49, as
        ``read_session(check_units=...)`` does for files); ``False`` skips that check (a session read with
        ``check_units=False`` gets ``False``)
    """

    name: str
    streams: dict[str, Stream] = field(default_factory=dict)
    steps: pd.DataFrame | None = None
    trajectory: pd.DataFrame | None = None
    extras: dict[str, pd.DataFrame] = field(default_factory=dict)
    meta: dict = field(default_factory=dict)
    frames: dict[str, AxisFrame] = field(default_factory=dict)
    folder: Path | None = None
    infer_frames: bool = True
    check_units: bool = True
    #: decision W607: ``"inferred"`` tracks a unit whose declared frame its data contradict with confidence (D10)
    #: in the frame the data give (a unit clipped turned on its mount); ``"declared"`` keeps the declared frame
    mount_frame: str = "declared"
    #: decision W615: the command reading the session that takes ``--mount-frame`` (``track``, ``track-all``), named
    #: in D10's line; None: the reader has no such option (another command, a notebook), the line names none
    mount_frame_command: str | None = None
    _inferred: dict[str, AxisFrame | DataError] = field(default_factory=dict, repr=False, compare=False)
    _checked: dict = field(default_factory=dict, repr=False, compare=False)  # placement -> DeclaredCheck
    _handed: dict[object, object] = field(default_factory=dict, repr=False, compare=False)
    _valid: tuple | None = field(default=None, repr=False, compare=False)
    #: decision B81: the recording's first sample (s) before ``read_session(spans="common")`` cut the session to
    #: its common span (None: not cut); ``track --window`` counts its seconds from it (L105)
    _t_start_uncut: float | None = field(default=None, repr=False, compare=False)
    #: decision B267: each unit's (first, last) sample (s) before ``read_session(spans="common")`` cut the session
    #: (None: not cut); ``track`` counts the seconds of the walk its track does not cover (``common_span_cut_s``,
    #: B273: :func:`pdrlearn.track.units.span_cut_s`)
    _unit_ends_uncut: dict | None = field(default=None, repr=False, compare=False)
    #: decision B113: the recording's :meth:`content_id` when this session is its copy resampled to a model's
    #: rate (``pdrlearn evaluate --resample``): the held-out check (B87) still knows the recording
    _source_id: str | None = field(default=None, repr=False, compare=False)
    #: decision E138: when ``steps`` is a ``--window``'s cut, each row's row in the session's steps.csv (from 0);
    #: None: the rows are steps.csv's
    _steps_rows: np.ndarray | None = field(default=None, repr=False, compare=False)
    #: decision W253: the sensor streams ``track --units`` left out (``pdrlearn.track.units.keep_units``); the
    #: waist track still reads the foot unit's cues from them (W173's backward, L219's sideways warnings)
    _left_out: dict[str, Stream] = field(default_factory=dict, repr=False, compare=False)
    #: decision E154: the warnings logged while ``read_session`` read it (clipping B77, dropped packets B64 / B183,
    #: jitter B182 ...); every pipeline adds them to its ``info["warnings"]``
    _read_warnings: list[str] = field(default_factory=list, repr=False, compare=False)
    #: decision B359 (R1): how the reader's lines name a session read from a zip (``walk1.zip:walk1``, its folder in the
    #: archive); results strip it as they strip a folder's path (None: read from a folder or built in memory)
    _read_from: str | None = field(default=None, repr=False, compare=False)

    def __post_init__(self) -> None:
        """Decision E181: a session built in memory with ``meta`` but no ``frames`` takes the frames its meta
        declares (:func:`~pdrlearn.io.frames.frames_from_meta`: its ``"frames"`` entry, else a known source), as
        :func:`pdrlearn.io.read_session` does for meta.json; before, they were ignored and inferred from the data."""
        from pdrlearn.io.frames import MOUNT_FRAMES

        if self.mount_frame not in MOUNT_FRAMES:  # decision W607
            raise DataError(f"session {self.name!r}: mount_frame={self.mount_frame!r}: give one of "
                            f"{', '.join(MOUNT_FRAMES)}")
        if not self.frames and isinstance(self.meta, dict) and self.meta:
            from pdrlearn.io.frames import frames_from_meta

            try:
                self.frames = frames_from_meta(self.meta)
            except DataError as exc:
                raise DataError(f"session {self.name!r}, meta: {exc}") from None

    def __repr__(self) -> str:
        """Decision B181: a short description (streams with rate and unit, duration, labels), not the arrays
        and meta.json a notebook cell printed before (~10 kB per session)."""
        streams = ", ".join(f"{n} {s.rate_hz:.4g} Hz {s.spec.unit}" for n, s in self.streams.items())
        parts = [repr(self.name)] + ([f"folder={str(self.folder)!r}"] if self.folder is not None else [])
        parts.append(f"{self.duration_s:.2f} s" if self.streams else "no streams")
        parts += [f"streams: {streams}"] if streams else []
        parts += [f"steps: {len(self.steps)} rows"] if self.steps is not None else []
        parts += [f"trajectory: {len(self.trajectory)} rows"] if self.trajectory is not None else []
        parts += [f"extras: {', '.join(self.extras)}"] if self.extras else []
        return f"Session({'; '.join(parts)})"

    # -- access -----------------------------------------------------------------------------------
    def __getitem__(self, name: str) -> Stream:
        return self.require(name)

    def __contains__(self, name: str) -> bool:
        return name in self.streams

    @property
    def where(self) -> str:
        """How warnings name the session (decision B34): the folder it was read from, as given (a copied
        folder keeps its meta.json "session" name, which would name the original); ``session 'NAME'`` for
        a session built in memory. Outputs (summary.json's ``session``) keep :attr:`name`."""
        return str(self.folder) if self.folder is not None else f"session '{self.name}'"

    @property
    def wheres(self) -> list[str]:
        """Decision B359 (R1): every name the session's warning lines start with: :attr:`where`, and for a zip's session
        the archive's folder the reader's lines name (``walk1.zip:walk1``)."""
        return [self.where, *([self._read_from] if self._read_from else [])]

    def validate(self) -> Session:
        """Check every stream as :func:`pdrlearn.io.read_session` checks a sensor file (decision B49:
        :func:`pdrlearn.io.validate.check_session`); raises :class:`DataError`, returns the session.

        All of it runs when the streams differ from the last time they passed (or from what ``read_session``
        checked), by :meth:`_fingerprint`: sums that any rescaling, shift, NaN or inf changes, also when the
        arrays are changed in place; else only the order of the timestamps is checked again (a 1 h session of
        8 streams at 20 Hz: 2.98 ms instead of 36.1 ms CPU, experiments/api_validate.py, decision B49)."""
        from pdrlearn.io.validate import check_samples, check_session

        fp = self._fingerprint()
        if fp is not None and fp == self._valid:
            for key, s in self.streams.items():
                if not bool(np.all(np.diff(s.t) > 0)):
                    check_samples(s.name, s.t, s.values, f"{self.where}, stream {key}")
            return self
        check_session(self)
        self._valid = self._fingerprint()
        return self

    def _fingerprint(self) -> tuple | None:
        """What :meth:`validate`'s cache compares (decision B49): per stream its name, length, first and last
        time, the sum of its times and of its values (NaN or inf in either never equals the cached one: a NaN
        compares unequal); ``None`` when a stream is not a Stream."""
        out: list = [self.check_units]
        if not isinstance(self.streams, dict):
            return None
        for key, s in self.streams.items():
            if not isinstance(s, Stream) or len(s) == 0:
                return None
            out.append((key, s.name, len(s), float(s.t[0]), float(s.t[-1]), float(s.t.sum()),
                        float(s.values.sum())))
        return tuple(out)

    def content_id(self) -> str:
        """Decision B87: what identifies the recording, whatever its folder is named: a hash (SHA-1, 16 hex
        digits) of every sensor stream's name, times and values, in name order. ``evaluate`` matches it against
        the model's training sessions (``training_data.session_ids``); a copy or re-import of the same data
        gives the same id, two recordings in folders of one name do not."""
        import hashlib

        if self._source_id is not None:  # decision B113: a resampled copy is still the recording
            return self._source_id
        h = hashlib.sha1()
        for key in sorted(self.streams):
            st = self.streams[key]
            h.update(key.encode())
            h.update(np.ascontiguousarray(st.t, dtype=float).tobytes())
            h.update(np.ascontiguousarray(st.values, dtype=float).tobytes())
        return h.hexdigest()[:16]

    def has(self, *names: str) -> bool:
        return all(n in self.streams for n in names)

    def require(self, *names: str, purpose: str = "") -> Stream:
        """Return the first named stream, raising :class:`MissingSensorError` if any is absent."""
        missing = [n for n in names if n not in self.streams]
        if missing:
            what = f" needed by {purpose}" if purpose else ""
            have = ", ".join(self.streams) or "none"
            raise MissingSensorError(
                f"session '{self.name}' has no {', '.join(missing)}{what} (it has: {have}); "
                "record that sensor or choose a method that does not need it"
            )
        return self.streams[names[0]]

    def require_cover(self, master: str, *others: str, max_missing_s: float = 1.0,
                      command: str = "pdrlearn track") -> None:
        """Raise :class:`DataError` when one of ``others`` starts more than ``max_missing_s`` after the
        ``master`` stream or ends more than that before it. The methods interpolate ``others`` onto the
        master's clock, and ``np.interp`` holds a stream's first/last value beyond its ends: a gyroscope that
        stopped after 6 s of a 137 s recording fed its last rate to the AHRS for 131 s without a word (waist-ic
        F1 0.938 -> 0.594, distance -54 %). ``max_missing_s``: the gap length decision B11 reports (1 s).
        ``command``: the command whose ``--common-span`` the line names (decision B230: ``pdrlearn run`` names its
        own, not ``track``'s)."""
        m = self.streams.get(master)
        if m is None or len(m) == 0:
            return
        for name in others:
            s = self.streams.get(name)
            if s is None or len(s) == 0:
                continue
            late, early = float(s.t[0] - m.t[0]), float(m.t[-1] - s.t[-1])
            if max(late, early) > max_missing_s:
                where = (f"{self.folder / (name + '.csv')}" if self.folder is not None
                         else f"session '{self.name}': {name}")
                lo, hi = max(float(m.t[0]), float(s.t[0])), min(float(m.t[-1]), float(s.t[-1]))
                alone = ""
                if m.placement and s.placement and m.placement != s.placement:  # B127: the master's unit alone
                    alone = f", or the {m.placement} unit alone with --units {m.placement} (decision B127)"
                fix = (f"track only {lo:.2f}-{hi:.2f} s, where both have data, with `{command} --common-span` "
                       f"(decision B83){alone}, or re-record" if hi > lo
                       else f"they do not overlap: re-record{alone}")
                if {m.placement, s.placement} == {"foot", "waist"}:  # decision B243: a shifted waist clock first
                    from pdrlearn.io.plasys import (
                        clock_drift_fix,
                        clock_offset_fix,
                        waist_clock_drift,
                        waist_clock_offset,
                    )

                    foot, waist = (m, s) if m.placement == "foot" else (s, m)
                    offset = waist_clock_offset((float(foot.t[0]), float(foot.t[-1])),
                                                (float(waist.t[0]), float(waist.t[-1])))
                    drift = waist_clock_drift((float(foot.t[0]), float(foot.t[-1])),
                                              (float(waist.t[0]), float(waist.t[-1]))) if offset is None else None
                    first = "foot" if float(foot.t[-1]) < float(waist.t[-1]) else "waist"
                    fix = (f"{clock_offset_fix(offset, command)}, {fix}" if offset is not None else  # B243
                           f"{clock_drift_fix(*drift, command, first)}, {fix}" if drift is not None else fix)  # B264
                raise DataError(
                    f"{where} covers {s.t[0]:.2f}-{s.t[-1]:.2f} s but {master} {m.t[0]:.2f}-{m.t[-1]:.2f} s; "
                    f"its values would be made up for the missing {max(late, 0) + max(early, 0):.2f} s -- {fix}")

    def require_frame(self, placement: str) -> AxisFrame:
        """The axis frame of the ``placement`` unit: the declared one (with ``infer_frames``, checked once
        against the data: a left-handed frame or one the data contradict with confidence is still used, with
        one warning naming the frame the data give, decision D10); else (``infer_frames``) the frame
        inferred from the unit's data (:mod:`pdrlearn.track.frame_inference`, decision D8), logged once
        as a warning that names what was found and the ``frames`` entry to declare if it is wrong; else, or
        when the data does not fix the axes, a :class:`DataError` naming the session's ``meta.json`` and
        the entry to add (the one wording of every method that needs a unit's axes, decision B18).
        With ``infer_frames`` the unit's accelerometer and gyroscope are also checked once for mirrored
        (left-handed) data, one warning naming the files and the fix (decision D11), and the foot and waist
        units once for swapped or duplicated files, a :class:`DataError` (decision B91)."""
        where = (f"{self.folder / 'meta.json'}: session '{self.name}'" if self.folder is not None
                 else f"session '{self.name}' (its meta.json)")
        if self.infer_frames:
            from pdrlearn.io.handedness import AXES_PLACEMENTS, WARN_PLACEMENTS

            if "units" not in self._checked:  # decision B91: swapped or duplicated unit files, once per session
                from pdrlearn.io.unit_check import unit_mixup

                self._checked["units"] = unit_mixup(self)
            if self._checked["units"]:
                raise DataError(f"{where}: {self._checked['units']}")

            if placement in WARN_PLACEMENTS:  # the waist ratio is not adopted: not paid for here
                self.handedness(placement)
            elif placement in AXES_PLACEMENTS:  # its axis agreement (D11 amendment) is cheap
                self.handedness(placement, ratio=False)
        frame = self.frames.get(placement)
        if frame is not None:
            if self.infer_frames and placement not in self._checked:  # decision D10: once per session
                from pdrlearn.track.frame_inference import check_declared_frame

                self._checked[placement] = chk = check_declared_frame(self, placement, frame,
                                                                      mount_frame=self.mount_frame,
                                                                      command=self.mount_frame_command)  # W615
                if chk.message and not chk.refuse:
                    log.warning("%s: %s", where, chk.message)
                if chk.used_found is not None:  # decision W607: summary's frames_inferred and frame_status say so
                    self._inferred[placement] = chk.used_found
            chk = self._checked.get(placement)
            if chk is not None and chk.refuse:
                raise DataError(f"{where}: {chk.message}")  # decision D23: a reversed forward is refused
            if chk is not None and chk.used_found is not None:
                return chk.used_found  # decision W607: mount_frame "inferred"
            return frame
        reason = ""
        if self.infer_frames:
            from pdrlearn.track.frame_inference import infer_session_frame

            if placement not in self._inferred:  # once per session: the frame, or why there is none
                try:
                    found = infer_session_frame(self, placement)
                except DataError as exc:
                    self._inferred[placement] = exc  # printed as its message; W61 reads its walk_s
                else:
                    self._inferred[placement] = found.frame
                    log.warning("%s declares no axis frame for the %s unit; inferred from the data: \"frames\": "
                                "%s (%s); if that is wrong, add the right \"frames\" entry to %s", where,
                                placement, json.dumps({placement: found.frame.to_dict()}), found.describe(),
                                "meta.json" if self.folder is not None else  # decision E181: built in memory
                                "the Session's frames= (or its meta's \"frames\")")
            known = self._inferred[placement]
            if isinstance(known, AxisFrame):
                return known
            reason = f" and its data does not fix the axes ({known})"
            h = self._handed.get(placement)
            if h is not None and h.mirrored:  # B29: a "frames" entry cannot fix mirrored data (D11)
                from pdrlearn.io.handedness import mirror_fix_text

                acc_n, gyr_n = UNIT_IMU[placement]
                raise DataError(  # decision L71: the axis named (mirror_fix_text, shared with the warning)
                    f"{where} declares no axis frame for the {placement} unit{reason}; the D11 test finds its {acc_n} "
                    f"and {gyr_n} {h.describe()}, a left-handed pair: {mirror_fix_text(h, acc_n, gyr_n)}; "
                    f"a \"frames\" entry cannot fix that")
            if h is not None and h.axes_differ:  # trial 2, finding 8: the D11 amendment's fix, not a frames entry
                from pdrlearn.io.handedness import axes_fix_text

                acc_n, gyr_n = UNIT_IMU[placement]
                fix = (axes_fix_text(h.axes, acc_n, gyr_n) if placement != "waist" else
                       f"rewrite {gyr_n}.csv's columns in the accelerometer's axes, or {acc_n}.csv's in the "
                       f"gyroscope's (or re-export both sensors in one frame); a \"frames\" entry cannot fix this")
                raise DataError(
                    f"{where} declares no axis frame for the {placement} unit{reason}; the D11 test finds its "
                    f"{acc_n} and {gyr_n} {h.describe()}: the two files disagree on the axes, which no frame can "
                    f"describe; {fix}")
        nearest = getattr(self._inferred.get(placement), "nearest", None)  # W394: the axes its walk gives
        example = json.dumps({placement: (nearest or EXAMPLE_FRAMES.get(placement, EXAMPLE_FRAMES["foot"])).to_dict()})
        what = ("the nearest axis assignment its walking gives (check it against the mounting)" if nearest is not None
                # decision C142 (trial T3 finding 6): a yawed or tilted unit is declared by its nearest axes
                else "the sensor axes nearest its forward, left and up (a unit yawed or tilted on its mount is "
                     "declared by its nearest axes), as in the thesis mounting")
        hint = self._waist_hint(placement)  # decision B288: a "foot" unit that never swings is named as a lower back
        frame = nearest or EXAMPLE_FRAMES.get(placement, EXAMPLE_FRAMES["foot"])
        fix = self._import_fix(placement, frame)
        # decision W580: an imported session's line leads with the frames fix; why the data did not fix the axes last
        lead, why = ("", f" ({reason.strip()})") if fix and reason else (reason, "")
        err = DataError(
            f"{where} declares no axis frame for the {placement} unit{lead}; {hint + '; else ' if hint else ''}"
            f"{fix}add a \"frames\" entry giving the "
            f"body direction of each of its axes (forward, backward, left, right, up, down), e.g. {what} "
            f"\"frames\": {example}{why}"
        )
        err.walk_s = getattr(self._inferred.get(placement), "walk_s", None)  # W61: too little walking to infer
        raise err

    def frame_forced(self, placement: str) -> bool:
        """Decision D23's override: meta.json ``"force_frame": true`` (or a list naming the unit), or an
        ``import --force-frame`` of this unit's frame (its ``"imported"`` record's ``frame_forced``): the
        declared frame is used even when the data find it reversed (with D10's warning)."""
        forced = self.meta.get("force_frame")
        if not (forced is None or isinstance(forced, bool)
                or (isinstance(forced, list) and all(isinstance(u, str) and u in UNIT_IMU for u in forced))):
            where = self.folder / "meta.json" if self.folder is not None else f"session '{self.name}' (its meta.json)"
            # decision B136: a misspelt override was ignored and the same refusal repeated its own advice
            raise DataError(f'{where}: "force_frame" is {json.dumps(forced)}: give true (every unit) or a list '
                            f'of units, e.g. ["foot"] (one of {", ".join(UNIT_IMU)}; decision D23)')
        if forced is True or (isinstance(forced, list) and placement in forced):
            return True
        recs = self.meta.get("imported")
        recs = recs if isinstance(recs, list) else [recs] if isinstance(recs, dict) else []
        frame = self.frames.get(placement)
        return frame is not None and any(isinstance(r, dict) and isinstance(r.get("frame_forced"), dict)
                                         and r["frame_forced"].get("declared") == frame.to_dict() for r in recs)

    def _import_fix(self, placement: str, frame: AxisFrame) -> str:
        """Decision B419: the frame refusal's first fix for a session ``pdrlearn import`` wrote (meta.json's
        ``"imported"`` record names the file): run that import again with ``--frames`` (the example ``frame``), and
        how to find the axes by standing still and leaning forward; ``""`` for any other session."""
        recs = self.meta.get("imported")
        recs = recs if isinstance(recs, list) else [recs] if isinstance(recs, dict) else []
        files = [r["file"] for r in recs if isinstance(r, dict) and isinstance(r.get("file"), str)
                 and r.get("unit", placement) == placement]
        if not files:
            return ""
        axes = ",".join(f"{k}={v}" for k, v in frame.to_dict().items())
        return (f"re-import it with its axes named: the same `pdrlearn import {files[0]} --unit {placement} ...` "
                f"command with --frames {axes} (an example: to find yours, stand still - the accelerometer axis "
                "reading about +1 g is up, -1 g down - then lean forward: the horizontal axis whose reading falls "
                "below zero is forward, above zero backward); or ")

    def _waist_hint(self, placement: str) -> str | None:
        """Decision B288: for a foot unit of a session without a waist unit whose gyroscope never swings, B287's
        hint that it is a lower-back unit imported as the foot (:func:`pdrlearn.io.unit_check.no_swing_hint`)."""
        acc_n, gyr_n = UNIT_IMU["foot"]
        if placement != "foot" or self.has(*UNIT_IMU["waist"]) or not self.has(acc_n, gyr_n):
            return None
        from pdrlearn.io.unit_check import no_swing_hint

        return no_swing_hint(self.streams[gyr_n].t, self.streams[gyr_n].values)

    def handedness(self, placement: str, *, ratio: bool = True):
        """The mirrored-data and axis-agreement tests of the ``placement`` unit
        (:func:`pdrlearn.io.handedness.check_handedness`, decision D11 and its amendment), run once per
        session (``ratio=False``: without the waist's costly, not adopted handedness ratio; run again with it
        when asked); its warning, naming the folder, is logged the first time only. ``None`` when the unit has
        no accelerometer + gyroscope pair."""
        key = (placement, "ratio")
        if placement not in self._handed or (ratio and key not in self._handed):
            from pdrlearn.io.handedness import check_handedness

            self._handed[placement], msg = check_handedness(self, placement, ratio=ratio)
            if ratio:
                self._handed[key] = True
            if msg and (placement, "warned") not in self._handed:
                self._handed[(placement, "warned")] = True
                log.warning("%s: %s", self.folder if self.folder is not None else f"session '{self.name}'", msg)
        return self._handed[placement]

    def frame_checks(self) -> dict[str, dict]:
        """Run the data checks of each IMU unit's axes now (what :meth:`require_frame` runs when a command
        needs them; each warning logged once) and return, per placement: ``frame`` (the frame used, or
        ``None``), ``source`` (``declared``, ``source_project``, ``inferred`` or ``none``), ``check`` (``ok``,
        the D10 warning of a declared frame, D22's refusal, what the data could not check of it, or why the data
        do not fix an undeclared one), ``status`` (``ok``, ``warned``, ``refused``, ``unchecked``, ``none``) and
        ``handedness`` (:meth:`pdrlearn.io.handedness.Handedness.to_dict` or ``None``, decision D11). For
        ``pdrlearn info``."""
        out: dict[str, dict] = {}
        for p in self.placements:
            if p not in UNIT_IMU or not self.has(*UNIT_IMU[p]):
                continue
            declared = p in self.frames
            try:
                frame = self.require_frame(p)
            except DataError as exc:
                chk = self._checked.get(p) if declared else None
                if chk is None or not chk.refuse:
                    frame, check, status = None, str(exc), "none"
                else:  # decision D23: the declared frame, refused
                    frame, check, status = self.frames[p], str(exc), "refused"
            else:
                chk = self._checked.get(p) if declared else None
                if not self.infer_frames:
                    check, status = "not checked (infer_frames is off)", "unchecked"
                elif chk is None or (not chk.message and chk.unchecked is None):
                    check, status = "ok", "ok"
                elif chk.message:
                    check, status = chk.message, "warned"
                else:  # decision D22: the data could not judge it; never "not contradicted"
                    check, status = chk.summary(), "unchecked"
            source = ("none" if frame is None else "inferred" if not declared or frame != self.frames[p]
                      else "declared" if isinstance(self.meta.get("frames"), dict) else "source_project")
            h = self.handedness(p) if self.infer_frames else None
            out[p] = {"frame": None if frame is None else frame.to_dict(), "source": source, "check": check,
                      "status": status, "handedness": None if h is None else h.to_dict()}
        return out

    def declared_check(self, placement: str):
        """The data's check of ``placement``'s declared frame run so far (decision D10's
        :class:`~pdrlearn.track.frame_inference.DeclaredCheck`), or None (not declared or not checked yet)."""
        chk = self._checked.get(placement)
        return chk if hasattr(chk, "forward_deg") else None

    @property
    def frame_warnings(self) -> list[str]:
        """Decision W334: the D10 warnings the data checks of the declared frames logged so far (one per unit, in
        placement order, without the session's name), for summary.json's warnings."""
        return [chk.message for _, chk in sorted(self._checked.items())
                if getattr(chk, "message", None) and not getattr(chk, "refuse", False)]

    @property
    def frames_inferred(self) -> dict[str, dict]:
        """The frames this session's commands inferred from the data so far (decision D8), as meta.json's
        ``frames`` entry would write them; empty when every frame used was declared."""
        return {p: f.to_dict() for p, f in sorted(self._inferred.items()) if isinstance(f, AxisFrame)}

    def frame_status(self, placement: str) -> str | None:
        """Decision C142: how the ``placement`` unit's frame was had, from the checks run so far (none run here):
        ``inferred`` (from the data, D8), ``forced`` (declared, rejected by the data, kept by ``"force_frame"``,
        D23), ``contradicted`` (declared, used with D10's warning: the data give another frame, or it is
        left-handed), ``declared`` (declared or ``source_project``, not contradicted); ``None`` when no command
        asked for it (the unit not used, absent, or refused)."""
        if isinstance(self._inferred.get(placement), AxisFrame):
            return "inferred"
        if placement not in self.frames:
            return None
        chk = self._checked.get(placement)
        if chk is None:
            return "declared" if not self.infer_frames else None
        if chk.refuse:
            return None
        return "forced" if chk.forced else "contradicted" if chk.message else "declared"

    def has_frame(self, placement: str) -> bool:
        """True when :meth:`require_frame` gives the ``placement`` unit a frame (declared, or inferred from
        the data with its warning); for methods that use a unit only when its axes are known."""
        try:
            self.require_frame(placement)
        except DataError:
            return False
        return True

    @property
    def placements(self) -> list[str]:
        return sorted({s.placement for s in self.streams.values() if s.placement})

    def placement_streams(self, placement: str) -> dict[str, Stream]:
        return {k: s for k, s in self.streams.items() if s.placement == placement}

    @property
    def t_start(self) -> float:
        return min((float(s.t[0]) for s in self.streams.values() if len(s)), default=0.0)

    @property
    def t_end(self) -> float:
        return max((float(s.t[-1]) for s in self.streams.values() if len(s)), default=0.0)

    @property
    def duration_s(self) -> float:
        return self.t_end - self.t_start

    @property
    def t_recording_start(self) -> float:
        """The recording's first sample (s): :attr:`t_start`, or before a ``--common-span`` cut (decision B81)
        the first sample of the files as recorded, so that times "from the session start" (``track --window``,
        L105) mean the same with and without the cut."""
        return self.t_start if self._t_start_uncut is None else min(self._t_start_uncut, self.t_start)

    def labelled(self, column: str) -> bool:
        """True when the steps table has ``column`` with at least one non-missing value."""
        return self.steps is not None and column in self.steps and self.steps[column].notna().any()

    def copy(self) -> Session:
        return copy.deepcopy(self)

    def _file_name(self, name: str) -> str:
        """The name of the file the stream ``name`` is read from (decision B369: ``.csv`` or ``.csv.gz``); the
        plain name for a session made in memory."""
        from pdrlearn.textfile import session_csv

        if self.folder is None:
            return SENSORS[name].filename
        try:
            return session_csv(self.folder, name).name
        except DataError:  # both there now: the reader refused that before; the plain one names it
            return SENSORS[name].filename

    def summary(self) -> dict:
        """Machine-readable summary (the ``pdrlearn info --json`` contract)."""
        from pdrlearn.io.validate import resolution

        sensors = {}
        for name, s in self.streams.items():
            gaps = s.gaps()
            sensors[name] = {
                "rate_hz": round(s.rate_hz, 4) if np.isfinite(s.rate_hz) else None,
                "samples": len(s),
                "duration_s": round(s.duration_s, 6),
                "gaps": len(gaps),
                "longest_gap_s": round(max((g.duration_s for g in gaps), default=0.0), 6),
                "unit": s.unit,
                "resolution": resolution(s.values, grid=True),  # B406: the smallest step (B412: None off a grid)
                "placement": s.placement,
                "file": self._file_name(name),  # decision B369: fAccelerometer.csv or fAccelerometer.csv.gz
            }
        labels: dict = {
            "steps": None if self.steps is None else int(len(self.steps)),
            "trajectory": None if self.trajectory is None else int(len(self.trajectory)),
        }
        if self.steps is not None:
            for col in ("terrain", "direction", "length_class"):
                if col in self.steps:
                    labels[col] = {str(k): int(v) for k, v in self.steps[col].value_counts().items()}
            if "length_m" in self.steps:
                labels["length_m_known"] = int(self.steps["length_m"].notna().sum())
        for k, df in self.extras.items():
            labels[k] = int(len(df))
        return {
            "name": self.name,
            "placements": self.placements,
            "sensors": sensors,
            "duration_s": round(self.duration_s, 6),
            "frames": {p: f.to_dict() for p, f in self.frames.items()},
            "labels": labels,
        }


#: True while a public entry point runs (decision B49): the entry points it calls on the same or derived
#: sessions (a pipeline's detectors, the windows of each training session) do not check again
_IN_ENTRY: ContextVar[bool] = ContextVar("pdrlearn_in_entry", default=False)


def as_session(obj, caller: str) -> Session:
    """Decision B51: ``obj`` as a :class:`Session`: a session as it is, a folder path (``str`` or
    :class:`os.PathLike`) read with :func:`pdrlearn.io.read_session`; anything else (a dict, a DataFrame, an
    array) is a :class:`~pdrlearn.errors.NotASessionError` (a ``TypeError`` and a ``DataError``) naming
    ``caller`` and how to get a session."""
    if isinstance(obj, Session):
        return obj
    if isinstance(obj, str | os.PathLike):
        from pdrlearn.io.plasys import read_session

        return read_session(obj)
    if isinstance(obj, bytes | bytearray):  # decision B395: its bytes were read as sessions ("got a int")
        raise NotASessionError(f"{caller}: got the bytes path {bytes(obj)!r}; pass a path as a str or "
                               "pathlib.Path (e.g. path.decode()), or a pdrlearn Session")
    what = type(obj).__name__
    what = f"{'an' if what[:1].lower() in 'aeiou' else 'a'} {what}"  # decision B395: "an int", not "a int"
    hint = ""
    if isinstance(obj, dict):
        hint = "; a dict of Streams becomes one with pdrlearn.io.Session(name=..., streams={name: Stream(...)})"
    elif isinstance(obj, pd.DataFrame):
        hint = "; a table of samples becomes one with `pdrlearn import FILE.csv --out SESSION`"
    raise NotASessionError(f"{caller}: expected a pdrlearn Session, got {what} (read one with "
                           f"pdrlearn.io.read_session(path), or pass the session folder's path){hint}")


def session_entry(fn=None, *, arg: int = 0, caller: str | None = None):
    """Decorator of a public entry point whose positional argument ``arg`` (or keyword ``session``) is a
    session (decisions B49, B51): the argument goes through :func:`as_session`, and the outermost entry point
    of a call checks it once (:meth:`Session.validate`); entry points called inside it do not check again
    (no repeated check in the pipelines' and the training's inner loops). ``caller`` names the entry point in
    errors (default: ``Class.method`` for a method, ``arg=1``, else the function's name)."""
    def deco(f):
        @functools.wraps(f)
        def wrapper(*args, **kwargs):
            name = caller or (f"{type(args[0]).__name__}.{f.__name__}" if arg == 1 and args else f.__name__)
            if len(args) > arg:
                args = (*args[:arg], as_session(args[arg], name), *args[arg + 1:])
            elif "session" in kwargs:
                kwargs["session"] = as_session(kwargs["session"], name)
            if _IN_ENTRY.get():
                return f(*args, **kwargs)
            session = args[arg] if len(args) > arg else kwargs.get("session")
            if session is not None:
                session.validate()
            token = _IN_ENTRY.set(True)
            try:
                return f(*args, **kwargs)
            finally:
                _IN_ENTRY.reset(token)
        return wrapper
    return deco(fn) if fn is not None else deco
