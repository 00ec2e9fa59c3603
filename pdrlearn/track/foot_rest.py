"""What the foot unit's rests say about its sensor and its placement (decisions B133, B134).

- B133: at foot-flat the accelerometer reads gravity alone, so the median |acc| over the detected rests (the
  ZUPT's own inertial test, :func:`pdrlearn.displace.foot.inertial_stance`) over standard gravity is the
  accelerometer's scale: shown by ``pdrlearn info`` (a display); B133's warning candidate (2 % off 1 g) was not adopted
  (``experiments/foot_rest_scale_b133.py``: real correctly scaled feet read 0.967-1.008 g).
- B134: a foot unit swings forward at several hundred deg/s every stride; a unit in the foot files that walks
  (its |acc| varies, B37) but never swings (B91's 99th percentile of |gyro| under ``FOOT_NO_SWING``) is not on
  the foot (waist, pocket): its "rests" are not foot-flats and its ZUPT track is meaningless (trial `placement`
  finding 4: 8.99 m for 89.5 m, warned only as running).
- B201: a foot accelerometer whose rest |acc| is more than :data:`REST_SCALE_TOL` off 1 g is warned about (its
  distances scale with it; the trial `fuzz`'s x0.8-x1.3 copies), and a foot detector that finds no stride on a
  foot that walks and swings says so instead of scoring 0 silently.
- B203: force sensors that load and unload beside a foot IMU that never moves (frozen, disconnected) is refused:
  every stride would integrate to 0 m.
"""

from __future__ import annotations

import numpy as np

from pdrlearn.displace.foot import inertial_stance
from pdrlearn.io.sensors import UNIT_IMU
from pdrlearn.kernels.foot_rhythm import foot_period, slow_swing_rate
from pdrlearn.kernels.frozen_foot import (
    block_motion,
    foot_still,
    frozen_foot_evidence,
    frozen_foot_reason,
)
from pdrlearn.kernels.units import FOOT_NO_SWING, STANDARD_GRAVITY, WALKING_ACC_STD
from pdrlearn.signal import interp_rows

#: fewer rest samples than this: no figure (nothing to judge)
MIN_REST_SAMPLES = 20
#: decision B201: a foot accelerometer whose rest |acc| (:func:`foot_rest_stats`) is more than this fraction off 1 g is
#: warned about. Correctly scaled feet read 0.967-1.008 g at their detected foot-flats (B133: 11 real gaitmap feet;
#: -3.3 % at most) and 0.990-1.012 g on 20 simulated walks (B133); lower-back units read 0.96-1.01 g in their quietest
#: windows (B97: -3.4 .. +1.2 % on the 23 real recordings). 7 % is twice the widest deviation of a correctly scaled
#: foot (3.3 %), so a 10 % mis-scale (the trial's x0.9 / x1.1: -10 % / +10 % distance) is warned about on every foot
#: read within 3 % of 1 g. A warning, not a refusal: B97 refuses outside x0.67-x1.5 only, because hand-made feet with
#: very short foot-flats read 1.30 g in their quietest windows, and the foot-flats are the ZUPT's own guess
REST_SCALE_TOL = 0.07


