"""A lift or escalator ride during a standstill, told from the weather's drift across a long rest (decision W231 in
docs/decisions/waist.md), numpy only.

W158 books a lower-back track's whole barometric change while the unit stood between two steps as ``pause_dz_m``
(a lift or escalator ride). Across an hour seated the pressure drifts with the weather and the room (the trial
`night`: -4.68 m over 3600 s, two phantom floors down). A ride is fast: its change is the change of the spans where
the altitude moves :data:`RIDE_MIN_M` within :data:`RIDE_WINDOW_S`; the rest of a long pause is drift.
"""

from __future__ import annotations

import numpy as np

from pdrlearn.kernels.barometer import STAIR_CLIMB_MIN_M, relative_altitude
from pdrlearn.kernels.units import STANDARD_GRAVITY

#: decision W231: a pause longer than this (s) has its ride told from its drift; the change of a shorter pause counts
#: whole, as W158 (a storey's drift within it: the weather's 0.3 hPa/h, ~0.04 m per minute, decision S4 / L172)
RIDE_WINDOW_S = 30.0
#: decision W231: a ride moves the altitude at least this much (m) within :data:`RIDE_WINDOW_S`: W108's half storey,
#: i.e. 0.05 m/s, a 3 m storey in a minute (L172: "a storey is climbed in well under a minute"). The slowest rides
#: are 3x faster (a platform lift's 0.15 m/s, as recalled of the Machinery Directive's platform lifts; an escalator's
#: 0.5 m/s on 30 deg is 0.25 m/s up, sim.ride); weather drift is 40x slower (the trial's 4.7 m/h is 0.0013 m/s, a
#: storm's 3 hPa/h ~7 m/h). The barometer's wander (W89's simulator: 0.3 m sd, 10 s) changes 1.5 m in 30 s at 3.5 sd
RIDE_MIN_M = STAIR_CLIMB_MIN_M
#: decision W231: the altitude is read on this grid (s) inside a long pause
RIDE_GRID_S = 1.0
#: decision W231: a drift of this much (m) or more left out across the rests is warned about (README: "a drift over
#: 1 m is warned", L172's)
PAUSE_DRIFT_WARN_M = 1.0


def pause_ride_dz(t: np.ndarray, p_hpa: np.ndarray, a: float, b: float, *,
                  smoothing: tuple[float, float | None] | None = None) -> tuple[float, float]:
    """Decision W231: ``(ride, whole)``: the barometric altitude change (m) from ``a`` to ``b`` (s) that is a ride
    and the whole change (W158's ``pause_dz_m``). A pause up to :data:`RIDE_WINDOW_S` long is all ride. In a longer
    one, every span of :data:`RIDE_WINDOW_S` (on a :data:`RIDE_GRID_S` grid) whose altitude changes by
    :data:`RIDE_MIN_M` or more is marked, and the ride is the change over the marked grid intervals (their union:
    a long lift ride is several windows); the rest is drift. ``smoothing``: the altitude's (decision W621's window
    and mean: the live tracker's, whose held samples are not the stream's first), else :func:`relative_altitude`'s."""
    grid = np.append(np.arange(a, b, RIDE_GRID_S), b)
    h = relative_altitude(t, p_hpa, grid, smoothing=smoothing)
    whole = float(h[-1] - h[0])
    if b - a <= RIDE_WINDOW_S or len(grid) < 3:
        return whole, whole
    k = int(round(RIDE_WINDOW_S / RIDE_GRID_S))
    if len(grid) <= k:
        return whole, whole
    fast = np.flatnonzero(np.abs(h[k:] - h[:-k]) >= RIDE_MIN_M)  # windows i .. i + k that move a half storey
    cover = np.zeros(len(grid), dtype=np.int64)  # intervals i .. i + k - 1 of each fast window
    np.add.at(cover, fast, 1)
    np.add.at(cover, fast + k, -1)
    inside = np.cumsum(cover)[:-1] > 0
    return float(np.diff(h)[inside].sum()), whole


def drift_line(drop, ends, starts) -> str | None:
    """Decision W231's one warning: ``drop`` (m) the drift left out of each pause from ``ends`` to ``starts`` (s; 0
    where nothing was), when it is :data:`PAUSE_DRIFT_WARN_M` or more in all or across one rest; else None. Shared by
    the offline track and the live waist tracker (decision E146)."""
    drop, ends, starts = (np.asarray(v, dtype=float) for v in (drop, ends, starts))
    long_ = np.flatnonzero(np.abs(drop) > 0)
    if not long_.size:
        return None
    total = float(drop.sum())
    if not (abs(total) >= PAUSE_DRIFT_WARN_M or np.abs(drop).max() >= PAUSE_DRIFT_WARN_M):
        return None
    worst = int(long_[np.argmax(np.abs(drop[long_]))])
    return (f"the barometric altitude drifted {total:+.2f} m across {len(long_)} rest(s) without steps (largest "
            f"{drop[worst]:+.2f} m over the {starts[worst] - ends[worst]:.0f} s before {starts[worst]:.1f} s), too "
            "slowly for a lift or escalator ride (a ride changes 1.5 m within 30 s): weather or room pressure, left "
            "out of the altitude and the floors (decision W231)")


