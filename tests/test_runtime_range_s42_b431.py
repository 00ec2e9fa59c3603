"""Decision B431 (docs/decisions/bad-input.md; B425 applied to the lean runtime, session 42): the lean reader
(``pdrlearn.runtime.replay.read_streams``, ``python -m pdrlearn.runtime``) refuses a sensor value beyond any sensor's
range with B425's one line naming the file, the line and the value, through the same kernel
(:func:`pdrlearn.kernels.units.out_of_range`), without numpy warnings; a whole file in another unit keeps its
wrong-unit line and an infinite value B9's."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.io.sensors import SENSORS
from pdrlearn.kernels.units import out_of_range
from pdrlearn.runtime import load_bundle
from pdrlearn.runtime.__main__ import main
from pdrlearn.runtime.replay import SENSOR_KINDS, read_streams
from tests.test_sensor_csv_s42_b425_b426 import _session, _set

BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"  # the shipped bundle


@pytest.fixture(scope="module")
def bundle():
    return load_bundle(BUNDLE)


def test_the_lean_reader_refuses_an_absurd_sample_in_b425s_line_b431(tmp_path, bundle):
    d = _session(tmp_path, acc=_set(100, [1e308, 1e308, -1e308]))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(DataError) as exc:
            read_streams(d, bundle)
    assert str(exc.value) == (f"{d / 'fAccelerometer.csv'}: 1 row(s) with a value beyond any accelerometer's range "
                              "(first at line 102: x = 1e+308; the limit is 2000 m/s^2, decision B425): a corrupt "
                              "sample; remove or repair those rows")


def test_blank_lines_do_not_shift_the_line_named_b431(tmp_path, bundle):
    d = _session(tmp_path, gyr=_set(500, [0.0, 0.0, 250.0]))  # 250 rad/s: beyond any gyroscope
    path = d / "fGyroscope.csv"
    lines = path.read_text().splitlines()
    path.write_text("\n".join([lines[0], "", *lines[1:300], "", "", *lines[300:]]) + "\n")
    with pytest.raises(DataError, match=r"fGyroscope\.csv: 1 row\(s\) .*first at line 505: z = 250; the limit is "
                                        r"100 rad/s"):
        read_streams(d, bundle)


def test_python_m_pdrlearn_runtime_says_it_in_one_line_exit_2_b431(tmp_path, capsys):
    d = _session(tmp_path, acc=_set(100, [1e308, 1e308, -1e308]))
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # before: 4 numpy RuntimeWarnings and "step features are NaN"
        assert main([str(BUNDLE), str(d), "--out", str(tmp_path / "o")]) == 2
    err = [ln for ln in capsys.readouterr().err.splitlines() if ln.startswith("error:")]
    assert len(err) == 1 and "fAccelerometer.csv: 1 row(s) with a value beyond" in err[0], err
    assert "line 102: x = 1e+308" in err[0] and "NaN" not in err[0]
    assert not (tmp_path / "o").exists()  # nothing half-written


def test_a_whole_file_in_another_unit_keeps_its_unit_line_and_inf_b9s_b431(tmp_path, bundle, capsys):
    d = _session(tmp_path, acc=lambda a: a * 1000.0)  # mm/s^2: every row beyond 2000
    with pytest.raises(DataError, match=r"fAccelerometer\.csv: median \|acc\| is \d+, which looks like raw counts or "
                                        "mm/s"):
        read_streams(d, bundle)
    d2 = _session(tmp_path, acc=_set(100, [np.inf, 0.0, 0.0]), name="s2")
    streams, _ = read_streams(d2, bundle)  # inf is the tracker's B9 line, as before
    assert np.isinf(streams["fAccelerometer"][1][100, 0])
    assert main([str(BUNDLE), str(d2)]) == 2
    assert "NaN/inf" in capsys.readouterr().err
    assert out_of_range("accelerometer", np.array([[np.inf, 0.0, 0.0], [3000.0, 0.0, 0.0]])).tolist() == [1]


def test_the_kinds_are_the_full_readers_b431():
    assert SENSOR_KINDS == {n: (s.kind, s.unit) for n, s in SENSORS.items()}
