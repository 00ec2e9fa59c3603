"""Decision L357: the reference a pelvis trajectory (``trajectory.csv``) gives where the session has labelled
contacts (``ics.csv``): the path averaged over one labelled stride, over the walking span only."""

from __future__ import annotations

import numpy as np
import pandas as pd

#: the ``distance_ref_source`` / ``altitude_ref_source`` of :func:`walking_reference`'s path (decision L357)
STRIDE_AVERAGED_SOURCE = "trajectory.csv path, stride-averaged over the labelled contacts' span (L357)"
STRIDE_AVERAGED_ALTITUDE_SOURCE = ("trajectory.csv z, stride-averaged, at the first and last labelled contact's span "
                                   "ends (standing moments, L357)")


def labelled_stride_time(ics: pd.DataFrame) -> float | None:
    """The median time (s) between a foot's successive labelled contacts (``ic_s``, per ``foot`` where the table
    names it; else twice the median interval between contacts of both feet); None with fewer than two."""
    if "ic_s" not in ics:
        return None
    if "foot" in ics and ics["foot"].nunique() >= 1 and ics["foot"].notna().all():
        gaps = np.concatenate([np.diff(np.sort(g["ic_s"].dropna().to_numpy(float))) for _, g in ics.groupby("foot")])
    else:
        gaps = 2.0 * np.diff(np.sort(ics["ic_s"].dropna().to_numpy(float)))
    gaps = gaps[np.isfinite(gaps) & (gaps > 0)]
    return float(np.median(gaps)) if gaps.size else None


def walking_reference(gt: pd.DataFrame | None, ics: pd.DataFrame | None) -> pd.DataFrame | None:
    """Decision L357: the pelvis trajectory ``gt`` (``t``, ``x``, ``y``, ``z``) averaged by a centred moving mean over
    one labelled stride (sway and bounce repeat once a stride), from half a stride before the first labelled contact
    to half a stride after the last (the chair transfers' and the standing sway's pelvis travel is no distance
    walked): columns ``t``, ``x``, ``y``, ``z`` on the trajectory's median sample spacing; None without ``ics``, with
    fewer than three contacts or a trajectory of under two samples."""
    if gt is None or ics is None or len(gt) < 2 or not {"t", "x", "y", "z"} <= set(gt.columns) or "ic_s" not in ics:
        return None
    ic = np.sort(ics["ic_s"].dropna().to_numpy(float))
    stride = labelled_stride_time(ics)
    if ic.size < 3 or stride is None:
        return None
    from pdrlearn.kernels.waist import rolling_mean

    t = gt["t"].to_numpy(float)
    dt = float(np.median(np.diff(t)))
    if not dt > 0:
        return None
    grid = np.arange(t[0], t[-1] + dt / 2, dt)
    a, b = max(ic[0] - stride / 2, t[0]), min(ic[-1] + stride / 2, t[-1])
    if not b > a:
        return None
    out = {"t": grid}
    for c in ("x", "y", "z"):
        out[c] = rolling_mean(np.interp(grid, t, gt[c].to_numpy(float)), 1.0 / dt, window_s=stride, causal=False)
    inside = (grid > a) & (grid < b)
    ends = {c: [np.interp(a, grid, out[c]), *out[c][inside], np.interp(b, grid, out[c])] for c in ("x", "y", "z")}
    return pd.DataFrame({"t": [a, *grid[inside], b], **ends})


def walked_length(path: pd.DataFrame) -> float:
    """Horizontal length (m) of :func:`walking_reference`'s path, summed sample to sample."""
    return float(np.hypot(np.diff(path["x"].to_numpy(float)), np.diff(path["y"].to_numpy(float))).sum())
