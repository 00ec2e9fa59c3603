"""Session model, PLASYS folder reader/writer and input validation."""

from __future__ import annotations

import json
import shutil

import numpy as np
import pandas as pd
import pytest

from pdrlearn.errors import DataError, MissingSensorError
from pdrlearn.io import SENSORS, AxisFrame, Session, Stream, read_session, write_session
from pdrlearn.io.frames import THESIS_FOOT_FRAME


def make_session(n: int = 200, rate: float = 20.0, seed: int = 0) -> Session:
    """A synthetic session with every PLASYS sensor, labels and extras."""
    rng = np.random.default_rng(seed)
    t = np.arange(n) / rate
    typical = {"accelerometer": 9.81, "gyroscope": 0.5, "force": 300.0, "magnetometer": 45.0, "barometer": 1013.0}
    streams = {}
    for name, spec in SENSORS.items():
        base = np.zeros(spec.n_axes)
        base[0] = typical[spec.kind]
        streams[name] = Stream(name, t + 0.0001 * (spec.kind == "barometer"),
                               base + rng.normal(0, 0.1, (n, spec.n_axes)))
    steps = pd.DataFrame({"start_s": [1.0, 2.0], "end_s": [2.0, 3.05], "ic_s": [1.5, 2.5],
                          "terrain": ["flat", "up"], "direction": ["forward", "backward"],
                          "length_m": [0.7, np.nan], "length_class": ["normal", "short"], "duration_s": [1.0, 1.05]})
    traj = pd.DataFrame({"t": t[:10], "x": np.arange(10.0), "y": 0.5, "z": 0.0})
    ics = pd.DataFrame({"ic_s": [1.5, 2.0, 2.5], "foot": ["right", "left", "right"]})
    return Session("synthetic", streams, steps=steps, trajectory=traj, extras={"ics": ics},
                   meta={"user": "u1"}, frames={"foot": THESIS_FOOT_FRAME})


def test_round_trip_every_sensor(tmp_path):
    s = make_session()
    write_session(s, tmp_path / "s")
    r = read_session(tmp_path / "s")
    assert set(r.streams) == set(SENSORS)
    for name in SENSORS:
        assert np.array_equal(r[name].values, s[name].values), name  # values exact (repr precision)
        np.testing.assert_allclose(r[name].t, s[name].t, rtol=0, atol=1e-12)
    pd.testing.assert_frame_equal(r.steps.reset_index(drop=True), s.steps, check_dtype=False)
    pd.testing.assert_frame_equal(r.trajectory, s.trajectory, check_dtype=False)
    pd.testing.assert_frame_equal(r.extras["ics"], s.extras["ics"], check_dtype=False)
    assert r.frames == {"foot": THESIS_FOOT_FRAME}
    assert r.meta["user"] == "u1"
    # on disk: milliseconds, single-valued sensors have only x
    head = (tmp_path / "s" / "wBarometer.csv").read_text().splitlines()[0]
    assert head == "timestamp,x"
    steps_head = (tmp_path / "s" / "steps.csv").read_text().splitlines()[0]
    assert steps_head.startswith("start_ms,end_ms,ic_ms") and "duration_s" in steps_head


def test_second_round_trip_is_stable(tmp_path):
    write_session(make_session(), tmp_path / "a")
    write_session(read_session(tmp_path / "a"), tmp_path / "b")
    for f in (tmp_path / "a").iterdir():
        assert f.read_text() == (tmp_path / "b" / f.name).read_text(), f.name


