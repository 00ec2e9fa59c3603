"""Clipped and stuck axes of an accelerometer / gyroscope (numpy only: ``pdrlearn info`` / ``track`` / ``run`` read
them through :mod:`pdrlearn.io.validate`, the live :class:`pdrlearn.runtime.Tracker` on its blocks, decision E303).

Decisions B77 / B311 (a rail held or pinned at the axis's extreme), B405 (coarse levels repeat), B456 (a declared full
scale: clipped within :data:`FULL_SCALE_MARGIN` of it) and B455 (one axis stuck while the others move).
"""

from __future__ import annotations

import math
import re

import numpy as np

from pdrlearn.kernels.barometer_check import CLIP_COSTLESS_G
from pdrlearn.kernels.units import MOVING_ACC, MOVING_RPS, STANDARD_GRAVITY, quantisation_margin
from pdrlearn.warning_lines import coded

#: decision B77: the smallest full scale of a body-worn accelerometer / gyroscope (2 g: MEMS ranges are +-2, 4, 8,
#: 16 g; 250 deg/s: +-250 ... 2000 deg/s, thesis Tables 5, 13). An axis's extreme value at or beyond it, held by
#: :data:`CLIP_RUN` or more consecutive samples, is a clipped (saturated) reading (3: a smooth peak sampled
#: symmetrically and rounded repeats its top value twice).
CLIP_LEVEL = {"accelerometer": 2.0 * STANDARD_GRAVITY, "gyroscope": float(np.deg2rad(250.0))}
CLIP_RUN = 3
#: decision B311: an axis's extreme value (at or beyond :data:`CLIP_LEVEL`) that this many samples or more sit at
#: exactly, consecutive or not, is a pinned full-scale value: 100 Hz impacts clip one sample at a time, which B77's
#: runs never see. An unclipped axis reaches its extreme once: its impact peaks spread over metres per second squared
#: (rad/s for a gyroscope) while a converter's step is under 0.08 m/s^2 (12 bits at +-16 g) or 0.02 rad/s (12 bits at
#: +-2000 deg/s), so 4 more peaks in the top step, (step / spread)^4 < 1e-6 per axis, do not happen by chance; a
#: smooth peak repeats its top value twice (B77), a held sample once more. 5 is that argument's count, not a fit.
#: And the rail must hold more samples than any other value near it (:func:`_pinned`).
CLIP_PINNED = 5


def clipped_samples(values: np.ndarray, kind: str, full_scale: float | None = None) -> tuple[int, float]:
    """Decision B77: (number of samples with a clipped axis, the largest clipped |value|) of an accelerometer
    or gyroscope file: on each axis, the samples equal to the axis's maximum (or minimum) over the file, where
    that extreme is at least :data:`CLIP_LEVEL` in magnitude, in runs of :data:`CLIP_RUN` or more equal
    consecutive samples (a sensor at its full scale repeats it; a real peak is not held). Decision B311: or all
    of them when :data:`CLIP_PINNED` or more samples sit at that extreme, one at a time or not (impacts at
    100 Hz clip single samples). Decision B456: with a declared ``full_scale`` (SI), :func:`declared_clipped`."""
    hit, top = clipped_axes(values, kind, full_scale)
    return int(hit.any(axis=1).sum()) if hit.size else 0, top


def clipped_axes(values: np.ndarray, kind: str, full_scale: float | None = None) -> tuple[np.ndarray, float]:
    """Decisions B77 / B311 per axis (the mechanism of :func:`clipped_samples`; decision B454 declips by it): a boolean
    array shaped like ``values`` (n x axes; empty for a file B77 does not judge) true at each axis's clipped samples,
    and the largest clipped |value| (0.0: none). Decision B456: with a declared ``full_scale`` (SI),
    :func:`declared_clipped` instead."""
    if full_scale is not None:
        return declared_clipped(values, full_scale)
    level = CLIP_LEVEL.get(kind)
    v = np.asarray(values, dtype=float)
    if level is None or v.ndim != 2 or v.shape[0] < CLIP_RUN:
        return np.zeros((0, 0), dtype=bool), 0.0
    hit = np.zeros(v.shape, dtype=bool)
    top = 0.0
    for j in range(v.shape[1]):
        col = v[:, j]
        step = axis_step(col)
        for ext in (col.max(), col.min()):
            if not abs(ext) >= level or step > CLIP_COARSE * abs(ext):  # decision B405: coarse levels repeat
                continue
            at = col == ext
            if _pinned(col, ext, at):  # decision B311: a pinned full-scale value, runs or not
                hit[:, j] |= at
                top = max(top, abs(float(ext)))
                continue
            # runs of equal extreme samples: a sample counts when its run is CLIP_RUN long or more
            edges = np.diff(np.concatenate([[0], at.astype(np.int8), [0]]))
            starts, ends = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)
            for a, b in zip(starts, ends, strict=True):
                if b - a >= CLIP_RUN:
                    hit[a:b, j] = True
                    top = max(top, abs(float(ext)))
    return hit, top


