"""``aid_track``: absolute fixes applied to a PDR track (the ``pdrlearn track --gnss/--fixes`` options), and
``plot_aided``: PDR-only, fixes and fused paths on one figure."""

from __future__ import annotations

import logging
import math
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.aid.fixes import DEFAULT_RMC_ACCURACY_M, FixLog, read_fixes, to_local
from pdrlearn.aid.geo import enu_to_geodetic
from pdrlearn.aid.gnss import GnssPdrFusion
from pdrlearn.aid.sporadic import SporadicFixFusion
from pdrlearn.decision_refs import decision_ref
from pdrlearn.errors import DataError
from pdrlearn.io.session import Session
from pdrlearn.kernels.fixes import FIX_TIME_HINT, initial_fix_sigma, sigma_from_accuracy, start_fixes
from pdrlearn.track.base import TrackResult

log = logging.getLogger(__name__)


def _parse_start(start) -> tuple[float, float] | None:
    if start is None:
        return None
    if isinstance(start, str):
        from pdrlearn.track.geodetic import parse_start

        lat, lon = parse_start(start)
    else:
        lat, lon = (float(v) for v in start)
    return lat, lon


def _utc_day_s(when) -> float:
    """UTC seconds of day of an aware datetime."""
    from datetime import UTC

    u = when.astimezone(UTC)
    return u.hour * 3600.0 + u.minute * 60.0 + u.second + u.microsecond * 1e-6


def _first_fix_session_t(flog: FixLog, session: Session, offset_s: float | None) -> tuple[float, str]:
    """Decision D38: the session-clock time (s) of a fix log's first fix, and how it was found.

    In order: ``offset_s`` (``--gnss-time-offset``: seconds after the session start); the log's absolute time against
    the session's absolute start -- a GPX / ISO-time CSV's UTC date-time against meta.json ``recording_start`` (with a
    UTC offset, L298), an NMEA UTC time of day against ``utc_start_s`` or the ``recording_start``'s UTC time of day
    (the nearest day); else the session start (``"assumed"``: the caller warns)."""
    st = flog.stats
    if offset_s is not None:
        return session.t_start + float(offset_s), "offset"
    meta = session.meta if isinstance(session.meta, dict) else {}
    from pdrlearn.track.clock import recording_start

    start = recording_start(meta, session.where)
    aware = start is not None and start.utcoffset() is not None
    utc0 = meta.get("utc_start_s")
    if st.get("time_base") == "utc" and aware:
        return float(st["first_epoch_s"]) - start.timestamp(), "recording_start"  # 0 s of the session = start
    tod = st.get("first_utc_s") if st.get("time_base") == "utc_day" else (
        float(st["first_epoch_s"]) % 86400.0 if st.get("time_base") == "utc" else None)
    if tod is not None and utc0 is not None:  # UTC seconds of day at the session clock's t_start
        return session.t_start + (tod - float(utc0) + 43200.0) % 86400.0 - 43200.0, "utc_start_s"
    if tod is not None and aware:
        return (tod - _utc_day_s(start) + 43200.0) % 86400.0 - 43200.0, "recording_start"
    return session.t_start, "assumed"


def check_time_offset(offset_s: float | None) -> float | None:
    """Decision D42: ``--gnss-time-offset`` (``gnss_time_offset_s``) as a float, None kept; a non-finite value (nan,
    inf) is refused in one line (it put every fix at nan / inf s, so the track was written unaided)."""
    if offset_s is None:
        return None
    if not math.isfinite(float(offset_s)):
        raise DataError(f"--gnss-time-offset {offset_s}: not a finite number of seconds; give the first fix's seconds "
                        "after the session start (e.g. --gnss-time-offset 120), or drop it to place the log by "
                        "meta.json recording_start")
    return float(offset_s)


#: decision D42: the all-outside line's advice, by how the log's times were placed (``time_alignment``, D38)
OUTSIDE_HINTS = {
    "offset": "--gnss-time-offset put the first fix at {first:.1f} s; give the first fix's seconds after the "
              "session start",
    "recording_start": "the log's UTC times were placed by meta.json recording_start (first fix at {first:.1f} s); "
                       "check recording_start's date, time and UTC offset, or pass --gnss-time-offset S",
    "utc_start_s": "the log's UTC times were placed by meta.json utc_start_s (first fix at {first:.1f} s); check "
                   "utc_start_s, or pass --gnss-time-offset S",
    "assumed": "the first fix was taken at the session start ({first:.1f} s); pass --gnss-time-offset S (the first "
               "fix's seconds after the session start) or write recording_start in meta.json",
}


