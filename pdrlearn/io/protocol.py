"""Streaming parser of the foot unit's Bluetooth text protocol (thesis ch.4.2.3, Table 10).

Each sampling period (50 ms, 20 Hz) the foot unit sends one *set*::

    %$1 ax ay az$2 gx gy gz$3 fa$4 fb

``%`` starts a set, ``$`` starts a measurement, the digit is the sensor type (Table 10: 1 accelerometer,
2 gyroscope, 3 force A, 4 force B) and the numbers are separated by blanks or commas (force: ``x`` only).
The protocol carries no timestamp: set *k* is stamped ``t0 + k / rate_hz``. A lost set (a Bluetooth packet
that never arrived) cannot be seen and shifts every later sample one period early (decision E91), unless the set
carries the optional sequence number of decision E91, ``%#N$1 ...``: text between ``%`` and the first ``$`` was
always ignored, so old parsers read such a capture unchanged; here ``N`` (counting sets, wrapping at
:data:`SEQ_MODULUS`) stamps the set and a jump counts the sets lost in :attr:`ProtocolStats.lost`.

Corrupted measurements (unknown type, wrong number of values, non-numeric text, a value beyond any sensor's
range: decision B432, B425's :func:`~pdrlearn.kernels.units.out_of_range`) are skipped and counted
in :attr:`BluetoothParser.stats` (the first one's line in ``first_line``); the set still advances the clock, so
a corrupted set leaves a gap instead of shifting later samples.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field

import numpy as np

from pdrlearn.io.sensors import PROTOCOL_TYPES, SENSORS
from pdrlearn.io.session import Session, Stream
from pdrlearn.kernels.units import out_of_range

FIRMWARE_RATE_HZ = 20.0  # thesis ch.4.2.3: sampling period 50 ms
#: decision E90: the lags (s) searched for the foot's stride period in a capture (a stride from 480 down to 30
#: steps/min: wider than L95's walking range on both sides, so that a capture read at a wrong rate is still timed)
STRIDE_LAGS_S = (0.25, 4.0)
_SPLIT = re.compile(r"[\s,;]+")
#: decision E91: a set's optional sequence number, ``#N`` after its ``%``; a 16-bit counter wraps at this
_SEQ = re.compile(r"\s*#(\d+)")
SEQ_MODULUS = 65536


@dataclass
class ProtocolStats:
    sets: int = 0
    measurements: int = 0
    corrupted: int = 0
    examples: list[str] = field(default_factory=list)
    #: decision E91: sets with a sequence number, and the sets their jumps say were lost
    numbered: int = 0
    lost: int = 0
    #: decision B432: the capture line (1-based) of the first corrupted measurement, 0 when none
    first_line: int = 0

    def to_dict(self) -> dict:
        return {"sets": self.sets, "measurements": self.measurements, "corrupted": self.corrupted,
                "numbered": self.numbered, "lost": self.lost}


@dataclass
class Measurement:
    t: float
    sensor: str
    values: tuple[float, ...]


class BluetoothParser:
    """Incremental parser: :meth:`feed` text chunks as they arrive, :meth:`close` at the end.

    Parameters
    ----------
    rate_hz : sampling rate of the sets (default 20 Hz, thesis ch.4.2.3).
    t0 : timestamp of the first set (s).
    scales : optional per-sensor multiplicative factor to SI units, e.g.
        ``{"fAccelerometer": 9.81 / 256}`` for raw ADXL345 counts (thesis eq. 24).
    """

    def __init__(self, *, rate_hz: float = FIRMWARE_RATE_HZ, t0: float = 0.0, scales: dict | None = None):
        self.rate_hz = float(rate_hz)
        self.t0 = float(t0)
        self.scales = dict(scales or {})
        self.stats = ProtocolStats()
        self._buf = ""
        self._started = False
        self._data: dict[str, tuple[list[float], list[tuple[float, ...]]]] = {}
        self._k = -1  # the clock index of the last set (sets + lost - 1)
        self._seq: int | None = None  # the last sequence number read (decision E91)
        self._line = 1  # decision B432: the capture line where self._buf starts
        self._set_line = 1  # and the line of the current set's '%'

    # -- parsing ----------------------------------------------------------------------------------
    def _next_index(self, body: str) -> int | None:
        """Decision E91: the clock index of a set: the next one, or, with a sequence number, the next plus the sets
        its jump skipped (counted lost); None for a repeated number (a packet received twice: skipped, counted
        corrupted); a number that jumps backwards (a restart) is counted corrupted and the set taken as the next."""
        m = _SEQ.match(body)
        step = 1
        if m is not None:
            n = int(m.group(1))
            self.stats.numbered += 1
            if self._seq is not None:
                d = (n - self._seq) % SEQ_MODULUS
                if d == 0:
                    self._corrupt(m.group(0))
                    return None
                if d < SEQ_MODULUS // 2:
                    step = d
                    self.stats.lost += d - 1
                else:
                    self._corrupt(m.group(0))
            self._seq = n
        self._k += step
        return self._k

    def _parse_set(self, body: str) -> list[Measurement]:
        k = self._next_index(body)
        self.stats.sets += 1
        if k is None:  # decision E91: a repeated set
            return []
        t = self.t0 + k / self.rate_hz
        out = []
        for part in body.split("$")[1:] if "$" in body else ([body] if body.strip() else []):
            tokens = [tok for tok in _SPLIT.split(part.strip()) if tok]
            sensor = PROTOCOL_TYPES.get(int(tokens[0])) if tokens and tokens[0].isdigit() else None
            n = SENSORS[sensor].n_axes if sensor else 0
            try:
                vals = tuple(float(x) for x in tokens[1:])
            except ValueError:
                vals = ()
            scale = self.scales.get(sensor, 1.0)
            if (sensor is None or len(vals) != n or not all(np.isfinite(vals))
                    or out_of_range(SENSORS[sensor].kind, np.array(vals), scale).size):  # decision B432 (B425)
                self._corrupt(part)
                continue
            m = Measurement(t, sensor, tuple(v * scale for v in vals))
            ts, vs = self._data.setdefault(sensor, ([], []))
            if ts and ts[-1] == t:  # a second measurement of the same sensor in one set
                self._corrupt(part)
                continue
            ts.append(t)
            vs.append(m.values)
            self.stats.measurements += 1
            out.append(m)
        return out

    def _corrupt(self, text: str, line: int | None = None) -> None:
        self.stats.corrupted += 1
        if not self.stats.first_line:
            self.stats.first_line = self._set_line if line is None else line
        if len(self.stats.examples) < 5:
            self.stats.examples.append(text.strip()[:60])

    def feed(self, chunk: str) -> list[Measurement]:
        """Parse a chunk of received text; returns the measurements of every set completed by it."""
        self._buf += chunk
        out: list[Measurement] = []
        while True:
            i = self._buf.find("%")
            if i < 0:
                if not self._started and self._buf.strip():
                    # text before the first '%' is not part of any set
                    self._corrupt(self._buf, self._line)
                    self._line += self._buf.count("\n")
                    self._buf = ""
                return out
            head, rest = self._buf[:i], self._buf[i + 1:]
            if self._started:
                out.extend(self._parse_set(head))
            elif head.strip():
                self._corrupt(head, self._line)
            self._line += head.count("\n")  # decision B432: the line of the next set's '%'
            self._set_line = self._line
            self._started = True
            self._buf = rest

    def close(self) -> list[Measurement]:
        """Flush the last set."""
        out = self._parse_set(self._buf) if self._started and self._buf.strip() else []
        self._buf = ""
        return out

    def parse(self, lines: Iterable[str]) -> Iterator[Measurement]:
        for line in lines:
            yield from self.feed(line)
        yield from self.close()

    # -- results ----------------------------------------------------------------------------------
    def streams(self) -> dict[str, Stream]:
        return {name: Stream(name, np.array(ts), np.array(vs)) for name, (ts, vs) in self._data.items() if ts}

    def to_session(self, name: str = "bluetooth") -> Session:
        from pdrlearn.io.frames import THESIS_FOOT_FRAME

        return Session(name=name, streams=self.streams(),
                       meta={"source": "bluetooth text protocol", "protocol_stats": self.stats.to_dict()},
                       frames={"foot": THESIS_FOOT_FRAME})


def parse_protocol(text: str | Iterable[str], **kwargs) -> tuple[Session, ProtocolStats]:
    """Parse a whole protocol capture (a string or an iterable of lines)."""
    parser = BluetoothParser(**kwargs)
    for _ in parser.parse([text] if isinstance(text, str) else text):
        pass
    return parser.to_session(), parser.stats


def format_protocol(session: Session, *, decimals: int = 6, numbered: bool = False) -> Iterator[str]:
    """Render a session's foot streams as protocol sets (one line per set), the inverse of the parser.

    Streams are aligned by sample index; all foot streams must have the same length. ``numbered``: each set
    carries its sequence number (``%#N``, decision E91).
    """
    names = [n for n in PROTOCOL_TYPES.values() if n in session.streams]
    inv = {v: k for k, v in PROTOCOL_TYPES.items()}
    n = min(len(session.streams[nm]) for nm in names) if names else 0
    for i in range(n):
        parts = []
        for nm in names:
            vals = " ".join(f"{v:.{decimals}f}" for v in session.streams[nm].values[i])
            parts.append(f"${inv[nm]} {vals}")
        yield "%" + (f"#{i % SEQ_MODULUS}" if numbered else "") + "".join(parts) + "\n"


def protocol_rate_line(streams: dict[str, Stream], rate_hz: float, where: str) -> str | None:
    """Decision E90: the warning line when the foot's stride rhythm in a capture stamped at ``rate_hz`` (the
    protocol carries no time, D5; ``streams``: :meth:`BluetoothParser.streams`) lies outside L95's walking range:
    the pod samples at another rate. The rhythm is the first dominant autocorrelation peak of the foot gyroscope's
    magnitude (W113's estimator, Moe-Nilssen & Helbostad 2004, over :data:`STRIDE_LAGS_S`); the rate that would put
    it at the middle of the range is named. None when the rhythm is inside the range or not found (under 10 s of
    gyroscope, no rhythmic motion)."""
    from pdrlearn.kernels.waist import step_period_s
    from pdrlearn.track.gait import CADENCE_RANGE_SPM

    g = streams.get("fGyroscope")
    if g is None or len(g.t) < 10 * rate_hz:
        return None
    stride_s = step_period_s(np.linalg.norm(g.values, axis=1), rate_hz, lags_s=STRIDE_LAGS_S)
    if not np.isfinite(stride_s):
        return None
    cadence = 120.0 / stride_s  # steps/min: a stride is two steps
    lo, hi = CADENCE_RANGE_SPM
    if lo <= cadence <= hi:
        return None
    mid = float(np.sqrt(lo * hi))  # the range's geometric middle: the rate error is a factor
    return (f"{where}: at --protocol-rate {rate_hz:g} Hz the foot's strides take {stride_s:.2f} s ({cadence:.0f} "
            f"steps/min), outside the walking range {lo:.0f}-{hi:.0f} steps/min (decision L95): the distance, "
            "speeds and floors are wrong if the pod samples at another rate (the protocol carries no time, D5); give "
            f"its rate with --protocol-rate HZ (this rhythm is {mid:.0f} steps/min at about "
            f"{rate_hz * mid / cadence:.0f} Hz; decision E90)")
