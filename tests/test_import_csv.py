"""Decision D12: `pdrlearn import` turns a one-CSV lab export into a session folder (round trips on simulated
and real sessions exported under other column names and units; guesses printed; one-line errors)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session

REAL = Path(__file__).resolve().parents[1] / "datasets" / "real"
G = 9.80665


@pytest.fixture(scope="module")
def sim():
    from pdrlearn.sim import simulate

    return simulate("A", 1)


def _foot_export(s, path: Path) -> Path:
    """The foot unit as a lab's semicolon/decimal-comma export: seconds, g, deg/s, its own column names."""
    a, w = s.streams["fAccelerometer"], s.streams["fGyroscope"]
    df = pd.DataFrame({"Time (s)": a.t, **{"AccX AccY AccZ".split()[i] + " (g)": a.values[:, i] / G for i in range(3)},
                       **{f"Gyro{c} (deg/s)": np.degrees(w.values[:, i]) for i, c in enumerate("XYZ")},
                       "Heel": s.streams["fForceA"].values[:, 0], "Toe": s.streams["fForceB"].values[:, 0],
                       "Battery": 3.7})
    df.to_csv(path, sep=";", decimal=",", index=False)
    return path


def _waist_export(s, path: Path) -> Path:
    a, w, m, b = (s.streams[n] for n in ("wAccelerometer", "wGyroscope", "wMagneticField", "wBarometer"))
    df = pd.DataFrame({"timestamp_ms": a.t * 1e3, **{f"acc_{c}": a.values[:, i] for i, c in enumerate("xyz")},
                       **{f"gyr_{c}": w.values[:, i] for i, c in enumerate("xyz")},
                       **{f"mag_{c}": m.values[:, i] for i, c in enumerate("xyz")}, "pressure": b.values[:, 0]})
    df.loc[1::2, ["mag_x", "mag_y", "mag_z"]] = np.nan  # a slower magnetometer: empty cells between its samples
    df.to_csv(path, index=False)
    return path


def test_simulated_foot_and_waist_round_trip(sim, tmp_path, capsys):
    out = tmp_path / "session"
    csv = _foot_export(sim, tmp_path / "foot.csv")
    assert main(["import", str(csv), "--out", str(out), "--frames", "x=forward,y=up,z=right"]) == 0
    err = capsys.readouterr().err
    assert "time: column 'Time (s)' in s (guessed column, unit header)" in err
    assert "fAccelerometer: AccX (g),AccY (g),AccZ (g) (guessed) in g (header, x 9.80665 to m/s^2)" in err
    assert "fGyroscope: GyroX (deg/s),GyroY (deg/s),GyroZ (deg/s) (guessed) in deg/s" in err
    assert "unused columns: Battery" in err
    assert main(["import", str(_waist_export(sim, tmp_path / "waist.csv")), "--out", str(out), "--unit", "waist",
                 "--merge", "--frames", '{"x": "left", "y": "up", "z": "forward"}', "--sensor-height", "1.05"]) == 0
    err = capsys.readouterr().err
    assert "wMagneticField: mag_x,mag_y,mag_z (guessed) in uT (default)" in err and "empty rows skipped" in err
    got = read_session(out)
    t0 = sim.streams["fAccelerometer"].t[0]
    assert set(got.streams) == set(sim.streams)
    for name, st in sim.streams.items():
        g = got.streams[name]
        step = 2 if name == "wMagneticField" else 1
        np.testing.assert_allclose(g.t, st.t[::step] - t0, rtol=0, atol=1e-9, err_msg=name)
        np.testing.assert_allclose(g.values, st.values[::step], rtol=1e-12, atol=1e-12, err_msg=name)
    assert {p: f.to_dict() for p, f in got.frames.items()} == {p: f.to_dict() for p, f in sim.frames.items()}
    assert got.meta["sensor_height_m"] == 1.05 and len(got.meta["imported"]) == 2
    assert main(["info", str(out), "--json"]) == 0
    info = json.loads(capsys.readouterr().out)
    assert set(info["sensors"]) == set(sim.streams)


