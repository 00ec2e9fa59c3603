"""Decision L771 (trial s50t1 F8): the end's distance from the start, in m and % of the walked distance."""

from __future__ import annotations

import pytest

from pdrlearn.kernels.travel import loop_closure


def test_loop_closure_is_the_end_to_start_distance_over_the_walked_distance():
    assert loop_closure([0, 10, 10, 3], [0, 0, 10, 4], 30.0) == pytest.approx((5.0, 100 * 5 / 30))
    assert loop_closure([1, 1], [2, 2], 12.0) == (0.0, 0.0)  # back at the start (the first row, not the origin)
    assert loop_closure([0, 3], [0, 4], 0.0) == (5.0, None)  # no walked distance: no percentage
    assert loop_closure([], [], 10.0) == (None, None)
