"""Second new-user trial (session 11): `pdrlearn import` let through foot acceleration with gravity subtracted
once (B36) and rad/s data declared as deg/s (B37); its errors named meta.json instead of its options (B38);
`acc_x_g`-style names were not guessed, `--force` deleted files added by hand, no subject height at import
(D12 amendment); `info` printed "none frame none" (finding 10)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import read_session

ROOT = Path(__file__).resolve().parents[1]
LEVEL = ROOT / "datasets" / "real" / "gaitmap_level_left"  # foot, 204.8 Hz, with still stretches
G = 9.80665


@pytest.fixture(scope="module")
def level():
    if not LEVEL.is_dir():
        pytest.skip("datasets/real/gaitmap_level_left not present")
    return read_session(LEVEL)


def _export(s, path: Path, *, acc=None, gyro=None, time_ms=False) -> Path:
    """The foot unit as a `time_s,acc_x_g,...,gyr_x_dps` export (the trial's names and units)."""
    a, w = s.streams["fAccelerometer"], s.streams["fGyroscope"]
    acc = a.values if acc is None else acc
    gyro = np.degrees(w.values) if gyro is None else gyro
    t = a.t - a.t[0]
    df = pd.DataFrame({"time_ms" if time_ms else "time_s": t * 1e3 if time_ms else t,
                       **{f"acc_{c}_g": acc[:, i] / G for i, c in enumerate("xyz")},
                       **{f"gyr_{c}_dps": gyro[:, i] for i, c in enumerate("xyz")}})
    df.to_csv(path, index=False, float_format="%.9g")
    return path


def _err(capsys) -> str:
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    return err


def test_names_with_unit_suffixes_are_guessed_with_their_units(level, tmp_path, capsys):
    csv = _export(level, tmp_path / "foot.csv")
    out = tmp_path / "s"
    assert main(["import", str(csv), "--out", str(out)]) == 0
    err = capsys.readouterr().err
    assert "fAccelerometer: acc_x_g,acc_y_g,acc_z_g (guessed) in g (header, x 9.80665" in err
    assert "fGyroscope: gyr_x_dps,gyr_y_dps,gyr_z_dps (guessed) in deg/s (header" in err
    assert "time: column 'time_s' in s (guessed column, unit header)" in err
    got = read_session(out)
    np.testing.assert_allclose(got.streams["fGyroscope"].values, level.streams["fGyroscope"].values, rtol=1e-7,
                               atol=1e-9)


def test_gravity_subtracted_once_is_refused_at_rest(level, tmp_path, capsys):
    a = level.streams["fAccelerometer"].values
    lin = a - a[0]  # the first resting sample's vector taken off (trial: mean vector passed B30's ratio)
    csv = _export(level, tmp_path / "lin.csv", acc=lin)
    assert main(["import", str(csv), "--out", str(tmp_path / "s")]) != 0
    err = _err(capsys)
    # decision B202: the quietest windows' ~0 g answers before B36's still stretches (the same diagnosis)
    assert "lin.csv (acc_x_g, acc_y_g, acc_z_g as g): the accelerometer reads ~0 g at rest" in err
    assert "gravity removed" in err and "check that these columns are an accelerometer" in err


def test_swapped_columns_name_gyroscope_columns(level, tmp_path, capsys):
    csv = _export(level, tmp_path / "foot.csv")
    assert main(["import", str(csv), "--out", str(tmp_path / "s"), "--acc", "gyr_x_dps,gyr_y_dps,gyr_z_dps",
                 "--gyro", "acc_x_g,acc_y_g,acc_z_g"]) != 0
    assert "or these columns are not an accelerometer (gyroscope columns?)" in _err(capsys)


def test_rad_s_declared_as_deg_s_is_refused(level, tmp_path, capsys):
    csv = _export(level, tmp_path / "si.csv", gyro=level.streams["fGyroscope"].values)  # rad/s under _dps names
    assert main(["import", str(csv), "--out", str(tmp_path / "s"), "--gyro-unit", "deg/s"]) != 0
    err = _err(capsys)
    assert "look like rad/s converted as deg/s" in err and "drop --gyro-unit deg/s" in err


def test_real_and_simulated_pairs_pass(level):
    from pdrlearn.io.validate import check_imu_pair
    from pdrlearn.sim import simulate

    sessions = [level] + [simulate(sc, 1) for sc in ("A", "standstill", "rotations")]
    for s in sessions:
        for acc, gyr, place in (("fAccelerometer", "fGyroscope", "foot"), ("wAccelerometer", "wGyroscope", "waist")):
            if acc in s.streams and gyr in s.streams:
                a, g = s.streams[acc], s.streams[gyr]
                check_imu_pair(a.t, a.values, g.t, g.values, place, acc, gyr)
    a, g = level.streams["fAccelerometer"], level.streams["fGyroscope"]
    with pytest.raises(DataError, match="median |acc| is 1.00"):
        check_imu_pair(a.t, a.values / G, g.t, g.values, "foot", "acc", "gyro")


def test_time_unit_errors_name_the_option_and_the_unit_the_values_look_like(level, tmp_path, capsys):
    csv = _export(level, tmp_path / "ms.csv", time_ms=True)
    assert main(["import", str(csv), "--out", str(tmp_path / "s"), "--time-unit", "s"]) != 0
    err = _err(capsys)
    assert "read as s (given with --time-unit) give 0.205 Hz; the values look like ms: pass --time-unit ms" in err
    assert "meta.json" not in err
    assert main(["import", str(csv), "--out", str(tmp_path / "s"), "--acc-unit", "m/s2"]) != 0
    err = _err(capsys)
    assert "or give the unit with --acc-unit" in err and "meta.json" not in err


def test_force_keeps_files_added_by_hand_and_subject_height(level, tmp_path, capsys):
    csv = _export(level, tmp_path / "foot.csv")
    out = tmp_path / "s"
    assert main(["import", str(csv), "--out", str(out), "--subject-height", "1.82"]) == 0
    assert json.loads((out / "meta.json").read_text())["height_m"] == 1.82
    (out / "ics.csv").write_text("ic_ms\n1000\n")
    capsys.readouterr()
    assert main(["import", str(csv), "--out", str(out), "--force"]) != 0
    assert "holds ics.csv, which 'pdrlearn import' did not write and --force would delete" in _err(capsys)
    assert (out / "ics.csv").exists()
    (out / "ics.csv").unlink()
    assert main(["import", str(csv), "--out", str(out), "--force"]) == 0
    capsys.readouterr()
    assert main(["import", str(csv), "--out", str(tmp_path / "s2"), "--subject-height", "182"]) != 0
    assert "not a person's height in m" in _err(capsys)


def test_info_without_a_frame_reads_as_a_sentence(level, tmp_path, capsys):
    a = level.streams["fAccelerometer"].values
    csv = _export(level, tmp_path / "swap.csv", acc=a[:, [1, 0, 2]])  # wrong accelerometer column order
    out = tmp_path / "s"
    assert main(["import", str(csv), "--out", str(out)]) == 0
    capsys.readouterr()
    main(["info", str(out)])
    text = capsys.readouterr()
    line = next(ln for ln in (text.out + text.err).splitlines() if ln.startswith("foot axes:"))
    assert "none frame none" not in line and line.startswith("foot axes: no frame declared or inferred (")