def test_real_session_round_trip_tab_separated_with_options(tmp_path, capsys):
    src = REAL / "gaitmap_level_left"
    if not src.is_dir():
        pytest.skip("datasets/real/gaitmap_level_left not present")
    s = read_session(src)
    a, w = s.streams["fAccelerometer"], s.streams["fGyroscope"]
    assert np.array_equal(a.t, w.t)
    clock_us = 1.7e15  # the lab's clock: epoch microseconds
    df = pd.DataFrame({"t_us": np.round(a.t * 1e6) + clock_us, "A1": a.values[:, 0], "A2": a.values[:, 1],
                       "A3": a.values[:, 2], "W1": w.values[:, 0], "W2": w.values[:, 1], "W3": w.values[:, 2]})
    csv = tmp_path / "export.tsv"
    df.to_csv(csv, sep="\t", index=False)
    frame = s.frames["foot"].to_dict()
    labels = pd.read_csv(src / "steps.csv")  # the labels on the lab's clock, in ms
    for c in [c for c in labels.columns if c.endswith("_ms")]:
        labels[c] = labels[c] + clock_us * 1e-3 - 1e-3 * np.round(a.t[0] * 1e6)
    labels.to_csv(tmp_path / "labels.csv", index=False)
    out = tmp_path / "imported"
    assert main(["import", str(csv), "--out", str(out), "--time", "t_us", "--acc", "A1,A2,A3", "--gyro", "W1,W2,W3",
                 "--frames", json.dumps(frame), "--steps", str(tmp_path / "labels.csv")]) == 0
    err = capsys.readouterr().err
    assert "time: column 't_us' in us (given column, unit header)" in err  # the _us suffix (trial 2, 14)
    assert f"steps: {len(labels)} labelled steps from labels.csv" in err
    got = read_session(out)
    np.testing.assert_allclose(got.steps["start_s"], s.steps["start_s"] - s.t_start, atol=1e-6)
    assert list(got.steps["terrain"]) == list(s.steps["terrain"])
    np.testing.assert_allclose(got.streams["fAccelerometer"].values, a.values, rtol=0, atol=0)
    np.testing.assert_allclose(got.streams["fGyroscope"].t, np.round(a.t * 1e6) * 1e-6 - np.round(a.t[0] * 1e6) * 1e-6,
                               atol=1e-9)
    assert got.frames["foot"].to_dict() == frame
    assert main(["info", str(out)]) == 0
    assert main(["track", "--no-plot", str(out), "--out", str(tmp_path / "trk"), "--json"]) == 0
    res = json.loads(capsys.readouterr().out.splitlines()[-1])
    assert res["n_steps"] > 20


def test_mapping_file_and_sample_index_time(tmp_path, capsys):
    """A mapping JSON; sample-index timestamps (0, 1, 2 ...) fit ms and s: refused without a unit or a rate
    (decision B39; before: read as ms and said so, which trial 12 followed to 6 steps for 146), --rate and
    --time-unit say what they are (new-user trial 4: an index read as ms without a word)."""
    n = 400
    rng = np.random.default_rng(0)
    df = pd.DataFrame({"sample": np.arange(n), "a_x": rng.normal(0, 1, n), "a_y": rng.normal(9.8, 1, n),
                       "a_z": rng.normal(0, 1, n), "r_x": rng.normal(0, 1, n), "r_y": rng.normal(0, 1, n),
                       "r_z": rng.normal(0, 1, n)})
    csv = tmp_path / "x.csv"
    df.to_csv(csv, index=False)
    mp = tmp_path / "map.json"
    mp.write_text(json.dumps({"time": "sample", "acc": ["a_x", "a_y", "a_z"], "gyro": ["r_x", "r_y", "r_z"]}))
    assert main(["import", str(csv), "--out", str(tmp_path / "a"), "--mapping", str(mp)]) != 0
    err = _err(capsys)
    # decision B439: a column named as sample numbers asks for the rate only
    assert "column 'sample' holds sample numbers (0-399, step 1)" in err and "--rate HZ" in err
    assert main(["import", str(csv), "--out", str(tmp_path / "a"), "--mapping", str(mp), "--rate", "50"]) == 0
    assert read_session(tmp_path / "a").streams["fAccelerometer"].rate_hz == pytest.approx(50.0)
    assert "in samples (given column, unit sample numbers at 50 Hz (given with --rate))" in capsys.readouterr().err
    # decision B144: read as s they are a 1 Hz accelerometer, under an IMU's 10 Hz floor: refused, nothing written
    assert main(["import", str(csv), "--out", str(tmp_path / "b"), "--mapping", str(mp), "--time-unit", "s"]) != 0
    assert "read as s (given with --time-unit) give 1 Hz" in _err(capsys) and not (tmp_path / "b").exists()
    mp.write_text(json.dumps({"acc": ["a_x", "a_y", "a_z"], "units": {"time": "s"}, "sampling": 1}))
    assert main(["import", str(csv), "--out", str(tmp_path / "c"), "--mapping", str(mp)]) != 0
    assert "unknown key(s) sampling" in capsys.readouterr().err


