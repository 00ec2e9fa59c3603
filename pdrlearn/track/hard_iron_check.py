"""Decision L708: the fused foot track's line when its walk's turns show a waist hard-iron offset that turns the
heading by more than :data:`HARD_IRON_WARN_DEG` (L707: the compass's error is a sinusoid of the walking direction
that L182's check fits and so does not flag)."""
from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.track.plasys import fit_waist_hard_iron

#: decision L708: the fitted hard-iron offset's heading amplitude asin(|b| / H) (deg) above which the line is printed:
#: a heading 5 deg off moves a track sideways by 8.7 % of the distance walked
HARD_IRON_WARN_DEG = 5.0


def hard_iron_amplitude_deg(offset_ut, field_ut: float) -> float:
    """The largest heading error (deg) a horizontal hard-iron offset ``offset_ut`` (uT, forward / left) gives on a
    horizontal field of ``field_ut`` (uT): asin(|b| / H), 90 when the offset is not under the field (L707)."""
    ratio = float(np.hypot(*np.asarray(offset_ut, float)[:2])) / float(field_ut) if field_ut > 0 else np.inf
    return float(np.degrees(np.arcsin(min(ratio, 1.0))))


def hard_iron_line(session, strides: pd.DataFrame, psi: np.ndarray,
                   keep: np.ndarray) -> tuple[str | None, float | None]:
    """Decision L708: (the line or None, the fitted amplitude in deg or None when L84's gates refuse the fit) for a
    fused track that subtracted no hard-iron fit; ``psi`` the foot's relative heading per stride (rad), ``keep`` the
    compass check's strides."""
    b, fit = fit_waist_hard_iron(session, strides, psi, keep=keep)
    if b is None:
        return None, None
    amp = hard_iron_amplitude_deg(b, fit["field_ut"])
    if not amp > HARD_IRON_WARN_DEG:
        return None, amp
    return (f"the waist compass carries a hard-iron offset of {float(np.hypot(b[0], b[1])):.1f} uT (fitted on this "
            f"walk's {fit['n_strides']} straight strides and their turns, decision L84): the fused heading follows the "
            f"compass and is off by up to {amp:.1f} deg depending on the walking direction (over "
            f"{HARD_IRON_WARN_DEG:g} deg warns, decision L708); track with --params '{{\"hard_iron_fit\": true}}' to "
            "subtract it (decision L636), or calibrate the unit"), amp
