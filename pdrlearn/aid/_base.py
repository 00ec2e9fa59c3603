"""Parameter protocol shared by the aiding filters (scikit-learn style ``get_params``/``set_params``)."""

from __future__ import annotations

import inspect

import numpy as np
import pandas as pd


class ParamsMixin:
    """``get_params``/``set_params`` from the keyword-only arguments of ``__init__``."""

    @classmethod
    def _param_names(cls) -> list[str]:
        sig = inspect.signature(cls.__init__)
        return [p.name for p in sig.parameters.values() if p.kind is inspect.Parameter.KEYWORD_ONLY]

    def get_params(self, deep: bool = True) -> dict:
        return {k: getattr(self, k) for k in self._param_names()}

    def set_params(self, **params):
        for k, v in params.items():
            if k not in self._param_names():
                raise ValueError(f"{type(self).__name__}: unknown parameter '{k}'")
            setattr(self, k, v)
        return self


def stretched_trajectory(t, out: np.ndarray, used, *, keep_causal: np.ndarray,
                         extra: dict | None = None) -> pd.DataFrame:
    """Trajectory table of a fix-fusion filter (seed 004 "stretching").

    ``out[:, 0:2]`` holds the stretched (smoothed between two fixes) positions, ``out[:, 2:4]`` the causal
    real-time ones; rows where ``keep_causal`` is true (after the last fix, or everywhere without
    stretching) take the causal position. Columns ``t, x, y, x_rt, y_rt`` + ``extra`` + ``fix_used``.

    The stretched path ends on the last fix itself (seed 004 eq. 26 closes the gap l(k) in full), the
    causal one on the EKF's posterior, which lies between the prediction and the fix; rows after the last
    stretched row therefore keep that row's offset stretched - causal (the last correction held, a
    zero-slope continuation of eq. 26), so the output does not jump after the last fix (decision D16).
    """
    keep = np.asarray(keep_causal, bool)
    smoothed = np.flatnonzero(~keep)
    if len(smoothed):
        a = smoothed[-1]
        after = keep & (np.arange(len(keep)) > a)
        out[after, 0:2] = out[after, 2:4] + (out[a, 0:2] - out[a, 2:4])
        keep = keep & ~after
    out[keep, 0:2] = out[keep, 2:4]
    cols = {"t": t, "x": out[:, 0], "y": out[:, 1], "x_rt": out[:, 2], "y_rt": out[:, 3]}
    cols.update(extra or {})
    cols["fix_used"] = used
    return pd.DataFrame(cols)
