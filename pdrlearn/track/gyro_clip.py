"""Decision L525: the offline track of a session whose foot gyroscope clips at its full scale.

A +-250 deg/s foot gyroscope loses tens of degrees of pitch in every swing (walking feet turn at 560-990 deg/s,
B401). The offline stride's gyroscope attitude then leaks gravity into the height change, and the foot's stride yaw
(L30) turns a few degrees per stride, which the fused heading (L17) cannot remove. The streamed stride does neither:
it re-levels at the stride's end rest (``kernels.window.foot_levelled``), removes the velocity drift linearly in time
and is headed by the waist gyroscope. So, when B77/B311 flag the foot gyroscope, the offline track takes the streamed
stride's treatment (:data:`CLIPPED_FOOT_SETTINGS`) and the waist's heading.
"""
from __future__ import annotations

from pdrlearn.warning_lines import coded

#: decision L525 (adopted by its rule, L526; the rule itself, no switch: W413 / L507): the FootDisplacement settings
#: of the streamed stride (L68's tilt correction at the end rest, the ZUPT's velocity drift linear in time instead of
#: L21's |a|-weighted clock); a user's ``params`` key wins
CLIPPED_FOOT_SETTINGS = {"tilt_dedrift": True, "accel_scale_error": 0.0}


def foot_gyro_clipped(session) -> tuple[int, float]:
    """Decision L525: (samples with a clipped axis, the clipped level in rad/s) of the session's foot gyroscope by
    B77/B311's :func:`~pdrlearn.io.validate.clipped_samples`; (0, 0.0) without one."""
    from pdrlearn.io.validate import clipped_samples

    if not session.has("fGyroscope"):
        return 0, 0.0
    return clipped_samples(session.streams["fGyroscope"].values, "gyroscope")


def clipped_foot_settings(settings: dict, params) -> dict:
    """Decision L525: ``settings`` (FootDisplacement keywords) with :data:`CLIPPED_FOOT_SETTINGS` for the keys the
    user's ``params`` do not set."""
    given = params if isinstance(params, dict) else {}
    return {**settings, **{k: v for k, v in CLIPPED_FOOT_SETTINGS.items() if k not in given}}


def clipped_foot_line(n: int, total: int, top: float, waist_heads: bool) -> str:
    """Decision L525's one line: what the offline track did about the clipped foot gyroscope."""
    import math

    head = ("and heads by the waist unit instead of fusing the foot's stride yaw (the Python API's heading='fused' "
            "and --params '{\"tilt_dedrift\": false}' undo it)" if waist_heads else
            "but its heading is the foot's own stride yaw, which the clipping turns: add a waist unit, or record the "
            "foot with a wider range")
    return coded(f"the foot gyroscope clips at +-{math.degrees(top):.0f} deg/s in {n} of {total} samples: the offline "
                 f"track re-levels each stride at its end rest (tilt_dedrift, accel_scale_error 0, as the streamed "
                 f"stride does) {head} (decision L525)", "L525")
