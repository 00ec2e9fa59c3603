"""Decisions S83 / B370 (session 36, trial T2 finding 8): ``simulate --gap UNIT:START:DURATION`` (repeatable) removes
a unit's samples for a battery swap; meta.json records the gaps, the truth files stay the walk's; bad values are one
line."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError


def test_simulate_gap_removes_the_units_samples_s83(tmp_path):
    from pdrlearn.io import read_session

    plain, gap = tmp_path / "plain", tmp_path / "gap"
    route = "stand:5, straight:60, stand:5"
    assert main(["simulate", "--route", route, "-u", "8909", "-o", str(plain)]) == 0
    assert main(["simulate", "--route", route, "-u", "8909", "--gap", "foot:20:5", "--gap", "both:40:3",
                 "-o", str(gap)]) == 0
    a, b = read_session(plain, bridge_drops=False), read_session(gap, bridge_drops=False)
    tf, tw = b.streams["fAccelerometer"].t, b.streams["wAccelerometer"].t
    assert not ((tf >= 20) & (tf < 25)).any() and not ((tf >= 40) & (tf < 43)).any()
    assert ((tw >= 20) & (tw < 25)).any() and not ((tw >= 40) & (tw < 43)).any()
    keep = ~(((a.streams["fAccelerometer"].t >= 20) & (a.streams["fAccelerometer"].t < 25))
             | ((a.streams["fAccelerometer"].t >= 40) & (a.streams["fAccelerometer"].t < 43)))
    np.testing.assert_array_equal(a.streams["fAccelerometer"].values[keep], b.streams["fAccelerometer"].values)
    assert b.streams["wBarometer"].t.size == tw.size  # every waist file has the gap
    gaps = [g.duration_s for g in b.streams["fGyroscope"].gaps()]
    assert len(gaps) == 2 and gaps[0] == pytest.approx(5.05, abs=0.06)
    for f in ("steps.csv", "trajectory.csv"):  # the truth stays the walk's
        pd.testing.assert_frame_equal(pd.read_csv(plain / f), pd.read_csv(gap / f))
    meta = json.loads((gap / "meta.json").read_text())
    assert meta["knobs"]["gaps"] == [["foot", 20.0, 5.0], ["both", 40.0, 3.0]]
    assert "gaps" not in json.loads((plain / "meta.json").read_text())["knobs"]  # default sessions as before


@pytest.mark.parametrize("bad", ["foot:20", "hand:20:5", "foot:-1:5", "foot:20:0", "foot:x:5", "both:20:nan"])
def test_bad_gap_is_one_line_b370(tmp_path, capsys, bad):
    capsys.readouterr()
    assert main(["simulate", "--route", "straight:10", "-u", "8909", "--gap", bad, "-o", str(tmp_path / "s")]) == 2
    err = capsys.readouterr().err.strip()
    assert "--gap" in err and "UNIT:START:DURATION" in err and "B370" in err and len(err.splitlines()) == 1
    assert not (tmp_path / "s").exists()


@pytest.mark.parametrize("bad", ["foot:20", "hand:20:5", "foot:-1:5", "foot:20:0", "foot:x:5", "both:20:nan",
                                 "foot:20:5:1", "foot:0:5", "foot:-0:5"])
def test_cli_gap_line_is_check_gaps_own_b370(tmp_path, capsys, bad):
    """Session 37 re-read: the CLI parses only the syntax (split at ':'); the one line is check_gaps', naming the
    option's text and its form (the CLI repeated the range checks with its own message)."""
    from pdrlearn.sim.simulate import check_gaps

    with pytest.raises(DataError) as exc:
        check_gaps([tuple(bad.split(":"))], option="--gap")
    line = str(exc.value)
    assert f"--gap {bad!r}" in line and "UNIT:START:DURATION, e.g. --gap foot:600:120" in line and "B370" in line
    capsys.readouterr()
    assert main(["simulate", "--route", "straight:10", "-u", "8909", "--gap", bad, "-o", str(tmp_path / "s")]) == 2
    err = capsys.readouterr().err.strip()
    assert line in err and len(err.splitlines()) == 1
    assert not (tmp_path / "s").exists()
    with pytest.raises(DataError, match=r"^simulate: gap \('hand', 20, 5\): the unit must be one of foot, waist, "
                                        r"both, the start a time > 0 s and the duration > 0 s \(decision B370\)$"):
        check_gaps([("hand", 20, 5)])  # the Python API's line as before


def test_gap_outside_the_recording_is_one_line_b370():
    from pdrlearn.sim import simulate

    with pytest.raises(DataError, match=r"gap foot:500:5 does not lie inside the recording .*B370"):
        simulate("A", 8909, gaps=(("foot", 500, 5),))


def test_check_gaps_non_sequence_is_one_line_with_option():
    """Review R1 (session 37): check_gaps([5], option="--gap") was a TypeError traceback (the name was built outside
    the try)."""
    from pdrlearn.sim.simulate import check_gaps

    with pytest.raises(DataError, match=r"^simulate: --gap 5: give UNIT:START:DURATION"):
        check_gaps([5], option="--gap")