#: decision B405: an axis whose resolution (:func:`axis_step`) is more than this fraction of its extreme has under 50
#: levels up to it, so its peak level repeats by quantisation (an 8-bit +-2000 deg/s gyroscope: 15.6 deg/s steps,
#: its 359 deg/s peaks 4.3 %); B77/B311 do not call it clipped. A clipped 8-bit +-250 deg/s one: 0.8 %, still said.
CLIP_COARSE = 0.02


def distinct_steps(col: np.ndarray) -> np.ndarray:
    """Decision B405/B406: the steps between the sorted distinct finite values of one axis (empty with fewer than two
    distinct values): the kernel of :func:`axis_step` and :func:`resolution`."""
    return np.diff(np.unique(np.asarray(col, dtype=float)[np.isfinite(col)]))


def axis_step(col: np.ndarray) -> float:
    """Decision B405/B406: the smallest step between the distinct values of one axis (its resolution; 0.0 with
    fewer than two distinct values)."""
    d = distinct_steps(col)
    return float(d.min()) if d.size else 0.0


def _pinned(col: np.ndarray, ext: float, at: np.ndarray) -> bool:
    """Decision B311: ``CLIP_PINNED`` or more samples sit at the axis's extreme ``ext`` (``at``), and more than at any
    other value in the top tenth of the axis's range: a rail piles up every sample beyond it, while the top of an
    unclipped signal is its rarest part (an exactly periodic synthetic sine repeats its top once a cycle, its
    shoulders twice)."""
    k = int(np.count_nonzero(at))
    if k < CLIP_PINNED:
        return False
    band = 0.1 * float(col.max() - col.min())
    near = col[~at & (np.abs(col - ext) <= band)]
    return k > (int(np.unique(near, return_counts=True)[1].max()) if near.size else 0)




#: decision B456: a sample of a stream with a declared full scale is clipped when an axis's |value| reaches this
#: fraction below the range (a filter after the converter rounds the rail off; stated before measuring)
FULL_SCALE_MARGIN = 0.05
#: decision B456: the units a declared full scale may be given in, and their factor to SI (m/s^2, rad/s)
FULL_SCALE_UNITS = {"accelerometer": {"g": STANDARD_GRAVITY, "m/s^2": 1.0, "m/s2": 1.0},
                    "gyroscope": {"deg/s": float(np.deg2rad(1.0)), "dps": float(np.deg2rad(1.0)), "rad/s": 1.0}}
#: decision B456: the meta.json key of the declared full scales (stream name -> "4 g", "500 deg/s")
FULL_SCALE_KEY = "full_scale"


def parse_full_scale(text, kind: str) -> float:
    """Decision B456: a declared full scale (``"4 g"``, ``"500 deg/s"``, ``"39.2 m/s^2"``, ``"8.7 rad/s"``) in SI units
    (m/s^2 or rad/s); ValueError naming the accepted forms for anything else."""
    units = FULL_SCALE_UNITS.get(kind, {})
    m = re.fullmatch(r"\s*\+?(?:\+-|±)?\s*([0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?)\s*([a-z/^0-9]+)\s*", str(text))
    if m is None or m.group(2) not in units or not float(m.group(1)) > 0:
        forms = ", ".join(f"'N {u}'" for u in units) or "none"
        raise ValueError(f"{text!r} is no {kind} full scale; give a positive number and a unit: {forms}")
    return float(m.group(1)) * units[m.group(2)]


