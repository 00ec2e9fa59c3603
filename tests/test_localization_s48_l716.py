"""Decision L716 (docs/decisions/localization.md): L714's 20 Hz foot stride yaw gain is the 20 Hz block means'
reconstruction, not the stride pipeline. A noise-free walk's strides at 100 Hz are exact; at 20 Hz the class
defaults (L628's x5 histospline) gain yaw on the right foot; the same 20 Hz pipeline (grid, integrator with L626's
term, stance, the accelerometer's start tilt, gap yaw, L690's unwrap) fed the walk's true 100 Hz rates on its x5
grid is exact again. If a change removes the 20 Hz gain, the last test fails: update L716 and the README's limit."""

from __future__ import annotations

import pytest

from experiments.foot_yaw_20hz_l716 import simulate, stride_yaw_errors
from pdrlearn.orient.filters import unit_data

ROUTE = "stand:3, straight:30, stand:3"


@pytest.fixture(scope="module")
def walks():
    """User 15940 (one of L716's trace users), right foot, noise-free, at 20 and 100 Hz: the same walk."""
    return simulate(15940, 20, route=ROUTE), simulate(15940, 100, route=ROUTE)


def test_the_100_hz_strides_yaw_is_exact_l716(walks):
    e = stride_yaw_errors(walks[1])
    assert len(e) > 15
    assert abs(e.mean()) < 0.002  # deg per stride (L716: -0.0001 on the 100 m walks)


def test_the_20_hz_pipeline_with_the_true_rates_is_exact_l716(walks):
    """The x5 grid's rates replaced by the walk's 100 Hz ones (fine sample j = 100 Hz sample j, the same block)."""
    e = stride_yaw_errors(walks[0], rates=unit_data(walks[1], "foot").gyr)
    assert abs(e.mean()) < 0.006  # L716: +0.0014 to +0.0027 deg per stride on users 15940-15959


def test_the_20_hz_block_means_still_gain_yaw_on_the_right_foot_l716(walks):
    """The known limit (README Limits, L626 / L628 / L714 / L716): the spline of the 20 Hz means misses the swing's
    fast roll; the same strides gain yaw to the left. Fails when the limit is removed."""
    e = stride_yaw_errors(walks[0])
    assert e.mean() > 0.01
    assert e.mean() > 3 * abs(stride_yaw_errors(walks[0], rates=unit_data(walks[1], "foot").gyr).mean())
