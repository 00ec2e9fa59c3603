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


def test_read_session_names_the_lower_back_for_a_clipped_waist_accelerometer(tmp_path, caplog):
    import logging

    import numpy as np

    from pdrlearn.io import read_session

    fs, g = 100.0, 9.80665
    t = np.arange(0.0, 20.0, 1.0 / fs)
    moving = (t > 6.0) & (t < 14.0)  # still, 8 s of jumps, still
    up = g + np.where(moving, 30.0 * np.sin(2 * np.pi * t / 0.5), 0.0)  # +-3 g about gravity, a +-2 g range clips
    # sensor noise: an exactly periodic sine has few distinct levels, which B405 reads as a coarse converter
    up = up + np.random.default_rng(0).normal(0.0, 0.02, t.size)
    acc = np.column_stack([0.3 * np.sin(t), np.clip(up, -2 * g, 2 * g), 0.2 * np.cos(t)])
    gyr = np.column_stack([0.1 * np.sin(t), 0.1 * np.cos(t), 0.05 * np.sin(2 * t)])
    folder = tmp_path / "s"
    folder.mkdir()
    for name, v in (("wAccelerometer", acc), ("wGyroscope", gyr)):
        rows = "\n".join(f"{round(a * 1000)},{x:.6f},{y:.6f},{z:.6f}" for a, (x, y, z) in zip(t, v, strict=True))
        (folder / f"{name}.csv").write_text("timestamp,x,y,z\n" + rows + "\n")
    with caplog.at_level(logging.WARNING):
        read_session(folder)
    line = next(r.getMessage() for r in caplog.records if "clipped" in r.getMessage())
    assert "wAccelerometer.csv" in line and "lower back" in line and "foot" not in line
