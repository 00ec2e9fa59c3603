"""Decisions B201-B205 (trial `fuzz` findings 1, 2, 4, 5, 6): foot input that was tracked silently wrong, exit 0.

B201: a foot accelerometer whose rest |acc| is more than 7 % off 1 g is warned about, and a foot detector finding 0
strides on a walking foot says so. B202: gravity-removed acceleration (each axis's median subtracted) is refused as
"reads ~0 g at rest". B203: a frozen foot IMU beside stepping force sensors is refused. B204: a foot + waist session
without fAccelerometer.csv says the foot unit is ignored. B205: a label table cut mid-row is refused.
"""

from __future__ import annotations

import shutil

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    from pdrlearn import sim
    from pdrlearn.io import write_session

    d = tmp_path_factory.mktemp("b201") / "walk"
    write_session(sim.simulate("walk", 2, length_m=12), d)
    return d


def _copy(src, tmp_path, name, edit=None, file="fAccelerometer.csv"):
    d = tmp_path / name
    shutil.copytree(src, d)
    if edit is not None:
        f = d / file
        df = pd.read_csv(f)
        edit(df).to_csv(f, index=False)
    return d


def _scaled(k):
    return lambda df: df.assign(**{c: df[c] * k for c in "xyz"})


def _lines(err: str, key: str) -> list[str]:
    return [ln for ln in err.splitlines() if key in ln]


def test_a_mis_scaled_foot_accelerometer_is_warned_b201(walk, tmp_path, capsys):
    assert main(["info", str(walk)]) == 0
    assert _lines(capsys.readouterr().err, "B201") == []  # as simulated: no word
    d = _copy(walk, tmp_path, "x12", _scaled(1.2))
    assert main(["info", str(d)]) == 0
    (line,) = _lines(capsys.readouterr().err, "B201")
    assert line.startswith(f"warning: {d}: fAccelerometer.csv reads 1.2") and "g at the foot's rests" in line
    assert "calibrate the accelerometer (scale), or divide its values by 1.2" in line
    assert main(["track", "--no-plot", str(d), "--out", str(tmp_path / "t"), "--json"]) == 0
    out = capsys.readouterr()
    assert len(_lines(out.err, "(decision B201)")) == 1 and "Traceback" not in out.err
    d = _copy(walk, tmp_path, "x104", _scaled(1.04))  # within 7 %: not warned (a correct real foot reads 0.967 g)
    assert main(["info", str(d)]) == 0
    assert _lines(capsys.readouterr().err, "B201") == []


def test_steps_finding_no_stride_on_a_walking_foot_warns_b201(gaitmap_level_left, tmp_path, capsys):
    """The trial's x1.2 copy of gaitmap_level_left: `steps` found 0 strides, exit 0, stderr empty."""
    d = _copy(gaitmap_level_left, tmp_path, "Ls_1.2", _scaled(1.2))
    assert main(["steps", str(d), "--json"]) == 0
    err = capsys.readouterr().err
    (line,) = _lines(err, "found no strides")
    assert line.startswith(f"warning: {d}: accel found no strides, but the foot unit walks")
    assert "reads 1.205 g at rest: check its scale" in line
    assert len(_lines(err, "B201")) == 2  # the scale line and this one


@pytest.mark.parametrize("unit", ["f", "w"])
def test_gravity_removed_acceleration_is_refused_b202(walk, tmp_path, capsys, unit):
    """Each axis's median subtracted: the foot was tracked (-44 %), the waist told to multiply by 9.80665."""
    d = _copy(walk, tmp_path, f"lin_{unit}", lambda df: df.assign(**{c: df[c] - df[c].median() for c in "xyz"}),
              f"{unit}Accelerometer.csv")
    for cmd in (["info", str(d)], ["track", "--no-plot", str(d), "--out", str(tmp_path / "t")]):
        assert main(cmd) == 2
        err = capsys.readouterr().err.strip()
        assert err.count("\n") == 0 and err.startswith(f"error: {d / f'{unit}Accelerometer.csv'}: the accelerometer "
                                                       "reads ~0 g at rest: ")
        assert "gravity removed (linear / free acceleration)? " in err and "record raw acceleration" in err
        assert "units of g" not in err and "is that unit right" not in err


def test_gravity_removed_rest_reading_kernel_b202():
    from pdrlearn.kernels.units import rest_without_gravity

    assert rest_without_gravity(5.94, 0.775) == pytest.approx(0.079, abs=1e-3)  # m/s^2: 0.079 g at rest
    assert rest_without_gravity(1.15, 0.341) == pytest.approx(0.341)  # g band: 0.34 g at rest
    assert rest_without_gravity(11.2, 9.84) is None and rest_without_gravity(1.1, 0.99) is None  # with gravity
    assert rest_without_gravity(6.0, 4.9) is None  # B97's x0.5 mis-scale keeps B97's "divide by 0.5"
    assert rest_without_gravity(3.0, 0.03) == pytest.approx(0.03)  # a walk with long pauses, gravity removed
    assert rest_without_gravity(0.0, 0.0) is None  # zeros: B123