def declared_clipped(values: np.ndarray, full_scale: float) -> tuple[np.ndarray, float]:
    """Decision B456: :func:`clipped_axes` for a stream whose full scale (SI) is declared: true where an axis's |value|
    is at or above (1 - :data:`FULL_SCALE_MARGIN`) x ``full_scale``; the level reported is the declared range
    (0.0: none clipped)."""
    v = np.asarray(values, dtype=float)
    if v.ndim != 2:
        return np.zeros((0, 0), dtype=bool), 0.0
    hit = np.abs(v) >= (1.0 - FULL_SCALE_MARGIN) * float(full_scale)
    return hit, (float(full_scale) if hit.any() else 0.0)


#: decision B455: a run of bit-identical values on one axis lasting this long (s) or more, at least :data:`CLIP_RUN`
#: samples, while the sensor's other axes move, is a stuck axis (0.05 s stated before measuring; amended to 0.08 s, the
#: trial's shortest stuck episode, 8 held samples at 100 Hz, after clean simulated 50 Hz walks held an axis 3 samples)
STUCK_S = 0.08
#: decision B455 (amended by the lead, session 46: a clean simulated 50 Hz walk of tests/test_clock_drift_b264 held its
#: accelerometer's z axis 4 samples (0.08 s) in 4 runs in the final CI): a stuck run also holds at least this many
#: samples (the trial's stuck episodes held 8 at 100 Hz and stay named)
STUCK_MIN_SAMPLES = 6
#: decision B455: each other axis of the sensor changes value at this share of the run's sample steps or more
STUCK_OTHERS_MOVING = 0.8
#: decision B455: the axis leaves the run by more than this many of its typical steps (B405/B406's axis_step as
#: stated first; amended: the median non-zero change between its samples, :func:`_typical_change`)
STUCK_JUMP_STEPS = 4
#: decision B455: the stuck runs on one axis a file needs for a warning
STUCK_MIN_RUNS = 3
#: decision B455 (amended after the first measurement): the share of a run's samples at which the sensor itself moves
#: (B120's thresholds, :data:`~pdrlearn.kernels.units.MOVING_RPS` / ``MOVING_ACC``, widened by B405's quantisation
#: margin): a resting sensor's noise hops between a few levels on every axis and repeats one now and then
STUCK_MOVING_SHARE = 0.5
def _sensor_moving(v: np.ndarray, kind: str, step: float) -> np.ndarray:
    """Decision B455 (B120's test on one sensor): its samples at which it moves, beyond B405's rounding margin."""
    norm = np.linalg.norm(v, axis=1)
    margin = quantisation_margin(step)
    if kind == "gyroscope":
        return norm > MOVING_RPS + margin
    return np.abs(norm - STANDARD_GRAVITY) > MOVING_ACC + margin


def _typical_change(col: np.ndarray) -> float:
    """Decision B455 (second amendment): the median of an axis's non-zero sample-to-sample changes (its typical step:
    a quantised slow axis leaves a held level by one or two of them, a stuck axis by what it missed)."""
    d = np.abs(np.diff(col))
    d = d[d > 0]
    return float(np.median(d)) if d.size else 0.0


