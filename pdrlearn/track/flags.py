"""A table's true/false column as booleans (decision B244): the same rule wherever a steps table's flag is read.

A column read back from a CSV may hold booleans, 0/1, the strings "True" / "False" or NaN (an empty cell); numpy's
``astype(bool)`` reads every non-empty string and NaN as True. Here only ``True``, ``"true"`` (any case, spaces
stripped), ``1`` and ``1.0`` are true."""

from __future__ import annotations

import numpy as np
import pandas as pd

#: decision B244: the spellings of true (after ``str(v).strip().lower()``)
TRUE_SPELLINGS = ("true", "1", "1.0")


def flag_values(column) -> np.ndarray:
    """The boolean array of ``column`` (a Series or any sequence): True only for :data:`TRUE_SPELLINGS`."""
    return np.array([str(v).strip().lower() in TRUE_SPELLINGS for v in pd.Series(column).tolist()], dtype=bool)
