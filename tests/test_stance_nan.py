"""StanceSegmenter (decisions E7, L27) refuses NaN/inf gyroscope samples: a NaN in the running sum of the
L27 stance floor would make every later threshold NaN, so no stance and no stride for the rest of a stream."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.kernels.stride import StanceSegmenter


def _walk(fs: float = 100.0, n: int = 6):
    """Strides of 0.4 s still foot + 0.6 s swing (|w| 0.05 / 6 rad/s)."""
    one = np.r_[np.full(int(0.4 * fs), 0.05), np.full(int(0.6 * fs), 6.0)]
    w = np.r_[np.tile(one, n), np.full(int(0.4 * fs), 0.05), np.full(5, 6.0)]
    t = np.arange(w.size) / fs
    return t, np.column_stack([np.zeros_like(w), w, np.zeros_like(w)])


def test_clean_stream_finds_strides():
    t, g = _walk()
    assert len(StanceSegmenter().update(t, g)) >= 5


@pytest.mark.parametrize("bad", [np.nan, np.inf])
def test_non_finite_sample_is_a_one_line_error(bad):
    t, g = _walk()
    g[30, 1] = bad
    seg = StanceSegmenter()
    with pytest.raises(DataError, match="NaN/inf") as e:
        seg.update(t, g)
    assert "\n" not in str(e.value)
