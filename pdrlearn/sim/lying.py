"""Lying down in bed, turning over, getting up again: the trunk motion of a ``lie`` route item (decisions S58, S59).

A ``lie:SECONDS[:TURNS_PER_H]`` route item (:class:`pdrlearn.sim.path.Lie`) is S36's ``sit`` on the edge of a bed
with a lying episode inside the seated time: the walker stops, sits down on the bed edge (S36's sit-down, a
``transfers.csv`` row), sits :data:`BED_SIT_S`, lies down (sit-to-lie), lies ``SECONDS`` turning over now and then,
sits up (lie-to-sit), sits :data:`BED_SIT_S` and stands up (S36's stand-up). No footstep happens and the foot unit
rests on the floor (its lift onto the bed is not modelled, as S36's loads are not: a known simplification).

The waist unit (decision S58), on top of the seated pelvis of S36, rotated in the body frame by
``Ry(recline) Rz(yaw) Ry(-pitch) Rz(roll)``:

* sit-to-lie over :data:`LIE_DOWN_S`: the seated recline is undone while the trunk turns by ``yaw`` = +-90 deg about
  the vertical (to lie along the bed; the side drawn) and pitches back until it is :data:`LIE_TILT_DEG` from the
  vertical (``pitch``, the whole tilt), and the pelvis
  slides :data:`LIE_BACK_M` back onto the bed; the three follow one C2 smoothstep, so the gravity vector in the
  waist unit goes from its up axis to horizontal; lie-to-sit is the same movement backwards (drawn separately);
* lying supine the roll is 0; turning over (decision S59) is a roll of the trunk about the body's long axis (its up
  axis after the pitch) by the shortest way to the next posture (supine 0, left side +90, right side -90, prone 180
  deg; :data:`POSTURE_WEIGHTS`), a smoothstep over :data:`ROLL_S`; the turns come at the times of a Poisson process
  of ``TURNS_PER_H`` per hour (default :data:`TURNS_PER_H`), none within :data:`ROLL_GAP_S` of the lying's start or
  end or of each other; the sit-up undoes the roll left (the nearest whole turn) with the pitch.

Ranges (drawn per episode, uniform) are assumptions, not from a seed: a bed is sat on and lain on as a chair seat is
(S36's ranges for the bed edge); 2-4 s for lying down or sitting up and 1.5-3.5 s for a turn are the order of the
bed-mobility timings in the rehabilitation literature as recalled, not checked against a text in this session; the
position-shift rate default (2 per hour) is the order reported for healthy adults' sleep as recalled (De Koninck,
Lorrain & Gagnon 1992, Sleep 15:143-149: fewer shifts with age), not checked.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pdrlearn.errors import DataError
from pdrlearn.sim.kernels import smoothstep

#: decision S58: seated on the bed edge before lying down and after sitting up (s)
BED_SIT_S = (1.0, 3.0)
#: decision S58: duration of lying down (sit-to-lie) and of sitting up (lie-to-sit) (s), each drawn on its own
LIE_DOWN_S = (2.0, 4.0)
#: decision S58: the lying trunk's tilt from the vertical (deg): a lumbar spine on a mattress, a pillow or not
LIE_TILT_DEG = (85.0, 95.0)
#: decision S58: the pelvis sliding back onto the bed while lying down (m)
LIE_BACK_M = (0.15, 0.30)
#: decision S59: default number of turns (position shifts) per hour while lying
TURNS_PER_H = 2.0
#: decision S59: the most turns per hour accepted (one a minute: restless, still a posture between two turns)
MAX_TURNS_PER_H = 60.0
#: decision S59: duration of one turn over (s)
ROLL_S = (1.5, 3.5)
#: decision S59: no turn within this of the lying's start or end or of another turn's end (s)
ROLL_GAP_S = 5.0
#: decision S59: the lying postures and their roll about the long axis (deg) ...
POSTURES = {"supine": 0.0, "left": 90.0, "right": -90.0, "prone": 180.0}
#: ... and the weights of the next posture after a turn (the current one excluded; an assumption: prone is rare)
POSTURE_WEIGHTS = {"supine": 0.35, "left": 0.3, "right": 0.3, "prone": 0.05}
#: decisions S58, S61: the longest lying (and seated, S61) time accepted (s): one day
MAX_LIE_S = 86_400.0


@dataclass(frozen=True)
class LyingEpisode:
    """The lying inside the bed-edge sit after the first ``after`` footsteps, starting (sit-to-lie) ``delay_s`` after
    the feet came to rest (as a :class:`~pdrlearn.sim.transfer.Transfer`, so that ``transfer_starts`` places it).
    Roll times are from the start of the lying (``lying_s`` after ``down_s``)."""

    after: int
    delay_s: float
    down_s: float
    lying_s: float
    up_s: float
    yaw_rad: float
    pitch_rad: float
    recline_rad: float
    back_m: float
    heading_rad: float
    roll_starts: tuple[float, ...]
    roll_durations: tuple[float, ...]
    roll_angles: tuple[float, ...]  # the roll after each turn (rad, unwrapped)
    postures: tuple[str, ...]  # the posture before the first turn and after each

    @property
    def total_s(self) -> float:
        return self.down_s + self.lying_s + self.up_s


def check_lie(seconds: float, turns_per_h: float | None, where: str) -> None:
    """One :class:`DataError` line for a lying time or a turn rate out of range (``where`` names the item)."""
    if not (math.isfinite(seconds) and 0 < seconds <= MAX_LIE_S):
        raise DataError(f"{where}: the lying time must be more than 0 and at most {MAX_LIE_S:g} s (a day)")
    if turns_per_h is not None and not (math.isfinite(turns_per_h) and 0 <= turns_per_h <= MAX_TURNS_PER_H):
        raise DataError(f"{where}: TURNS_PER_H must be 0-{MAX_TURNS_PER_H:g} turns per hour (0 = never turns over)")


def _pick(lo_hi: tuple[float, float], u: float) -> float:
    return lo_hi[0] + u * (lo_hi[1] - lo_hi[0])


def draw_lying(after: int, delay_s: float, lying_s: float, turns_per_h: float | None, recline_rad: float,
               heading_rad: float, rng: np.random.Generator) -> LyingEpisode:
    """A :class:`LyingEpisode` with the module's ranges drawn from ``rng``; ``recline_rad`` is the seated pelvis's
    own backward tilt (S36), undone while lying down so that the drawn :data:`LIE_TILT_DEG` is the trunk's tilt."""
    u = rng.uniform(0.0, 1.0, 5)
    rate = TURNS_PER_H if turns_per_h is None else float(turns_per_h)
    starts, durations, angles, postures = [], [], [], ["supine"]
    t, roll = ROLL_GAP_S, 0.0
    names = list(POSTURES)
    while rate > 0:
        t += rng.exponential(3600.0 / rate)  # decision S59: a Poisson process of ``rate`` per hour
        d = _pick(ROLL_S, float(rng.uniform()))
        if t + d > lying_s - ROLL_GAP_S:
            break
        w = np.array([0.0 if n == postures[-1] else POSTURE_WEIGHTS[n] for n in names])
        nxt = names[int(rng.choice(len(names), p=w / w.sum()))]
        step = (POSTURES[nxt] - POSTURES[postures[-1]] + 180.0) % 360.0 - 180.0  # the shortest way round
        if step == -180.0:  # supine <-> prone: either side, drawn
            step = 180.0 if rng.uniform() < 0.5 else -180.0
        roll += math.radians(step)
        starts.append(t)
        durations.append(d)
        angles.append(roll)
        postures.append(nxt)
        t += d + ROLL_GAP_S
    return LyingEpisode(
        after=int(after), delay_s=float(delay_s), down_s=_pick(LIE_DOWN_S, u[0]), lying_s=float(lying_s),
        up_s=_pick(LIE_DOWN_S, u[1]), yaw_rad=math.radians(90.0 if u[2] < 0.5 else -90.0),
        pitch_rad=math.radians(_pick(LIE_TILT_DEG, u[3])), recline_rad=float(recline_rad),
        back_m=_pick(LIE_BACK_M, u[4]),
        heading_rad=float(heading_rad), roll_starts=tuple(starts), roll_durations=tuple(durations),
        roll_angles=tuple(angles), postures=tuple(postures))


