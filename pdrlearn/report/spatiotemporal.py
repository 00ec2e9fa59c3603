"""clinical.md's spatiotemporal and leg-length-normalised lines (decisions C195, C196, docs/decisions/cohort.md;
trial T1 F7): what a gait clinic reports beside speed and cadence - stride length, stance / swing % of the stride,
double support (two feet only) and the stride-time CV - and, for a walker whose meta.json gives ``leg_length_m``, the
dimensionless speed and stride length of dynamic similarity (Hof 1996, "Scaling gait data to body size", Gait &
Posture 4: 222-223). Read from what ``track`` / ``gait`` already wrote (summary.json, gait_summary.json): no new
measure, nothing a track did not measure, each line naming the unit it comes from."""

from __future__ import annotations

import math

from pdrlearn.kernels.units import STANDARD_GRAVITY

#: decision C196: the leg length a normalised value is given for is a measured one - meta.json ``leg_length_m``
#: (decision L148's source text); L148's height estimate (0.53 x height) is not one (a child's or a crouch
#: walker's leg is not a fixed share of the height)
MEASURED_LEG_SOURCE = "meta.json leg_length_m"


def _number(v) -> float | None:
    return float(v) if isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v) else None


def _cv_text(summary: dict) -> str | None:
    cv = _number(summary.get("stride_time_cv_pct"))
    if cv is not None:
        n = summary.get("n_cv_strides")
        return f"stride-time CV {cv:.1f} %" + (f" ({n} strides)" if isinstance(n, int) and n else "")
    withheld = summary.get("stride_time_cv_withheld")
    cause = withheld.get("cause") if isinstance(withheld, dict) else None
    if cause == "lower_back" and summary.get("step_count_withheld"):  # decision C247: two contacts are no stride
        return "stride-time CV not given: the lower back's contacts are no step count (W476, C247)"
    if cause == "lower_back":  # decision W559: why, in numbers (W557), and what gives it
        from pdrlearn.track.clinical import JITTER_FREE_WALK, LOWER_BACK_CV_INFLATION

        jf = _number(withheld.get("jitter_free_cv_pct"))
        if jf is not None:  # decisions W558, W598: a long walk's CV, steady straight runs, timing jitter taken out
            return (f"stride-time CV {jf:.1f} % (lower back, steady straight runs, its contacts' timing jitter "
                    f"taken out, {withheld.get('n_jitter_free_strides')} stride intervals; W558, W598)")
        return (f"stride-time CV not given: on the lower back {LOWER_BACK_CV_INFLATION} (W557); a foot unit "
                f"gives it, {JITTER_FREE_WALK} one with the jitter taken out (W558)")
    return f"stride-time CV not given ({str(cause).replace('_', ' ')})" if cause else None


def spatiotemporal_line(summary: dict, unit: str, stride_given: bool = True) -> str | None:
    """Decision C195: ``- Spatiotemporal: stride length 0.82 m, stance 59.1 % / swing 40.9 % of the stride,
    stride-time CV 1.8 % (10 strides) (foot unit; ...)`` from a track's summary.json: the median stride length
    (foot; decision C197: a lower back's, W537, only when ``stride_given``, i.e. calibrated), the median stance
    share (``--toe-off``; swing is its complement, the same strides' median), the stride-time CV or why it is
    withheld. None when the track measured none of the three (an uncalibrated lower-back track: its stride length
    is the height model's, no stance or CV, L104). One foot has no double support: that needs two feet (`pdrlearn
    gait`)."""
    parts = []
    stride = _number(summary.get("median_stride_length_m")) if stride_given else None
    if summary.get("step_count_withheld"):  # decision C247: a summary written before C247 still holds it
        stride = None
        parts.append("stride length not given")
    if stride is not None:
        parts.append(f"stride length {stride:.2f} m")
    stance = _number(summary.get("median_stance_pct"))
    if stance is not None:  # median(100 - x) = 100 - median(x): the swing share of the same strides
        parts.append(f"stance {stance:.1f} % / swing {100.0 - stance:.1f} % of the stride")
    measured = bool(parts)
    cv = _cv_text(summary)
    withheld = summary.get("stride_time_cv_withheld")
    lower_back = isinstance(withheld, dict) and withheld.get("cause") == "lower_back" and bool(summary.get("n_steps"))
    if cv and (measured or lower_back or _number(summary.get("stride_time_cv_pct")) is not None):  # W559
        parts.append(cv)
    if not parts:
        return None
    notes = [unit]
    if stance is not None:
        notes.append("stance from --toe-off; read the track's toe-off warnings")
    if unit == "foot unit":
        notes.append("double support needs a unit on each foot (pdrlearn gait)")
    return f"- Spatiotemporal: {', '.join(parts)} ({'; '.join(notes)})"


