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
    """
    out[keep_causal, 0:2] = out[keep_causal, 2:4]
    cols = {"t": t, "x": out[:, 0], "y": out[:, 1], "x_rt": out[:, 2], "y_rt": out[:, 3]}
    cols.update(extra or {})
    cols["fix_used"] = used
    return pd.DataFrame(cols)