def _rest_samples(acc_s, gyr_s) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The foot's (acc, gyr on the accelerometer's clock, |acc|, detected foot-flat samples)."""
    acc = np.asarray(acc_s.values, dtype=float)
    gyr = interp_rows(acc_s.t, gyr_s.t, np.asarray(gyr_s.values, dtype=float))
    return acc, gyr, np.linalg.norm(acc, axis=1), inertial_stance(acc, gyr, float(acc_s.rate_hz))


def foot_rest_gravity(session) -> float:
    """Decision L621 (second part): the foot accelerometer's own rest reading (m/s^2), B201's ``rest_acc_g``: the median
    |acc| over the detected foot-flats; 1 g without the foot IMU or under :data:`MIN_REST_SAMPLES` of them."""
    acc_n, gyr_n = UNIT_IMU["foot"]
    if not session.has(acc_n, gyr_n) or len(session.streams[acc_n]) < 4 or len(session.streams[gyr_n]) < 4:
        return STANDARD_GRAVITY
    _, _, norm, rest = _rest_samples(session.streams[acc_n], session.streams[gyr_n])
    ok = np.isfinite(norm) & rest
    return float(np.median(norm[ok])) if ok.sum() >= MIN_REST_SAMPLES else STANDARD_GRAVITY


def foot_rest_stats(session) -> dict | None:
    """The foot unit's rest figures: ``rest_acc_g`` (median |acc| over the detected foot-flat samples, in g;
    None with fewer than :data:`MIN_REST_SAMPLES`), ``rest_fraction``, ``swing_rad_s`` (B91's statistic) and
    ``walking`` (B37's sd of |acc| over :data:`WALKING_ACC_STD`), the two the largest of any 10 s block (decision
    B253, :func:`~pdrlearn.kernels.frozen_foot.block_motion`). None without both foot IMU streams. |acc| and
    |gyro| do not depend on the axes, so no frame is needed."""
    acc_n, gyr_n = UNIT_IMU["foot"]
    if not session.has(acc_n, gyr_n):
        return None
    acc_s, gyr_s = session.streams[acc_n], session.streams[gyr_n]
    if len(acc_s) < 4 or len(gyr_s) < 4:
        return None
    acc, gyr, norm, rest = _rest_samples(acc_s, gyr_s)
    ok = np.isfinite(norm) & rest
    # decision B253: "walks" and "swings" are B251's largest figures of any 10 s block (a night's whole-session sd
    # and 99th percentile read a short walk as still, hiding B134's and B201's faults)
    sd, swing = block_motion(acc_s.t, acc, gyr_s.t, gyr_s.values)
    fs = float(acc_s.rate_hz)
    period = foot_period(gyr, fs)
    return {"rest_acc_g": float(np.median(norm[ok]) / STANDARD_GRAVITY) if ok.sum() >= MIN_REST_SAMPLES else None,
            "rest_fraction": float(rest.mean()), "swing_rad_s": swing, "walking": bool(sd > WALKING_ACC_STD),
            "stride_period_s": period if np.isfinite(period) else None,  # decision L598 (None: no rhythm found)
            "no_swing_rad_s": slow_swing_rate(FOOT_NO_SWING, period)}


def _swings(stats: dict) -> bool:
    """B91's swing test against the rate a foot of this rhythm must reach (decision L598)."""
    return stats["swing_rad_s"] >= stats.get("no_swing_rad_s", FOOT_NO_SWING)


def foot_scale_warning(stats: dict | None, where: str) -> str | None:
    """Decision B201: one line when the foot accelerometer's rest |acc| is more than :data:`REST_SCALE_TOL` off 1 g
    on a foot that walks and swings like a foot (B134's unit that never swings has other rests); ``where`` leads it
    (``""``: the caller's logger adds it)."""
    g = (stats or {}).get("rest_acc_g")
    if g is None or not stats["walking"] or not _swings(stats) or abs(g - 1.0) <= REST_SCALE_TOL:
        return None
    return ((f"{where}: " if where else "") + f"fAccelerometer.csv reads {g:.3f} g at the foot's rests (its detected "
            "foot-flats, "
            f"{100 * stats['rest_fraction']:.0f} % of the samples), {100 * (g - 1):+.1f} % off the 1 g a still "
            f"accelerometer reads (correctly scaled feet: 0.967-1.008 g, decision B133): its scale is wrong, so "
            f"distances come out about {100 * abs(g - 1):.0f} % {'long' if g > 1 else 'short'} and the step detector's "
            f"thresholds may miss strides; calibrate the accelerometer (scale), or divide its values by {g:.3f} "
            "(decision B201)")


def foot_motion(session) -> tuple[float, float] | None:
    """(sd of |acc| in m/s^2, B91's swing statistic in rad/s) of the foot IMU, each the largest over B213's 10 s
    blocks (decision B251, :func:`~pdrlearn.kernels.frozen_foot.block_motion`); None without both its files."""
    acc_n, gyr_n = UNIT_IMU["foot"]
    if not session.has(acc_n, gyr_n) or len(session.streams[acc_n]) < 4 or len(session.streams[gyr_n]) < 4:
        return None
    acc, gyr = session.streams[acc_n], session.streams[gyr_n]
    return block_motion(acc.t, acc.values, gyr.t, gyr.values)


def frozen_foot_imu(session) -> str | None:
    """Decision B203: the refusal when the force sensors (fForceA / fForceB) load and unload at least
    :data:`~pdrlearn.kernels.frozen_foot.FORCE_STEPS_MIN` times while the foot IMU does not move (sd of |acc| at
    most B37's :data:`WALKING_ACC_STD`, B91's swing statistic under :data:`FOOT_NO_SWING`): a frozen or disconnected
    IMU, whose strides (found by the force sensors) would all integrate to 0 m. None otherwise (a subject standing still
    loads the force sensors once). The test is :func:`pdrlearn.kernels.frozen_foot.frozen_foot_evidence`, the live
    ``Tracker``'s too (decision B213)."""
    motion = foot_motion(session)
    if motion is None or not foot_still(*motion):
        return None
    names = [n for n in ("fForceA", "fForceB") if n in session.streams and len(session.streams[n]) >= 2]
    if not names:
        return None
    acc_n, gyr_n = UNIT_IMU["foot"]
    acc = session.streams[acc_n]
    session.require_cover(acc_n, *names)  # B21: the force sensors read on the accelerometer's clock
    forces = [np.interp(acc.t, session.streams[n].t, session.streams[n].values[:, 0]) for n in names]
    found = frozen_foot_evidence(acc.values, session.streams[gyr_n].values, forces)
    if found is None:
        return None
    n = found[0]
    sd, swing = motion  # decision B251: the largest figures of any 10 s block (the foot never moved in any)
    return (f"{session.where}: no strides detected; is the foot unit moving? "
            + frozen_foot_reason(", ".join(f"{k}.csv" for k in names), n, sd, swing)
            + "; check the IMU and its link, and re-record (decision B203)")


def no_strides_warning(stats: dict | None, where: str, detector: str) -> str | None:
    """Decision B201: the line when ``detector`` found no stride on a foot that walks and swings like a foot."""
    if not stats or not stats["walking"] or not _swings(stats):
        return None
    g = stats.get("rest_acc_g")
    return (f"{where}: {detector} found no strides, but the foot unit walks (it swings up to "
            f"{np.degrees(stats['swing_rad_s']):.0f} deg/s): its thresholds did not fire"
            + (f" (the accelerometer reads {g:.3f} g at rest: check its scale, decision B201)" if g is not None
               and abs(g - 1.0) > REST_SCALE_TOL else "")
            + ("; try --detector accel (the IMU alone; decision B285)" if "force" in detector else
               "; try --detector accel-force with force sensors") + ", or `pdrlearn track`, which segments the strides "
            "at the foot's rests (decision B201)")


def foot_placement_warning(stats: dict | None, where: str, kinds: dict | None = None) -> str | None:
    """Decision B134: one line when the foot unit walks but never swings like a foot (``where``: the line's prefix;
    "" for none, when the caller prefixes its lines itself - decision L352: ``track`` printed it twice). Decision
    W415: none when ``kinds`` (:func:`pdrlearn.track.stride_kinds.foot_stride_kinds`) has at least
    :data:`~pdrlearn.track.stride_kinds.MIN_CLASSED_STRIDES` long strides, mostly sideways or backward (a side step
    swings the foot less than a forward stride: 127-144 deg/s)."""
    from pdrlearn.track.stride_kinds import MIN_CLASSED_STRIDES, not_judged

    if not stats or not stats["walking"] or _swings(stats):
        return None
    if not_judged(kinds, MIN_CLASSED_STRIDES):  # decision W415: a side-shuffle drill's foot
        return None
    return (f"{where + ': ' if where else ''}no foot-flat rests found: the foot unit (fAccelerometer.csv, "
            "fGyroscope.csv) walks but never "
            f"swings like a foot (at most {np.degrees(stats['swing_rad_s']):.0f} deg/s, 99th percentile of |gyro| "
            "in any 10 s block; a "
            f"walking foot exceeds {np.degrees(stats.get('no_swing_rad_s', FOOT_NO_SWING)):.0f} at this rhythm, "
            "decision L598), so the rests its ZUPT finds are not foot-flats "
            "and its distance is meaningless: is this unit on the foot? (pocket/waist/shank placements are not "
            "supported for the foot unit: mount it on the shoe, instep, heel or side; a lower-back unit's data go "
            "in the w* files; decision B134)")


def foot_placement_line(session, stats: dict | None, where: str) -> str | None:
    """:func:`foot_placement_warning` with W415's stride kinds of the session's foot unit, measured only when B134's
    line would otherwise be given (a ZUPT pass)."""
    if foot_placement_warning(stats, where) is None:
        return None
    from pdrlearn.track.stride_kinds import foot_stride_kinds

    return foot_placement_warning(stats, where, foot_stride_kinds(session))


#: decision L599: what the offline foot distance did at stride periods over L80's 3 s (L596's walks and trial T2's
#: sessions b175 and g_0.45_2.0, no model; decision L607: with L605 / L606's fresh users 11962-11967, 11974, 11976,
#: 11977 at 1.6-2.5 s steps)
SLOW_RHYTHM_DISTANCE = ("-16.64 to +14.03 % at 1.6-2.0 s steps of 0.2-0.45 m, +2.56 to +46.54 % at 2.5 s steps "
                        "(a gyroscope rate error grows over such long strides, L606), simulated")


def slow_rhythm_line(period: float, cap_s: float | None = None, window_s: float | None = None) -> str | None:
    """Decision L599: one line when the foot's own stride period ``period`` (s;
    :func:`~pdrlearn.kernels.foot_rhythm.foot_period`) is longer than L80's
    :data:`~pdrlearn.kernels.contact.MAX_STRIDE_S`: the strides are found (L597); with the track's stride cap
    ``cap_s`` over 3 s (decision L605, :func:`~pdrlearn.kernels.contact.stride_cap_s`) their stride times are given
    up to it, else every stride time, and so the cadence, speed and bouts, treats each stride as a stop. Decision
    L658: None when the strides' median rest-to-rest window ``window_s`` (s, None: not judged) fills less than L605's
    :data:`~pdrlearn.kernels.contact.RHYTHM_CAP_MIN_FILL` of the period (that rhythm is a stop-and-go cycle of
    short bouts, not the strides'). None otherwise."""
    from pdrlearn.kernels.contact import MAX_STRIDE_S, RHYTHM_CAP_MIN_FILL, RHYTHM_CAP_PERIODS

    if not np.isfinite(period) or period <= MAX_STRIDE_S:
        return None
    if window_s is not None and not window_s >= RHYTHM_CAP_MIN_FILL * period:  # decision L658 (L605's gate)
        return None
    head = (f"the foot's strides take {period:.1f} s (its gyroscope's rhythm, about {120 / period:.0f} steps/min; "
            "decision L596), longer than ")
    if cap_s is not None and cap_s > MAX_STRIDE_S:  # decision L605
        what = (f"L80's {MAX_STRIDE_S:g} s: stride times up to {cap_s:.1f} s ({RHYTHM_CAP_PERIODS:g} of that rhythm) "
                "count as strides and give the cadence, speed and walking bouts, longer ones are stops (decision "
                "L605); this is slower than the walking the pipelines were validated on; ")
    else:
        what = (f"the {MAX_STRIDE_S:g} s a stride may take (L80): this is slower than the walking the pipelines were "
                "validated on; no cadence, stride time or speed is given and each stride counts as a pause between "
                "walking bouts; ")
    return (head + what + f"the offline foot distance was measured at {SLOW_RHYTHM_DISTANCE} (no model; decisions "
            "L597, L599)")
