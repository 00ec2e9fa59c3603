"""Flight phases in a foot recording (decision W363, docs/decisions/waist.md): both feet off the ground.

In flight the body falls freely, and an accelerometer, which measures specific force (a - g), reads about 0 g; while
walking one foot is always on the ground and the foot unit reads about 1 g plus its swing accelerations. A run of
samples under :data:`FLIGHT_MAX_G` lasting more than :data:`FLIGHT_MIN_S` (W409, W412) is a flight phase: a jump
or a running stride, which the foot pipeline would count as a walking stride. Pure functions.
"""

from __future__ import annotations

import numpy as np

from pdrlearn.kernels.units import STANDARD_GRAVITY as G  # m/s^2, the unit conversion's (decision D4)

#: decision W363: a flight phase's accelerometer magnitude is under this (g; free fall reads 0 g; room for the foot's
#: own acceleration relative to the falling body)
FLIGHT_MAX_G = 0.3
#: decision W363: the shortest flight phase (s; trial T3's "near 0 g for > 0.1 s")
FLIGHT_MIN_S = 0.1
#: decision W363: the summary keys of :func:`flight_summary`
KEYS = ("n_flight_phases", "flight_time_s")


def flight_phases(t, acc) -> list[tuple[float, float]]:
    """Decision W363: ``(start_s, end_s)`` of each run of samples of ``acc`` (n, 3) m/s^2 at times ``t`` (s) whose
    magnitude is under :data:`FLIGHT_MAX_G` for at least :data:`FLIGHT_MIN_S`: decision W409, its first and last low
    samples that far apart (a slow walker's late swing dips under 0.3 g for two samples at 20 Hz, which k x dt would
    count as 0.1 s). ``end_s`` is the last low sample's time plus one sample interval."""
    t = np.asarray(t, float)
    if t.size < 2:
        return []
    from pdrlearn.signal.conditioning import runs

    low = np.linalg.norm(np.asarray(acc, float), axis=1) < FLIGHT_MAX_G * G
    dt = float(np.median(np.diff(t)))
    out = []
    for a, b in runs(low):  # samples a .. b-1 are low
        start, last = float(t[a]), float(t[b - 1])
        if last - start >= FLIGHT_MIN_S - 1e-9:  # decision W409: seen under 0.3 g for 0.1 s, not k x dt
            out.append((start, last + dt))
    return out


#: decision W538: a lower-back flight phase this long (s) or longer is a jump (a walking bounce's sub-0.3 g trough is
#: under a third of a step period: 0.2 s at 0.5 s steps would need a +-2.3 g bounce)
WAIST_JUMP_S = 0.2
#: decision W538: a lower-back step period (s) under this is a running cadence (over 150 steps/min; running 150-190)
RUN_STEP_S = 0.4
#: decision W538: the span (s) centred on a phase whose step period W113's autocorrelation reads
CADENCE_SPAN_S = 4.0


def step_period_at(t, acc, phase: tuple[float, float]) -> float:
    """Decision W538: the step period (s) of the acceleration magnitude in the :data:`CADENCE_SPAN_S` centred on
    ``phase`` (W113's autocorrelation, :func:`pdrlearn.kernels.waist.step_period_s`); NaN without a rhythm."""
    from pdrlearn.kernels.waist import step_period_s

    t = np.asarray(t, float)
    mid = 0.5 * (phase[0] + phase[1])
    keep = np.abs(t - mid) <= 0.5 * CADENCE_SPAN_S
    if keep.sum() < 3:
        return float("nan")
    fs = 1.0 / float(np.median(np.diff(t[keep])))
    return step_period_s(np.linalg.norm(np.asarray(acc, float)[keep], axis=1), fs)


def unit_flights(unit: str, t, acc) -> list[tuple[float, float]]:
    """The flight phases a unit's accelerometer names: the foot's all of :func:`flight_phases` (W363); decision W538:
    the lower back's only those of :data:`WAIST_JUMP_S` or more (a jump) or at a step period under
    :data:`RUN_STEP_S` (:func:`step_period_at`: running), not the trough of a brisk walker's bounce."""
    phases = flight_phases(t, acc)
    if unit != "waist":
        return phases
    return [p for p in phases
            if p[1] - p[0] >= WAIST_JUMP_S - 1e-9 or step_period_at(t, acc, p) < RUN_STEP_S - 1e-9]  # R1 F4


