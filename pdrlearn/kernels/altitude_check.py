"""Plausibility of a foot track's height (decisions L69, C28): a warning where the altitude change would
otherwise be silently wrong.

- Without terrain classes (L69) the height of a stride is its integrated vertical displacement; on level foot
  recordings that reached 0.47 m per stride (L68), so the altitude change is said to be an integration.
- With a trained model's terrain classes (C28) a stride whose class contradicts its integrated height change
  (``up`` with dz <= 0, ``down`` with dz >= 0, ``flat`` with |dz| >= 0.10 m) is counted; many of them, or
  strides classed ``flat`` that add height, give one warning.

Numpy only: ``pdrlearn track`` (offline, ``--streaming``) and the streaming runtime (``Tracker.height_checks``,
``pdrlearn run``; decision E47) call these same functions.
"""

from __future__ import annotations

import re

import numpy as np

from pdrlearn.kernels.barometer import BARO_C_PER_M, BARO_EXPONENT, STANDARD_P0_HPA
from pdrlearn.kernels.distance import LEVEL_DZ_M

#: Decision L68 (experiments/level_dz.py): the largest integrated |dz| of a level stride on the gaitmap foot
#: recordings measured (gaitmap_ms_right) and the largest altitude change per 100 m of level walking there
#: (gaitmap_ms_left, dz before L39) - the accuracy the warnings quote.
LEVEL_STRIDE_DZ_MAX_M = 0.47
LEVEL_ALTITUDE_PER_100M_MAX_M = 4.7
#: Decision C28: a warning when at least this many strides, and this fraction of them, contradict their class,
CONFLICT_MIN_STRIDES = 3
CONFLICT_MIN_FRACTION = 0.10
#: or when the strides classed flat add at least this much (m) to the altitude change
FLAT_ALTITUDE_M = 0.5

#: decision C159 (session 41, trial T3 finding F5): a steady slope under the foot - at least this many consecutive
#: classified strides whose integrated height changes share one sign, each from :data:`SLOPE_STRIDE_DZ_MIN_M` to
#: under :data:`SLOPE_STRIDE_DZ_MAX_M` - makes C28's line name a ramp or slope the model never saw
SLOPE_MIN_STRIDES = 5
#: decision C159: the least |dz| (m) of a slope stride: L301's 3 % ramp grade over a 0.7 m stride (a slow walker's)
SLOPE_STRIDE_DZ_MIN_M = 0.02
#: decision C159: a slope stride's |dz| is under this (m): under one stair riser of the simulator's 0.17 m (S3)
#: climbed step-to-step; the foot's integrated heights read a 1:12 ramp's (8.33 %, ADA 2010 sec. 405.2) 1.5 m strides
#: at 0.127-0.151 m, ~15 % over the true 0.125 m (C159's measurement; 0.14 m, set first, missed them)
SLOPE_STRIDE_DZ_MAX_M = 0.16
#: decision C159: what C28's line adds on a steady slope
SLOPE_HINT = ("; the foot's height says a steady slope ({n} consecutive strides of {lo:.2f}-{hi:.2f} m one way): "
              "likely a ramp or slope the model never saw - terrain models (default or trained by `pdrlearn train` "
              "on the calibration exercises, which hold no ramp) class a downhill ramp's strides up and an uphill "
              "one's flat; for ramps and grades track with --altitude fused (ramps.csv, L300) (decision C159)")

_ACCURACY = (f"level walks measured gave integrated heights up to {LEVEL_STRIDE_DZ_MAX_M:.2f} m per stride and "
             f"{LEVEL_ALTITUDE_PER_100M_MAX_M:.1f} m per 100 m (L68)")