def stuck_runs(values: np.ndarray, dt: float, kind: str, full_scale: float | None = None) -> list[list[tuple]]:
    """Decision B455: per axis of a 3-axis accelerometer / gyroscope ``values`` (n, 3) sampled every ``dt`` s, its
    stuck runs as ``(first index, length)``: bit-identical consecutive values for :data:`STUCK_S` or more (and
    :data:`CLIP_RUN` samples or more) while each other axis changes at :data:`STUCK_OTHERS_MOVING` of the run's steps
    or more, left by a jump of more than :data:`STUCK_JUMP_STEPS` of the axis's resolution steps, and not at the
    axis's extreme at or beyond :data:`CLIP_LEVEL` (or within B456's margin of a declared ``full_scale``): B77's;
    amended: while the sensor moves at :data:`STUCK_MOVING_SHARE` of the run's samples; the jump against the axis's
    typical change (:func:`_typical_change`)."""
    v = np.asarray(values, dtype=float)
    if v.ndim != 2 or v.shape[1] != 3 or len(v) < CLIP_RUN + 1 or not dt > 0:
        return [[] for _ in range(v.shape[1] if v.ndim == 2 else 0)]
    need = max(CLIP_RUN, STUCK_MIN_SAMPLES, int(np.ceil(STUCK_S / dt - 1e-9)))
    level = CLIP_LEVEL.get(kind, np.inf)
    changes = np.diff(v, axis=0) != 0  # (n-1, 3): sample k -> k+1 changed
    moves = _sensor_moving(v, kind, max(axis_step(v[:, j]) for j in range(3)))
    out = []
    for j in range(3):
        col = v[:, j]
        same = ~changes[:, j]
        edges = np.diff(np.concatenate([[0], same.astype(np.int8), [0]]))
        starts, ends = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)  # steps same[a:b]: samples a..b
        runs = []
        step = _typical_change(col)
        extremes = (col.max(), col.min())
        others = [k for k in range(3) if k != j]
        for a, b in zip(starts, ends, strict=True):
            length = b - a + 1
            if length < need or b >= len(col) - 1:  # too short, or still held at the end (no jump seen)
                continue
            held = col[a]
            if held in extremes and abs(held) >= level:  # a clipped rail: B77 / B311's
                continue
            if full_scale is not None and abs(held) >= (1.0 - FULL_SCALE_MARGIN) * full_scale:  # B456's
                continue
            if not abs(col[b + 1] - held) > STUCK_JUMP_STEPS * step:
                continue
            moving = changes[a:b, others].mean(axis=0)
            if np.all(moving >= STUCK_OTHERS_MOVING) and moves[a:b + 1].mean() >= STUCK_MOVING_SHARE:
                runs.append((int(a), int(length)))
        out.append(runs)
    return out


def stuck_message(where: str, axis: str, runs: list[tuple], dt: float, first_s: float) -> str:
    """Decision B455's one line per stuck axis: the file (or stream), the axis, the runs, the longest, the first."""
    longest = max(n for _, n in runs)
    return (f"{where}: axis {axis} held one value for {len(runs)} runs of {STUCK_S:g} s or more (longest {longest} "
            f"samples, {longest * dt:.2g} s; first at {first_s:.2f} s) while the sensor's other axes "
            "moved: a stuck axis (a loose connection or a faulty sensor), which bends the strides it falls in and "
            "shortens the distance; check the sensor (decision B455)")


#: decision L529 (adopted, docs/decisions/localization.md): L525 acts when the clipped samples are at least this share
#: of the foot gyroscope's moving samples (|w| >= B401's MOVING_RAD_S); fixed before the measurement (a spike: 0.14 %,
#: a +-250 deg/s foot: 22-33 %)
CLIPPED_MOVING_MIN_SHARE = 0.01


def clipping_acts(n: int, moving: int | None) -> bool:
    """Decision L529: whether ``n`` clipped samples of a foot gyroscope with ``moving`` moving samples (B401) are
    enough for L525 to act (:data:`CLIPPED_MOVING_MIN_SHARE`; ``moving`` None: not counted, any clipping acts)."""
    return n > 0 and (moving is None or n >= CLIPPED_MOVING_MIN_SHARE * moving)


#: decision B401: a gyroscope sample is "moving" at |w| >= this (rad/s): the stance segmenter's default threshold
#: (``kernels.stride.StanceSegmenter.stance_gyro_rad_s``), so the share of clipped samples is of the swings'
MOVING_RAD_S = 0.8
#: decision B401: the per-axis peak rates (deg/s) of walking feet measured on the real gaitmap recordings in
#: datasets/external (lwalk, level, stairs, walk4x10, ms: 560-987 deg/s); a foot needs a range above them
FOOT_PEAK_DPS = (560, 990)
FOOT_GYRO_RANGE_DPS = 1000


