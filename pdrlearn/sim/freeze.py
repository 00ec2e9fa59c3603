"""Freezing of gait: trembling in place without a step (decision S51).

A :class:`FreezeEpisode` is planned by the ``freeze:SECONDS[:HZ[:ACC]]`` route item (:class:`pdrlearn.sim.path.Freeze`)
between two walking bouts, like S45's rides: the walker stops (the trailing foot closes beside the other), stands
:data:`FREEZE_MARGIN_S`, then the legs tremble in place for ``SECONDS`` with no progression, then it stands
:data:`FREEZE_MARGIN_S` again and walks on. No footstep happens: ``steps.csv`` and ``ics.csv`` have no row inside a
freeze, and the session gets ``freezes.csv`` (start_s, end_s, hz, acc_mps2).

The trembling (assumptions, not from a seed; the amplitude ratios are the session 29 trial's tremor script, which
reproduced the lower back's false steps): the legs alternate at ``hz`` (3-8 Hz: the "freeze" band of Moore et al.
2008, J Neurosci Methods 167:340-348, as recalled), the frequency drifting by :data:`FREEZE_DRIFT_HZ` at
:data:`FREEZE_DRIFT_RATE_HZ`. With ``acc`` the foot unit's peak acceleration (m/s^2):

* foot: a fore-aft oscillation of peak acceleration ``acc`` and a vertical one of 0.3 ``acc``, and a pitch
  oscillation about the unit of peak rate 0.5 ``acc`` rad/s (the trial's 0.5 x); the heel and forefoot loads
  alternate (each loses up to 60 % of its load, the trial's FORCE=1);
* waist: vertical peak acceleration 0.12 ``acc``, fore-aft 0.10 ``acc``, sideways 0.05 ``acc`` (the trial's ratios);
  the other leg trembles in antiphase, so the pelvis moves at the trembling frequency.

Each displacement's amplitude is its peak acceleration / (2 pi hz)^2 (a sine at the nominal frequency); the motion
fades in and out over :data:`FREEZE_FADE_S` (C1: no jump in the acceleration).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pdrlearn.errors import DataError

#: decision S51: the trembling's frequency band (Hz): Moore et al. 2008's "freeze" band (as published; not verified
#: against the paper text here); a given HZ must lie inside it
FREEZE_BAND_HZ = (3.0, 8.0)
#: decision S51: a drawn freeze's nominal frequency (Hz): inside the band with the drift added
FREEZE_DRAW_HZ = (3.5, 7.5)
#: decision S51: the drift of the frequency around its nominal value (Hz) and its rate (Hz) (the trial's script)
FREEZE_DRIFT_HZ = 0.5
FREEZE_DRIFT_RATE_HZ = 0.2
#: decision S51: a drawn freeze's foot peak acceleration (m/s^2): the trial's amplitudes 5-10 (its lower back read
#: false steps from 7 on); a given ACC must be positive and at most :data:`FREEZE_MAX_ACC`
FREEZE_DRAW_ACC = (5.0, 10.0)
FREEZE_MAX_ACC = 30.0
#: decision S51: the longest freeze accepted (s)
FREEZE_MAX_S = 600.0
#: decision S51: standing still before and after the trembling (s): the walker stops, then freezes
FREEZE_MARGIN_S = 0.5
#: decision S51: fade in / out of the trembling (s)
FREEZE_FADE_S = 0.3
#: decision S51: the trial's amplitude ratios - foot vertical, foot pitch rate (rad/s per m/s^2), waist vertical,
#: waist fore-aft, waist sideways, each x ``acc``
FOOT_VERTICAL, FOOT_PITCH_RATE, WAIST_VERTICAL, WAIST_AP, WAIST_LATERAL = 0.3, 0.5, 0.12, 0.10, 0.05
#: decision S51: the share of a foot's heel / forefoot load lost at the trembling's extreme (the trial's 0.6)
LOAD_SWING = 0.6


@dataclass(frozen=True)
class FreezeEpisode:
    """One freeze after the first ``after`` footsteps of the plan, starting ``delay_s`` after the feet came to rest
    (as :class:`pdrlearn.sim.transfer.Transfer`); ``heading_rad`` is the walker's facing, ``phases`` the foot's,
    the pelvis's three axes' and the drift's phases (rad)."""

    after: int
    delay_s: float
    duration_s: float
    hz: float
    acc_mps2: float
    heading_rad: float
    phases: tuple[float, float, float, float, float]


def check_freeze(duration_s, hz, acc, what: str) -> None:
    """One :class:`DataError` line naming ``what`` when the freeze's values are out of range (None = drawn)."""
    ok = isinstance(duration_s, int | float) and math.isfinite(duration_s) and 0 < duration_s <= FREEZE_MAX_S
    if not ok:
        raise DataError(f"{what}: a freeze lasts a positive number of seconds up to {FREEZE_MAX_S:g}, "
                        f"not {duration_s!r}")
    lo, hi = FREEZE_BAND_HZ
    if hz is not None and not (isinstance(hz, int | float) and math.isfinite(hz) and lo <= hz <= hi):
        raise DataError(f"{what}: the trembling's frequency must be {lo:g}-{hi:g} Hz (the freeze band), not {hz!r}")
    if acc is not None and not (isinstance(acc, int | float) and math.isfinite(acc) and 0 < acc <= FREEZE_MAX_ACC):
        raise DataError(f"{what}: the foot's trembling acceleration must be a positive number of m/s^2 up to "
                        f"{FREEZE_MAX_ACC:g}, not {acc!r}")


