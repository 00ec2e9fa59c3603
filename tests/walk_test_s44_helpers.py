"""Hand-made step tables for the session-44 walk-test tests (decisions L642-L646): 1 s foot strides and cone
turns at given times."""

from __future__ import annotations

import numpy as np
import pandas as pd


def strides(t, step_m=1.0, unit: str = "foot") -> pd.DataFrame:
    """A ``unit`` table of 1 s strides starting at ``t`` (s), ``step_m`` tracked metres each."""
    t = np.asarray(t, float)
    return pd.DataFrame({"start_s": t, "end_s": t + 1.0, "event_s": t + 1.0, "length_m": step_m, "unit": unit})


def turns_at(mids) -> pd.DataFrame:
    """Cone turns (180 deg, 1 s) centred on ``mids`` (s)."""
    mids = np.asarray(mids, float)
    return pd.DataFrame({"start_s": mids - 0.5, "end_s": mids + 0.5, "angle_deg": 180.0})


def laps_after(go: float, n: int, lap: int = 30, extra: int = 10) -> tuple[np.ndarray, list[float]]:
    """Stride starts of ``n`` laps of ``lap`` 1 s strides from ``go`` and ``extra`` strides more, and the cone turns
    between the laps (at each lap's end)."""
    t = go + np.arange(n * lap + extra, dtype=float)
    return t, [go + lap * k for k in range(1, n + 1)]