def _outside_hint(stats: dict) -> str:
    """Decision D42: the advice of the "none of the fixes lies within the track" line: a CSV's session-seconds
    ``t`` (:data:`FIX_TIME_HINT`) or, for a log placed by D38, how it was placed (:data:`OUTSIDE_HINTS`)."""
    how = stats.get("time_alignment")
    if how not in OUTSIDE_HINTS:
        return FIX_TIME_HINT.replace("a fix's t", "a fix CSV's t")
    return OUTSIDE_HINTS[how].format(first=float(stats.get("first_fix_s", float("nan"))))


def _blank_hdop_line(path, flog: FixLog) -> str | None:
    """Decision D44: one line counting a fix CSV's blank ``hdop`` cells (kept with the default accuracy), or None."""
    n = int(flog.stats.get("blank_hdop", 0))
    if not n:
        return None
    return (f"aid: {path}: {n} of {flog.stats['lines']} fix(es) have a blank hdop (unknown accuracy) and were kept "
            f"with the default accuracy {DEFAULT_RMC_ACCURACY_M:g} m, as a GPX point without <hdop> (decision D44); "
            "give accuracy_m or hdop for every fix to weight them by it")


#: decision D47: how far (s) a fix CSV's epoch-second times may lie outside the session's own time span and still be
#: read on its clock (a receiver logging a little before the first or after the last IMU sample)
SESSION_CLOCK_MARGIN_S = 5.0


def on_session_epoch_clock(stats: dict, session: Session, margin_s: float = SESSION_CLOCK_MARGIN_S) -> bool:
    """Decision D47 (amends D46): whether a fix CSV's numeric epoch-second ``t`` (``stats['time_source']``
    "epoch_seconds") is the session's own clock -- a session whose timestamps are epoch ms (PLASYS) has session
    seconds of ~1.77e9 -- so its fixes are kept as session seconds, not placed as UTC by D38: true when the fixes'
    span [first, last] overlaps the session's [t_start, t_end] widened by ``margin_s``."""
    if stats.get("time_source") != "epoch_seconds" or not session.streams:
        return False
    first, last = float(stats["first_epoch_s"]), float(stats["last_epoch_s"])
    return first <= session.t_end + margin_s and last >= session.t_start - margin_s


def _load(path, session: Session, offset_s: float | None = None) -> tuple[FixLog, list[str]]:
    """Read a fix file (NMEA, GPX or CSV, decision D37) and put its times on the session clock (decision D38);
    returns the log and its warning lines: blank hdop cells (D44), times that could not be placed (D38)."""
    path = Path(path)
    if not path.is_file():
        raise DataError(f"{path}: no such fix file; pass an NMEA log (.nmea/.txt), a GPX track (.gpx) or a CSV "
                        "(t, lat, lon, accuracy_m)")
    offset_s = check_time_offset(offset_s)
    out = read_fixes(path)
    lines = [x for x in [_blank_hdop_line(path, out)] if x]
    if on_session_epoch_clock(out.stats, session):  # decision D47: epoch seconds that are the session's own clock
        out.fixes["t"] = out.fixes["t"] + float(out.stats.pop("first_epoch_s"))
        for k in ("time_base", "last_epoch_s"):
            del out.stats[k]
        out.stats["time_source"] = "session_epoch_clock"
    if "time_base" not in out.stats:  # a CSV's t on the session clock
        if offset_s is not None:
            raise DataError(f"{path}: --gnss-time-offset places a log's UTC times (NMEA, GPX, ISO-time CSV) on the "
                            "session clock, but this CSV's t is already in session seconds; drop the option or shift t")
        return out, lines
    t0, how = _first_fix_session_t(out, session, offset_s)
    out.fixes["t"] = out.fixes["t"] + t0
    out.stats["time_alignment"] = how
    out.stats["first_fix_s"] = round(float(t0), 3)
    if how != "assumed":
        return out, lines
    return out, lines + [
        f"aid: {path}: the fixes' UTC times cannot be placed on the session clock (its meta.json has no "
        "recording_start with a UTC offset, nor utc_start_s), so the first fix is taken at the session start; "
        "if the receiver's first fix came later, pass --gnss-time-offset S (its seconds after the session "
        "start) or write recording_start in meta.json (decision D38)"]