def draw_freeze(after: int, duration_s: float, hz: float | None, acc: float | None, heading_rad: float,
                rng: np.random.Generator, *, delay_s: float = FREEZE_MARGIN_S) -> FreezeEpisode:
    """A :class:`FreezeEpisode`; a frequency or amplitude not given is drawn from :data:`FREEZE_DRAW_HZ` /
    :data:`FREEZE_DRAW_ACC` (the phases always)."""
    u = rng.uniform(0.0, 1.0, 7)
    f = float(hz) if hz is not None else FREEZE_DRAW_HZ[0] + u[0] * (FREEZE_DRAW_HZ[1] - FREEZE_DRAW_HZ[0])
    a = float(acc) if acc is not None else FREEZE_DRAW_ACC[0] + u[1] * (FREEZE_DRAW_ACC[1] - FREEZE_DRAW_ACC[0])
    return FreezeEpisode(int(after), float(delay_s), float(duration_s), f, a, float(heading_rad),
                  tuple(float(v) for v in 2 * np.pi * u[2:7]))


def _phase_envelope(fz: FreezeEpisode, tau: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The trembling's phase (rad) and fade (0..1) ``tau`` seconds after the freeze's start."""
    w = 2 * np.pi * FREEZE_DRIFT_RATE_HZ
    drift = fz.phases[4]
    # phase = 2 pi * integral of (hz + drift sin(w s + p)) ds from 0 to tau
    phase = 2 * np.pi * (fz.hz * tau - FREEZE_DRIFT_HZ / w * (np.cos(w * tau + drift) - math.cos(drift)))
    x = np.clip(tau, 0.0, fz.duration_s)
    ramp = min(FREEZE_FADE_S, 0.5 * fz.duration_s)
    fade = np.minimum(np.clip(x / ramp, 0, 1), np.clip((fz.duration_s - x) / ramp, 0, 1))
    return phase, np.sin(0.5 * np.pi * fade) ** 2


def _active(t: np.ndarray, fz: FreezeEpisode, t0: float) -> np.ndarray:
    return (t > t0) & (t < t0 + fz.duration_s)


def freeze_foot(t: np.ndarray, freezes: list[FreezeEpisode], starts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The foot unit's trembling at ``t``: ENU position offset (n, 3) and pitch angle (n,) rad about the unit."""
    pos, pitch = np.zeros((t.size, 3)), np.zeros(t.size)
    for fz, t0 in zip(freezes, starts, strict=True):
        on = _active(t, fz, t0)
        if not on.any():
            continue
        phase, env = _phase_envelope(fz, t[on] - t0)
        om = 2 * np.pi * fz.hz
        d = fz.acc_mps2 / om**2  # displacement whose second derivative peaks at acc (nominal frequency)
        s = env * np.sin(phase + fz.phases[0])
        pos[on, 0] += math.cos(fz.heading_rad) * d * s
        pos[on, 1] += math.sin(fz.heading_rad) * d * s
        pos[on, 2] += FOOT_VERTICAL * d * env * np.sin(phase + fz.phases[0] + 0.5 * np.pi)
        pitch[on] += FOOT_PITCH_RATE * fz.acc_mps2 / om * env * np.sin(phase + fz.phases[0])
    return pos, pitch


def freeze_pelvis(t: np.ndarray, freezes: list[FreezeEpisode], starts: np.ndarray) -> np.ndarray:
    """The pelvis's (waist unit's) ENU position offset (n, 3) of the trembling at ``t``."""
    pos = np.zeros((t.size, 3))
    for fz, t0 in zip(freezes, starts, strict=True):
        on = _active(t, fz, t0)
        if not on.any():
            continue
        phase, env = _phase_envelope(fz, t[on] - t0)
        d = fz.acc_mps2 / (2 * np.pi * fz.hz) ** 2
        ap = WAIST_AP * d * env * np.sin(phase + fz.phases[1])
        lat = WAIST_LATERAL * d * env * np.sin(phase + fz.phases[2])
        c, s_ = math.cos(fz.heading_rad), math.sin(fz.heading_rad)
        pos[on, 0] += c * ap - s_ * lat
        pos[on, 1] += s_ * ap + c * lat
        pos[on, 2] += WAIST_VERTICAL * d * env * np.sin(phase + fz.phases[3])
    return pos


def freeze_loads(t: np.ndarray, heel: np.ndarray, fore: np.ndarray, freezes: list[FreezeEpisode],
                 starts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The heel and forefoot loads with the trembling's alternating weight shift (the trial's FORCE=1)."""
    heel, fore = heel.copy(), fore.copy()
    for fz, t0 in zip(freezes, starts, strict=True):
        on = _active(t, fz, t0)
        if not on.any():
            continue
        phase, env = _phase_envelope(fz, t[on] - t0)
        s = np.sin(phase + fz.phases[0])
        heel[on] *= 1.0 - env * LOAD_SWING * 0.5 * (1.0 + s)
        fore[on] *= 1.0 - env * LOAD_SWING * 0.5 * (1.0 - s)
    return heel, fore


def freeze_table(freezes: list[FreezeEpisode], starts: np.ndarray) -> list[dict]:
    """Rows of ``freezes.csv``: start and end of the trembling (s), its nominal frequency and foot amplitude."""
    return [{"start_s": float(t0), "end_s": float(t0 + fz.duration_s), "hz": round(fz.hz, 6),
             "acc_mps2": round(fz.acc_mps2, 6)} for fz, t0 in zip(freezes, starts, strict=True)]
