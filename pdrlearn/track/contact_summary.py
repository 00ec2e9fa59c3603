"""Decision L756: the session's toe-contact share from steps.csv's per-stride ``contact`` (a foot track's)."""

from __future__ import annotations

import numpy as np
import pandas as pd

#: decision L756: the summary keys (None / 0 on a track without the sole angle: a lower-back or streamed track)
CONTACT_KEYS = ("toe_contact_share_pct", "n_contact_strides")


def contact_summary(steps: pd.DataFrame) -> dict:
    """``toe_contact_share_pct`` (100 x the steady strides whose ``contact`` is ``forefoot`` / the steady strides
    with a contact type) and ``n_contact_strides`` (those strides) - decision L756: only steady strides (steps.csv
    ``steady``: straight, level, forward, L104 / L415), as a turn's or a stair's contact is no gait pattern."""
    from pdrlearn.kernels.contact_type import toe_contact_share

    out: dict = {"toe_contact_share_pct": None, "n_contact_strides": 0}
    if "contact" not in steps or not len(steps):
        return out
    from pdrlearn.track.flags import flag_values
    from pdrlearn.track.steady import steady_flags

    steady = flag_values(steps["steady"]) if "steady" in steps else steady_flags(steps)
    if steady is None:
        return out
    share, n = toe_contact_share(steps["contact"].to_numpy(object), np.asarray(steady, dtype=bool))
    out["toe_contact_share_pct"], out["n_contact_strides"] = share, n
    return out
