"""Decisions L95 / L148 / W144 / W178: the walking range the pipelines are validated on and the fast gait it names,
numpy only (decision E325: the lean runtime judges each streamed stride by them; ``pdrlearn.track.gait`` judges the
session's medians by the same functions and re-exports them)."""

from __future__ import annotations

import math

import numpy as np

from pdrlearn.kernels.gait_values import cadence_speed

#: decision L95: the gait the pipelines are validated on is walking - the simulator's users at 100-118
#: steps/min x its speed factors (83-137 steps/min, docs/simulator.md), 0.7-2.1 m/s; the real recordings at
#: 98-110 steps/min, 0.95-1.26 m/s (L66, W70). A session whose median cadence (steps/min) or speed (m/s) lies
#: outside these bounds (the validated ranges with a margin; the adult walk-run transition is ~2 m/s) gets one
#: warning line from `pdrlearn track`.
CADENCE_RANGE_SPM, SPEED_RANGE_MPS = (70.0, 160.0), (0.5, 2.5)
#: decision W178: a cadence above L95's range at a judged speed of at least this (m/s, the adult L95 scale; scaled
#: with the leg as the speed range, L148) names running first: at 160 steps/min it is a 0.56 m step, no shuffle (the
#: simulated festinating walks of W100 read 0.6-0.7 m/s on the uncalibrated waist), while the uncalibrated waist reads
#: fast-cadence walks short (the session-27 trial: 1.95 m/s at 200 steps/min for a true 3.33 m/s)
RUNNING_FIRST_SPEED_MPS = 1.5
#: decision L123: the speed L95 judges is the straight strides' median (L79) when there are at least this many; a
#: stride turning on the spot covers little ground at a walking cadence (the trial's 360-deg spins: median 0.16
#: m/s over all strides, 0.73 m/s straight, distance +0.81 %). Here since E350 (the live Tracker judges it too)
MIN_STRAIGHT_FOR_RANGE = 5


def reference_leg_m() -> float:
    """Decision L148: the leg length L95's adult range holds for: the waist pipelines' default adult (1.70 m x
    0.53 = 0.901 m), so a session without a body measure keeps L95's range exactly."""
    from pdrlearn.waist.params import DEFAULT_HEIGHT_M, LEG_PER_HEIGHT

    return DEFAULT_HEIGHT_M * LEG_PER_HEIGHT


def gait_ranges(leg_m: float | None) -> tuple[tuple[float, float], tuple[float, float]]:
    """Decision L148: L95's cadence (steps/min) and speed (m/s) ranges for a walker with leg length ``leg_m`` (m;
    None = the adult range). Dynamic similarity (Hof 1996, "Scaling gait data to body size", Gait & Posture
    4:222-223): walkers of leg lengths L and L0 walk alike at equal dimensionless step frequency f / sqrt(g / L) and
    speed v / sqrt(g L), so the bounds scale as cadence x sqrt(L0 / L) and speed x sqrt(L / L0), L0 =
    :func:`reference_leg_m`."""
    if leg_m is None or not np.isfinite(leg_m) or leg_m <= 0:
        return CADENCE_RANGE_SPM, SPEED_RANGE_MPS
    k = float(np.sqrt(reference_leg_m() / leg_m))  # Hof 1996: f ~ sqrt(g / L), v ~ sqrt(g L)
    return ((CADENCE_RANGE_SPM[0] * k, CADENCE_RANGE_SPM[1] * k), (SPEED_RANGE_MPS[0] / k, SPEED_RANGE_MPS[1] / k))


def range_side(cad: float | None, speed: float | None, leg_m: float | None) -> str | None:
    """Decisions L95 / L148: ``"fast"`` when the cadence (steps/min) or the speed (m/s) is above the leg-scaled
    walking range (:func:`gait_ranges`), ``"slow"`` when one is below it (and none above), None inside it or with
    neither figure. The one test of the range for the session (``pdrlearn.track.gait.gait_range_warning``), each bout
    (``bout_range_flags``, decision L195) and each streamed stride (:func:`running_stride`, decision E325)."""
    cad_range, speed_range = gait_ranges(leg_m)
    if (cad is not None and cad > cad_range[1]) or (speed is not None and speed > speed_range[1]):
        return "fast"
    if (cad is not None and cad < cad_range[0]) or (speed is not None and speed < speed_range[0]):
        return "slow"
    return None


