"""Shared helper of the step-detector tests: push a session's samples through a detector's online mode."""

from __future__ import annotations

import numpy as np
import pandas as pd


def chunked(det, session_inputs, cuts, *, each=None) -> pd.DataFrame:
    """``det.online`` fed ``session_inputs`` (``det._inputs(session)``: t, values, context) in chunks of the
    sizes ``cuts`` then the rest, flushed; ``each(part)`` is called on every chunk's output."""
    t, v, ctx = session_inputs
    online = det.online(1.0 / np.median(np.diff(t)), **ctx)
    parts, i = [], 0
    for c in cuts:
        parts.append(online.push(t[i:i + c], v[i:i + c]))
        if each is not None:
            each(parts[-1])
        i += c
    parts.append(online.push(t[i:], v[i:]))
    parts.append(online.flush())
    return pd.concat(parts, ignore_index=True)