def _file_stats(stats: dict) -> dict:
    """The reader's counters for the summary; its ``used`` (rows kept from the file) is ``fixes_read`` there, so
    it cannot be mistaken for the filter's ``fixes_used`` (decision D17)."""
    return {("fixes_read" if k == "used" else k): v for k, v in stats.items()}


def _unused_fixes_line(f: SporadicFixFusion, n: int, path, period_s: float | None, t_end: float) -> str:
    """One line: how many fixes were not used, why, and the option that changes it (decision D18)."""
    st = f.stats_
    why = []
    if st["fixes_outside_track"]:
        why.append(f"{st['fixes_outside_track']} outside the track's steps (up to {t_end:.1f} s)")
    if st["fixes_not_queried"] and period_s is not None:  # none without a query period (D14)
        why.append(
            f"{st['fixes_not_queried']} not within {f.query_tolerance_s:g} s of a query instant every "
            f"{period_s:g} s while walking (--fix-period / fix_period_s; omit it to use every fix)"
        )
    if st["fixes_superseded"]:
        why.append(f"{st['fixes_superseded']} followed by a later fix before the same step ended (the later one "
                   "is used)")
    if st.get("fixes_rejected"):  # decision D31: each one named
        from pdrlearn.kernels.fixes import rejected_phrase

        why.append(f"{st['fixes_rejected']} rejected by the innovation gate (more than 3 sigma from the filter's "
                   f"estimate, decision D31: {rejected_phrase(f.rejected_)})")
    return f"aid: {st['fixes_unused']} of the {n} fixes in {path} not used: " + "; ".join(why)


#: decision D39: the GNSS scale replaces the steps' lengths only when its windows cover at least this much PDR path (m)
MIN_SCALE_COVER_M = 1000.0
#: decision D45: the PDR's own expected relative distance error by the step table's unit, the RMS error of D39's seven
#: tracks of that unit (m60-m66): a foot's ZUPT-measured strides -0.42 to +0.75 % (RMS 0.41 %), a lower back's
#: modelled steps (waist-pll) -4.90 to +11.24 % (RMS 5.96 %); a table of no single known unit has none
PDR_DISTANCE_ERROR = {"foot": 0.0041, "waist": 0.0596}
#: decision D45: the scale is "more precise than the PDR" when its Student-t interval at this level (two-sided 95 %) is
#: no wider than the PDR's normal one, and "finds the PDR off" when 1 lies outside its interval at this level (99 %)
PRECISE_LEVEL, OFF_LEVEL = 0.975, 0.995


def scale_applies(scale: float, se: float, n: int, cover_m: float, expected: float) -> bool:
    """Decision D45: whether the GNSS scale (:func:`~pdrlearn.kernels.fixes.fit_length_scale`: ``scale``, its
    standard error ``se`` from ``n`` windows covering ``cover_m``) replaces the steps' lengths of a PDR whose expected
    relative distance error is ``expected``: D39's cover, and either the scale is more precise than the PDR (its
    t-interval no wider: t(:data:`PRECISE_LEVEL`, n - 1) x se <= z(:data:`PRECISE_LEVEL`) x expected) or it finds the
    PDR off (|scale - 1| >= t(:data:`OFF_LEVEL`, n - 1) x se). Student's t, as the standard error is estimated from a
    few windows (t = 2.78 / 4.60 at 5 windows, 2.23 / 3.17 at 11)."""
    from scipy.stats import norm, t

    if not (np.isfinite(scale) and np.isfinite(se) and n >= 2 and cover_m >= MIN_SCALE_COVER_M):
        return False
    precise = t.ppf(PRECISE_LEVEL, n - 1) * se <= norm.ppf(PRECISE_LEVEL) * expected
    return bool(precise or abs(scale - 1.0) >= t.ppf(OFF_LEVEL, n - 1) * se)
#: decision D41: the stride columns proportional to ``length_m`` (``speed_mps`` = |length_m| / a time), scaled with it
SCALED_COLUMNS = ("length_m", "speed_mps")