def lying_angles(t: np.ndarray, episodes: list[LyingEpisode], starts: np.ndarray) -> tuple[np.ndarray, ...]:
    """(undone recline, yaw, backward pitch, roll) (rad) and the backward slide (m) of the lying episodes at times
    ``t`` (a pure kernel: every value depends on its own time only)."""
    unrecline, yaw, pitch, roll, back = (np.zeros_like(t) for _ in range(5))
    for ep, t0 in zip(episodes, starts, strict=True):
        t_lie, t_up = t0 + ep.down_s, t0 + ep.down_s + ep.lying_s
        m = (t >= t0) & (t <= t_up + ep.up_s)
        if not m.any():
            continue
        tt = t[m]
        # the lying phase: 0 seated -> 1 lying; sitting up runs it backwards
        v = smoothstep(np.where(tt < t_up, (tt - t0) / ep.down_s, 1.0 - (tt - t_up) / ep.up_s))
        unrecline[m] += ep.recline_rad * v
        yaw[m] += ep.yaw_rad * v
        pitch[m] += ep.pitch_rad * v
        back[m] += ep.back_m * v
        r = np.zeros_like(tt)
        prev = 0.0
        for s, d, a in zip(ep.roll_starts, ep.roll_durations, ep.roll_angles, strict=True):
            r += (a - prev) * smoothstep((tt - t_lie - s) / d)
            prev = a
        # sitting up undoes the roll left to the nearest whole turn, with the pitch
        home = 2.0 * math.pi * round(prev / (2.0 * math.pi))
        r += (home - prev) * smoothstep((tt - t_up) / ep.up_s)
        roll[m] += r
    return unrecline, yaw, pitch, roll, back