def _err(capsys) -> str:
    err = capsys.readouterr().err.strip()
    assert err.startswith("error: ") and "\n" not in err, err
    return err


def test_errors_are_one_line_and_name_the_columns(sim, tmp_path, capsys):
    csv = _foot_export(sim, tmp_path / "foot.csv")
    out = tmp_path / "s"
    assert main(["import", str(csv), "--out", str(out), "--acc", "AccX (g),AccY (g),nope"]) != 0
    err = _err(capsys)
    assert "no column 'nope' for acc" in err and "Time (s), AccX (g)" in err and "Battery" in err
    assert main(["import", str(csv), "--out", str(out), "--acc", "AccX (g),AccY (g)"]) != 0
    assert "acc needs 3 column name(s)" in _err(capsys)
    plain = tmp_path / "plain.csv"
    pd.DataFrame({"time": [0, 10, 20, 30], "u": [1, 2, 3, 4], "v": [1, 2, 3, 4]}).to_csv(plain, index=False)
    assert main(["import", str(plain), "--out", str(out)]) != 0
    err = _err(capsys)
    assert "no accelerometer/gyroscope columns recognised among: time, u, v" in err and "--acc X,Y,Z" in err
    notime = tmp_path / "notime.csv"
    pd.DataFrame({"ax": [1.0] * 4, "ay": [9.8] * 4, "az": [0.0] * 4}).to_csv(notime, index=False)
    assert main(["import", str(notime), "--out", str(out)]) != 0
    assert "no timestamp column found among: ax, ay, az; name it with --time COLUMN" in _err(capsys)
    # values in g declared as m/s^2: the unit check's message plus the option that says the unit
    assert main(["import", str(csv), "--out", str(out), "--acc-unit", "m/s2"]) != 0
    assert "looks like units of g" in (e := _err(capsys)) and "--acc-unit (m/s2 | g | mg)" in e
    assert main(["import", str(csv), "--out", str(out), "--unit", "waist", "--heel", "Heel"]) != 0
    assert "the waist unit has no heel sensor" in _err(capsys)
    assert not out.exists()


def test_output_safety_and_merge_errors(sim, tmp_path, capsys):
    csv = _foot_export(sim, tmp_path / "foot.csv")
    out = tmp_path / "s"
    assert main(["import", str(csv), "--out", str(out)]) == 0
    capsys.readouterr()
    assert main(["import", str(csv), "--out", str(out)]) != 0
    assert "already holds an imported session; pass --force" in _err(capsys)
    assert main(["import", str(csv), "--out", str(out), "--force"]) == 0
    assert "foot unit replaced" in capsys.readouterr().err
    assert main(["import", str(csv), "--out", str(out), "--merge"]) != 0
    assert "already has fAccelerometer, fForceA, fForceB, fGyroscope; --merge adds the other unit" in _err(capsys)
    other = tmp_path / "recorded"
    other.mkdir()
    (other / "notes.txt").write_text("mine")
    assert main(["import", str(csv), "--out", str(other)]) != 0
    assert "is not a session 'pdrlearn import' wrote" in _err(capsys)
    assert main(["import", str(csv), "--out", str(other), "--force"]) != 0
    _err(capsys)
    assert (other / "notes.txt").read_text() == "mine"
    assert main(["import", str(csv), "--out", str(tmp_path)]) != 0  # the input's own folder
    assert "holds the input" in _err(capsys)
    (out / "notes.txt").write_text("mine")
    wcsv = _waist_export(sim, tmp_path / "waist.csv")
    assert main(["import", str(wcsv), "--out", str(out), "--unit", "waist", "--merge"]) != 0
    assert "holds notes.txt, which a session rewrite would drop" in _err(capsys)
    assert main(["import", str(wcsv), "--out", str(tmp_path / "absent"), "--unit", "waist", "--merge"]) != 0
    assert "no such session folder to --merge into" in _err(capsys)