def integrated_altitude_check(dz: np.ndarray, levelled: bool = True, raw_dz: np.ndarray | None = None
                               ) -> tuple[str | None, dict]:
    """Decision L69: ``dz`` (m) the strides' final height changes of a track without terrain classes (after
    L39; ``levelled`` False: the streamed rules of a model without terrain classes keep every stride's raw
    height, C17). Returns the warning (None when every stride is level) and ``info["altitude_check"]``.
    ``raw_dz`` (the heights before L39, decision L145): ``info["level_zeroed_m"]``, the net height L39 set to 0
    (sum of raw minus final dz), and ``level_zeroed_strides``, how many strides it zeroed."""
    dz = np.asarray(dz, dtype=float)
    kept = np.abs(dz) >= LEVEL_DZ_M
    info = {"source": "integrated (no terrain classes)", "strides": len(dz), "strides_with_height": int(kept.sum()),
            "altitude_change_m": float(dz.sum()),
            "levelled": bool(levelled)}  # decision L717: L39's heights, which a foot track's own ramps are read from
    if raw_dz is not None and len(raw_dz) == len(dz):  # decision L145: what L39 discarded
        raw = np.nan_to_num(np.asarray(raw_dz, dtype=float))
        info["level_zeroed_m"] = float((raw - np.nan_to_num(dz)).sum())
        info["level_zeroed_strides"] = int(((dz == 0) & (raw != 0)).sum())
    if not kept.any():
        return None, info
    msg = (f"altitude change {dz.sum():+.2f} m is the foot's integrated height without terrain classes: "
           f"{int(kept.sum())} of {len(dz)} strides kept a height change >= {LEVEL_DZ_M:.2f} m "
           f"{'(L39 zeroes the others)' if levelled else '(streamed: no L39 level rule, each keeps its own)'}; "
           f"{_ACCURACY}, so it may be drift, not stairs; a model with terrain classes (`pdrlearn train`) "
           "decides which strides climb (decision L69)")
    return msg, info


#: Decision L430: the steepest stair a stride may climb or descend (deg). Building codes cap a stair's pitch at 42 deg
#: (UK Approved Document K 1.4, private stair; IBC 1011.5.2's 7 3/4 in rise on a 10 in tread is 37.8 deg); a one-tread
#: stride on such a stair (0.20 m rise, 0.22 m going) whose length reads two stride MAEs short (2 x 0.035 m, the
#: gaitmap level walk, decision D7) is still under 55 deg, so 60 deg leaves room for the track's own error.
STEEPEST_STAIR_DEG = 60.0
#: ... and how many such strides make the warning (one can be a stumble or a glitch)
STEEP_STRIDES_MIN = 2


def steep_stride_check(length: np.ndarray, dz: np.ndarray) -> tuple[str | None, dict]:
    """Decision L430: ``length`` (m, horizontal) and ``dz`` (m) of a foot track's strides. A stride that changes
    height by :data:`LEVEL_DZ_M` or more (L39) while moving less than |dz| / tan(:data:`STEEPEST_STAIR_DEG`)
    horizontally is steeper than any stair: its ends are not the foot's rests on two treads (a slow gait's mid-swing
    lull taken for a rest, S77, or a foot rest missed), so its height change is not a climb. With
    :data:`STEEP_STRIDES_MIN` of them, one warning; returns ``(line or None, info)``."""
    length = np.abs(np.nan_to_num(np.asarray(length, dtype=float)))
    dz = np.nan_to_num(np.asarray(dz, dtype=float))
    climb = np.abs(dz) >= LEVEL_DZ_M
    steep = climb & (length < np.abs(dz) / np.tan(np.radians(STEEPEST_STAIR_DEG)))
    n, k = int(climb.sum()), int(steep.sum())
    info = {"strides_with_height": n, "steep_strides": k, "steep_dz_m": float(dz[steep].sum())}
    if k < STEEP_STRIDES_MIN:
        return None, info
    return (f"{k} of the {n} strides that change height by {LEVEL_DZ_M:.2f} m or more do it over less horizontal "
            f"travel than a {STEEPEST_STAIR_DEG:.0f} deg slope allows (median {np.median(length[steep]):.2f} m for "
            f"{np.median(np.abs(dz[steep])):.2f} m of height; no building stair is steeper than 42 deg): these strides "
            "do not run from one rest of the foot on a tread to the next, so their "
            f"{dz[steep].sum():+.2f} m of height change is not a climb - on a slow gait (under ~70 steps/min) the "
            "foot's slow mid-swing can pass for a rest and split a stride (decisions S77, L430); check the altitude "
            "against a barometer (`--altitude fused`) or the lower back (`--pipeline waist-pendulum`)"), info


#: decision L543: at least this many strides a model classed up / down whose height the level rule zeroed, together
#: climbing at least :data:`ZEROED_CLIMB_MIN_M`, warn: a ramp run is at least two foot strides (L301's 2 m) and a stair
#: riser 0.17 m (the simulator's, L39) is the least height change a user reads as a climb
ZEROED_CLIMB_MIN_STRIDES = 2
ZEROED_CLIMB_MIN_M = 0.17