@pytest.mark.parametrize("name", ["gaitmap_level_left", "gaitmap_stairs_up_left", "mobgap_HA001_Test11_Trial1"])
def test_real_sessions_keep_labels_and_frames(real_dir, tmp_path, name):
    s = read_session(real_dir / name)
    raw_steps = pd.read_csv(real_dir / name / "steps.csv")
    assert len(s.steps) == len(raw_steps)
    # every extra column is kept; *_ms become *_s
    for col in raw_steps.columns:
        assert (col[:-3] + "_s" if col.endswith("_ms") else col) in s.steps.columns
    np.testing.assert_allclose(s.steps["start_s"], raw_steps["start_ms"] / 1000)
    if name.startswith("mobgap"):
        assert {"ics", "bouts", "turns"} <= set(s.extras)
        assert s.frames["waist"] == AxisFrame(x="up", y="right", z="forward")
        assert s["wAccelerometer"].rate_hz == pytest.approx(100.0)
    else:
        assert s.frames["foot"] == AxisFrame(x="forward", y="left", z="up")
        assert s["fAccelerometer"].rate_hz == pytest.approx(204.8)
    write_session(s, tmp_path / name)
    r = read_session(tmp_path / name)
    for k in s.streams:
        assert np.array_equal(r[k].values, s[k].values)
    assert set(r.extras) == set(s.extras)


def test_axis_frame_matrix_is_rotation():
    for f in (THESIS_FOOT_FRAME, AxisFrame("up", "right", "forward"), AxisFrame("forward", "left", "up")):
        m = f.matrix()
        np.testing.assert_allclose(m @ m.T, np.eye(3))
        assert f.right_handed
    # thesis foot: y along gravity at rest -> body up
    np.testing.assert_allclose(THESIS_FOOT_FRAME.matrix() @ [0, 9.81, 0], [0, 0, 9.81])
    with pytest.raises(DataError, match="same direction"):
        AxisFrame("up", "up", "left")
    with pytest.raises(DataError, match="not one of"):
        AxisFrame("north", "up", "left")


def test_require_names_missing_sensor():
    s = make_session()
    del s.streams["fForceA"]
    with pytest.raises(MissingSensorError, match="no fForceA needed by the force step detector"):
        s.require("fForceA", purpose="the force step detector")


def test_summary_contract():
    s = make_session()
    s.streams["fGyroscope"] = Stream("fGyroscope", np.delete(s["fGyroscope"].t, [50, 51, 52]),
                                     np.delete(s["fGyroscope"].values, [50, 51, 52], axis=0))
    d = s.summary()
    assert d["sensors"]["fGyroscope"]["gaps"] == 1
    assert d["sensors"]["fGyroscope"]["longest_gap_s"] == pytest.approx(0.2)
    assert d["sensors"]["fAccelerometer"]["rate_hz"] == pytest.approx(20.0)
    assert d["labels"]["steps"] == 2 and d["labels"]["terrain"] == {"flat": 1, "up": 1}
    json.dumps(d)


# --- bad input ---------------------------------------------------------------------------------

def _folder(tmp_path, text: str, name: str = "fAccelerometer") -> str:
    d = tmp_path / "bad"
    d.mkdir(exist_ok=True)
    (d / f"{name}.csv").write_text(text)
    return str(d)


ACC_OK = "timestamp,x,y,z\n0,0,9.8,0\n50,0,9.8,0.1\n100,0,9.7,0\n"


@pytest.mark.parametrize(
    ("text", "name", "pattern"),
    [
        ("timestamp,x,y\n0,0,9.8\n", "fAccelerometer", r"fAccelerometer.csv: missing column\(s\) z"),
        ("timestamp,x,y,z\n0,0,9.8,0\n50,a,9.8,0\n", "fAccelerometer", "non-numeric, NaN or infinite.*line 3"),
        ("timestamp,x,y,z\n0,0,9.8,0\n50,,9.8,0\n", "fAccelerometer", "non-numeric, NaN"),
        ("timestamp,x,y,z\n0,0,9.8,0\n100,0,9.8,0\n50,0,9.8,0\n", "fAccelerometer", "backwards.*sort the file"),
        ("timestamp,x,y,z\n0,0,9.8,0\n0,0,9.8,0\n50,0,9.8,0\n", "fAccelerometer", "duplicate timestamp"),
        ("timestamp,x,y,z\n", "fAccelerometer", "no samples"),
        ("", "fAccelerometer", "file is empty"),
        ("timestamp,x,y,z\n0,0,1.0,0\n50,0,0.98,0\n", "fAccelerometer", "units of g; multiply by 9.80665"),
        ("timestamp,x,y,z\n0,0,250,0\n50,0,300,0\n", "fAccelerometer", "raw counts"),
        ("timestamp,x,y,z\n0,0,150,0\n50,0,-200,3\n", "fGyroscope", "deg/s: multiply by pi/180"),
        ("timestamp,x\n0,101325\n50,101320\n", "wBarometer", "Pa; divide by 100"),
        ("timestamp,x\n0,101.3\n50,101.3\n", "wBarometer", "kPa"),
        ("timestamp,x,y,z\n0,0.2,0.3,0.1\n50,0.2,0.3,0.1\n", "wMagneticField", "gauss or tesla"),
        ("timestamp,x,y,z\n0,0,9.8,0\n50,0,9.8\n", "fAccelerometer", "non-numeric"),
    ],
)
def test_bad_sensor_files_give_one_line_errors(tmp_path, text, name, pattern):
    d = _folder(tmp_path, text, name)
    with pytest.raises(DataError, match=pattern) as exc:
        read_session(d)
    msg = str(exc.value)
    assert "\n" not in msg and f"{name}.csv" in msg


