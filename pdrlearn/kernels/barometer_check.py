"""Decision L145's foot-vs-barometer altitude check, numpy only: the summary keys from the barometric altitude at the
strides' ends (:func:`barometer_keys`) and the warning line on them (:func:`barometer_warning`), shared by ``pdrlearn
track`` / ``run`` (:mod:`pdrlearn.track.evaluate`, which re-exports them) and the live
:class:`~pdrlearn.runtime.Tracker` (decision E232)."""

from __future__ import annotations

import numpy as np

#: decision L145: a foot track's altitude change and the unused waist barometer's may differ by this much (m)
#: plus the weather's drift over the track before a warning: 0.5 m is ~4 SDs of one barometer sample's altitude
#: noise (0.13 m, W89) and ~7 strides of a 5 % slope that L39 reads level
BAROMETER_DISAGREE_M = 0.5
#: decision L145: the weather's pressure drift, 0.3 hPa per hour (the simulator's 1-SD trend, decision S4, from
#: thesis Table 18's 30-day range) = ~2.5 m of barometric altitude per hour
BAROMETER_DRIFT_M_PER_H = 2.5
#: decision B453: a foot accelerometer clipped at this full scale (g) or more cost the simulated walks nothing
#: measurable (+-16 g; +-8 g cost 0.22 m of end height, :data:`pdrlearn.io.validate.FOOT_ACCEL_CLIP_COST`), so
#: L688's line calls clipping the likely cause only under it (review R2 finding F2)
CLIP_COSTLESS_G = 12.0


#: decision L180: what the foot cannot see, named in L145's line: a ride (lift, escalator; no strides while the
#: height changes, the likely cause indoors) and slopes / hills (L144, outdoors)
_FOOT_BLIND = ("the foot's height is integrated stride by stride: it misses a lift or escalator ride (the likely "
               "cause indoors: the height changes while the feet stand) and slopes and hills (L144)")


def ridden_climbs(summary: dict) -> dict | None:
    """Decision L396: a foot track's rides read from the barometer (L378; ``info["rides"]``) as their height up
    (``"ascent"``), down (``"descent"``, positive) and net (``"net"``); None where no ride was read."""
    rides = (summary.get("info") or {}).get("rides")
    if rides is None:
        return None
    # decision L632: a ride without a barometric height (L624's vibration rows: dz_m empty) adds none
    dz = [float(r["dz_m"]) for r in rides if r.get("dz_m") is not None and np.isfinite(float(r["dz_m"]))]
    return {"ascent": sum(d for d in dz if d > 0), "descent": -sum(d for d in dz if d < 0), "net": sum(dz)}


def _climb_miss(summary: dict, ridden: dict | None = None) -> tuple[str, float] | None:
    """Decision L180: the barometer's ascent or descent (``barometer_ascent_m`` / ``barometer_descent_m``, L172's
    climbs of 0.5 m within a minute) that the track's own (``ascent_m`` / ``descent_m``) misses by the most, as
    (``"ascent"`` or ``"descent"``, metres missed); None without them. Decision L396: ``ridden``
    (:func:`ridden_climbs`), the rides' part of the barometer's climbs is no miss."""
    misses = [(k, float(summary[f"barometer_{k}_m"]) - (ridden or {}).get(k, 0.0) - float(summary[f"{k}_m"]))
              for k in ("ascent", "descent")
              if summary.get(f"barometer_{k}_m") is not None and summary.get(f"{k}_m") is not None]
    return max(misses, key=lambda m: m[1]) if misses else None


def clipped_cause(clip_g: float | None, fused: bool, over_m: float) -> str:
    """Decision L688 (trial T3 finding F2): the words naming a clipped foot accelerometer (B77, at +-``clip_g`` g) as
    the likely cause of a foot altitude the barometer disagrees with, and ``--altitude fused`` as the remedy when the
    track did not fuse it; "" when the accelerometer did not clip (None). Amended (review R2 finding F2): the likely
    cause only where its creep points - the foot above the barometer, ``over_m`` (foot - barometer, m) more than
    the limit (the caller's ``inf``: above) - and its size is measured (a full scale under
    :data:`CLIP_COSTLESS_G`); otherwise the clipping is only named, "also clips"."""
    if not clip_g:
        return ""
    if not over_m > 0:  # a clipped heel strike makes the foot climb (L688): a foot below the barometer is not it
        return f"the foot accelerometer also clips at +-{clip_g:.3g} g (B77; it would make the foot read higher); "
    if not clip_g < CLIP_COSTLESS_G:
        return (f"the foot accelerometer also clips at +-{clip_g:.3g} g (B77; at +-{CLIP_COSTLESS_G:g} g or more "
                "simulated walks up to a brisk 2.26 m/s lost no height measurable, B453); ")
    return (f"the foot accelerometer clips at +-{clip_g:.3g} g (B77), the likely cause here: a clipped heel strike "
            "leaves each stride's vertical velocity off, so the foot's height creeps stride by stride"
            + ("" if fused else "; `track --altitude fused` (L154) takes the height from the barometer instead")
            + " (decision L688); otherwise ")