def judged_terrain(terrain, unjudged):
    """Decision C240: the terrain classes the height checks (C28 / C233's :func:`terrain_dz_check`, L543's
    :func:`zeroed_climb_check`) judge: None at the strides ``unjudged`` marks - a data gap's (E30) and one L94 moved
    0 m as impossible (its integrated height is no stride's: one such stride must not blame the terrain model).
    ``terrain`` (n,) with ``unjudged`` (n,) bool gives an (n,) object array; one stride's class with one bool (the
    live Tracker's, stride by stride) gives that class or None."""
    if np.ndim(unjudged) == 0:
        return None if unjudged else terrain
    return np.where(np.asarray(unjudged, dtype=bool), None, np.asarray(terrain, dtype=object))


def zeroed_climb_check(terrain, raw_dz: np.ndarray, dz: np.ndarray) -> tuple[str | None, dict]:
    """Decision L543: ``terrain`` (n,) a model's top terrain classes (None / NaN: none), ``raw_dz`` (n,) the strides'
    integrated height changes, ``dz`` (n,) the track's. A stride classed up (down) whose ``dz`` is 0 while its
    ``raw_dz`` rose (fell) lost its climb to L39's level rule (its class under L18's confidence gate, L184, and its
    |dz| under 0.10 m: a ramp stride - a 1:12 ramp rises 0.083 m per 1 m stride). With
    :data:`ZEROED_CLIMB_MIN_STRIDES` of them climbing :data:`ZEROED_CLIMB_MIN_M` or more, one warning; returns
    ``(line or None, info)``."""
    terr = np.array([t if isinstance(t, str) else "" for t in terrain], dtype=object)
    raw = np.nan_to_num(np.asarray(raw_dz, dtype=float))
    fin = np.nan_to_num(np.asarray(dz, dtype=float))
    zeroed = (fin == 0.0) & (((terr == "up") & (raw > 0)) | ((terr == "down") & (raw < 0)))
    up_m, down_m = float(raw[zeroed & (terr == "up")].sum()), float(raw[zeroed & (terr == "down")].sum())
    info = {"zeroed_climb_strides": int(zeroed.sum()), "zeroed_up_m": up_m, "zeroed_down_m": down_m}
    if zeroed.sum() < ZEROED_CLIMB_MIN_STRIDES or max(up_m, -down_m) < ZEROED_CLIMB_MIN_M:
        return None, info
    return (f"{int(zeroed.sum())} strides the model classed up or down kept no height ({up_m:+.2f} m up, "
            f"{down_m:+.2f} m down of integrated height left out): each changed height by under {LEVEL_DZ_M:.2f} m "
            "and its class was under the 0.95 confidence gate, so L39's level rule zeroed it (L184) - a ramp "
            "walked in strides of under 0.10 m rise (a 1:12 ramp at strides under 1.2 m), so the altitude and "
            "ramps.csv miss it; with a waist barometer, --altitude fused measures it (decision L543)"), info


def fused_altitude_line(msg: str, fused_m: float) -> str:
    """Decision L292: L69's line (:func:`integrated_altitude_check`) of a track whose altitude was then fused with
    the waist barometer (L154): it quotes the reported (fused) altitude change, the foot's own after it."""
    m = re.match(r"altitude change ([+-]\d+\.\d\d) m is the foot's integrated height without terrain classes", msg)
    if m is None:
        return msg
    return (f"altitude change {fused_m:+.2f} m (fused with the waist barometer, L154) is built on the foot's "
            f"integrated height without terrain classes ({m.group(1)} m)" + msg[m.end():])


def steady_slope(classified, raw_dz, min_strides: int = SLOPE_MIN_STRIDES,
                 dz_min_m: float = SLOPE_STRIDE_DZ_MIN_M, dz_max_m: float = SLOPE_STRIDE_DZ_MAX_M
                 ) -> tuple[int, int] | None:
    """Decision C159: ``(first, last + 1)`` of the longest run of at least ``min_strides`` consecutive ``classified``
    strides whose integrated height changes ``raw_dz`` share one sign with ``dz_min_m`` <= |dz| < ``dz_max_m``;
    None without one. A pure kernel."""
    raw = np.nan_to_num(np.asarray(raw_dz, dtype=float))
    ok = np.asarray(classified, bool) & (np.abs(raw) >= dz_min_m) & (np.abs(raw) < dz_max_m)
    best = None
    for sign in (1, -1):  # numpy only (the streaming runtime imports this module, E47)
        d = np.diff(np.concatenate([[0], (ok & (np.sign(raw) == sign)).astype(np.int8), [0]]))
        for a, b in zip(np.flatnonzero(d == 1), np.flatnonzero(d == -1), strict=True):
            if b - a >= min_strides and (best is None or b - a > best[1] - best[0]):
                best = (int(a), int(b))
    return best