#: decision L376: a ride's window runs from where its altitude has moved this fraction of its change to where it has
#: moved 1 - this fraction; its duration is that span / (1 - 2 x this fraction)
RIDE_EDGE_FRACTION = 0.1
#: decision L376: the grid (s) the altitude is read on inside a pause for the ride's window
RIDE_WINDOW_GRID_S = 0.5
#: decision L376: a lift moves 0.5 m/s or more vertically (passenger lifts 1-2.5 m/s, low-rise hydraulic 0.5-1 m/s,
#: as recalled); an escalator 0.15-0.5 m/s (EN 115-1: 0.5-0.75 m/s along a 30-35 deg incline, 0.25-0.375 m/s up)
LIFT_MIN_RATE_MPS = 0.5
ESCALATOR_MIN_RATE_MPS = 0.15
#: decision L376: an escalator ride lasts at most this long (s): ~11 m of rise at 0.25 m/s (station / shop escalators
#: rise 3-10 m); a longer slow climb while standing is a vehicle's or a ride of another kind
ESCALATOR_MAX_S = 45.0
#: decision L377: the inclination (deg) an escalator's horizontal travel is estimated at (EN 115-1's common 30 deg)
ESCALATOR_INCLINE_DEG = 30.0


def ride_window(t: np.ndarray, p_hpa: np.ndarray, a: float, b: float) -> tuple[float, float, float]:
    """Decision L376: ``(start, end, duration)`` (s) of the ride in the pause from ``a`` to ``b``: W89's altitude on a
    :data:`RIDE_WINDOW_GRID_S` grid, ``start`` where it first moved :data:`RIDE_EDGE_FRACTION` of its whole change,
    ``end`` where it first moved 1 - that fraction, ``duration`` = (end - start) / (1 - 2 x fraction) (the 10-90 %
    span of a steady ride is 80 % of it), at least one grid step."""
    grid = np.append(np.arange(a, b, RIDE_WINDOW_GRID_S), b)
    h = relative_altitude(t, p_hpa, grid)
    whole = float(h[-1])
    if len(grid) < 2 or whole == 0.0:
        return float(a), float(b), float(b - a)
    moved = h / whole  # 0 at a, 1 at b
    lo = grid[int(np.argmax(moved >= RIDE_EDGE_FRACTION))]
    hi = grid[int(np.argmax(moved >= 1.0 - RIDE_EDGE_FRACTION))]
    duration = max(float(hi - lo) / (1.0 - 2.0 * RIDE_EDGE_FRACTION), RIDE_WINDOW_GRID_S)
    return float(lo), float(max(hi, lo)), duration


def ride_kind(dz: float, duration_s: float, vibration_mps2: float | None = None) -> str:
    """Decision L376: ``"lift"``, ``"escalator"`` or ``"other"`` from a ride's height change ``dz`` (m) and
    :func:`ride_window`'s ``duration_s``: its vertical rate and duration against the typical lift and escalator.
    Decision L402: a ride whose :func:`ride_vibration` is :data:`VEHICLE_VIBRATION_MPS2` or more is a vehicle's
    (a vehicle on a hill climbs at a lift's or an escalator's rate; None / NaN: not known, the rate decides), kind
    ``"vehicle"`` (decision L615; no storeys, as "other": :data:`NO_STOREY_KINDS`)."""
    if vibration_mps2 is not None and float(vibration_mps2) >= VEHICLE_VIBRATION_MPS2:
        return "vehicle"  # decision L615: named for what it is (L402 had called it "other")
    rate = abs(float(dz)) / max(float(duration_s), 1e-9)
    if rate >= LIFT_MIN_RATE_MPS:
        return "lift"
    if rate >= ESCALATOR_MIN_RATE_MPS and duration_s <= ESCALATOR_MAX_S:
        return "escalator"
    return "other"


def walked_ride(vibration_mps2: float, *, min_mps2: float = 1.2) -> bool:
    """Decision W609: True when a standstill's "ride" shook the unit at ``min_mps2`` or more (:func:`ride_vibration`):
    a walk whose steps the detector missed (a stair flight), not a ride. 1.2 m/s^2 lies above every rider and real
    standstill decision L403 measured (vehicles 0.357-0.990, lifts / escalators under 0.09, mobgap standstills at
    most 0.981 m/s^2); NaN: not known, False."""
    return bool(np.isfinite(vibration_mps2) and float(vibration_mps2) >= float(min_mps2))