#: decision B453 (trial T3 finding F1): what a foot accelerometer clipped at a full scale (g) cost the offline foot
#: track without B454's correction, printed by experiments/clip_range_s46.py (simulated users 14300-14305, 100 Hz,
#: the foot gyroscope clipped at 250 / 500 / 1000 deg/s alongside): the median distance error (%) at --speed slow,
#: normal, fast and a brisk 2.26 m/s level walk, and the median |final altitude error| (m) of the normal-speed stair
#: walks (a 2.04 m flight up and back down); +-16 g cost nothing measurable (the brisk walk's peaks reach ~16 g)
FOOT_ACCEL_CLIP_COST = {2.0: (-7.12, -15.13, -29.19, -50.77, 4.54), 4.0: (-1.26, -2.75, -8.25, -26.85, 1.06),
                        8.0: (+0.14, -0.11, -0.37, -3.20, 0.22)}
#: decision B454: the same figures with ``FootDisplacement(clip_noise=True)`` (kept as an option by B454's rule; the
#: offline track's default on a clipped foot accelerometer since B470), measured at +-4 g and +-8 g only
FOOT_ACCEL_CLIP_NOISE = {4.0: (+0.35, -0.39, -1.04, -21.40, 0.01), 8.0: (+0.15, -0.13, -0.11, -0.46, 0.01)}
#: decision B471 (session 48, trial T1 finding F1): the median distance error (%) of race walks at the simulator's own
#: +-16 g, 100 Hz (0.93-1.00 m steps at 200-222 steps/min, 3.1-3.6 m/s; 2.5-8.1 % of the foot's samples clipped), with
#: ``{"clip_noise": false}`` and with B470's default ``clip_noise``, printed by experiments/clip_default_s48.py (users
#: 15876-15899, trial T1's half lap)
FOOT_ACCEL_RACE_WALK_16G = (-4.34, -0.41)
#: decision B453: the median distance error (%) of the same walks unclipped reaches at most this far from 0
FOOT_UNCLIPPED_PCT = 0.20
#: decision B453: the foot accelerometer ranges to buy (g): walking, brisk walking (the simulator has no running gait)
FOOT_ACCEL_RANGE_G = (8, 16)


def foot_accel_cost(top: float) -> str:
    """Decision B453: the clause giving a clipped foot accelerometer's cost at the measured full scale nearest
    ``top`` (m/s^2) in ratio (:data:`FOOT_ACCEL_CLIP_COST`) and, decision B454, what ``clip_noise`` left of it
    (:data:`FOOT_ACCEL_CLIP_NOISE`); "" above 12 g (+-16 g: nothing measurable)."""
    g = top / STANDARD_GRAVITY
    if not g < CLIP_COSTLESS_G:
        return ""
    scale = min(FOOT_ACCEL_CLIP_COST, key=lambda k: abs(math.log(k / g)))

    def figures(row: tuple) -> str:
        return " / ".join(f"{x:+.2f}" for x in row[:4]) + f" %, {row[4]:.2f} m"

    noise = FOOT_ACCEL_CLIP_NOISE.get(scale)
    fix = ("" if noise is None else "; the offline track puts each stride's ZUPT error at the clipped samples by "
           f"default (B470; --params '{{\"clip_noise\": false}}' turns it off): {figures(noise)} (B454)")
    return (f"; simulated walks clipped at +-{scale:g} g tracked the distance (median at slow / normal / fast / a "
            f"brisk 2.26 m/s; unclipped within {FOOT_UNCLIPPED_PCT:.2f} %) and the end height after a 2 m flight up "
            f"and back down: {figures(FOOT_ACCEL_CLIP_COST[scale])} off without it{fix}")


