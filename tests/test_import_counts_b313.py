"""Decisions B313 / B314 (docs/decisions/bad-input.md): ``pdrlearn import``'s --acc-unit / --gyro-unit read raw counts
as meta.json's ``units`` do ("1/2048 g", one parser), and the undeclared counts / mg refusals name the declaration
that reads the file."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.io.importer import import_csv
from pdrlearn.io.sensors import SENSORS
from pdrlearn.kernels.units import check_units
from tests.test_counter_wrap_b312 import G, _imu

COLUMNS = {"acc": ["ax", "ay", "az"], "gyro": ["gx", "gy", "gz"]}


def _export(tmp_path, acc, gyr):
    t = 1e4 * np.arange(acc.shape[0])  # us at 100 Hz
    rows = "\n".join(f"{a:.0f}," + ",".join(f"{x:.0f}" for x in (*ac, *gy)) for a, ac, gy in zip(t, acc, gyr,
                                                                                                 strict=True))
    path = tmp_path / "fw.csv"
    path.write_text("t_us,ax,ay,az,gx,gy,gz\n" + rows + "\n")
    return path


def test_import_reads_raw_counts_given_as_the_size_of_one_count_b313(tmp_path):
    acc, gyr = _imu(1000)
    path = _export(tmp_path, np.round(acc / G * 2048), np.round(np.rad2deg(gyr) * 16.4))
    s, record = import_csv(path, columns=COLUMNS, time_unit="us", units={"acc": "1/2048 g", "gyro": "1/16.4 deg/s"})
    np.testing.assert_allclose(s.streams["fAccelerometer"].values, acc, atol=G / 2048)
    np.testing.assert_allclose(s.streams["fGyroscope"].values, gyr, atol=np.deg2rad(1 / 16.4))
    st = record["streams"]["fAccelerometer"]
    assert st["unit"] == "1/2048 g" and st["factor"] == pytest.approx(G / 2048) and st["unit_source"] == "given"
    assert record["streams"]["fGyroscope"]["unit"] == "1/16.4 deg/s"
    with pytest.raises(DataError, match=r"acc unit '1/2048 furlong' is not one of m/s2, g, mg, nor the size of "
                                        r"one count and one of them \(\"1/2048 g\", as meta.json's \"units\""):
        import_csv(path, columns=COLUMNS, time_unit="us", units={"acc": "1/2048 furlong"})


def test_undeclared_counts_and_mg_name_the_declaration_that_reads_them_b314(tmp_path):
    acc, _ = _imu(1000)
    t = 0.01 * np.arange(1000)
    spec = SENSORS["fAccelerometer"]
    with pytest.raises(DataError, match=r"or declare \"units\": \{\"fAccelerometer\": \"1/2048 g\"\} in meta.json "
                                        r"\(decision B314\)"):
        check_units(spec, acc / G * 2048, "f.csv", t=t)
    with pytest.raises(DataError, match=r"or declare \"units\": \{\"fAccelerometer\": \"mg\"\} in meta.json"):
        check_units(spec, acc / G * 1000, "f.csv", t=t)
    with pytest.raises(DataError, match=r"--acc-unit \(m/s2 \| g \| mg\) or \"1/2048 g\" \(the unit of one count"):
        import_csv(_export(tmp_path, np.round(acc / G * 2048), np.zeros_like(acc)), columns=COLUMNS, time_unit="us")


def test_a_wrong_declaration_suggests_the_unit_of_the_raw_values_b314(tmp_path):
    """Review R2 #11: ``--acc-unit "2048 g"`` on counts at 2048 per g suggested "1/41165425 g", worked out from the
    values the wrong declaration had already converted; the file's own values say "1/2048 g"."""
    acc, gyr = _imu(3000, seed=8260)
    path = _export(tmp_path, np.round(acc / G * 2048), np.round(np.rad2deg(gyr) * 16.4))
    with pytest.raises(DataError) as err:
        import_csv(path, columns=COLUMNS, time_unit="us", units={"acc": "2048 g", "gyro": "1/16.4 deg/s"})
    assert '"1/2048 g"' in str(err.value) and "41165425" not in str(err.value)