def _distance_scale(f: GnssPdrFusion, steps: pd.DataFrame) -> tuple[dict, pd.DataFrame | None]:
    """Decision D39: the GNSS-calibrated distance. The filter's fitted scale (``distance_scale_``, on stretches of good
    fixes) multiplies the steps' ``length_m`` when its windows cover :data:`MIN_SCALE_COVER_M`, so ``distance_m``,
    splits and periods are the calibrated ones; the PDR's own distance stays in the info. Decision D45: and only when
    :func:`scale_applies` (the scale more precise than the PDR of the steps' unit, :data:`PDR_DISTANCE_ERROR`, or
    finding it off): a scale less precise than a good foot track (within a few tenths of a percent; 5 windows of 5 m
    fixes scatter about 1 %) and not telling it off leaves the PDR's lengths. Decision D41: every
    length-derived stride column (:data:`SCALED_COLUMNS`: ``length_m`` and the ``speed_mps`` the pipeline already
    derived from it) is scaled together, so ``speed_mps * stride_time_s == |length_m|`` still holds; ``raw_length_m``
    (the estimate before the rules) stays the PDR's. Returns (info keys, the scaled steps or None)."""
    pdr_m = float(np.nansum(steps["length_m"].to_numpy(float)))
    scale, cover, se = float(f.distance_scale_), float(f.distance_scale_covered_m_), float(f.distance_scale_se_)
    units = set(steps["unit"].astype(str)) if "unit" in steps else set()
    expected = PDR_DISTANCE_ERROR.get(next(iter(units)), 0.0) if len(units) == 1 else 0.0
    ok = scale_applies(scale, se, int(f.distance_scale_windows_), cover, expected)  # decision D45
    info = {"distance_pdr_m": round(pdr_m, 2),
            "distance_scale": round(scale, 4) if np.isfinite(scale) else None,
            "distance_scale_se": round(se, 4) if np.isfinite(se) else None,
            "distance_scale_cover_m": round(cover, 1),
            "distance_scale_windows": int(f.distance_scale_windows_),
            "distance_scaled": bool(ok)}
    if not ok:
        return info, None
    out = steps.copy()
    for col in SCALED_COLUMNS:
        if col in out:
            out[col] = out[col].to_numpy(float) * scale
    return info, out


#: decision D48: the console line's phrase for each counter of GNSS fixes not used (summary ``info.aid.gnss``)
UNUSED_FIX_PHRASES = (("fixes_outside_track", "outside the walk"), ("fixes_before_ttff", "before the first fix time"),
                      ("fixes_while_off", "while the receiver was off"), ("fixes_inaccurate", "over 50 m accuracy"),
                      ("fixes_gated", "gated"), ("fixes_superseded", "superseded by a later fix"))


def gnss_line(gnss: dict) -> str:
    """Decision D48: the console line of the GNSS fusion from the summary's ``info.aid.gnss``: the fixes used of
    those read, why the others were not (each non-zero counter of :data:`UNUSED_FIX_PHRASES`), and whether the
    distance is the GNSS-scaled one (D39, D45) or the PDR's own; "" without a GNSS file."""
    if not gnss:
        return ""
    total = gnss.get("fixes_total", gnss.get("fixes_read"))
    why = [f"{gnss[key]} {phrase}" for key, phrase in UNUSED_FIX_PHRASES if gnss.get(key)]
    line = f"gnss: {gnss.get('fixes_used', 0)} of {total} fixes used" + (f" ({', '.join(why)})" if why else "")
    scale, cover = gnss.get("distance_scale"), gnss.get("distance_scale_cover_m")
    d39, d45 = decision_ref("D39", topic="aided"), decision_ref("D45", topic="aided")  # decision D49
    if gnss.get("distance_scaled"):
        return line + (f", distance scaled by {scale:.4f} from the PDR's {gnss['distance_pdr_m']:.2f} m "
                       f"({decision_ref('D39', 'D45', topic='aided')})")
    if scale is None or cover is None or cover < MIN_SCALE_COVER_M:  # decision D39: too little cover for a scale
        return line + (f", distance kept from the PDR ({d39}: the fixes' scale windows cover {cover or 0:g} m of "
                       f"the {MIN_SCALE_COVER_M:g} m a scale needs)")
    return line + f", distance kept from the PDR ({d45}: the scale {scale:.4f} is not more precise than it)"