#: decision W416: each unit's accelerometer; a lower-back track reads the waist's (a pelvis in free fall reads ~0 g too)
UNIT_ACC = {"foot": "fAccelerometer", "waist": "wAccelerometer"}


def flight_unit(pipeline: str | None) -> str:
    """The unit whose accelerometer a track's flight test reads: ``"waist"`` for a lower-back pipeline (W416)."""
    return "waist" if "waist" in str(pipeline) else "foot"


#: decision W417: flights.csv's columns (:func:`flight_rows`)
FLIGHT_COLUMNS = ("unit", "start_s", "end_s", "flight_time_s", "jump_height_m")


def jump_height(flight_time_s):
    """Decision W417: the flight-time jump height (m), g t^2 / 8 (a body that leaves and lands at the same height rises
    for half its flight: h = g (t/2)^2 / 2; Bosco et al. 1983)."""
    return G * np.square(np.asarray(flight_time_s, float)) / 8.0


def in_span(phases: list[tuple[float, float]], span: tuple[float, float] | None) -> list[tuple[float, float]]:
    """Decision W425: the flight phases of a ``--window`` ``span`` ``(t0, t1)`` (the session's clock): those whose
    middle lies inside it, whole (a flight is under a second; a cut one would misstate its jump height). None: all."""
    if span is None:
        return list(phases)
    return [(a, b) for a, b in phases if span[0] <= 0.5 * (a + b) <= span[1]]


def flight_rows(session, span: tuple[float, float] | None = None) -> list[dict]:
    """Decision W417: flights.csv's rows (:data:`FLIGHT_COLUMNS`), one per flight phase (:func:`flight_phases`) of
    each unit with an accelerometer (:data:`UNIT_ACC`), in time order; decision W425: those of ``span``
    (:func:`in_span`)."""
    rows = []
    for unit, name in UNIT_ACC.items():
        acc = session.streams.get(name)
        if acc is None:
            continue
        for a, b in in_span(unit_flights(unit, acc.t, acc.values), span):
            rows.append({"unit": unit, "start_s": round(a, 3), "end_s": round(b, 3), "flight_time_s": round(b - a, 3),
                         "jump_height_m": round(float(jump_height(b - a)), 3)})
    return sorted(rows, key=lambda r: (r["start_s"], r["unit"]))


def flight_summary(session, pipeline: str | None,
                   span: tuple[float, float] | None = None) -> tuple[dict, str | None]:
    """Decision W363: ``(keys, line)`` - :data:`KEYS` of the tracked unit's accelerometer (the foot's; decision
    W416: a lower-back track's the waist's; None for both without the stream) and the warning line when it has a
    flight phase; decision W425: of ``span``'s phases only (:func:`in_span`)."""
    unit = flight_unit(pipeline)
    acc = session.streams.get(UNIT_ACC[unit])
    if acc is None:
        return dict.fromkeys(KEYS), None
    phases = in_span(unit_flights(unit, acc.t, acc.values), span)
    total = float(sum(b - a for a, b in phases))
    keys = {"n_flight_phases": len(phases), "flight_time_s": round(total, 3)}
    if not phases:
        return keys, None
    longest = max(b - a for a, b in phases)
    # decision W412: "more than", as W409's rule (an exact 0.1 s run, 10 samples at 100 Hz, spans 0.09 s: not one)
    low = (f"{len(phases)} flight phase(s) (the {'lower-back' if unit == 'waist' else 'foot'} accelerometer under "
           f"{FLIGHT_MAX_G:g} g for more than {FLIGHT_MIN_S:g} s, its first and last low samples {FLIGHT_MIN_S:g} s "
           f"or more apart, {total:.2f} s in all, the longest {longest:.2f} s)")
    if unit == "waist":  # decision W416: the lower-back pipelines' own consequence
        return keys, (f"{low}: the body left the ground - jumps (0.2 s or more) or running (dips at over "
                      f"{60.0 / RUN_STEP_S:.0f} steps/min; a brisk walker's bounce is not counted, decision W538); "
                      "the lower-back pipelines count the take-offs and landings as walking steps and place every "
                      "step forward, so the step count and the distance include them and are not validated "
                      "(decision W416)")
    return keys, (f"{low}: the foot left the ground with both feet - jumps or running; strides across them may be "
                  "jumps, not walking strides, and their lengths and the distance are not validated (decision W363)")