def test_column_guesses():
    from pdrlearn.io.importer import guess_columns, guess_time_column

    cols = ["Time (ms)", "Accelerometer X", "Accelerometer Y", "Accelerometer Z", "gx", "gy", "gz",
            "FreeAccX", "FreeAccY", "FreeAccZ", "mag_x", "mag_y", "mag_z", "Pressure (hPa)"]
    g = guess_columns(cols)
    assert g == {"acc": cols[1:4], "gyro": ["gx", "gy", "gz"], "mag": ["mag_x", "mag_y", "mag_z"],
                 "baro": ["Pressure (hPa)"]}  # a gravity-free "FreeAcc" is never taken for the accelerometer
    assert guess_time_column(cols) == "Time (ms)"
    assert guess_time_column(["t", "time"]) is None  # two candidates: asked for, not guessed
    assert guess_columns(["AccX", "AccY"]) == {}  # an incomplete set is not guessed
    assert math.isclose(__import__("pdrlearn.io.importer", fromlist=["UNITS"]).UNITS["gyro"]["deg/s"],
                        math.pi / 180)


def test_date_time_texts_and_waist_units(tmp_path, capsys):
    """ISO date-time texts in the time column; a waist phone export in g and deg/s given by option."""
    t = pd.date_range("2026-12-02T10:00:00", periods=600, freq="20ms", tz="UTC")
    rng = np.random.default_rng(1)
    df = pd.DataFrame({"datetime": t.strftime("%Y-%m-%dT%H:%M:%S.%fZ"), "AccelX": rng.normal(0, .1, 600),
                       "AccelY": rng.normal(-1, .1, 600), "AccelZ": rng.normal(0, .1, 600),
                       "GyrX": rng.normal(0, 20, 600), "GyrY": rng.normal(0, 20, 600), "GyrZ": rng.normal(0, 20, 600)})
    csv = tmp_path / "phone.csv"
    df.to_csv(csv, index=False)
    out = tmp_path / "w"
    assert main(["import", str(csv), "--out", str(out), "--unit", "waist", "--time", "datetime", "--acc-unit", "g",
                 "--gyro-unit", "deg/s"]) == 0
    err = capsys.readouterr().err
    assert "in s (given column, unit date-time text)" in err and "in g (given, x 9.80665" in err
    assert "note: no" not in err
    df.drop(columns=["GyrX", "GyrY", "GyrZ"]).to_csv(csv, index=False)
    assert main(["import", str(csv), "--out", str(tmp_path / "w2"), "--unit", "waist", "--acc-unit", "g"]) == 0
    assert "note: no gyroscope columns recognised; the pipelines need one: map them with --gyro X,Y,Z" in \
        capsys.readouterr().err
    s = read_session(out)
    assert s.streams["wAccelerometer"].rate_hz == pytest.approx(50.0)
    np.testing.assert_allclose(s.streams["wGyroscope"].values, np.radians(df[["GyrX", "GyrY", "GyrZ"]].to_numpy()),
                               rtol=1e-12)


def test_a_folder_with_an_export_says_to_import_it(sim, tmp_path, capsys):
    """New-user trial 14: `info raw/` said only "no sensor files found"."""
    raw = tmp_path / "raw"
    raw.mkdir()
    _foot_export(sim, raw / "labx_export.csv")
    pd.DataFrame({"start_ms": [0, 1000], "end_ms": [1000, 2000]}).to_csv(raw / "labels_steps.csv", index=False)
    assert main(["info", str(raw)]) != 0
    err = _err(capsys)
    assert "no sensor files found" in err and f"`pdrlearn import {raw / 'labx_export.csv'} --out SESSION`" in err
    (raw / "labx_export.csv").unlink()
    assert main(["info", str(raw)]) != 0
    assert "pdrlearn import" not in _err(capsys)  # a label table is no export


