"""Decision L525: the offline track of a session whose foot gyroscope clips at its full scale.

A +-250 deg/s foot gyroscope loses tens of degrees of pitch in every swing (walking feet turn at 560-990 deg/s,
B401). The offline stride's gyroscope attitude then leaks gravity into the height change, and the foot's stride yaw
(L30) turns a few degrees per stride, which the fused heading (L17) cannot remove. The streamed stride does neither:
it re-levels at the stride's end rest (``kernels.window.foot_levelled``), removes the velocity drift linearly in time
and is headed by the waist gyroscope. So, when B77/B311 flag the foot gyroscope, the offline track takes the streamed
stride's treatment (:data:`CLIPPED_FOOT_SETTINGS`) and the waist's heading. Decision L529: only when the clipped
samples are :data:`CLIPPED_MOVING_MIN_SHARE` or more of the foot's moving samples (B401's share): a spike of a few
held samples leaves the track alone.
"""
from __future__ import annotations

from pdrlearn.kernels.clipping import CLIPPED_MOVING_MIN_SHARE, clipping_acts  # noqa: F401 - re-exported (L529)
from pdrlearn.warning_lines import coded

#: decision L525 (adopted by its rule, L526; the rule itself, no switch: W413 / L507): the FootDisplacement settings
#: of the streamed stride (L68's tilt correction at the end rest, the ZUPT's velocity drift linear in time instead of
#: L21's |a|-weighted clock); a user's ``params`` key wins
CLIPPED_FOOT_SETTINGS = {"tilt_dedrift": True, "accel_scale_error": 0.0}


def foot_gyro_clipped(session) -> tuple[int, float, int]:
    """Decision L525: (samples with a clipped axis, the clipped level in rad/s, decision L529: the moving samples,
    B401's) of the session's foot gyroscope by B77/B311's :func:`~pdrlearn.io.validate.clipped_samples`; (0, 0.0, 0)
    without one."""
    import numpy as np

    from pdrlearn.io.plasys import declared_full_scales
    from pdrlearn.io.validate import MOVING_RAD_S, clipped_samples

    if not session.has("fGyroscope"):
        return 0, 0.0, 0
    values = session.streams["fGyroscope"].values
    n, top = clipped_samples(values, "gyroscope", declared_full_scales(session).get("fGyroscope"))  # B456
    return n, top, int(np.count_nonzero(np.linalg.norm(values, axis=1) >= MOVING_RAD_S))


def applied_settings(params) -> dict:
    """Decision L525: the :data:`CLIPPED_FOOT_SETTINGS` the user's ``params`` do not set (those the track applies)."""
    given = params if isinstance(params, dict) else {}
    return {k: v for k, v in CLIPPED_FOOT_SETTINGS.items() if k not in given}


def clipped_foot_settings(settings: dict, params) -> dict:
    """Decision L525: ``settings`` (FootDisplacement keywords) with :data:`CLIPPED_FOOT_SETTINGS` for the keys the
    user's ``params`` do not set."""
    return {**settings, **applied_settings(params)}


def clipped_foot_line(n: int, total: int, top: float, waist_heads: bool, applied: dict | None = None) -> str:
    """Decision L525's one line: what the offline track did about the clipped foot gyroscope, worded from the
    settings it ``applied`` (:func:`applied_settings`; None: all of them) and whether the waist heads it."""
    import math

    applied = CLIPPED_FOOT_SETTINGS if applied is None else applied
    names = ", ".join(f"{k} {str(v).lower() if isinstance(v, bool) else f'{v:g}'}" for k, v in applied.items())
    undo = [f'"{k}": {"false" if v is True else "null"}' for k, v in applied.items() if k == "tilt_dedrift"]
    fix = (f"re-levels each stride at its end rest ({names}, as the streamed stride does)" if applied else
           "keeps the foot settings your --params file gives (tilt_dedrift, accel_scale_error)")
    if waist_heads:
        ways = ["the Python API's heading='fused'"] + ([f"a --params JSON file with {{{undo[0]}}}"] if undo else [])
        verb = "undo" if len(ways) > 1 else "undoes"
        head = f"and heads by the waist unit instead of fusing the foot's stride yaw ({' and '.join(ways)} {verb} it)"
    else:
        head = ("but its heading is the foot's own stride yaw, which the clipping turns: add a waist unit, or record "
                "the foot with a wider range")
    return coded(f"the foot gyroscope clips at +-{math.degrees(top):.0f} deg/s in {n} of {total} samples: the offline "
                 f"track {fix} {head} (decision L525)", "L525")