def barometer_warning(summary: dict, *, foot_clip_g: float | None = None) -> str | None:
    """Decision L145: one line when a foot track's ``altitude_change_m`` and the session's waist barometer
    (``barometer_altitude_change_m``, recorded; read by the foot pipeline only with ``altitude="fused"``, L154)
    differ by more than ``barometer_disagree_limit_m`` (:data:`BAROMETER_DISAGREE_M` + the weather's drift over the
    track), with the height L39 set to 0 (``info.altitude_check.level_zeroed_m``) when known; None otherwise.
    Decision L172: the barometer's change compared is its climbs' (``barometer_climb_change_m``, changes of 0.5 m
    within a minute), so the weather's slow drift does not blame the foot; a drift is named in the line; a fused
    track's own altitude is compared by its climbs too (``altitude_change_m`` - ``altitude_drift_m``).
    Decision L180: when the net changes agree, the climbs are compared: the barometer's ascent (descent) that the
    track's ``ascent_m`` (``descent_m``) misses by more than the same limit (a lift or escalator ride up and back
    down, a hill up and down) is one line too; both lines name a lift or escalator as the likely cause indoors."""
    raw = summary.get("barometer_altitude_change_m")
    baro = summary.get("barometer_climb_change_m", raw)
    foot = summary.get("altitude_change_m")
    if foot is not None and summary.get("altitude_drift_m") is not None:  # fused (L154): its climbs too, L172
        foot = float(foot) - float(summary["altitude_drift_m"])
    limit = summary.get("barometer_disagree_limit_m", BAROMETER_DISAGREE_M)
    if baro is None or foot is None:
        return None
    fused = not summary.get("barometer_unused", True)  # decision L154: the barometer was fused into the altitude
    # decision L396: the rides L378 read are no disagreement; L632: a fused track's too (L154 fuses the strides'
    # height: its z leaves the rides out as the foot's does)
    ridden = ridden_climbs(summary)
    source = (f"(wBarometer.csv, {'fused with the strides by L154' if fused else 'not read by foot tracks'})"
              if ridden is None else "(wBarometer.csv, " + ("fused with the strides by L154" if fused else
                                                            "read for rides only, L378")
              + (f"; without its rides' {ridden['net']:+.2f} m, L396)" if ridden["net"] else ")"))
    if ridden is not None:
        baro, raw = float(baro) - ridden["net"], float(baro if raw is None else raw) - ridden["net"]
    # decision L632: a track whose rides.csv holds a ride read the lifts; the lower back would read no more of them
    lifts = ("" if ridden is not None and (ridden["ascent"] or ridden["descent"]) else
             "; for floors by lift or escalator track the lower back, `--pipeline waist-pendulum`")
    cause = clipped_cause(foot_clip_g, fused, float(foot) - float(baro))  # decision L688
    advice = (lifts + "; for altitude on slopes, hills and ramps "
              + ("" if fused else "fuse the barometer, `--altitude fused` (L154), or ") + "track the lower back")
    if not abs(float(foot) - float(baro)) > float(limit):
        miss = _climb_miss(summary, ridden)  # decision L180: the net agrees; did the foot miss a climb and its return?
        if miss is None or not miss[1] > float(limit):
            return None
        kind, missed = miss
        return (f"the waist barometer {source} climbed {float(summary['barometer_ascent_m']):.2f} m and descended "
                f"{float(summary['barometer_descent_m']):.2f} m (0.5 m within a minute, L172), the track "
                f"{float(summary['ascent_m']):.2f} m and {float(summary['descent_m']):.2f} m: its {kind} misses "
                f"{missed:.2f} m (more than {float(limit):.2f} m) although the net changes agree "
                f"({float(foot):+.2f} m against {float(baro):+.2f} m; L180); {_FOOT_BLIND}{advice}")
    check = (summary.get("info") or {}).get("altitude_check") or {}
    zeroed = check.get("level_zeroed_m")
    why = ("" if zeroed is None else
           f"; L39 set {check.get('level_zeroed_strides', 0)} strides under 0.10 m of height change to level, "
           f"{float(zeroed):+.2f} m in all (a slope under ~7 % reads level on the foot)")
    drift = float(raw) - float(baro)
    drifted = (f" ({float(raw):+.2f} m recorded, of which {drift:+.2f} m slow drift, L172: the weather, which "
               "`--altitude fused` adds to altitude_change_m)" if abs(drift) > BAROMETER_DISAGREE_M else "")
    closed = _closed_by_floors(summary, float(foot))
    if closed and not fused:  # decision L225: the foot's floors close the loop; fusing would add the barometer's error
        return (f"foot altitude change {float(foot):+.2f} m disagrees with the waist barometer's {float(baro):+.2f} m"
                f"{drifted} {source} by {abs(float(foot) - float(baro)):.2f} m (more than {float(limit):.2f} m){why}; "
                f"{closed}: if the walk ended on the storey it started on, the foot's height is the right one and "
                f"the barometer's {float(baro):+.2f} m is its own error (its climbs of 0.5 m within a minute, L172, "
                "do not cancel), which `--altitude fused` would add to the track: keep the foot's altitude; "
                f"otherwise {_FOOT_BLIND}{advice} (decision L225)")
    return (f"foot altitude change {float(foot):+.2f} m disagrees with the waist barometer's {float(baro):+.2f} m"
            f"{drifted} {source} by {abs(float(foot) - float(baro)):.2f} m (more than {float(limit):.2f} m){why}; "
            f"{cause}{_FOOT_BLIND}{advice}")