def test_conflicting_unit_hints_are_an_error_not_si(sim, tmp_path, capsys):
    """Review s11: 'AccX (g), AccY (m/s^2), AccZ (g)' fell back to m/s2 for all three ('default'), silently
    leaving x and z in g; hints that disagree within one sensor's columns are a one-line error naming them."""
    a, w = sim.streams["fAccelerometer"], sim.streams["fGyroscope"]
    df = pd.DataFrame({"Time (s)": a.t, "AccX (g)": a.values[:, 0] / G, "AccY (m/s^2)": a.values[:, 1],
                       "AccZ (g)": a.values[:, 2] / G, **{f"Gyro{c}": w.values[:, i] for i, c in enumerate("XYZ")}})
    df.to_csv(tmp_path / "mixed.csv", index=False)
    assert main(["import", str(tmp_path / "mixed.csv"), "--out", str(tmp_path / "s")]) != 0
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "g, m/s2" in err and "--acc-unit" in err, err
    assert not (tmp_path / "s").exists()


def test_merge_into_a_session_not_imported_says_the_unit_was_shifted(sim, tmp_path, capsys):
    """Review s11: --merge into a recorded (not imported) session moved the added unit to start at 0 ms, but
    the note said 'the units' clocks are as recorded'."""
    from pdrlearn.io import write_session

    base = tmp_path / "s"
    write_session(sim, base)
    for n in ("wAccelerometer", "wGyroscope", "wMagneticField", "wBarometer"):
        (base / f"{n}.csv").unlink()
    a, w = sim.streams["wAccelerometer"], sim.streams["wGyroscope"]
    pd.DataFrame({"timestamp": 1e3 * a.t + 500.0, **{f"acc_{c}": a.values[:, i] for i, c in enumerate("xyz")},
                  **{f"gyr_{c}": w.values[:, i] for i, c in enumerate("xyz")}}).to_csv(tmp_path / "w.csv", index=False)
    assert main(["import", str(tmp_path / "w.csv"), "--out", str(base), "--unit", "waist", "--merge"]) == 0
    note = [ln for ln in capsys.readouterr().err.splitlines() if ln.startswith("note: the session was not imported")]
    assert len(note) == 1 and "as recorded" not in note[0] and "starts at 0 ms" in note[0], note
    assert read_session(base).streams["wAccelerometer"].t[0] == 0.0  # what the note says


def test_lower_back_labels_are_shifted_like_the_steps_and_score_the_track(tmp_path, capsys):
    """Second new-user trial, finding 3: ``--labels`` copies a lower-back export's extra label tables (ics.csv,
    bouts.csv, turns.csv, ms on the export's clock) into the session, shifted as ``--steps`` is, so ``track``
    scores the waist steps against the contacts and bouts (``--steps`` alone: step_f1 null)."""
    src = REAL / "mobgap_HA001_Test5_Trial1"
    if not src.is_dir():
        pytest.skip(f"{src} not present")
    s = read_session(src)
    a, w = s.streams["wAccelerometer"], s.streams["wGyroscope"]
    clock_s = 5000.0  # the lab's clock: the export starts at 5000 s
    df = pd.DataFrame({"time_ms": np.round((a.t + clock_s) * 1e3, 3),
                       **{f"acc_{c}": a.values[:, i] for i, c in enumerate("xyz")},
                       **{f"gyr_{c}": np.interp(a.t, w.t, w.values[:, i]) for i, c in enumerate("xyz")}})
    df.to_csv(tmp_path / "lowback.csv", index=False)
    origin_ms = float(df["time_ms"].iloc[0])
    files = []
    for name in ("steps", "ics", "bouts", "turns"):
        t = pd.read_csv(src / f"{name}.csv")
        for c in [c for c in t.columns if c.endswith("_ms")]:
            t[c] = t[c] + clock_s * 1e3
        t.to_csv(tmp_path / f"{name}.csv", index=False)
        files.append(tmp_path / f"{name}.csv")
    out = tmp_path / "lb"
    frame = json.dumps(s.frames["waist"].to_dict())
    args = ["import", str(tmp_path / "lowback.csv"), "--out", str(out), "--unit", "waist", "--frames", frame,
            "--steps", str(files[0])]
    assert main([*args, *(x for f in files[1:] for x in ("--labels", str(f)))]) == 0
    err = capsys.readouterr().err
    assert "labels: ics.csv with" in err and "labels: bouts.csv with" in err and "labels: turns.csv with" in err
    got = read_session(out)
    shift = origin_ms * 1e-3 - clock_s - s.t_start  # what the import takes off the source's clock (s)
    for name in ("ics", "bouts", "turns"):
        assert list(got.extras[name].columns) == list(s.extras[name].columns)
        for c in [c for c in s.extras[name].columns if c.endswith("_s") and c != "duration_s"]:
            np.testing.assert_allclose(got.extras[name][c], s.extras[name][c] - s.t_start - shift, atol=1e-6)
    assert main(["track", "--no-plot", str(out), "--out", str(tmp_path / "trk"), "--json"]) == 0
    res = json.loads(capsys.readouterr().out.splitlines()[-1])
    assert res["step_f1"] is not None and res["step_f1"] > 0.8
    assert res["distance_ref_source"].startswith("bouts.csv")
    # the label tables are import's own files: --force replaces them (hand-copied ones it refuses to delete)
    assert main([*args, "--force", *(x for f in files[1:] for x in ("--labels", str(f)))]) == 0
    capsys.readouterr()
    # bad label files: one line naming the file and the fix
    assert main([*args, "--force", "--labels", str(files[0])]) == 2
    assert "pass labelled steps with --steps" in _err(capsys)
    assert main([*args, "--force", "--labels", str(files[1]), "--labels", str(files[1])]) == 2
    assert "already has ics.csv" in _err(capsys)
    pd.DataFrame({"ic_s": [1.0, 2.0]}).to_csv(tmp_path / "sec.csv", index=False)
    assert main([*args, "--force", "--labels", str(tmp_path / "sec.csv")]) == 2
    assert "no *_ms time column" in _err(capsys)


