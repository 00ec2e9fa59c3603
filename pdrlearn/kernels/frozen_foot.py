"""A foot IMU that never moves beside force sensors that step (decisions B203, B213 in docs/decisions/bad-input.md).

B203 (offline, ``pdrlearn.track.foot_rest.frozen_foot_imu``): the force sensors (fForceA / fForceB) load
:data:`FORCE_STEPS_MIN` times or more while the foot IMU does not move (sd of |acc| at most B37's
:data:`~pdrlearn.kernels.units.WALKING_ACC_STD`, B91's swing statistic under
:data:`~pdrlearn.kernels.units.FOOT_NO_SWING`): a frozen or disconnected IMU, every stride of which would integrate to
0 m. :func:`frozen_foot_evidence` is that test on arrays, shared by the offline check (the whole session) and the
live ``Tracker`` (:class:`pdrlearn.runtime.guard.FrozenFootWatch`, B213: blocks of :data:`LIVE_BLOCK_S` of stream
time). numpy only (runtime boundary).
"""

from __future__ import annotations

import numpy as np

from pdrlearn.kernels.units import FOOT_NO_SWING, WALKING_ACC_STD, swing_rate

#: decision B203: force sensors that load this many times or more beside a foot IMU that does not move is a frozen IMU
FORCE_STEPS_MIN = 3
#: the force sensors load above this fraction of their own 95th percentile (``displace.foot.force_stance``'s level)
FORCE_LOAD_LEVEL = 0.2
#: the percentile of a force sensor's samples that is its load reference (``displace.foot.force_stance``)
FORCE_REF_PERCENTILE = 95
#: decision B260: a loaded foot is unloaded only below this fraction of its reference (hysteresis): quiet standing
#: after a walk holds a force sensor near FORCE_LOAD_LEVEL (simulated 10 % incline: 74-119 N against a 430 N
#: reference), whose noise crossed that one level 3 times in 7 s and read as 3 steps (B213's false "frozen IMU")
FORCE_UNLOAD_LEVEL = 0.1
#: decision B213: the live check judges consecutive blocks of this much stream time (s) from the first foot
#: accelerometer sample: simulated scenario A (users 1-3, slow / normal) loads the foot once per 1.66-2.00 s with its
#: standing ends, so a walking block holds ~5 loads (B203 needs 3), and a standing subject's one load stays one
LIVE_BLOCK_S = 10.0


def foot_imu_motion(acc: np.ndarray, gyr: np.ndarray) -> tuple[float, float]:
    """(sd of |acc| in m/s^2, B91's swing statistic in rad/s) of foot accelerometer ``acc`` (n, 3) and gyroscope
    ``gyr`` (m, 3) samples (B203's two figures)."""
    norm = np.linalg.norm(np.asarray(acc, dtype=float), axis=1)
    return float(np.nanstd(norm)), swing_rate(gyr)


def block_cuts(t: np.ndarray, t0: float, n_blocks: int, block_s: float = LIVE_BLOCK_S) -> np.ndarray:
    """Decision B251: the first index of each of ``n_blocks`` consecutive blocks of ``block_s`` seconds from ``t0``
    in sorted times ``t`` (s), and the end: block ``k`` is ``[cuts[k]:cuts[k + 1]]``."""
    idx = np.floor((np.asarray(t, dtype=float) - t0) / block_s).astype(np.int64)
    return np.searchsorted(idx, np.arange(0, n_blocks + 1))


def n_blocks(t: np.ndarray, t0: float, block_s: float = LIVE_BLOCK_S) -> int:
    """How many ``block_s`` blocks from ``t0`` the times ``t`` (s) reach."""
    t = np.asarray(t, dtype=float)
    return int(np.floor((t[-1] - t0) / block_s)) + 1 if len(t) else 0


def block_motion(t_acc: np.ndarray, acc: np.ndarray, t_gyr: np.ndarray, gyr: np.ndarray,
                 block_s: float = LIVE_BLOCK_S) -> tuple[float, float]:
    """Decision B251: B203's two figures (:func:`foot_imu_motion`) on each consecutive block of ``block_s`` seconds
    (B213's :data:`LIVE_BLOCK_S`, from the first accelerometer sample; accelerometer ``acc`` (n, 3) at ``t_acc`` s,
    gyroscope ``gyr`` (m, 3) at ``t_gyr`` s), and the largest of each over the blocks: a foot that walks in one
    block moved, however long it sat still around it (a whole night's sd and 99th percentile of |gyro| read a 1 %
    walk as still). A block with fewer than 4 samples of either sensor is not judged; none judged: the whole
    recording's figures (as before B251). Also B134's and B201's "walks" and "swings" (decision B253)."""
    t_acc, t_gyr = np.asarray(t_acc, dtype=float), np.asarray(t_gyr, dtype=float)
    acc, gyr = np.asarray(acc, dtype=float), np.asarray(gyr, dtype=float)
    t0 = float(t_acc[0]) if len(t_acc) else 0.0
    nb = max(n_blocks(t_acc, t0, block_s), 1)
    a_cut, g_cut = block_cuts(t_acc, t0, nb, block_s), block_cuts(t_gyr, t0, nb, block_s)
    sds, swings = [], []
    for k in range(nb):
        a, g = acc[a_cut[k]:a_cut[k + 1]], gyr[g_cut[k]:g_cut[k + 1]]
        if len(a) >= 4 and len(g) >= 4:
            sd, swing = foot_imu_motion(a, g)
            sds.append(sd)
            swings.append(swing)
    if not sds:
        return foot_imu_motion(acc, gyr)
    return _largest(sds), _largest(swings)


