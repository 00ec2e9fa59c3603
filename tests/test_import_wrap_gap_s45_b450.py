"""Decision B450 (docs/decisions/bad-input.md): ``pdrlearn import`` unwraps a 32-bit ms counter across which packets
were lost (trial T2 finding 2 of session 45: refused as "a clock reset", B312 taking at most 1.5 sample intervals
across a wrap), when the counter's tick is declared and the interval across is within B11's 1 s gap limit; the
wrap line says the gap. Longer, or the tick not declared, B73's refusal stands."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.io.importer import import_csv
from pdrlearn.kernels.counter_wrap import counter_wraps
from tests.test_counter_wrap_b312 import _imu

COLS = {"acc": ["ax", "ay", "az"], "gyro": ["gx", "gy", "gz"]}


def _log(path, lost_s: float, name: str = "counter_ms"):
    """A 20 Hz foot log on a uint32 ms counter that wraps 15 s in, with ``lost_s`` of packets lost at the wrap."""
    true = (2.0 ** 32 - 15000) + 50.0 * np.arange(600)
    keep = ~((true > 2.0 ** 32 - 100) & (true < 2.0 ** 32 - 100 + lost_s * 1000))
    acc, gyr = _imu(true.size, seed=12822)
    rows = "\n".join(f"{t % 2 ** 32:.0f}," + ",".join(f"{x:.5f}" for x in (*a, *g))
                     for t, a, g in zip(true[keep], acc[keep], gyr[keep], strict=True))
    path.write_text(f"{name},ax,ay,az,gx,gy,gz\n" + rows + "\n")
    return true[keep]


def test_import_unwraps_a_32_bit_ms_counter_with_packets_lost_across_the_wrap(tmp_path, caplog):
    true = _log(tmp_path / "fw.csv", 0.35)
    with caplog.at_level(logging.WARNING):
        s, _ = import_csv(tmp_path / "fw.csv", columns=COLS, time_column="counter_ms", time_unit="ms")
    np.testing.assert_allclose(s.streams["fAccelerometer"].t, (true - true[0]) * 1e-3, atol=1e-9)
    line = next(r.getMessage() for r in caplog.records if "wrap around" in r.getMessage())
    assert "the timestamps wrap around from 4294967196 to 250 ms at line 301: a 32-bit counter overflowing" in line
    assert "with samples lost across it, not a clock reset" in line
    assert "the interval across the wrap at line 301 is 350 ms, 7.0 sample intervals: a gap (packets lost)" in line
    caplog.clear()
    with caplog.at_level(logging.WARNING):  # the header's unit declares the tick as well (counter_ms)
        import_csv(tmp_path / "fw.csv", columns=COLS, time_column="counter_ms")
    assert any("350 ms, 7.0 sample intervals" in r.getMessage() for r in caplog.records)


def test_a_longer_gap_or_an_undeclared_tick_is_still_a_clock_reset(tmp_path):
    _log(tmp_path / "long.csv", 1.2)  # 1.2 s across: over B11's 1 s, the number of wraps not taken on trust
    with pytest.raises(DataError, match="a clock reset"):
        import_csv(tmp_path / "long.csv", columns=COLS, time_column="counter_ms", time_unit="ms")
    raw = _log(tmp_path / "t.csv", 0.35, name="t") % 2 ** 32  # no unit anywhere: B312's 1.5 intervals, as before
    assert counter_wraps(raw)[0] == 0 and counter_wraps(raw, 1e-3)[0] == 32
    with pytest.raises(DataError, match="a clock reset"):
        import_csv(tmp_path / "t.csv", columns=COLS, time_column="t")