def _steps_from_path(x: np.ndarray, y: np.ndarray, steps: pd.DataFrame) -> pd.DataFrame:
    """Steps whose lengths/headings reproduce a path (to chain a second filter after the first)."""
    dx, dy = np.diff(x), np.diff(y)
    out = steps[["start_s", "end_s"]].copy()
    out["length_m"] = np.hypot(dx, dy)
    out["heading_rad"] = np.arctan2(dy, dx)
    return out


def aid_track(
    result: TrackResult,
    session: Session,
    *,
    gnss_path=None,
    gnss_period_s: float | None = None,
    fixes_path=None,
    fix_period_s: float | None = None,
    start=None,
    gnss_time_offset_s: float | None = None,
) -> TrackResult:
    """Fuse a PDR track with GNSS fixes (seed 001) and/or sporadic absolute fixes (seed 004).

    Parameters
    ----------
    result : a pipeline's :class:`TrackResult` (steps with ``length_m``, ``heading_rad``).
    session : the session the track came from (its clock; ``meta['utc_start_s']`` maps NMEA UTC times).
    gnss_path : NMEA 0183 log or fix CSV for the GNSS/PDR Kalman filter.
    gnss_period_s : ``None``/0 = best performance (every valid fix); > 0 = energy saving, receiver on every
        ``gnss_period_s`` seconds (seed 001 uses 60 and 180 s).
    fixes_path : fix CSV (``t, lat, lon, accuracy_m`` or ``t, x, y, accuracy_m``) of an external
        infrastructure (cameras, beacons) for the sporadic-fix EKF with heading stretching.
    fix_period_s : T_p (s): the fix stream is queried every T_p seconds while moving (seed 004; thins a dense
        stream such as 10 Hz cameras); ``None`` (default) = every fix is used at the step it falls in
        (sporadic fixes, decision D14).
    start : start coordinate ``(lat, lon)`` or ``"lat,lon"`` (degrees): origin of the local frame, where
        the track starts. Default: the first fix (decision D38: the path before it is projected back from it).
    gnss_time_offset_s : decision D38: the session-clock seconds after the session start of the GNSS log's first fix
        (``--gnss-time-offset``), for a log with UTC times when the session gives no absolute start (meta.json
        ``recording_start`` with a UTC offset, or ``utc_start_s``); without either the first fix is taken at the
        session start and a warning says so.

    Returns
    -------
    TrackResult with the fused trajectory (``x``, ``y``; ``x_pdr``, ``y_pdr`` = PDR only; ``x_rt``, ``y_rt`` = the
    causal estimate at each step, what the live trackers' ``add_fix`` gives (D19); ``lat``/``lon``
    when the origin is geodetic) and ``info['aid']`` (fixes read/used/unused and why, GNSS-on fraction, fix
    table; the keys are documented in docs/aided.md, decision D17). Fixes that are not used are warned in
    one line with the reason (D18).
    """
    if gnss_path is None and fixes_path is None:
        raise DataError("aid_track: give gnss_path (--gnss) and/or fixes_path (--fixes)")
    steps = result.steps
    if steps is None or not len(steps):
        raise DataError(f"session '{session.name}': the track has no steps, nothing to fuse with fixes")
    warnings = []
    if {"length_m", "heading_rad"} <= set(steps.columns):
        bad = ~np.isfinite(steps[["length_m", "heading_rad"]].to_numpy(float)).all(axis=1)
        if bad.any():
            warnings.append(f"aid: {int(bad.sum())} step(s) without length/heading ignored by the fusion")
            steps = steps[~bad].reset_index(drop=True)
            result = TrackResult(
                steps,
                result.trajectory.iloc[np.r_[0, np.flatnonzero(~bad) + 1]].reset_index(drop=True)
                if len(result.trajectory) == len(bad) + 1
                else result.trajectory,
                result.info,
            )
    origin = _parse_start(start)
    traj0 = result.trajectory
    same_rows = len(traj0) == len(steps) + 1  # the pipeline's trajectory: start row + one row per step
    info: dict = {"origin": list(origin) if origin else None}
    x0 = np.array([float(traj0["x"].iloc[0]), float(traj0["y"].iloc[0])]) if len(traj0) else np.zeros(2)
    t_start = float(traj0["t"].iloc[0]) if len(traj0) else None
    cur_steps = steps
    scaled_steps = None  # decision D39: the steps with GNSS-calibrated lengths
    fused = None
    all_fixes = []
    for kind, path in (("gnss", gnss_path), ("fixes", fixes_path)):
        if path is None:
            continue
        flog, lines = _load(path, session, gnss_time_offset_s if kind == "gnss" else None)
        warnings += lines
        fx, origin = to_local(flog.fixes, origin)
        n_file, start_fix, x0_run, fx_file = len(fx), None, x0, fx
        if kind == "fixes" and t_start is not None and len(fx):  # decision D50: the fixes before the first stride
            fx = fx_file = fx.sort_values("t", kind="stable").reset_index(drop=True)
            pre = start_fixes(fx["t"], float(session.t_recording_start), t_start)
            if len(pre):
                start_fix = fx.iloc[pre[-1]]
                x0_run = np.array([float(start_fix["x"]), float(start_fix["y"])])
                fx = fx.drop(index=pre).reset_index(drop=True)
                n_pre = len(pre)
        all_outside = False
        if t_start is not None and len(fx):
            t_end = float(traj0["t"].iloc[-1])
            ft = fx["t"].to_numpy(float)
            if not ((ft >= t_start) & (ft <= t_end)).any() and start_fix is None:
                all_outside = True
                warnings.append(
                    f"aid: none of the {len(fx)} fixes in {path} lies within the track ({t_start:.1f} to "
                    f"{t_end:.1f} s; fixes at {ft.min():.1f} to {ft.max():.1f} s), so none is used; "
                    + _outside_hint(flog.stats)  # decision D42
                )
        info["origin"] = list(origin) if origin else None
        # start known (or local fixes around the track's own origin): 1 m; else the first fix's sigma
        sigma0 = initial_fix_sigma(start_known=start is not None, xy_fixes="x" in flog.fixes.columns,
                                   first_accuracy_m=fx["accuracy_m"].iloc[0] if len(fx) else None)
        if start_fix is not None:  # decision D50: the start fix's own per-axis sigma (seed 004: P_p(0) from the fix)
            sigma0 = float(sigma_from_accuracy(float(start_fix["accuracy_m"])))
        if kind == "gnss":
            mode = "saving" if gnss_period_s else "best"
            f = GnssPdrFusion(mode=mode, period_s=float(gnss_period_s or 60.0), initial_sigma_m=sigma0,
                              start_known=start is not None or "x" in flog.fixes.columns)  # decision D38
            f.run(cur_steps, fx, start_xy=x0, t_start=t_start)
            scale_info, scaled_steps = _distance_scale(f, steps)
            info["gnss"] = {
                "file": str(path),
                "mode": mode,
                "period_s": gnss_period_s,
                **_file_stats(flog.stats),
                **f.stats_,
                "length_scale": f.scale_,
                "heading_bias_deg": float(np.degrees(f.heading_bias_rad_)),
                **scale_info,
            }
        else:
            tp = fix_period_s
            f = SporadicFixFusion(period_s=tp, initial_sigma_m=sigma0)
            f.run(cur_steps, fx, start_xy=x0_run, t_start=t_start)
            if start_fix is not None:  # decision D50: one start fix used, the earlier ones superseded by it
                f.stats_["fixes_used"] += 1
                f.stats_["fixes_superseded"] += n_pre - 1
                f.stats_["fixes_unused"] += n_pre - 1
            if f.stats_["fixes_unused"] and not all_outside:
                warnings.append(_unused_fixes_line(f, n_file, path, tp, float(cur_steps["end_s"].iloc[-1])))
            info["fixes"] = {
                "file": str(path),
                "period_s": tp,
                **_file_stats(flog.stats),
                **f.stats_,
                "heading_offset_deg": float(np.degrees(f.heading_offset_rad_)),
                # decision D50: the fix that gave the start position (None: the track's own start)
                "start_fix": None if start_fix is None else {k: round(float(start_fix[k]), 3)
                                                             for k in ("t", "x", "y", "accuracy_m")},
            }
        tr = f.trajectory_
        if fused is None:
            fused = tr.copy()
        else:
            fused["x"], fused["y"] = tr["x"].to_numpy(), tr["y"].to_numpy()
            if "x_rt" in tr:
                fused["x_rt"], fused["y_rt"] = tr["x_rt"].to_numpy(), tr["y_rt"].to_numpy()
            fused["fix_used"] = fused["fix_used"].to_numpy(bool) | tr["fix_used"].to_numpy(bool)
        cur_steps = _steps_from_path(tr["x"].to_numpy(), tr["y"].to_numpy(), check_sorted(steps))
        all_fixes.append(fx_file.assign(source=kind))  # decision D50: the start fixes drawn too
    out = pd.DataFrame({"t": fused["t"].to_numpy(), "x": fused["x"].to_numpy(), "y": fused["y"].to_numpy()})
    out["z"] = traj0["z"].to_numpy() if "z" in traj0 and len(traj0) == len(out) else 0.0
    out["x_pdr"], out["y_pdr"] = fused["x_pdr"].to_numpy(), fused["y_pdr"].to_numpy()
    if same_rows and len(traj0) == len(out):  # keep the pipeline's own PDR path
        out["x_pdr"], out["y_pdr"] = traj0["x"].to_numpy(), traj0["y"].to_numpy()
    if "fix_used" in fused:
        out["fix_used"] = fused["fix_used"].to_numpy()
    if "x_rt" in fused and len(fused) == len(out):  # the causal estimate: what a live tracker shows (D19)
        out["x_rt"], out["y_rt"] = fused["x_rt"].to_numpy(), fused["y_rt"].to_numpy()
    if origin is not None:
        out["lat"], out["lon"] = enu_to_geodetic(out["x"].to_numpy(), out["y"].to_numpy(), *origin)
    fixes = pd.concat(all_fixes, ignore_index=True)
    info["fix_table"] = {c: np.round(fixes[c].to_numpy(float), 3).tolist() for c in ("t", "x", "y", "accuracy_m")}
    info["fix_table"]["source"] = fixes["source"].tolist()
    # decision D39: the fused path's own length (it follows the fixes' noise: longer than the walk)
    info["path_length_m"] = round(float(np.sum(np.hypot(np.diff(out["x"].to_numpy()), np.diff(out["y"].to_numpy())))),
                                  2)
    new_info = dict(result.info)
    new_info["aid"] = info
    if warnings:
        new_info["warnings"] = list(new_info.get("warnings", [])) + warnings
    for w in warnings:  # logged once, like the pipelines' warnings (the CLI prints log records, decision B13)
        log.warning("%s: %s", session.where, w)
    return TrackResult(scaled_steps if scaled_steps is not None else result.steps.copy(), out, new_info)