def _ratio(num, den) -> float | None:
    num, den = _number(num), _number(den)
    return 100.0 * num / den if num is not None and den is not None and den > 0 else None


def gait_spatiotemporal_line(walk: dict, caveat: str | None = None) -> str | None:
    """Decision C195: a gait_summary.json ``walk``'s line: stride length left / right, stance % of each side's
    stride (mean stance / mean stride time, when ``--toe-off`` measured stance) and double support % of the cycle
    (L262). Decision L762: with ``caveat`` (gait_summary.json ``reason``: the foot units' known support bias, L703)
    and a stance or double support shown, the line says in words that they are not measured values."""
    parts = []
    left, right = _number(walk.get("stride_length_m_left")), _number(walk.get("stride_length_m_right"))
    if left is not None and right is not None:
        parts.append(f"stride length L/R {left:.2f} / {right:.2f} m")
    sl = _ratio(walk.get("stance_time_s_left"), walk.get("stride_time_s_left"))
    sr = _ratio(walk.get("stance_time_s_right"), walk.get("stride_time_s_right"))
    if sl is not None and sr is not None:
        parts.append(f"stance L/R {sl:.1f} / {sr:.1f} % of the stride")
    ds = _number(walk.get("double_support_pct"))
    if ds is not None:
        parts.append(f"double support {ds:.1f} % of the gait cycle")
    if not parts:
        return None
    line = f"- Spatiotemporal (both foot units): {', '.join(parts)}"
    if isinstance(caveat, str) and caveat and (ds is not None or sl is not None):  # decision L762
        line += f" - stance and double support are not measured values here: {caveat}"
    return line


def measured_leg(leg_m, source) -> float | None:
    """Decision C196: the leg length (m) when it is meta.json's measured ``leg_length_m``, else None."""
    leg = _number(leg_m)
    return leg if leg is not None and leg > 0 and source == MEASURED_LEG_SOURCE else None


def normalised_line(speed_mps, stride_m, leg_m: float | None, unit: str) -> str | None:
    """Decision C196: ``- Leg-length normalised (Hof 1996; leg 0.68 m, meta.json leg_length_m): speed v / sqrt(g L)
    0.36, stride length / leg 1.21 (foot unit)``: the dimensionless speed ``v / sqrt(g L)`` and stride length
    ``lambda / L`` (Hof 1996), each only when measured; None without a measured leg or either value."""
    if leg_m is None:
        return None
    parts = []
    speed, stride = _number(speed_mps), _number(stride_m)
    if speed is not None:
        parts.append(f"speed v / sqrt(g L) {speed / math.sqrt(STANDARD_GRAVITY * leg_m):.2f}")  # Hof 1996
    if stride is not None:
        parts.append(f"stride length / leg {stride / leg_m:.2f}")  # Hof 1996
    if not parts:
        return None
    return f"- Leg-length normalised (Hof 1996; leg {leg_m:.2f} m, {MEASURED_LEG_SOURCE}): {', '.join(parts)} ({unit})"