def fast_gait(cad: float | None, speed: float | None, leg_m: float | None, other_speed: float | None = None) -> str:
    """The ``FAST_GAITS`` key of a gait above L95's range. Decision W144: "looks like running" needs the speed
    above the range (or no cadence); a fast cadence at a walking speed is short fast steps or running. Decision
    L197: with no speed judged (a walk of stairs or slopes, L179), ``other_speed`` (the gait speed) above the range
    says running. Decision W178: a fast cadence at :data:`RUNNING_FIRST_SPEED_MPS` or more (leg-scaled) names
    running first."""
    _, speed_range = gait_ranges(leg_m)
    k = speed_range[1] / SPEED_RANGE_MPS[1]  # L148's speed scale of this leg
    if (speed is not None and speed > speed_range[1]) or cad is None or \
            (speed is None and other_speed is not None and other_speed > speed_range[1]):  # W144, L197
        return "running"
    if speed is not None and speed >= RUNNING_FIRST_SPEED_MPS * k:  # decision W178
        return "running_first"
    return "short_fast"


def running_stride(length_m: float, stride_s: float, leg_m: float | None = None) -> bool:
    """Decision E325: the session's "looks like running" rule (L95's :func:`range_side` "fast" and W144's
    :func:`fast_gait` "running") on one stride's own figures: its cadence 120 / ``stride_s`` and speed |``length_m``|
    / ``stride_s`` (L66's :func:`~pdrlearn.kernels.gait_values.cadence_speed`). False without a finite stride time."""
    if not (math.isfinite(stride_s) and stride_s > 0 and math.isfinite(length_m)):
        return False
    cad, speed = (float(v[0]) for v in cadence_speed(np.array([length_m]), np.array([stride_s])))  # L66
    return range_side(cad, speed, leg_m) == "fast" and fast_gait(cad, speed, leg_m) == "running"


def validated_text(leg_m: float | None, leg_source: str | None = None) -> str:
    """Decisions L95 / L148: the ranges the pipelines are validated on, as L95's line says them (the leg-scaled ones
    too for a known ``leg_m``, from ``leg_source``); offline ``track``'s line and the live Tracker's (E350) share it."""
    cad_range, speed_range = gait_ranges(leg_m)  # decision L148
    text = (f"the pipelines are validated on walking at {CADENCE_RANGE_SPM[0]:.0f}-{CADENCE_RANGE_SPM[1]:.0f} "
            f"steps/min and {SPEED_RANGE_MPS[0]:g}-{SPEED_RANGE_MPS[1]:g} m/s (decision L95)")
    if leg_m is not None:
        text += (f", for the {leg_m:.2f} m leg of {leg_source or 'meta.json'} "
                 f"{cad_range[0]:.0f}-{cad_range[1]:.0f} steps/min and {speed_range[0]:.2f}-{speed_range[1]:.2f} "
                 f"m/s (scaled to a {reference_leg_m():.2f} m adult leg by dynamic similarity, Hof 1996; "
                 "decision L148)")
    return text


def slow_words() -> str:
    """Decision L95: what the line of a walk below the range says before :func:`validated_text`."""
    return "this is slower than the walking the pipelines were validated on: "


def streamed_slow_line(cadence_spm, speed_mps, straight, *, leg_m: float | None = None) -> str | None:
    """Decision E350: offline ``track``'s L95 line for a walk below the range (:func:`range_side` "slow"), on a
    stream's strides: ``cadence_spm`` / ``speed_mps`` (B,) each stride's (NaN: none), ``straight`` (B,) bool (L79:
    level and turning under 15 deg). The speed judged is the straight strides' median when there are
    :data:`MIN_STRAIGHT_FOR_RANGE` of them (L123), else all strides'; None inside the range, above it (E325 flags a
    running stride) or with neither figure. The line ends with what a streamed track cannot trust (offline's words
    for a streamed track)."""
    cad = np.asarray(cadence_spm, dtype=float)
    speed = np.asarray(speed_mps, dtype=float)
    straight = np.asarray(straight, dtype=bool) & np.isfinite(speed)
    c = float(np.median(cad[np.isfinite(cad)])) if np.isfinite(cad).any() else None
    if int(straight.sum()) >= MIN_STRAIGHT_FOR_RANGE:  # decision L123
        v, what = float(np.median(speed[straight])), "straight-walking speed"
    else:
        v, what = (float(np.median(speed[np.isfinite(speed)])) if np.isfinite(speed).any() else None), "speed"
    if range_side(c, v, leg_m) != "slow":
        return None
    figs = ", ".join([*([f"median cadence {c:.0f} steps/min"] if c is not None else []),
                      *([f"{what} {v:.2f} m/s"] if v is not None else [])])
    return (f"{figs}: {slow_words()}{validated_text(leg_m)}; the distance, the terrain / direction / length classes "
            "and the floors are not reliable")