def test_merge_keeps_the_added_units_labels(sim, tmp_path, capsys):
    """``--merge --labels``: the label tables come with the added unit (merge_sessions dropped them)."""
    out = tmp_path / "session"
    assert main(["import", str(_foot_export(sim, tmp_path / "foot.csv")), "--out", str(out)]) == 0
    ic = np.round(sim.steps["start_s"].to_numpy() * 1e3, 3)
    pd.DataFrame({"ic_ms": ic}).to_csv(tmp_path / "ics.csv", index=False)
    args = ["import", str(_waist_export(sim, tmp_path / "waist.csv")), "--out", str(out), "--unit", "waist", "--merge"]
    assert main([*args, "--labels", str(tmp_path / "ics.csv")]) == 0
    got = read_session(out)
    np.testing.assert_allclose(got.extras["ics"]["ic_s"], ic * 1e-3 - sim.t_start, atol=1e-6)


def test_merge_warns_once_when_the_units_time_spans_hardly_overlap(sim, tmp_path, capsys):
    """Second new-user trial, finding 11: a 137.6 s lower-back export merged into a 38.7 s foot session gave
    rc 0 and no word; spans sharing less than half of the longer one now warn (decision D12), naming both."""
    foot = _foot_export(sim, tmp_path / "foot.csv")
    waist = pd.read_csv(_waist_export(sim, tmp_path / "waist.csv"))
    t = waist["timestamp_ms"].to_numpy()
    waist[t - t[0] <= 0.3 * (t[-1] - t[0])].to_csv(tmp_path / "short.csv", index=False)  # 30 % of the walk
    for name, warned in (("waist.csv", False), ("short.csv", True)):
        out = tmp_path / name.split(".")[0]
        assert main(["import", str(foot), "--out", str(out)]) == 0
        capsys.readouterr()
        assert main(["import", str(tmp_path / name), "--out", str(out), "--unit", "waist", "--merge"]) == 0
        warn = [ln for ln in capsys.readouterr().err.splitlines() if ln.startswith("warning: ")]
        assert len(warn) == int(warned), warn
    span = sim.streams["fAccelerometer"].t[-1] - sim.streams["fAccelerometer"].t[0]
    assert f"the session's fAccelerometer, fForceA, fForceB, fGyroscope span 0.0-{span:.1f} s" in warn[0], warn
    assert "the added waist unit spans 0.0-" in warn[0] and "under half of the longer" in warn[0]
    assert "`pdrlearn track --align-units`" in warn[0] and str(tmp_path / "short") in warn[0]  # decision L162
