"""Decisions B115 / B116: per-unit sampling rates and clock offsets in meta.json ``"clocks"``; a sample counter on
one unit only needs that unit's clock."""

from __future__ import annotations

import json
import shutil

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session, write_session

OFFSET_S = 0.5


@pytest.fixture(scope="module")
def sessions(tmp_path_factory):
    """A simulated 50 Hz session and its copy as the curator has it: foot timestamps a sample counter (0, 1, 2
    ...), waist decimated to 25 Hz on a clock reading OFFSET_S s behind the foot's."""
    root = tmp_path_factory.mktemp("clocks")
    orig = root / "orig"
    assert main(["simulate", "--scenario", "terrain", "--user-seed", "3", "--rate", "50", "--out", str(orig),
                 "--json"]) == 0
    units = root / "units"
    shutil.copytree(orig, units)
    for f in units.glob("f*.csv"):
        d = pd.read_csv(f)
        d["timestamp"] = np.arange(len(d))
        d.to_csv(f, index=False)
    for f in units.glob("w*.csv"):
        d = pd.read_csv(f).iloc[::2].copy()
        d["timestamp"] = d["timestamp"] - 1000 * OFFSET_S
        d.to_csv(f, index=False)
    meta = json.loads((units / "meta.json").read_text())
    meta.pop("rate_hz", None)
    meta["clocks"] = {"foot": {"rate_hz": 50, "timestamp": "samples"}, "waist": {"clock_offset_s": OFFSET_S}}
    (units / "meta.json").write_text(json.dumps(meta))
    return orig, units


def _set_meta(folder, **changes):
    meta = json.loads((folder / "meta.json").read_text())
    for k, v in changes.items():
        if v is None:
            meta.pop(k, None)
        else:
            meta[k] = v
    (folder / "meta.json").write_text(json.dumps(meta))


def _info_error(units, folder, capsys, **changes) -> list[str]:
    """``pdrlearn info`` on a copy of ``units`` with meta.json changed: it must exit 2; its stderr lines."""
    shutil.copytree(units, folder)
    _set_meta(folder, **changes)
    assert main(["info", str(folder)]) == 2
    return capsys.readouterr().err.strip().splitlines()


def test_per_unit_rate_and_offset_put_both_units_on_the_session_clock(sessions):
    orig, units = sessions
    a, b = read_session(orig), read_session(units)
    for name, st in b.streams.items():
        ref = a.streams[name].t if name.startswith("f") else a.streams[name].t[::2]
        assert np.allclose(st.t, ref, atol=1e-9), name
    assert b.streams["fAccelerometer"].rate_hz == pytest.approx(50.0)
    assert b.streams["wAccelerometer"].rate_hz == pytest.approx(25.0)


def test_an_undeclared_counter_is_read_at_its_units_rate(sessions, tmp_path):
    """No timestamp unit declared anywhere: the foot counter is read as samples at clocks.foot.rate_hz (B31 per
    unit), the waist's ms as ms."""
    orig, units = sessions
    c = tmp_path / "c"
    shutil.copytree(units, c)
    meta = json.loads((c / "meta.json").read_text())
    meta["units"].pop("timestamp", None)
    meta["clocks"]["foot"].pop("timestamp")
    (c / "meta.json").write_text(json.dumps(meta))
    b = read_session(c)
    assert np.allclose(b.streams["fGyroscope"].t, read_session(orig).streams["fGyroscope"].t, atol=1e-9)


def test_track_of_the_curators_copy_is_the_original_track(sessions, tmp_path, capsys):
    orig, units = sessions
    got = []
    for s in (orig, units):
        assert main(["track", "--no-plot", str(s), "--out", str(tmp_path / s.name), "--json"]) == 0
        got.append(json.loads(capsys.readouterr().out))
    assert got[1]["n_steps"] == got[0]["n_steps"]
    assert got[1]["distance_m"] == pytest.approx(got[0]["distance_m"], rel=1e-3)


@pytest.mark.parametrize("clocks, words", [
    ({"foot": {"rate_hz": -50, "timestamp": "samples"}}, "clocks.foot.rate_hz -50 is not a positive number of Hz"),
    ({"foot": {"rate_hz": 50, "timestamp": "samples"}, "waist": {"clock_offset_s": 5000}},
     "clocks.waist.clock_offset_s 5000 s is longer than the waist unit's recording"),
    ({"foot": {"rate_hz": 50, "timestamp": "samples"}, "hip": {"rate_hz": 20}}, "clocks.hip: unknown unit"),
    ({"foot": {"rate": 50}}, "clocks.foot.rate: unknown field"),
    ({"waist": {"clock_offset_s": "0.5 s"}}, "is not a number of seconds"),
])
def test_bad_clocks_are_one_line_naming_meta_json(sessions, tmp_path, capsys, clocks, words):
    err = _info_error(sessions[1], tmp_path / "bad", capsys, clocks=clocks)
    assert len(err) == 1 and "meta.json" in err[0] and words in err[0], err