#: decision C233 (session 49, trial s49t2 F4): a stride classed up / down whose integrated |dz| is under this (m)
#: clearly contradicts its class: half L39's 0.10 m level bound; a stair stride climbs at least one riser (IBC
#: 1011.5.2's least riser, 4 in = 0.10 m)
CLEAR_LEVEL_DZ_M = 0.05
#: decision C233: a stride classed flat whose integrated |dz| is this (m) or more clearly contradicts its class, next
#: to a stair stride or not: more than one riser of the steepest building stair (IBC 1011.5.2's 7 3/4 in = 0.20 m)
#: plus the track's error; a staircase's first or last stride (C30) climbs one riser only
CLEAR_STAIR_DZ_M = 0.25
#: decision C233: ... and a flat stride not next to a stair stride (C30) from this |dz| (m): a riser's 0.15 m
CLEAR_FLAT_ALONE_DZ_M = 0.15


def next_to_stairs(terr: np.ndarray) -> np.ndarray:
    """Decision C30: the strides of the string classes ``terr`` whose previous or next stride is classed up / down."""
    stairs = (terr == "up") | (terr == "down")
    near = np.zeros(len(terr), dtype=bool)
    near[1:] |= stairs[:-1]
    near[:-1] |= stairs[1:]
    return near


def clear_contradictions(terr: np.ndarray, raw: np.ndarray, near: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Decision C233: the masks (strides classed up / down with |dz| < :data:`CLEAR_LEVEL_DZ_M`, strides classed flat
    with |dz| >= :data:`CLEAR_STAIR_DZ_M`, or >= :data:`CLEAR_FLAT_ALONE_DZ_M` when not ``near`` a stair stride, C30)
    of the string classes ``terr`` and the integrated heights ``raw`` (NaN: not counted)."""
    size = np.abs(np.asarray(raw, dtype=float))
    ok = np.isfinite(size)
    size = np.where(ok, size, 0.0)
    level = ok & ((terr == "up") | (terr == "down")) & (size < CLEAR_LEVEL_DZ_M)
    stair = ok & (terr == "flat") & (size >= np.where(near, CLEAR_STAIR_DZ_M, CLEAR_FLAT_ALONE_DZ_M))
    return level, stair


def clear_contradiction_line(n_level: int, n_stair: int, n: int) -> str:
    """Decision C233: the line (or C28's clause) for the strides :func:`clear_contradictions` counted."""
    from pdrlearn.decision_refs import decision_ref

    return (f"{n_level + n_stair} of {n} strides' terrain classes clearly contradict the foot's measured height "
            f"({n_level} classed up/down that changed height by under {CLEAR_LEVEL_DZ_M:.2f} m, {n_stair} classed "
            f"flat that climbed or descended {CLEAR_FLAT_ALONE_DZ_M:.2f} m or more, or {CLEAR_STAIR_DZ_M:.2f} m next "
            "to a stair stride): the altitude and stairs.csv use the measured heights, the terrain column is the "
            "model's class - the measured terrain is steps.csv's terrain_dz (offline track, L424); check the model "
            f"on this user's own labelled walk (`pdrlearn evaluate MODEL DIR`) "
            f"({decision_ref('C233', 'C28', topic='classifiers')})")


def terrain_dz_check(terrain, raw_dz: np.ndarray, dz: np.ndarray, *,
                     clear_line: bool = True) -> tuple[str | None, dict]:
    """Decision C28: ``terrain`` (n,) a model's classes (None/NaN: not classified, not counted), ``raw_dz`` (n,)
    the integrated height changes before the rules, ``dz`` (n,) the track's final ones. Returns the warning
    (None when the classes and heights agree well enough) and ``info["terrain_dz_check"]``. ``clear_line``
    (decision C233, adopted): a stride whose measured height clearly contradicts its class is said from one; False
    gives C28's thresholds alone (the measurement's baseline; a keyword, no module switch: W413)."""
    terr = np.array([t if isinstance(t, str) else "" for t in terrain], dtype=object)
    raw = np.asarray(raw_dz, dtype=float)
    fin = np.asarray(dz, dtype=float)
    up, down, flat = terr == "up", terr == "down", terr == "flat"
    sign = (up & (raw <= 0)) | (down & (raw >= 0))
    # decision C30: a flat stride next to an up/down stride is a stair's first or last stride (a transition
    # that does climb); it is not counted against its class, nor in the height the flat strides add
    near = next_to_stairs(terr)
    flat = flat & ~near
    level = flat & (np.abs(raw) >= LEVEL_DZ_M)
    n = int((up | down | (terr == "flat")).sum())
    bad = int(sign.sum() + level.sum())
    flat_alt = float(fin[flat].sum())
    info = {"strides_classified": n, "stairs_against_sign": int(sign.sum()), "flat_with_height": int(level.sum()),
            "altitude_from_flat_m": flat_alt,
            "flat_next_to_stairs": int(((terr == "flat") & near).sum())}
    masks = clear_contradictions(terr, raw, near)  # decision C233 (counted; said unless clear_line=False)
    info["clear_level_as_stairs"], info["clear_stairs_as_flat"] = clear = tuple(int(m.sum()) for m in masks)
    clear = clear if clear_line else (0, 0)
    many = bad >= CONFLICT_MIN_STRIDES and n and bad >= CONFLICT_MIN_FRACTION * n
    if not (many or abs(flat_alt) >= FLAT_ALTITUDE_M):
        return (clear_contradiction_line(*clear, n) if sum(clear) else None), info
    counts = (f"{int(sign.sum())} up/down against its sign, {int(level.sum())} flat with |dz| >= "
              f"{LEVEL_DZ_M:.2f} m")
    flat_part = f"strides classed flat (not next to stairs, C30) add {flat_alt:+.2f} m to the altitude change"
    # decision B135: the line starts with what triggered it (the count, or only the flat strides' height)
    lead = (f"{bad} of {n} strides' terrain classes contradict their integrated height change ({counts}); "
            f"{flat_part}" if many else
            f"{flat_part} (C28 warns from {FLAT_ALTITUDE_M:.2f} m), though only {bad} of {n} strides' terrain "
            f"classes contradict their integrated height change ({counts})")
    msg = (f"{lead}: the classes or the foot's integrated height are wrong ({_ACCURACY}); check the model on "
           "this user's own labelled walk (`pdrlearn evaluate MODEL DIR`)")
    if sum(clear):  # decision C233: C28's line carries the clear contradictions' count
        msg += (f"; {sum(clear)} strides clearly contradict it ({clear[0]} up/down under {CLEAR_LEVEL_DZ_M:.2f} m, "
                f"{clear[1]} flat climbing a stair's height; C233)")
    slope = steady_slope(up | down | (terr == "flat"), raw)  # decision C159
    if slope is not None:  # info["steady_slope_strides"]: the slope strides named (absent: none)
        info["steady_slope_strides"] = slope[1] - slope[0]
        size = np.abs(np.nan_to_num(raw[slope[0]:slope[1]]))
        msg += SLOPE_HINT.format(n=slope[1] - slope[0], lo=float(size.min()), hi=float(size.max()))
    return msg, info


#: Decision L146: the hysteresis band (m) of the cumulative ascent / descent of a lower-back track, whose z is the
#: barometer's: 4 x the BMP280's 0.13 m per-sample altitude noise (thesis Table 18: 0.0157 hPa; W89), so level
#: walking's barometer noise adds no ascent. Foot tracks use 0: their strides' heights are already levelled
#: (L39) or set by terrain classes.
ASCENT_BAND_BARO_M = 0.5


#: Decision L172: a barometric altitude change counts towards the ascent / descent only when it crosses
#: :data:`ASCENT_BAND_BARO_M` within this many seconds (a storey is climbed in well under a minute); 0.5 m per
#: minute is a 0.6 % slope at 1.4 m/s and 12x the weather's 0.3 hPa/h drift (~0.04 m per minute, decision S4)
CLIMB_WINDOW_S = 60.0


#: Decision W229: the rate (m/s) under which a barometric change is the weather's drift, not a climb: L172's own
#: bound, :data:`ASCENT_BAND_BARO_M` per :data:`CLIMB_WINDOW_S` (0.5 m per minute, 12x the 0.3 hPa/h drift, S4)
DRIFT_RATE_M_PER_S = ASCENT_BAND_BARO_M / CLIMB_WINDOW_S
#: Decision W229: the span (s) over which that rate is read before and after each change: half L172's window, so
#: a change of 0.25 m within 30 s is a climb; the 1-s averaged altitude's noise (0.13 m / sqrt(20) at 20 Hz, W89)
#: gives a rate SD of ~0.0014 m/s there, 1/6 of the bound
DRIFT_RATE_SPAN_S = CLIMB_WINDOW_S / 2


#: Decision W370: the fastest weather, a pressure "rising / falling very rapidly": more than 6.0 hPa in 3 hours
#: (the WMO pressure-tendency terms of marine forecasts) = 2 hPa/h, at the barometric formula's 1 / (C E P0) =
#: 8.32 m/hPa at sea level (kernels.barometer, ICAO standard atmosphere): 16.6 m/h, 0.0046 m/s (0.28 m per minute)
WEATHER_RATE_MAX_M_PER_S = 2.0 / (BARO_C_PER_M * BARO_EXPONENT * STANDARD_P0_HPA) / 3600.0
#: Decision W370 (an option, measured and not adopted: the nine mobgap lower-back recordings' ascent + descent rose
#: 16.629 -> 17.940 m, HA001 Test5 Trial1's by 0.687 m, over the rule's 1.0 / 0.5 m): True = a barometric track's
#: ascent / descent are :func:`climbs_within_weather`'s; False (the default): L172's count
CLIMBS_WITHIN_WEATHER = False


def climbs_within_weather(z: np.ndarray, t: np.ndarray, band_m: float = ASCENT_BAND_BARO_M,
                          window_s: float = CLIMB_WINDOW_S) -> tuple[float, float]:
    """Decision W370 (with :data:`CLIMBS_WITHIN_WEATHER`; else L172's count as it is): the barometric ascent /
    descent (m) of ``z`` at the times ``t`` (s): L172's (the band crossed
    within ``window_s``, :func:`ascent_descent`) where the drift it drops (the net change less ascent plus descent)
    is one the weather can make in the track's span at :data:`WEATHER_RATE_MAX_M_PER_S`; else - a drift larger than
    that, or a span too short for the fastest weather to cross ``band_m`` at all - what L172 dropped was the
    remainder of climbs (the end of a flight down, the top of a flight), and the climbs are counted from turning
    point to turning point (W229's count on z as it is, the end's remainder too: ascent - descent = the net
    change)."""
    up, down = ascent_descent(z, band_m, t, window_s)
    if not CLIMBS_WITHIN_WEATHER:
        return up, down
    z = np.asarray(z, dtype=float).ravel()
    t = np.asarray(t, dtype=float).ravel()
    keep = np.isfinite(z) & np.isfinite(t)
    z, t = z[keep], t[keep]
    if len(z) < 2:
        return up, down
    limit = WEATHER_RATE_MAX_M_PER_S * float(t[-1] - t[0])
    if limit < band_m or abs(float(z[-1] - z[0]) - up + down) > limit:
        return _zigzag(z, band_m)
    return up, down


def drift_free_altitude(z: np.ndarray, t: np.ndarray, rate_m_s: float = DRIFT_RATE_M_PER_S,
                        span_s: float = DRIFT_RATE_SPAN_S) -> np.ndarray:
    """Decision W229: the altitudes ``z`` (m) at the times ``t`` (s, increasing) without the weather's slow drift.
    Each change between two samples is read against the altitude's mean rate over ``span_s`` ending at its end
    and over ``span_s`` starting at its start (at least the interval itself: a standstill's ride is read over the
    stand); when both are under ``rate_m_s`` it is drift and removed, else (a climb, a ramp, a ride, and the noise
    around them) it is kept. Two one-sided spans, not one centred: a climb straight up and back down (a stair
    flight, a turn, the flight down) cancels in a centred mean. A climb of 0.4 m in 5 s is kept whole, however
    long the walk stays level after it (L172 dropped what of a climb had not crossed its band when its window ran
    out). Returns z rebuilt from the kept changes (same start)."""
    z = np.asarray(z, dtype=float).ravel()
    t = np.asarray(t, dtype=float).ravel()
    if len(z) < 2:
        return z.copy()
    a, b = t[:-1], t[1:]

    def rate(lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
        lo, hi = np.maximum(lo, t[0]), np.minimum(hi, t[-1])
        return np.abs(np.interp(hi, t, z) - np.interp(lo, t, z)) / np.maximum(hi - lo, 1e-9)

    fast = np.maximum(rate(np.minimum(a, b - span_s), b), rate(a, np.maximum(b, a + span_s))) >= rate_m_s
    return np.concatenate([[z[0]], z[0] + np.cumsum(np.where(fast, np.diff(z), 0.0))])


def ascent_descent(z: np.ndarray, band_m: float = 0.0, t: np.ndarray | None = None,
                   window_s: float | None = None, *, by_rate: bool = False) -> tuple[float, float]:
    """Decision L146: the cumulative ascent and descent (m, both >= 0) of the altitudes ``z`` (walking order):
    a change counts once z has moved at least ``band_m`` from the last counted level (a hysteresis; 0 = every
    rise and every drop), and the last level's difference to the final z is counted at the end, so ascent -
    descent is the net change exactly. Non-finite values are skipped.

    Decision L172: with the times ``t`` (s) and ``window_s`` the band must be crossed within ``window_s``: where
    z has not moved ``band_m`` from the last counted level after ``window_s``, that level follows z (it becomes
    z as it was ``window_s`` earlier), so a slow drift is dropped, and nothing is counted at the end.
    Decision W229 (``by_rate``, an option measured and not adopted: CURB's 0.45 m on waist-pendulum read 0.063 m
    off, its rule 0.06 m; decision L584: a keyword, no module switch): with ``t`` and ``window_s`` the weather's
    slow drift is first taken out by its rate
    (:func:`drift_free_altitude`; the rate bound is ``band_m`` per ``window_s``), then the swings of at least
    ``band_m`` are counted whole, from turning point to turning point (a zigzag: a climb's top is counted when z
    has come ``band_m`` down from it, so no part of a climb under the band is lost), and the end's remainder too;
    ascent - descent is the net change without the drift."""
    z = np.asarray(z, dtype=float).ravel()
    keep = np.isfinite(z)
    z = z[keep]
    if len(z) < 2:
        return 0.0, 0.0
    if band_m <= 0:
        d = np.diff(z)
        return float(d[d > 0].sum()) + 0.0, float(-d[d < 0].sum()) + 0.0
    bounded = t is not None and window_s is not None
    tt = np.asarray(t, dtype=float).ravel()[keep] if bounded else np.zeros(len(z))
    if bounded and by_rate:  # decision W229
        return _zigzag(drift_free_altitude(z, tt, band_m / window_s, window_s / 2), band_m)
    up = down = 0.0
    ref, r = float(z[0]), 0  # the last counted level and its sample
    for i in range(1, len(z) + (0 if bounded else 1)):
        last = i == len(z)
        v = float(z[-1]) if last else float(z[i])
        if v - ref >= (0.0 if last else band_m):
            up, ref, r = up + v - ref, v, i
        elif ref - v >= (0.0 if last else band_m):
            down, ref, r = down + ref - v, v, i
        elif bounded and tt[i] - tt[r] > window_s:  # decision L172: not crossed within the window: follow z
            r = int(np.searchsorted(tt, tt[i] - window_s))
            ref = float(z[r])
    return up, down


def _zigzag(z: np.ndarray, band_m: float) -> tuple[float, float]:
    """Decision W229: the ascent and descent of ``z`` between its turning points, a turning point being an extreme
    that z then leaves by ``band_m`` the other way; the remainder to the last value is counted at the end."""
    up = down = 0.0
    ref = ext = float(z[0])  # the last turning point, the extreme since
    sign = 0
    for v in map(float, z[1:]):
        if sign == 0:
            if abs(v - ref) >= band_m:
                sign, ext = (1 if v > ref else -1), v
        elif (v - ext) * sign > 0:
            ext = v
        elif (ext - v) * sign >= band_m:
            up, down = (up + ext - ref, down) if sign > 0 else (up, down + ref - ext)
            ref, ext, sign = ext, v, -sign
    for a, b in ((ref, ext), (ext, float(z[-1]))):
        up, down = up + max(b - a, 0.0), down + max(a - b, 0.0)
    return up, down
