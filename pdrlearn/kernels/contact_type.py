"""The contact type of each stride and the session's toe-contact share (decision L756, trial s49t4 finding F1).

The sole angle at the initial contact (steps.csv ``ic_angle_deg``, decision L421: + toes up, 0 at the starting
rest) tells a heel strike (toes up, the heel rocker) from a forefoot contact (toes down: a toe walker, simulator
decision S108's 12 deg) and from a flat-foot contact in between. Pure functions of the column."""

from __future__ import annotations

import numpy as np

#: decision L756: |ic_angle_deg| within this (deg) of the standing sole is a flat-foot contact; beyond it toes down
#: is ``forefoot``, toes up ``heel`` (a quarter of seed-S108's 12-deg toe walker)
FLAT_CONTACT_DEG = 3.0
#: decision L756: the session's share needs this many steady strides with a contact type (L123's minimum)
MIN_CONTACT_STRIDES = 5
CONTACT_TYPES = ("forefoot", "flat", "heel")


def contact_types(ic_angle_deg, flat_deg: float = FLAT_CONTACT_DEG) -> np.ndarray:
    """(n,) object: ``forefoot`` where ``ic_angle_deg`` < -``flat_deg``, ``heel`` where > ``flat_deg``, ``flat``
    in between, None where the angle is NaN (decision L756)."""
    a = np.asarray(ic_angle_deg, dtype=float)
    out = np.full(len(a), None, dtype=object)
    out[a < -flat_deg] = "forefoot"
    out[a > flat_deg] = "heel"
    out[np.isfinite(a) & (np.abs(a) <= flat_deg)] = "flat"
    return out


def toe_contact_share(contact, keep) -> tuple[float | None, int]:
    """Decision L756: (100 x the ``forefoot`` rows / the rows with a contact type, their count) over the rows of
    ``keep`` (the steady strides); the share None under :data:`MIN_CONTACT_STRIDES` such rows."""
    c = np.asarray(contact, dtype=object)[np.asarray(keep, dtype=bool)]
    typed = np.array([v in CONTACT_TYPES for v in c], dtype=bool)
    n = int(typed.sum())
    if n < MIN_CONTACT_STRIDES:
        return None, n
    return 100.0 * float(np.sum(c[typed] == "forefoot")) / n, n
