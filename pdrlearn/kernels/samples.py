"""Per-sample loops over numpy arrays without a whole-session list of Python objects (decision E195).

A per-sample kernel written on Python floats (E20: the same IEEE arithmetic, no numpy scalars) used to take
``x.tolist()``: a list of one float object per sample, 32 bytes each, where the array holds 8. On a whole-day
recording (100 Hz, 360 000 samples an hour) the Madgwick filter's six input lists and its list of output tuples
were about 120 MB per recorded hour at once (trial T2 finding 5). :func:`values` gives the same Python floats
(or bools) one at a time from the array's own buffer; :class:`Rows` collects a kernel's output rows as doubles.
"""

from __future__ import annotations

from array import array

import numpy as np


def values(x: np.ndarray):
    """The elements of the 1-D array ``x`` as Python objects, equal to ``x.tolist()``'s, without building that list:
    a float64 or bool array is iterated from its buffer (a memoryview yields the same Python float / bool per
    element); another dtype falls back to ``tolist()``."""
    a = np.asarray(x)
    if a.ndim == 1 and a.dtype in (np.float64, np.bool_):
        return memoryview(np.ascontiguousarray(a))
    return a.tolist()


class Rows:
    """Rows of ``width`` floats appended one at a time and returned as an ``(n, width)`` float64 array; stored as
    doubles (8 bytes a value), not as a list of tuples of float objects (about 150 bytes a row of 4)."""

    def __init__(self, width: int) -> None:
        self.width = width
        self._buf = array("d")
        self.append = self._buf.extend  # rows are appended as tuples of ``width`` floats

    def to_array(self) -> np.ndarray:
        return np.frombuffer(self._buf, dtype=np.float64).reshape(-1, self.width).copy()
