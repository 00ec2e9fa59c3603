"""Decisions B66-B68: `pdrlearn import` on a Shimmer Consensys-style export (an Excel ``sep=`` first line, tab
separated, ``Shimmer_7A1F_..._CAL`` names, a units row), a declared frame the data contradict (refused unless
--force-frame) and the origin printed to the millisecond. The fixture is synthetic
(tests/fixtures/make_shimmer_fixture.py: a simulated 6 m walk written as a Shimmer export and as a plain CSV)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.io.importer import guess_columns, guess_time_column, import_csv
from pdrlearn.io.plasys import read_table

FIX = Path(__file__).resolve().parent / "fixtures"
SHIMMER = FIX / "shimmer_foot.csv"
PLAIN = FIX / "shimmer_foot_plain.csv"
FRAME = "x=forward,y=up,z=right"  # the simulator's foot frame


def _track(folder: Path, out: Path, capsys) -> dict:
    assert main(["track", "--no-plot", str(folder), "--out", str(out), "--json"]) == 0
    return json.loads(capsys.readouterr().out.splitlines()[-1])


def test_the_fixture_is_a_shimmer_layout():
    lines = SHIMMER.read_text().splitlines()
    assert lines[0] == "sep=\t"
    assert lines[1].startswith("Shimmer_7A1F_Timestamp_Unix_CAL\tShimmer_7A1F_Accel_LN_X_CAL\t")
    assert lines[2].startswith("ms\tm/(s^2)\tm/(s^2)\tm/(s^2)\tdeg/s\t")


def test_shimmer_export_imports_and_tracks_as_the_plain_csv(tmp_path, capsys):
    shim, plain = tmp_path / "shim", tmp_path / "plain"
    assert main(["import", str(SHIMMER), "--out", str(shim), "--frames", FRAME]) == 0
    err = capsys.readouterr().err
    assert ("time: column 'Shimmer_7A1F_Timestamp_Unix_CAL' in ms (guessed column, unit units row); "
            "0 ms = 1733200000.123 s (2024-12-03T04:26:40.123+00:00) on the export's clock") in err
    assert "note: line 3 read as a units row (ms, m/(s^2), deg/s, local_flux, mV, kPa)" in err
    assert ("fAccelerometer: Shimmer_7A1F_Accel_LN_X_CAL,Shimmer_7A1F_Accel_LN_Y_CAL,Shimmer_7A1F_Accel_LN_Z_CAL "
            "(guessed) in m/s2 (units row)") in err
    assert "fGyroscope: Shimmer_7A1F_Gyro_X_CAL,Shimmer_7A1F_Gyro_Y_CAL,Shimmer_7A1F_Gyro_Z_CAL (guessed) in deg/s " \
           "(units row, x 0.0174533 to rad/s)" in err
    # the magnetometer (no foot sensor) is left unused, the trailing tab's empty column is no column
    assert ("unused columns: Shimmer_7A1F_Mag_X_CAL, Shimmer_7A1F_Mag_Y_CAL, Shimmer_7A1F_Mag_Z_CAL, "
            "Shimmer_7A1F_Battery_CAL, Shimmer_7A1F_Pressure_BMP280_CAL\n") in err
    meta = json.loads((shim / "meta.json").read_text())
    assert meta["imported"]["time"]["origin_s"] == pytest.approx(1733200000.123, abs=1e-6)
    assert meta["imported"]["skipped_rows"]["units"]["Shimmer_7A1F_Gyro_X_CAL"] == "deg/s"
    assert main(["import", str(PLAIN), "--out", str(plain), "--frames", FRAME]) == 0
    capsys.readouterr()
    a, b = read_session(shim), read_session(plain)
    for name in ("fAccelerometer", "fGyroscope"):
        np.testing.assert_allclose(a.streams[name].t, b.streams[name].t, atol=1e-9)
        np.testing.assert_allclose(a.streams[name].values, b.streams[name].values, atol=1e-5)
    ta, tb = _track(shim, tmp_path / "ta", capsys), _track(plain, tmp_path / "tb", capsys)
    assert ta["n_steps"] == tb["n_steps"] >= 4
    assert ta["distance_m"] == pytest.approx(tb["distance_m"], abs=1e-3)
    assert ta["distance_m"] == pytest.approx(6.0, rel=0.05)  # the simulated walk's 6.00 m


@pytest.mark.parametrize("first", ["sep=\t", '"sep=\t"', "sep=\\t", "sep="])
def test_sep_line_variants_are_read(tmp_path, first):
    body = SHIMMER.read_text().split("\n", 1)[1]
    p = tmp_path / "x.csv"
    p.write_text(first + "\n" + body)
    df = read_table(p)
    assert list(df.columns[:2]) == ["Shimmer_7A1F_Timestamp_Unix_CAL", "Shimmer_7A1F_Accel_LN_X_CAL"]


def test_sep_comma_line_and_name_guesses(tmp_path):
    p = tmp_path / "c.csv"
    p.write_text("sep=,\nShimmer_1E2B_Timestamp_Unix_CAL,Shimmer_1E2B_Accel_WR_X_CAL,x\nms,m/(s^2),\n1,2,3\n2,3,4\n")
    assert list(read_table(p).columns) == ["Shimmer_1E2B_Timestamp_Unix_CAL", "Shimmer_1E2B_Accel_WR_X_CAL", "x"]
    cols = [f"Shimmer_7A1F_{n}_CAL" for n in ("Timestamp_Unix", "Accel_LN_X", "Accel_LN_Y", "Accel_LN_Z",
                                               "Gyro_X", "Gyro_Y", "Gyro_Z")]
    assert guess_time_column(cols) == cols[0]
    assert guess_columns(cols) == {"acc": cols[1:4], "gyro": cols[4:7]}
    assert guess_time_column(["Sensor Timestamp", "ax"]) == "Sensor Timestamp"  # "timestamp" anywhere


def test_units_row_without_sep_line_and_header_units(tmp_path):
    """No sep= line, comma separated, units in g and s: the units row converts them (B66)."""
    s = read_session_values()
    p = tmp_path / "u.csv"
    rows = ["Timestamp,Accel_X,Accel_Y,Accel_Z,Gyro_X,Gyro_Y,Gyro_Z", "s,g,g,g,rad/s,rad/s,rad/s"]
    rows += [",".join(f"{v:.6f}" for v in r) for r in s]
    p.write_text("\n".join(rows) + "\n")
    session, rec = import_csv(p)
    assert rec["time"]["unit"] == "s" and rec["streams"]["fAccelerometer"]["unit"] == "g"
    assert rec["streams"]["fAccelerometer"]["unit_source"] == "units row"
    np.testing.assert_allclose(session.streams["fAccelerometer"].values[:, 1], s[:, 2] * 9.80665, atol=1e-5)


def read_session_values() -> np.ndarray:
    """200 rows of a foot at rest in s, g, rad/s."""
    rng = np.random.default_rng(1)
    n = 200
    return np.column_stack([np.arange(n) * 0.01, rng.normal(0, 0.01, n), 1 + rng.normal(0, 0.01, n),
                            rng.normal(0, 0.01, n), *(rng.normal(0, 0.01, n) for _ in range(3))])


def _refused(args: list[str], out: Path, capsys) -> str:
    assert main(["import", *args, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("error: ") and "\n" not in err, err
    assert not out.exists()
    return err[len("error: "):]


def test_a_row_2_that_is_not_all_text_gets_the_units_row_hint(tmp_path, capsys):
    """A units row with one number in it is not taken for one, but the error says what it looks like."""
    p = tmp_path / "h.csv"
    v = read_session_values()
    rows = ["time_ms,ax,ay,az,gx,gy,gz", "ms,m/s2,m/s2,m/s2,1,rad/s,rad/s"]
    rows += [",".join([f"{r[0] * 1e3:.1f}", *(f"{x:.5f}" for x in r[1:])]) for r in v]
    p.write_text("\n".join(rows) + "\n")
    err = _refused([str(p)], tmp_path / "o", capsys)
    assert "first at line 2" in err and "line 2 (ms, m/s2, m/s2, m/s2 ...) looks like a units row" in err
    assert "--skip-rows 1" in err
    assert main(["import", str(p), "--out", str(tmp_path / "o"), "--skip-rows", "1", "--acc-unit", "g"]) == 0
    assert "note: 1 row(s) under the header skipped (given (--skip-rows))" in capsys.readouterr().err
    assert len(read_session(tmp_path / "o").streams["fAccelerometer"]) == len(v)


def test_line_numbers_count_the_sep_line(tmp_path, capsys):
    lines = SHIMMER.read_text().splitlines()
    cells = lines[10].split("\t")
    cells[1] = "oops"
    lines[10] = "\t".join(cells)
    p = tmp_path / "bad.csv"
    p.write_text("\n".join(lines) + "\n")
    err = _refused([str(p)], tmp_path / "o", capsys)
    assert "(first at line 11)" in err  # the file's own line, counted with its sep= and units lines


def test_origin_printed_to_the_millisecond(tmp_path, capsys):
    """B68: an origin of 0.0125 s (not an epoch clock) is printed as s with ms, without a date."""
    v = read_session_values()
    df = pd.DataFrame(v, columns=["time_s", "ax", "ay", "az", "gx", "gy", "gz"])
    df["time_s"] += 12.5125
    df[["ax", "ay", "az"]] *= 9.80665
    p = tmp_path / "o.csv"
    df.to_csv(p, index=False)
    assert main(["import", str(p), "--out", str(tmp_path / "o")]) == 0
    assert "0 ms = 12.512 s on the export's clock" in capsys.readouterr().err  # 12.5125 rounds half to even


@pytest.fixture(scope="module")
def walk10(tmp_path_factory) -> Path:
    """A simulated 10 m walk (foot frame x=forward, y=up, z=right) as a plain export."""
    from pdrlearn.sim import simulate

    s = simulate("walk", 1, length_m=10.0)
    a, w = s.streams["fAccelerometer"], s.streams["fGyroscope"]
    p = tmp_path_factory.mktemp("w") / "walk10.csv"
    pd.DataFrame({"time_ms": a.t * 1e3, **{f"acc_{c}": a.values[:, i] for i, c in enumerate("xyz")},
                  **{f"gyr_{c}": w.values[:, i] for i, c in enumerate("xyz")}}).to_csv(p, index=False)
    return p


@pytest.mark.parametrize("frames, off", [("x=forward,y=up,z=left", "left"), ("x=forward,y=down,z=right", "up"),
                                         ("x=up,y=forward,z=right", "up")])
def test_a_declared_frame_the_data_contradict_is_refused(walk10, tmp_path, capsys, frames, off):
    """B67: before, a left-handed --frames the data contradict was written and only warned of at track time
    (a trial tracked 3.33 m of a 10 m walk with it)."""
    err = _refused([str(walk10), "--frames", frames], tmp_path / "o", capsys)
    assert f"--frames {frames} is left-handed and contradicted by the data, which give x=forward,y=up,z=right" in err
    assert f"{off} 1" in err or f"{off} 9" in err  # the direction that is off, with its angle
    assert "nothing written: import again with --frames x=forward,y=up,z=right" in err
    assert "--force-frame" in err
    if off == "left":
        assert "its data are mirrored: negate that axis with --acc/--gyro" in err


def test_right_handed_contradiction_refused_and_force_frame_writes(walk10, tmp_path, capsys):
    err = _refused([str(walk10), "--frames", "x=backward,y=up,z=left"], tmp_path / "o", capsys)
    assert "is contradicted by the data" in err and "left-handed" not in err
    out = tmp_path / "f"
    assert main(["import", str(walk10), "--out", str(out), "--frames", "x=forward,y=up,z=left", "--force-frame"]) == 0
    err = capsys.readouterr().err
    assert ("warning: " + str(out) + ": --frames x=forward,y=up,z=left is left-handed and contradicted by the data "
            "(x=forward,y=up,z=right; left 179 deg off); written as given (--force-frame)") in err
    meta = json.loads((out / "meta.json").read_text())
    assert meta["frames"]["foot"] == {"x": "forward", "y": "up", "z": "left"}
    assert meta["imported"]["frame_forced"]["data"] == {"x": "forward", "y": "up", "z": "right"}


def test_a_truthful_frame_is_written_and_a_left_handed_one_only_with_force_frame(walk10, tmp_path, capsys):
    assert main(["import", str(walk10), "--out", str(tmp_path / "a"), "--frames", FRAME]) == 0
    assert "warning" not in capsys.readouterr().err
    # the 6 m Shimmer walk has too few strides for the inference (D8); a left-handed frame is refused all the same
    # (decision B130: handedness needs no data), --force-frame writes it
    args = ["import", str(SHIMMER), "--frames", "x=forward,y=up,z=left"]
    assert main([*args, "--out", str(tmp_path / "b")]) == 2
    assert "--frames x=forward,y=up,z=left is left-handed" in capsys.readouterr().err
    assert main([*args, "--out", str(tmp_path / "b"), "--force-frame"]) == 0
    capsys.readouterr()
    assert read_session(tmp_path / "b").frames["foot"].to_dict() == {"x": "forward", "y": "up", "z": "left"}


def test_force_frame_without_frames_is_refused(tmp_path, capsys):
    """B69: --force-frame without a frame to keep was silently ignored; now one line naming the fix."""
    err = _refused([str(PLAIN), "--force-frame"], tmp_path / "o", capsys)
    assert err.startswith(f"{PLAIN}: --force-frame keeps a --frames entry the data contradict (B67)")
    assert "add --frames AXES" in err and "drop --force-frame" in err
    # a frame from the --mapping file is one to keep: accepted
    m = tmp_path / "map.json"
    m.write_text(json.dumps({"frames": {"x": "forward", "y": "up", "z": "right"}}))
    assert main(["import", str(PLAIN), "--mapping", str(m), "--force-frame", "--out", str(tmp_path / "m")]) == 0
    assert read_session(tmp_path / "m").frames["foot"].to_dict() == {"x": "forward", "y": "up", "z": "right"}


def test_shimmer_ln_and_wr_accelerometers_are_named_not_dropped_silently(tmp_path, capsys):
    """A Shimmer3 export with both the low-noise (LN) and the wide-range (WR) accelerometer: no set is guessed
    (two candidates per axis), and the import names both sets and which one a foot needs, instead of saying that
    no accelerometer column was recognised; mapping WR with --acc imports it."""
    lines = SHIMMER.read_text().splitlines()
    split = [ln.rstrip("\t").split("\t") for ln in lines[1:]]
    wr = [c.replace("_LN_", "_WR_") for c in split[0][1:4]]
    rows = [split[0][:4] + wr + split[0][4:], split[1][:4] + split[1][1:4] + split[1][4:]]
    rows += [r[:4] + [f"{float(v) + 0.01:.6f}" for v in r[1:4]] + r[4:] for r in split[2:]]
    src = tmp_path / "lnwr.csv"
    src.write_text("\n".join(["sep=;"] + [";".join(r) for r in rows]) + "\n")
    assert main(["import", str(src), "--out", str(tmp_path / "a"), "--frames", FRAME]) == 0
    err = capsys.readouterr().err
    assert "no accelerometer columns recognised" not in err
    assert ("note: several accelerometer column sets (Shimmer_7A1F_Accel_LN_X_CAL, Shimmer_7A1F_Accel_LN_Y_CAL, "
            "Shimmer_7A1F_Accel_LN_Z_CAL, Shimmer_7A1F_Accel_WR_X_CAL, Shimmer_7A1F_Accel_WR_Y_CAL, "
            "Shimmer_7A1F_Accel_WR_Z_CAL): none guessed (Shimmer3: Accel_WR is the wide-range accelerometer") in err
    meta = json.loads((tmp_path / "a" / "meta.json").read_text())
    assert meta["imported"]["ambiguous_columns"]["acc"][3:] == wr
    assert main(["import", str(src), "--out", str(tmp_path / "b"), "--frames", FRAME, "--acc", ",".join(wr)]) == 0
    err = capsys.readouterr().err
    assert "note: several" not in err
    assert f"fAccelerometer: {','.join(wr)} (given) in m/s2 (units row)" in err
    # the plain fixture's names give one set per axis: nothing is said to be ambiguous
    assert main(["import", str(PLAIN), "--out", str(tmp_path / "c"), "--frames", FRAME]) == 0
    capsys.readouterr()
    assert "ambiguous_columns" not in json.loads((tmp_path / "c" / "meta.json").read_text())["imported"]


def test_units_row_hint_counts_every_text_row_and_the_rows_already_skipped(tmp_path, capsys):
    """A row of CAL above the units row: the hint asks for both rows to be skipped (--skip-rows 2), and with
    --skip-rows 1 already given it still asks for 2 (it said --skip-rows 1 again before)."""
    lines = SHIMMER.read_text().splitlines()
    cal = "\t".join(["CAL"] * len(lines[1].rstrip("\t").split("\t")))
    src = tmp_path / "calrow.csv"
    src.write_text("\n".join([lines[0], lines[1], cal, *lines[2:]]) + "\n")
    assert main(["import", str(src), "--out", str(tmp_path / "a")]) != 0
    err = capsys.readouterr().err
    assert ("lines 3-4 (the first: CAL, CAL, CAL, CAL ...) look like units rows or more header rows: pass "
            "--skip-rows 2 to skip them") in err
    assert main(["import", str(src), "--skip-rows", "1", "--out", str(tmp_path / "b")]) != 0
    err = capsys.readouterr().err
    assert "line 4 (ms, m/(s^2), m/(s^2), m/(s^2) ...) looks like a units row or a second header: pass " \
           "--skip-rows 2 to skip it" in err
    assert not (tmp_path / "a").exists() and not (tmp_path / "b").exists()


def test_two_time_like_columns_are_named_and_time_picks_one(tmp_path, capsys):
    """Decision B70: a Shimmer export with Timestamp_Unix and TimestampSync_Unix columns names both instead of
    saying no timestamp column was found; --time picks one and the import goes through."""
    p = tmp_path / "two.csv"
    v = read_session_values()
    rows = ["S_Timestamp_Unix_CAL,S_TimestampSync_Unix_CAL,ax,ay,az,gx,gy,gz"]
    rows += [",".join([f"{r[0] * 1e3:.1f}", f"{r[0] * 1e3 + 5:.1f}", *(f"{x:.5f}" for x in r[1:])]) for r in v]
    p.write_text("\n".join(rows) + "\n")
    err = _refused([str(p)], tmp_path / "o", capsys)
    assert "several columns look like the time: S_Timestamp_Unix_CAL, S_TimestampSync_Unix_CAL" in err
    assert "no timestamp column found" not in err
    assert main(["import", str(p), "--out", str(tmp_path / "o"), "--time", "S_Timestamp_Unix_CAL",
                 "--time-unit", "ms", "--acc-unit", "g"]) == 0
    assert len(read_session(tmp_path / "o").streams["fAccelerometer"]) == len(v)
