"""Sitting down on a chair and standing up again: the pelvis motion of a sit-to-stand transfer (decision S36).

A :class:`Transfer` is planned by the ``sit:S`` route item (:class:`pdrlearn.sim.path.Sit`) between two walking
bouts; the feet stay flat and still (no footstep), only the pelvis moves:

* sitting down (``down_s``): the trunk pitches forward by ``flexion_rad`` and back upright (a smooth bell) while the
  pelvis lowers by ``drop_m`` and moves ``back_m`` backward onto the seat (smooth ramps, the lowering starting after
  the first ``LOWER_DELAY`` of the movement, when the trunk is already leaning forward);
* seated ``seat_s`` seconds, the waist unit reclined by ``recline_rad`` (posterior pelvic tilt);
* standing up (``up_s``): the mirror image in time of sitting down (trunk forward, seat-off, rise, trunk upright).

Ranges (drawn per transfer, uniform). Not from a seed: the durations and the trunk flexion follow the ranges
reported for healthy adults in the sit-to-stand literature as recalled from Janssen, Bussmann & Stam 2002
("Determinants of the sit-to-stand movement: a review", Phys Ther 82:866-879) and Schenkman et al. 1990 (Phys Ther
70:638-648, the four phases: flexion momentum, momentum transfer, extension, stabilisation) - not checked against
the texts in this session. The pelvis drop is the difference between standing hip height (~0.9 m) and a chair seat
(~0.45 m); the backward shift onto the seat and the seated recline are assumptions of this model.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from pdrlearn.sim.kernels import smoothstep

TRANSFER_S = (1.5, 2.5)  # duration of sitting down / standing up (s), each drawn on its own (the default of S95's knob)
#: decision S95: the range ``simulate --transfer-time LO:HI`` accepts (s): a frail person's 3-6 s sit-to-stand and
#: slower; above 10 s one movement is no longer one transfer
TRANSFER_TIME_RANGE_S = (0.5, 10.0)
FLEXION_DEG = (30.0, 45.0)  # peak forward trunk (waist unit) pitch during the movement
DROP_M = (0.40, 0.50)  # pelvis lowering from standing to seated
BACK_M = (0.10, 0.20)  # pelvis moving backward onto the seat (assumption)
RECLINE_DEG = (3.0, 10.0)  # seated posterior tilt of the waist unit (assumption)
SIT_MARGIN_S = 0.5  # standing still before sitting down and after standing up
LOWER_DELAY = 0.2  # fraction of the sit-down before the pelvis starts to lower (trunk leans first)
#: decision S43: the seated trunk of a session that starts or ends seated leans forward by this much (deg; the session
#: 26 brief's 10-25 deg, e.g. sitting at a desk; an assumption like S36's recline, not from a seed)
SEATED_FLEXION_DEG = (10.0, 25.0)
#: decision S43: a session that starts seated has been seated this long before its first sample (s), so that the
#: recording starts with the pelvis at rest
SEATED_BEFORE_S = 1.0


@dataclass(frozen=True)
class Transfer:
    """One sit-down / seated / stand-up episode after the first ``after`` footsteps of the plan.

    It starts ``delay_s`` after the feet have come to rest following footstep ``after - 1`` (or after the
    initial standstill when ``after`` is 0)."""

    after: int
    delay_s: float
    down_s: float
    seat_s: float
    up_s: float
    flexion_rad: float
    drop_m: float
    back_m: float
    recline_rad: float

    @property
    def total_s(self) -> float:
        """Sitting down + seated + standing up (s)."""
        return self.down_s + self.seat_s + self.up_s


def draw_transfer(after: int, delay_s: float, seat_s: float, rng: np.random.Generator,
                  transfer_s: tuple[float, float] = TRANSFER_S) -> Transfer:
    """A :class:`Transfer` with the module's ranges drawn from ``rng``; ``transfer_s`` the range of the sitting-down
    and standing-up durations (s; decision S95: ``simulate --transfer-time LO:HI``, a frail person's 3-6 s)."""
    u = rng.uniform(0.0, 1.0, 6)

    def pick(lo_hi: tuple[float, float], x: float) -> float:
        return lo_hi[0] + x * (lo_hi[1] - lo_hi[0])

    return Transfer(
        after=int(after),
        delay_s=float(delay_s),
        down_s=pick(transfer_s, u[0]),
        seat_s=float(seat_s),
        up_s=pick(transfer_s, u[1]),
        flexion_rad=math.radians(pick(FLEXION_DEG, u[2])),
        drop_m=pick(DROP_M, u[3]),
        back_m=pick(BACK_M, u[4]),
        recline_rad=math.radians(pick(RECLINE_DEG, u[5])),
    )


def transfer_starts(transfers: list[Transfer], rest: np.ndarray, stand_s: float) -> np.ndarray:
    """Start time (s) of each transfer: ``delay_s`` after the feet's last rest before it (``rest`` = the
    schedule's per-footstep rest times; ``stand_s`` = the initial standstill), as ``body.schedule`` settles."""
    return np.array(
        [max([stand_s, *rest[: tr.after]]) + tr.delay_s for tr in transfers], dtype=float
    )


def _bell(u: np.ndarray) -> np.ndarray:
    """0 -> 1 -> 0 on ``u`` in [0, 1], C2 (two quintic ramps)."""
    return smoothstep(2.0 * u) - smoothstep(2.0 * u - 1.0)


def transfer_motion(t: np.ndarray, transfers: list[Transfer], starts: np.ndarray) -> tuple[np.ndarray, ...]:
    """Pelvis offsets of the transfers at times ``t``: (backward shift m, lowering m, pitch rad, > 0 forward)."""
    back, down, pitch = np.zeros_like(t), np.zeros_like(t), np.zeros_like(t)
    for tr, t0 in zip(transfers, starts, strict=True):
        t_up = t0 + tr.down_s + tr.seat_s
        m = (t >= t0) & (t <= t_up + tr.up_s)
        if not m.any():
            continue
        tt = t[m]
        # the phase of the sitting-down movement: 0 standing -> 1 seated; standing up runs it backwards
        v = np.where(tt < t_up, (tt - t0) / tr.down_s, 1.0 - (tt - t_up) / tr.up_s)
        v = np.clip(v, 0.0, 1.0)
        seated = smoothstep(v)
        back[m] += tr.back_m * seated
        down[m] += tr.drop_m * smoothstep((v - LOWER_DELAY) / (1.0 - LOWER_DELAY))
        pitch[m] += tr.flexion_rad * _bell(v) - tr.recline_rad * seated
    return back, down, pitch


def transfer_table(transfers: list[Transfer], starts: np.ndarray) -> list[dict]:
    """Rows of the ``transfers`` label table: start, seated, seat-off and end times (s) of each transfer."""
    rows = []
    for tr, t0 in zip(transfers, starts, strict=True):
        rows.append({
            "start_s": float(t0),
            "seated_s": float(t0 + tr.down_s),
            "rise_s": float(t0 + tr.down_s + tr.seat_s),
            "end_s": float(t0 + tr.total_s),
            "flexion_deg": round(math.degrees(tr.flexion_rad), 4),
            "drop_m": round(tr.drop_m, 6),
        })
    return rows


def session_sits(sit_start_s: float, sit_end_s: float, rng: np.random.Generator,
                 transfer_s: tuple[float, float] = TRANSFER_S) -> tuple[Transfer | None, ...]:
    """Decision S43: the transfers of a session that starts seated ``sit_start_s`` seconds (then stands up) and / or
    ends seated ``sit_end_s`` seconds (after sitting down); None for a zero time. Drawn as :func:`draw_transfer`'s,
    except the seated posture: a forward lean of :data:`SEATED_FLEXION_DEG` (a negative ``recline_rad``). The first
    is seated from :data:`SEATED_BEFORE_S` before the recording (``seat_s`` counts it); the last stays seated past
    the recording's end (its stand-up is never reached). Place them with :func:`session_sit_starts`."""
    out = []
    for seat in (sit_start_s, sit_end_s):
        if seat > 0:
            tr = draw_transfer(0, 0.0, float(seat) + SEATED_BEFORE_S, rng, transfer_s)
            out.append(replace(tr, recline_rad=-math.radians(float(rng.uniform(*SEATED_FLEXION_DEG)))))
        else:
            out.append(None)
    return tuple(out)


def session_sit_starts(first: Transfer | None, last: Transfer | None, end_s: float) -> list[float]:
    """Start times (s) of :func:`session_sits`' transfers: the first sits down before the recording so that it rises
    at ``seat_s - SEATED_BEFORE_S``; the last starts sitting down at ``end_s`` (the end of the last standstill)."""
    return ([-first.down_s - SEATED_BEFORE_S] if first else []) + ([end_s] if last else [])