def check_sorted(steps: pd.DataFrame) -> pd.DataFrame:
    return steps.sort_values("end_s", kind="stable").reset_index(drop=True)


def plot_aided(result: TrackResult, out, *, truth: pd.DataFrame | None = None, title: str | None = None,
               dpi: float | None = None) -> Path:
    """Overlay PDR-only path, fixes and fused path (and the truth when given); PNG, atomic save (``dpi``:
    :func:`pdrlearn.plots.save_atomic`)."""
    from pdrlearn.plots import new_figure, save_atomic

    tr = result.trajectory
    if "x_pdr" not in tr:
        raise DataError("plot_aided: the track has no x_pdr/y_pdr columns; pass the result of aid_track")
    fig, ax = new_figure(figsize=(7.5, 7.5))  # decision E88: the user's backend left alone
    if truth is not None:
        ax.plot(truth["x"], truth["y"], color="0.3", lw=1.2, ls="--", label="truth")
    ax.plot(tr["x_pdr"], tr["y_pdr"], color="tab:blue", lw=1.0, label="PDR only")
    ft = result.info.get("aid", {}).get("fix_table")
    if ft and len(ft["t"]):
        src = np.asarray(ft["source"])
        for s, colour in (("gnss", "tab:orange"), ("fixes", "tab:purple")):
            m = src == s
            if m.any():
                ax.scatter(
                    np.asarray(ft["x"])[m],
                    np.asarray(ft["y"])[m],
                    s=6,
                    color=colour,
                    alpha=0.5,
                    label="GNSS fixes" if s == "gnss" else "absolute fixes",
                )
    ax.plot(tr["x"], tr["y"], color="tab:green", lw=1.4, label="fused")
    if "fix_used" in tr:
        u = tr["fix_used"].to_numpy(bool)
        ax.scatter(tr["x"][u], tr["y"][u], s=18, facecolors="none", edgecolors="k", lw=0.6, label="fix used")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("east [m]")
    ax.set_ylabel("north [m]")
    ax.grid(alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    ax.set_title(title or f"{result.info.get('pipeline', 'track')}: PDR, fixes and fused path")
    save_atomic(fig, Path(out), dpi=dpi)
    return Path(out)
