"""meta.json fields that are present but malformed: one ``error:`` line naming meta.json and the fix, never a
traceback and never silently ignored (decisions B60, B61 in docs/decisions/bad-input.md; the other cases pin
existing messages that no test reached, docs/testing.md)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import read_session


@pytest.fixture(scope="module")
def session_dir(tmp_path_factory) -> Path:
    """A 10 s foot unit at 100 Hz (standing, a little noise), written as a session folder with a meta.json."""
    d = tmp_path_factory.mktemp("meta") / "s"
    d.mkdir()
    rng = np.random.default_rng(0)
    t = np.arange(1000) * 10.0
    acc = np.column_stack([rng.normal(0, 0.1, t.size), 9.81 + rng.normal(0, 0.1, t.size), rng.normal(0, 0.1, t.size)])
    gyr = rng.normal(0, 0.01, (t.size, 3))
    for name, v in (("fAccelerometer", acc), ("fGyroscope", gyr)):
        pd.DataFrame({"timestamp": t, "x": v[:, 0], "y": v[:, 1], "z": v[:, 2]}).to_csv(d / f"{name}.csv", index=False)
    (d / "meta.json").write_text(json.dumps({"session": "s", "frames": {"foot": {"x": "forward", "y": "up",
                                                                                   "z": "right"}}}))
    return d


def _with_meta(src: Path, dst: Path, change) -> Path:
    dst.mkdir()
    for f in src.iterdir():
        (dst / f.name).write_bytes(f.read_bytes())
    meta = json.loads((src / "meta.json").read_text())
    change(meta)
    (dst / "meta.json").write_text(json.dumps(meta))
    return dst


def _error(d: Path, capsys) -> str:
    assert main(["info", str(d)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and err.startswith("error: "), err
    return err


def test_a_valid_frames_entry_is_read(session_dir):
    assert read_session(session_dir).frames["foot"].to_dict() == {"x": "forward", "y": "up", "z": "right"}


@pytest.mark.parametrize("frames", [
    {"x": "forward", "y": "up", "z": "right"},  # the placement level left out
    {"foot": "x=forward,y=up,z=right"},  # the --frames option's text form
    {"foot": ["forward", "up", "right"]},
], ids=["no-placement", "text-value", "list-value"])
def test_a_frame_that_is_not_an_object_is_one_line(session_dir, tmp_path, capsys, frames):
    """Decision B60: these raised ``TypeError: string indices must be integers`` (a traceback)."""
    d = _with_meta(session_dir, tmp_path / "s", lambda m: m.update(frames=frames))
    err = _error(d, capsys)
    assert "meta.json" in err and '"frames"' in err
    assert '{"foot": {"x": "forward", "y": "up", "z": "right"}}' in err  # the form to write


@pytest.mark.parametrize("frames", ["x=forward,y=up,z=right", ["foot"]], ids=["text", "list"])
def test_a_frames_entry_that_is_not_an_object_is_refused(session_dir, tmp_path, capsys, frames):
    """Decision B61: a "frames" entry that is not an object was ignored, and the unit's frame silently
    inferred from the data instead of the one the user declared."""
    d = _with_meta(session_dir, tmp_path / "s", lambda m: m.update(frames=frames))
    err = _error(d, capsys)
    assert "meta.json" in err and '"frames" must be an object' in err


def test_a_frame_for_an_unknown_unit_is_refused(session_dir, tmp_path, capsys):
    """Decision B61: "Foot" (or "hand") was kept in Session.frames but never used: the foot unit read as
    declaring no frame."""
    d = _with_meta(session_dir, tmp_path / "s",
                   lambda m: m.update(frames={"Foot": {"x": "forward", "y": "up", "z": "right"}}))
    err = _error(d, capsys)
    assert "meta.json" in err and "'Foot'" in err and "foot or waist" in err


def test_units_must_be_an_object(session_dir, tmp_path, capsys):
    d = _with_meta(session_dir, tmp_path / "s", lambda m: m.update(units=["ms"]))
    assert '"units" must be an object such as {"timestamp": "ms"}' in _error(d, capsys)


def test_sample_index_timestamps_need_the_rate(session_dir, tmp_path, capsys):
    d = _with_meta(session_dir, tmp_path / "s", lambda m: m.update(units={"timestamp": "samples"}))
    err = _error(d, capsys)
    assert "units.timestamp 'samples' (sample indices) needs the sampling rate" in err and '"rate_hz"' in err


@pytest.mark.parametrize("rate", [True, -5, "100"])
def test_rate_hz_must_be_a_positive_number(session_dir, tmp_path, capsys, rate):
    d = _with_meta(session_dir, tmp_path / "s", lambda m: m.update(rate_hz=rate))
    assert f"rate_hz {rate!r} is not a positive number of Hz; fix it or remove the field" in _error(d, capsys)


def test_a_magnetometer_in_nanotesla_names_the_conversion(session_dir, tmp_path):
    d = _with_meta(session_dir, tmp_path / "s", lambda m: None)
    t = np.arange(1000) * 10.0
    pd.DataFrame({"timestamp": t, "x": 20000.0, "y": 0.0, "z": -40000.0}).to_csv(d / "wMagneticField.csv", index=False)
    with pytest.raises(DataError, match=r"wMagneticField.csv: median \|B\| is 44721; looks like nT: divide by 1000"):
        read_session(d)


def test_a_barometer_outside_the_atmosphere_is_refused(session_dir, tmp_path):
    d = _with_meta(session_dir, tmp_path / "s", lambda m: None)
    pd.DataFrame({"timestamp": np.arange(1000) * 10.0, "x": 2000.0}).to_csv(d / "wBarometer.csv", index=False)
    with pytest.raises(DataError, match=r"wBarometer.csv: median pressure 2000.0 hPa is outside 300-1100 hPa"):
        read_session(d)
