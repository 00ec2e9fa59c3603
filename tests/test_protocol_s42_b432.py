"""Decision B432: the Bluetooth protocol parser applies B425's range check (a 1e308 gyro value is a corrupted
measurement, counted with its capture line), not only the non-finite check."""

import warnings

from pdrlearn.io.protocol import parse_protocol

GOOD = "%$1 0.72 9.77 -0.87$2 0.01 -0.005 -0.009$3 74.7$4 73.9\n"


def test_a_value_beyond_any_sensors_range_is_a_corrupted_measurement_b432():
    bad = "%$1 0.72 9.77 -0.87$2 1e308 -0.005 -0.009$3 74.7$4 73.9\n"
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no numpy overflow
        session, stats = parse_protocol(GOOD * 4 + bad + GOOD * 3)
    assert stats.corrupted == 1
    assert stats.first_line == 5
    assert stats.examples == ["2 1e308 -0.005 -0.009"]
    assert len(session.streams["fGyroscope"].t) == 7
    assert len(session.streams["fAccelerometer"].t) == 8


def test_the_range_is_checked_after_the_scale_b432():
    # raw ADXL345 counts (thesis eq. 24): 300 counts are 11.5 m/s^2, 1e6 counts beyond 2000 m/s^2
    raw = "%$1 0 0 300$2 0 0 0$3 1$4 1\n%$1 0 0 1e6$2 0 0 0$3 1$4 1\n"
    _, stats = parse_protocol(raw, scales={"fAccelerometer": 9.81 / 256})
    assert stats.corrupted == 1 and stats.first_line == 2
    _, stats = parse_protocol(GOOD * 2)
    assert stats.corrupted == 0 and stats.first_line == 0