def escalator_travel_m(dz: float) -> float:
    """Decision L377: the horizontal travel (m) of an escalator ride of height change ``dz``, estimated at
    :data:`ESCALATOR_INCLINE_DEG` (dz / tan 30 deg)."""
    return abs(float(dz)) / float(np.tan(np.radians(ESCALATOR_INCLINE_DEG)))


#: decision L402: the vibration of a ride is read in windows of this many seconds, each detrended (a straight line
#: removed: a lift's or a vehicle's slow changes of acceleration, under ~0.5 Hz, are no vibration; a bus body's 1-3
#: Hz bounce, S71, is)
VIBRATION_WINDOW_S = 1.0
#: decision L402: a ride whose median windowed vibration of |specific force| is this much (m/s^2 RMS) or more is a
#: vehicle's, not a lift's nor an escalator's: half of ISO 2631-1's 0.315 m/s^2 "not uncomfortable" bound (as
#: recalled, not checked; public transport usually rides at 0.3-1, S71) and 8-9 x a still unit's own |a| noise
#: (thesis Table 4: foot 0.0193, Table 12: waist 0.0175 m/s^2 sd)
VEHICLE_VIBRATION_MPS2 = 0.15
#: decisions L376, L615: the ride kinds that count no storey (a ride that is neither a lift nor an escalator)
NO_STOREY_KINDS = ("other", "vehicle")
#: decision L616: a standstill at least this long (s) that vibrates like a vehicle is a vehicle ride, level or not
#: (the simulator's shortest vehicle ride, S71's ``VEHICLE_MIN_S``: a stop-to-stop hop)
VEHICLE_STILL_MIN_S = 20.0


def _window_sds(t: np.ndarray, acc: np.ndarray, a: float, b: float) -> tuple[np.ndarray, np.ndarray] | None:
    """Decision L402: ``(edges, sds)`` of the specific force's magnitude ``acc`` (n, 3) at ``t`` from ``a`` to ``b``
    (s), scaled so that its median over the span is 1 g (any unit), cut into :data:`VIBRATION_WINDOW_S` windows
    (``edges``: n_win + 1 times), each detrended, and each window's standard deviation (NaN under 4 samples); None
    with fewer than 8 finite samples in the span."""
    t = np.asarray(t, dtype=float)
    mag = np.linalg.norm(np.asarray(acc, dtype=float), axis=1)
    inside = (t >= a) & (t <= b) & np.isfinite(mag)
    if int(inside.sum()) < 8:
        return None
    tt, mag = t[inside], mag[inside]
    med = float(np.median(mag))
    if not med > 0:
        return None
    mag = mag * (STANDARD_GRAVITY / med)  # the specific force of a standing unit is 1 g
    n_win = max(int((tt[-1] - tt[0]) // VIBRATION_WINDOW_S), 1)
    edges = tt[0] + (tt[-1] - tt[0]) * np.arange(n_win + 1) / n_win
    sds = np.full(n_win, np.nan)
    for k in range(n_win):
        w = (tt >= edges[k]) & (tt <= edges[k + 1])
        if int(w.sum()) >= 4:
            x, y = tt[w] - tt[w].mean(), mag[w]
            slope = float(np.dot(x, y - y.mean()) / max(float(np.dot(x, x)), 1e-12))
            sds[k] = float(np.std(y - y.mean() - slope * x))
    return edges, sds


def ride_vibration(t: np.ndarray, acc: np.ndarray, a: float, b: float) -> float:
    """Decision L402: the vibration (m/s^2) of the standing unit during a ride from ``a`` to ``b`` (s): the median of
    :func:`_window_sds` (the detrended |specific force|'s SD in 1 s windows: a shift of the feet or a bag in one
    window does not make a ride a vehicle's). NaN with fewer than 8 finite samples in the ride (decision B301: said
    by :func:`pdrlearn.track.rides.ride_lines`)."""
    w = _window_sds(t, acc, a, b)
    if w is None or not np.isfinite(w[1]).any():
        return float("nan")
    return float(np.nanmedian(w[1]))


def vibrating_span(t: np.ndarray, acc: np.ndarray, a: float, b: float) -> tuple[float, float, float] | None:
    """Decision L616: ``(start, end, vibration)`` of a standstill from ``a`` to ``b`` (s) that vibrates like a
    vehicle: its :func:`ride_vibration` is :data:`VEHICLE_VIBRATION_MPS2` or more, ``start`` / ``end`` the first
    window's start and the last window's end of the 1 s windows at that level (the vehicle's motion; the wait before
    it and the stop after it read under it); None otherwise."""
    w = _window_sds(t, acc, a, b)
    if w is None or not np.isfinite(w[1]).any():
        return None
    edges, sds = w
    vib = float(np.nanmedian(sds))
    if not vib >= VEHICLE_VIBRATION_MPS2:
        return None
    on = np.flatnonzero(sds >= VEHICLE_VIBRATION_MPS2)
    return float(edges[on[0]]), float(edges[on[-1] + 1]), vib