def _largest(values: list[float]) -> float:
    # NaN figures (all-NaN blocks) do not count as movement (foot_still), nor as a block's largest figure
    v = np.asarray(values, dtype=float)
    return float(np.nanmax(v)) if np.isfinite(v).any() else float("nan")


def block_swing_rate(t: np.ndarray, gyr: np.ndarray, block_s: float = LIVE_BLOCK_S) -> float:
    """Decision B256: B91's swing statistic (:func:`~pdrlearn.kernels.units.swing_rate`) of gyroscope ``gyr``
    (n, 3) at ``t`` s, the largest over B251's consecutive ``block_s`` blocks from its first sample with 4 samples
    or more (none: the whole recording's, as before): a unit swings if it swings in any block, however long it sat
    still around it."""
    t, gyr = np.asarray(t, dtype=float), np.asarray(gyr, dtype=float)
    if len(t) == 0:
        return swing_rate(gyr)
    nb = n_blocks(t, float(t[0]), block_s)
    cut = block_cuts(t, float(t[0]), nb, block_s)
    rates = [swing_rate(gyr[cut[k]:cut[k + 1]]) for k in range(nb) if cut[k + 1] - cut[k] >= 4]
    return _largest(rates) if rates else swing_rate(gyr)


def foot_still(sd: float, swing: float) -> bool:
    """Decision B203: the foot IMU does not move - its |acc| sd is at most B37's :data:`WALKING_ACC_STD` and B91's
    swing statistic under :data:`FOOT_NO_SWING` (a NaN figure does not count as movement, as before)."""
    return not (sd > WALKING_ACC_STD or swing >= FOOT_NO_SWING)


def force_reference(force: np.ndarray) -> float:
    """A force sensor's load reference: the :data:`FORCE_REF_PERCENTILE` th percentile of its samples."""
    return float(np.percentile(np.asarray(force, dtype=float), FORCE_REF_PERCENTILE))


def load_onsets(forces: list[np.ndarray], refs: list[float]) -> int | None:
    """How many times the foot is loaded (either sensor above :data:`FORCE_LOAD_LEVEL` x its reference) after
    being unloaded (both sensors below :data:`FORCE_UNLOAD_LEVEL` x their references, decision B260's hysteresis;
    a foot between the two levels keeps its state, and the first sample counts as loaded when above the lower
    level), over ``forces`` (each (n,) on one common clock) with references ``refs``; None when a reference is not a
    positive finite number (no usable force sensor, as ``force_stance``)."""
    if not forces:
        return None
    high = np.zeros(len(forces[0]), dtype=bool)
    low = np.ones(len(forces[0]), dtype=bool)
    for f, ref in zip(forces, refs, strict=True):
        if not np.isfinite(ref) or ref <= 0:
            return None
        f = np.asarray(f, dtype=float)
        high |= f > FORCE_LOAD_LEVEL * ref
        low &= ~(f > FORCE_UNLOAD_LEVEL * ref)
    if len(high) == 0:
        return 0
    # state per sample: 1 loaded (above the load level), 0 unloaded (below the unload level), else the last state
    mark = np.where(high, 1, np.where(low, 0, -1))
    if mark[0] < 0:
        mark[0] = 1  # between the levels from the start: already carrying weight (standing), no onset
    idx = np.maximum.accumulate(np.where(mark >= 0, np.arange(len(mark)), 0))
    loaded = mark[idx] == 1
    return int(np.count_nonzero(loaded[1:] & ~loaded[:-1]))


def frozen_foot_evidence(acc: np.ndarray, gyr: np.ndarray, forces: list[np.ndarray],
                         refs: list[float] | None = None) -> tuple[int, float, float] | None:
    """Decision B203's test: ``(loads, sd of |acc|, swing)`` when the foot IMU (``acc`` (n, 3), ``gyr`` (m, 3)) does
    not move and the force sensors ``forces`` (each (n,), on the accelerometer's clock) load
    :data:`FORCE_STEPS_MIN` times or more; None otherwise. ``refs``: the sensors' load references (default: each
    one's own :func:`force_reference`)."""
    if len(acc) < 4 or len(gyr) < 4 or not forces:
        return None
    sd, swing = foot_imu_motion(acc, gyr)
    if not foot_still(sd, swing):
        return None
    n = load_onsets(forces, [force_reference(f) for f in forces] if refs is None else refs)
    if n is None or n < FORCE_STEPS_MIN:
        return None
    return n, sd, swing


def frozen_foot_reason(names: str, n: int, sd: float, swing: float, *,
                       imu: str = "fAccelerometer.csv, fGyroscope.csv") -> str:
    """The middle of B203's line: what the force sensors ``names`` and the foot IMU (``imu``) did (shared with
    B213's)."""
    return (f"The force sensors ({names}) load {n} times, but the foot IMU ({imu}) does "
            f"not move (|acc| sd {sd:.2g} m/s^2, |gyro| at most {np.degrees(swing):.0f} deg/s; a walking foot swings "
            f"over {np.degrees(FOOT_NO_SWING):.0f} deg/s): a frozen or disconnected IMU, so every stride would "
            "integrate to 0 m")