def test_missing_folder_and_no_sensor_files(tmp_path):
    with pytest.raises(DataError, match="session folder not found"):
        read_session(tmp_path / "nope")
    (tmp_path / "empty").mkdir()
    with pytest.raises(DataError, match="no sensor files found"):
        read_session(tmp_path / "empty")
    (tmp_path / "f.csv").write_text("x")
    with pytest.raises(DataError, match="not a folder"):
        read_session(tmp_path / "f.csv")


def test_bad_meta_and_steps(tmp_path):
    d = _folder(tmp_path, ACC_OK)
    (tmp_path / "bad" / "meta.json").write_text("{oops")
    with pytest.raises(DataError, match="meta.json: invalid JSON"):
        read_session(d)
    (tmp_path / "bad" / "meta.json").write_text("{}")
    (tmp_path / "bad" / "steps.csv").write_text("start_ms,stop\n1,2\n")
    with pytest.raises(DataError, match=r"steps.csv.*missing column\(s\) end_ms"):  # as written, in ms (B222)
        read_session(d)
    (tmp_path / "bad" / "steps.csv").write_text("start_ms,end_ms\n10,5\n")
    with pytest.raises(DataError, match="end before they start"):
        read_session(d)


def test_timestamp_unit_from_meta(tmp_path):
    d = _folder(tmp_path, "timestamp,x,y,z\n0,0,9.8,0\n0.05,0,9.8,0.1\n0.1,0,9.7,0\n")
    (tmp_path / "bad" / "meta.json").write_text(json.dumps({"units": {"timestamp": "s"}}))
    assert read_session(d)["fAccelerometer"].rate_hz == pytest.approx(20.0)


def test_writer_refuses_non_empty_and_leaves_nothing_on_failure(tmp_path):
    s = make_session()
    out = tmp_path / "out"
    out.mkdir()
    (out / "keep.txt").write_text("x")
    with pytest.raises(DataError, match="already exists and is not empty"):
        write_session(s, out)
    assert [p.name for p in out.iterdir()] == ["keep.txt"]
    s.meta["bad"] = object()  # not JSON serialisable -> fails mid-write
    with pytest.raises(TypeError):
        write_session(s, tmp_path / "new")
    assert not (tmp_path / "new").exists()
    assert [p.name for p in tmp_path.iterdir()] == ["out"]  # no temp folder left behind


def test_stream_shape_errors():
    with pytest.raises(DataError, match="3 timestamps but 2 rows"):
        Stream("fAccelerometer", [0, 1, 2], np.zeros((2, 3)))
    with pytest.raises(DataError, match="expected 1 value columns"):
        Stream("wBarometer", [0, 1], np.zeros((2, 3)))


def test_copy_of_real_session_is_independent(real_dir, tmp_path):
    src = tmp_path / "s"
    shutil.copytree(real_dir / "mobgap_HA001_Test5_Trial1", src)
    s = read_session(src)
    c = s.copy()
    c["wAccelerometer"].values[:] = 0
    assert s["wAccelerometer"].values.any()
