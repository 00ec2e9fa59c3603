"""Decision L502 (review R1 finding 4): the fused altitude's climb bias learnt going up must not worsen the height
after the descent that follows; L503 measured the variants ("one" = L479, "split", "scale")."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.kernels import barometer
from pdrlearn.kernels.barometer import fuse_altitude
from tests.test_slopes import _baro, _strides


def _up_then_down(over: float, mode: str | None, on: bool = True) -> tuple[float, float]:
    """60 strides of 0.17 m up then 60 down, the foot reading every dz ``over`` times: (top, end) fused errors."""
    s0, s1 = _strides(120)
    true = np.r_[np.full(60, 0.17), np.full(60, -0.17)]
    t = np.arange(0.0, s1[-1] + 2.0, 0.04)
    baro = _baro(t, np.interp(t, np.r_[s0[0], s1], np.r_[0.0, np.cumsum(true)]))
    keys = {} if mode is None else {"climb_bias": on, "bias_mode": mode}  # None: fuse_altitude's defaults
    c = np.cumsum(fuse_altitude(true * over, s0, s1, t, baro, **keys))
    return float(c[59] - 10.2), float(c[-1])


@pytest.mark.parametrize("over", [1.03, 1.05])
def test_default_bias_keeps_the_end_height_after_an_up_then_down_walk(over):
    off, one, new = (_up_then_down(over, "one", False), _up_then_down(over, "one"), _up_then_down(over, None))
    assert abs(one[1]) > abs(off[1]) + 0.05  # L479's one state: the climb's bias kept its sign going down
    assert abs(new[1]) <= abs(off[1])  # the default (L503) no worse than the bias off at the end
    assert abs(new[0]) < 0.5 * abs(off[0])  # and still the better top (L478)


def test_bias_mode_is_checked():
    with pytest.raises(ValueError, match="L502"):
        _up_then_down(1.03, "both")
    assert set(barometer.BIAS_MODES) == {"one", "split", "scale"}


def test_default_is_the_scale_keyword_and_no_module_switch_w413():
    """W413: the adopted bias (L479 on, L503 "scale") is fuse_altitude's keyword default, not a module global an
    experiment flips."""
    assert _up_then_down(1.05, None) == _up_then_down(1.05, "scale")
    assert _up_then_down(1.05, None) != _up_then_down(1.05, "scale", False)
    assert not hasattr(barometer, "FUSED_CLIMB_BIAS") and not hasattr(barometer, "FUSED_CLIMB_BIAS_MODE")
