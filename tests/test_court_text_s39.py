"""Trial T3 finding 9 (session 39): the waist accelerometer's clipping line names the lower back, a side item's route
error gives a side example, and the model speed line counts side / backward strides as such."""

from __future__ import annotations

import pandas as pd
import pytest

from pdrlearn.errors import DataError


def test_waist_clipping_line_names_the_lower_back_not_the_foot():
    from pdrlearn.io.validate import saturation_warning

    waist = saturation_warning("s/wAccelerometer.csv", "accelerometer", 40, 1000, 156.9, "waist")
    assert "foot" not in waist and "lower back" in waist
    assert "foot's integrated stride lengths" in saturation_warning("s/fAccelerometer.csv", "accelerometer", 40,
                                                                    1000, 156.9)


def test_side_item_error_gives_a_side_example():
    from pdrlearn.sim.route import parse_route

    with pytest.raises(DataError, match=r"e\.g\. 'side:3 \(3 m to the left"):
        parse_route("side:4:fast")


def test_speed_line_counts_side_strides_as_side():
    from pdrlearn.track.speed_domain import flag_speeds

    n = 8
    table = pd.DataFrame({"start_s": [float(i) for i in range(n)], "end_s": [i + 1.0 for i in range(n)],
                          "raw_length_m": [0.5] * n, "dz_m": [0.0] * n, "heading_rad": [0.0] * n,
                          "speed_mps": [0.5] * n, "travel": ["side"] * 6 + ["forward"] * 2})
    lines: list[str] = []
    flag_speeds(table, [1.0, 1.6], lines, "all")
    assert lines and "8 of 8 strides (of them 6 side steps, not forward walking)" in lines[0]
