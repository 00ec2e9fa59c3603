"""Decision C126: ``track --length-reference session``, the length class of a tracked session's flat, forward,
straight strides against the median of ALL its such strides (offline), guarded: the model's classes stay unless the
model itself calls fewer than half of them short and fewer than half long
(:func:`pdrlearn.kernels.relative_length.session_length_classes` with ``causal=False, guard=True``, the kernel
C117's running rule shares). Only the reported class changes (its ``p_length_*`` one-hot, as C88); lengths,
positions, terrain and direction are the track's."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.kernels.relative_length import TABLE_COLUMNS, session_length_classes


def whole_session_length(steps: pd.DataFrame, source: str = "track") -> pd.DataFrame:
    """A copy of a tracked stride table (steps.csv's columns, walking order) with decision C126's length classes;
    a table without a ``length_class`` column (no length model) is returned unchanged."""
    if "length_class" not in steps or not len(steps):
        return steps
    cols = [c for c in (*TABLE_COLUMNS, "turn_angle_rad") if c in steps]
    table = steps[cols].astype(object)
    text = [c for c in cols if not pd.api.types.is_numeric_dtype(steps[c])]  # an absent class is None, a number NaN
    table[text] = table[text].where(steps[text].notna(), None)
    rows = table.to_dict("records")  # closing re-read: a NaN length or turn was None, a TypeError in the kernel
    new = session_length_classes(rows, causal=False, guard=True, source=source)
    out = steps.copy()
    old = out["length_class"].to_numpy(dtype=object)
    changed = np.array([isinstance(a, str) and a != b for a, b in zip(new, old, strict=True)], dtype=bool)
    out["length_class"] = np.array(new, dtype=object)
    for c in [c for c in out.columns if c.startswith("p_length_")]:  # one-hot, as decision C88
        out.loc[changed, c] = [float(cls == c[len("p_length_"):]) for cls in np.asarray(new, dtype=object)[changed]]
    return out


__all__ = ["whole_session_length"]