def _frozen(df):
    return df.assign(x=0.0, y=9.81, z=0.0)


def test_a_frozen_foot_imu_beside_stepping_force_sensors_is_refused_b203(walk, tmp_path, capsys):
    d = _copy(walk, tmp_path, "frozen", _frozen)
    g = d / "fGyroscope.csv"
    pd.read_csv(g).assign(x=0.0, y=0.0, z=0.0).to_csv(g, index=False)
    for cmd in (["track", "--no-plot", str(d), "--out", str(tmp_path / "t")],
                ["track", "--no-plot", str(d), "--out", str(tmp_path / "t"), "--streaming"]):
        assert main(cmd) == 2
        err = capsys.readouterr().err.strip().splitlines()[-1]
        assert err.startswith(f"error: {d}: no strides detected; is the foot unit moving? The force sensors "
                              "(fForceA.csv, fForceB.csv) load ")
        assert err.endswith("(decision B203)")
    assert main(["steps", str(d)]) == 0
    assert len(_lines(capsys.readouterr().err, "(decision B203)")) == 1


def test_run_refuses_a_frozen_foot_imu_b203(tmp_path_factory, tmp_path, capsys):
    from tests.runtime_helpers import trained_dirs_and_walk

    dirs = trained_dirs_and_walk(tmp_path_factory, "b203")
    d = _copy(dirs["walk"], tmp_path, "frozen", _frozen)
    g = d / "fGyroscope.csv"
    pd.read_csv(g).assign(x=0.0, y=0.0, z=0.0).to_csv(g, index=False)
    capsys.readouterr()
    assert main(["run", str(dirs["root"] / "bundle"), str(d), "--json"]) == 2
    err = capsys.readouterr().err.strip().splitlines()[-1]
    assert "no strides detected; is the foot unit moving?" in err and err.endswith("(decision B203)")


def test_a_standing_subject_is_not_a_frozen_imu_b203():
    from pdrlearn import sim
    from pdrlearn.track.foot_rest import frozen_foot_imu

    assert frozen_foot_imu(sim.simulate("walk", 2, length_m=12)) is None


def test_a_session_without_its_foot_accelerometer_says_the_foot_is_ignored_b204(walk, tmp_path, capsys):
    d = _copy(walk, tmp_path / "batch", "noacc")
    (d / "fAccelerometer.csv").unlink()
    assert main(["track", "--no-plot", str(d), "--out", str(tmp_path / "t")]) == 0
    (line,) = _lines(capsys.readouterr().err, "B204")
    assert line.startswith(f"warning: {d}: fAccelerometer.csv missing: foot unit ignored, tracking the waist (")
    assert main(["track-all", "--no-plot", str(tmp_path / "batch"), "--out", str(tmp_path / "ta")]) == 0
    assert len(_lines(capsys.readouterr().err, "fAccelerometer.csv missing: foot unit ignored")) == 1
    assert "foot unit ignored" in pd.read_csv(tmp_path / "ta" / "sessions.csv")["warnings"].iloc[0]


@pytest.mark.parametrize("table", ["steps", "ics"])
def test_a_label_table_cut_mid_row_is_refused_b205(walk, tmp_path, capsys, table):
    d = _copy(walk, tmp_path, f"cut_{table}")
    f = d / f"{table}.csv"
    if not f.is_file():
        pytest.skip(f"the simulated walk has no {table}.csv")
    text = f.read_text()
    lines = text.splitlines()
    f.write_text("\n".join(lines[:3]) + "\n" + lines[3].split(",")[0][:6])  # line 4 stops inside its first cell
    assert main(["steps", str(d)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and err.startswith(f"error: {f}: last line incomplete (line 4 stops mid-row, no "
                                                   "line break at the end): file truncated? (it has no ")
    f.write_text("\n".join(lines))  # complete, only the last line break missing: read as before
    assert main(["info", str(d)]) == 0


def test_the_label_check_keeps_a_blank_cell_other_rows_leave_blank_too_b205(tmp_path):
    from pdrlearn.io.validate import check_last_row

    f = tmp_path / "t.csv"
    f.write_text("a,b\n1,\n2,")  # b blank in every row: not a cut
    check_last_row(pd.read_csv(f), f, str(f))
    f.write_text("a,b\n1,2\n3")
    with pytest.raises(Exception, match="last line incomplete"):
        check_last_row(pd.read_csv(f), f, str(f))
    assert np.isnan(pd.read_csv(f)["b"].iloc[-1])