def lying_rotation(unrecline: np.ndarray, yaw: np.ndarray, pitch: np.ndarray, roll: np.ndarray) -> np.ndarray:
    """``Ry(unrecline) @ Rz(yaw) @ Ry(-pitch) @ Rz(roll)`` (n, 3, 3): the seated recline undone, turned about the
    vertical, pitched back, rolled about the lying trunk's long axis (body frame, right-multiplied onto the seated
    orientation)."""
    cz, sz, cy, sy, cr, sr = np.cos(yaw), np.sin(yaw), np.cos(pitch), -np.sin(pitch), np.cos(roll), np.sin(roll)
    out = np.empty((yaw.size, 3, 3))
    # Rz(yaw) @ Ry(beta) with beta = -pitch
    a = np.empty((yaw.size, 3, 3))
    a[:, 0, 0], a[:, 0, 1], a[:, 0, 2] = cz * cy, -sz, cz * sy
    a[:, 1, 0], a[:, 1, 1], a[:, 1, 2] = sz * cy, cz, sz * sy
    a[:, 2, 0], a[:, 2, 1], a[:, 2, 2] = -sy, 0.0, cy
    # ... @ Rz(roll)
    out[:, :, 0] = a[:, :, 0] * cr[:, None] + a[:, :, 1] * sr[:, None]
    out[:, :, 1] = -a[:, :, 0] * sr[:, None] + a[:, :, 1] * cr[:, None]
    out[:, :, 2] = a[:, :, 2]
    # Ry(unrecline) @ ...
    cu, su = np.cos(unrecline)[:, None], np.sin(unrecline)[:, None]
    top, bottom = out[:, 0, :].copy(), out[:, 2, :].copy()
    out[:, 0, :] = cu * top + su * bottom
    out[:, 2, :] = -su * top + cu * bottom
    return out


def lying_table(episodes: list[LyingEpisode], starts: np.ndarray) -> list[dict]:
    """Rows of ``lying.csv``: the sit-to-lie start, lying reached, lie-to-sit start and seated again (s), the
    posture lain down in and the one sat up from, the number of turns."""
    return [{"start_s": float(t0), "lying_s": float(t0 + ep.down_s), "rise_s": float(t0 + ep.down_s + ep.lying_s),
             "end_s": float(t0 + ep.total_s), "first_posture": ep.postures[0], "last_posture": ep.postures[-1],
             "n_turns": len(ep.roll_starts)} for ep, t0 in zip(episodes, starts, strict=True)]


def roll_table(episodes: list[LyingEpisode], starts: np.ndarray) -> list[dict]:
    """Rows of ``rolls.csv``: each turn over's start and end (s), the posture before and after, its angle (deg,
    > 0 toward the left side)."""
    rows = []
    for ep, t0 in zip(episodes, starts, strict=True):
        prev = 0.0
        for k, (s, d, a) in enumerate(zip(ep.roll_starts, ep.roll_durations, ep.roll_angles, strict=True)):
            rows.append({"start_s": float(t0 + ep.down_s + s), "end_s": float(t0 + ep.down_s + s + d),
                         "from_posture": ep.postures[k], "to_posture": ep.postures[k + 1],
                         "angle_deg": round(math.degrees(a - prev), 4)})
            prev = a
    return rows