def saturation_warning(where: str, kind: str, n: int, total: int, top: float, unit_name: str = "foot", *,
                       moving: int | None = None, waist: bool = True, declared: bool = False) -> str:
    """Decision B77's one line: the file, the fraction of clipped samples and what it does to the results;
    ``unit_name`` the body unit (``"foot"`` or ``"waist"``: its consequence named for it, trial T3 finding 9).
    Decision B401, a gyroscope: ``moving`` (the file's samples with |w| >= :data:`MOVING_RAD_S`) gives the share of
    the motion at full scale, and a foot's line says what the offline track does about it (L525; decision L530: by
    the heading ``waist`` gives, a session with a waist unit or not; L529: nothing under its share) and the range a
    foot needs. Decision B456: ``declared`` (the full scale given in meta.json's ``full_scale``) says the samples
    counted are those within :data:`~pdrlearn.kernels.clipping.FULL_SCALE_MARGIN` of it."""
    unit = "m/s^2" if kind == "accelerometer" else "rad/s"
    rng = f"{top / STANDARD_GRAVITY:.3g} g" if kind == "accelerometer" else f"{np.rad2deg(top):.4g} deg/s"
    accel = ("the foot's integrated stride lengths and the step detector's impact peaks are cut short"
             if unit_name == "foot" else "the lower back's step peaks and the step lengths read from its vertical "
             "movement are cut short")
    effect = accel if kind == "accelerometer" else "the integrated attitude and heading lose the rotation beyond it"
    share, remedy, codes, cost = "", "", "B77, B311", ""
    if kind == "accelerometer" and unit_name == "foot":  # decision B453: the size of the effect and the range to buy
        cost = foot_accel_cost(top)
        walk, brisk = FOOT_ACCEL_RANGE_G
        if top < 0.99 * walk * STANDARD_GRAVITY:
            remedy = f" (a foot: +-{walk} g or more for walking, +-{brisk} g for brisk walking or running)"
        elif top < 0.99 * brisk * STANDARD_GRAVITY:
            remedy = f" (a foot: +-{brisk} g for brisk walking or running)"
        codes = ("B77, B311, B453, B470" if "B470" in cost else "B77, B311, B453") if cost else codes
        if not cost:  # decisions B467 / B471: the cost at +-16 g measured at race pace, and what B470 leaves
            off, left = FOOT_ACCEL_RACE_WALK_16G
            cost = (f"; simulated race walks at this range (100 Hz, 3.1-3.6 m/s) read the distance {off:+.2f} % off "
                    "(median), walks up to a brisk 2.26 m/s nothing measurable (B453); the offline track puts each "
                    f"stride's ZUPT error at the clipped samples by default, which left {left:+.2f} % (B470; --params "
                    "'{\"clip_noise\": false}' turns it off); at a higher rate the impacts reach further: a 1000 Hz "
                    "stair walk clipped in 0.08 % of its samples read its flights +52 / -26 % high / low without it "
                    "and within 0.01 m with it (B467) - check the altitude and the stair heights")
            codes = "B77, B311, B453, B467, B470, B471"
    if kind == "gyroscope" and moving:  # decision B401: the size of the effect, measured on the file
        share = f"; {100.0 * n / moving:.2g} % of its moving samples (|w| >= {MOVING_RAD_S:g} rad/s) are at full scale"
        codes = "B77, B311, B401"
    if kind == "gyroscope" and unit_name == "foot":
        if not clipping_acts(n, moving):  # decision L529: too rare a clipping for L525 to act on
            effect += (f" (the foot's stride pitch and yaw; under {100 * CLIPPED_MOVING_MIN_SHARE:g} % of the moving "
                       "samples, the offline track keeps its usual settings, decision L529)")
        else:  # decision L530: the heading named by the units present
            effect += (" (the foot's stride pitch and yaw: the offline track re-levels each stride at its end rest "
                       + ("and heads by the waist unit" if waist else
                          "and keeps the foot's own stride yaw, which the clipping turns (no waist unit)")
                       + ", decision L525)")
        remedy = (f" (+-{FOOT_GYRO_RANGE_DPS} deg/s or more for a foot: walking feet turned at {FOOT_PEAK_DPS[0]}-"
                  f"{FOOT_PEAK_DPS[1]} deg/s in the real gaitmap recordings)")
        codes = "B77, B311, B401"
    how = (f"the full scale declared in meta.json's full_scale: within {100 * FULL_SCALE_MARGIN:g} % of it, decision "
           "B456" if declared else f"the sensor's full scale: held for {CLIP_RUN}+ samples in a row, or reached by "
           f"{CLIP_PINNED}+ samples one at a time")
    return coded(f"{where}: {n} of {total} samples ({100.0 * n / total:.2g} %) are clipped at +-{top:.4g} {unit} "
            f"({how}){share}: {effect}, so distances and headings come out wrong there{cost}; record with a range "
            f"above +-{rng}{remedy} (decision {codes})", "B77")  # decision E170