def test_per_unit_clocks_under_units_are_refused_naming_clocks(sessions, tmp_path, capsys):
    _, units = sessions
    c = tmp_path / "misplaced"
    shutil.copytree(units, c)
    meta = json.loads((c / "meta.json").read_text())
    meta["units"]["foot"] = meta.pop("clocks")["foot"]
    (c / "meta.json").write_text(json.dumps(meta))
    assert main(["info", str(c)]) == 2
    err = capsys.readouterr().err
    assert "\"units\" holds the files' measurement units" in err and "\"clocks\"" in err


def test_a_counter_on_one_unit_without_its_clock_is_refused(sessions, tmp_path, capsys):
    """B116: read as ms, the 50 Hz foot counter made the foot recording 20 times too short, silently."""
    err = _info_error(sessions[1], tmp_path / "mixed", capsys, clocks=None)
    assert len(err) == 1 and "the foot unit's timestamps are consecutive integers" in err[0]
    assert "\"clocks\": {\"foot\": {\"rate_hz\": <Hz>" in err[0]


def test_a_session_written_back_is_not_shifted_twice(sessions, tmp_path):
    """write_session writes the times on the session's clock in ms and drops "clocks" (import --merge does so)."""
    _, units = sessions
    b = read_session(units)
    write_session(b, tmp_path / "w")
    assert "clocks" not in json.loads((tmp_path / "w" / "meta.json").read_text())
    c = read_session(tmp_path / "w")
    for name, st in b.streams.items():
        assert np.allclose(c.streams[name].t, st.t, atol=1e-9), name


def test_with_clocks_trajectory_csv_follows_the_sensor_files_unit(sessions, tmp_path, capsys):
    """B115 amended (review): every file in s with no declared unit (B22 infers s on each unit) and "clocks": the
    trajectory is read in s too, as without clocks (B25); when the units' files were read in different units
    and none is declared, a trajectory that does not fit the default ms is refused naming "clocks"."""
    orig, units = sessions
    c = tmp_path / "s"
    shutil.copytree(orig, c)
    for f in [*c.glob("[fw]*.csv"), c / "trajectory.csv"]:
        if f.stem != "foot_trajectory":
            d = pd.read_csv(f)
            d["timestamp"] = d["timestamp"] / 1000.0
            d.to_csv(f, index=False)
    meta = json.loads((c / "meta.json").read_text())
    meta.get("units", {}).pop("timestamp", None)
    meta.pop("rate_hz", None)
    meta["clocks"] = {"foot": {"rate_hz": 50}}
    (c / "meta.json").write_text(json.dumps(meta))
    got, want = read_session(c).trajectory, read_session(orig).trajectory
    assert np.allclose(got["t"], want["t"], atol=1e-9)
    m = tmp_path / "mixed"  # foot counting samples, waist in ms: the trajectory in s fits neither
    shutil.copytree(units, m)
    d = pd.read_csv(m / "trajectory.csv")
    d["timestamp"] = d["timestamp"] / 1000.0
    d.to_csv(m / "trajectory.csv", index=False)
    _set_meta(m, units={k: v for k, v in json.loads((m / "meta.json").read_text())["units"].items()
                        if k != "timestamp"})
    assert main(["info", str(m)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "trajectory.csv" in err[0] and "\"clocks\"" in err[0], err


def test_a_session_wide_rate_beside_unit_clocks_is_not_written_back(sessions, tmp_path):
    """B115 amended (review): foot at 50 Hz by its clock, "rate_hz": 25 for the waist; the written copy (in ms)
    kept rate_hz 25, which its 50 Hz foot then contradicted on re-reading."""
    _, units = sessions
    c = tmp_path / "c"
    shutil.copytree(units, c)
    _set_meta(c, rate_hz=25)
    b = read_session(c)
    write_session(b, tmp_path / "w")
    assert "rate_hz" not in json.loads((tmp_path / "w" / "meta.json").read_text())
    again = read_session(tmp_path / "w")
    assert again.streams["fAccelerometer"].rate_hz == pytest.approx(50.0)
    assert again.streams["wAccelerometer"].rate_hz == pytest.approx(25.0)


def test_a_declared_1000_hz_ms_clock_on_one_unit_is_not_refused(sessions, tmp_path, capsys):
    """B116 amended (review): "units": {"timestamp": "ms"} with "rate_hz": 1000 says that consecutive integers are
    ms at 1000 Hz: the foot's are read so (as before B116), with B32's warning for the 25 Hz waist, not refused."""
    _, units = sessions
    c = tmp_path / "ms1000"
    shutil.copytree(units, c)
    meta = json.loads((c / "meta.json").read_text())
    meta.pop("clocks")
    meta["units"]["timestamp"] = "ms"
    meta["rate_hz"] = 1000
    (c / "meta.json").write_text(json.dumps(meta))
    s = read_session(c)
    assert s.streams["fAccelerometer"].rate_hz == pytest.approx(1000.0)
    assert s.streams["wAccelerometer"].rate_hz == pytest.approx(25.0)
    meta["rate_hz"] = 100  # a 100 Hz counter declared as ms is still refused naming the unit's clock
    (c / "meta.json").write_text(json.dumps(meta))
    assert main(["info", str(c)]) == 2
    assert "the foot unit's timestamps are consecutive integers" in capsys.readouterr().err