def _closed_by_floors(summary: dict, foot: float) -> str | None:
    """Decision L225: the words for a foot track whose floors close a loop - it climbed and descended as many storeys
    (``floors_up`` = ``floors_down`` > 0) and its altitude change is under half a storey (``storey_height_m``) - else
    None."""
    up, down, storey = summary.get("floors_up"), summary.get("floors_down"), summary.get("storey_height_m")
    if not up or up != down or storey is None or not abs(foot) < 0.5 * float(storey):
        return None
    return (f"the foot climbed {int(up)} and descended {int(down)} storeys of {float(storey):g} m and ends "
            f"{foot:+.2f} m from its start")


def barometer_keys(at: np.ndarray, z: np.ndarray, change_m: float) -> dict:
    """Decisions L145 / L172 / L180 / L290 (E232: one function for the offline summary and the live Tracker): the
    barometer's keys of a foot track from its altitude ``z`` (m, relative to the first) at the times ``at`` (s: the
    strides' span start, then their ends) and ``change_m`` (its change over the span, ``relative_altitude`` at the
    span's end): ``barometer_altitude_change_m``, ``barometer_climb_change_m`` (without the weather's slow drift,
    W229), ``barometer_ascent_m`` / ``barometer_descent_m`` (L172's climbs), ``barometer_drift_m`` and
    ``barometer_disagree_limit_m``."""
    from pdrlearn.kernels.altitude_check import ASCENT_BAND_BARO_M, CLIMB_WINDOW_S, ascent_descent, drift_free_altitude

    at, z = np.asarray(at, dtype=float), np.asarray(z, dtype=float)
    up, down = ascent_descent(z, ASCENT_BAND_BARO_M, at, CLIMB_WINDOW_S)
    # decision L290 (L172): the barometer's NET change without the weather's slow drift (W229's rate), not the
    # climbs' up - down, which left a band's remainder of each climb out (a 1:12 loop: +0.41 m for -0.01 m)
    climb = float(drift_free_altitude(z, at)[-1] - z[0]) if len(z) else 0.0
    span = float(at[-1] - at[0]) if len(at) else 0.0
    return {"barometer_altitude_change_m": float(change_m), "barometer_climb_change_m": climb,
            "barometer_ascent_m": float(up), "barometer_descent_m": float(down),  # decision L180: the climbs
            "barometer_drift_m": float(change_m) - climb,
            "barometer_disagree_limit_m": BAROMETER_DISAGREE_M + BAROMETER_DRIFT_M_PER_H * span / 3600}
