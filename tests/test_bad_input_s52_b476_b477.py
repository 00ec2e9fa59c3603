"""Decisions B476 (a session folder's lower-back gyroscope in deg/s is refused when read, by import's B40 tilt-rate
test) and B477 (a sensor file's timestamps that repeat and go backwards: one line names both repairs)."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.io import read_session, write_session
from pdrlearn.io.session import Stream
from pdrlearn.io.validate import check_timestamps
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route


@pytest.fixture(scope="module")
def walk():
    """A slow straight lower-back walk without a turn (trial s52t3 F2's case), 20 Hz."""
    return simulate_path(parse_route("stand:2, straight:12, stand:2"), UserProfile.from_seed(19370), speed="slow",
                         rate_hz=20.0, seed=1)


def _copy(session, folder, scale: dict):
    streams = {k: (Stream(k, s.t, np.degrees(s.values)) if k in scale else s) for k, s in session.streams.items()}
    s = session.__class__(name=session.name, streams=streams, meta=dict(session.meta), frames=session.frames)
    write_session(s, folder)
    return folder


def test_a_lower_back_gyroscope_in_deg_s_is_refused_when_the_folder_is_read(walk, tmp_path):
    folder = _copy(walk, tmp_path / "degs", {"wGyroscope"})
    with pytest.raises(DataError) as exc:
        read_session(folder)
    msg = str(exc.value)
    assert "wGyroscope.csv" in msg and "deg/s read as rad/s" in msg and "\n" not in msg
    assert '"units": {"wGyroscope": "deg/s"}' in msg and "B476" in msg
    read_session(folder, check_units=False)  # the documented opt-out


def test_the_same_walk_in_rad_s_and_declared_deg_s_are_read(walk, tmp_path):
    read_session(_copy(walk, tmp_path / "rads", set()))  # the right unit: not refused
    folder = _copy(walk, tmp_path / "declared", {"wGyroscope"})
    meta = dict(walk.meta)
    import json

    meta["units"] = {**(meta.get("units") or {}), "wGyroscope": "deg/s"}
    (folder / "meta.json").write_text(json.dumps(meta))
    s = read_session(folder)
    np.testing.assert_allclose(s["wGyroscope"].values, walk["wGyroscope"].values, rtol=1e-9, atol=1e-9)


def test_a_foot_gyroscope_in_deg_s_is_refused_when_read_too(walk, tmp_path):
    """The foot's deg/s is B30's line (its p99 |rate| over 40), before B476's test."""
    with pytest.raises(DataError, match=r"fGyroscope\.csv.*deg/s"):
        read_session(_copy(walk, tmp_path / "fdegs", {"fGyroscope"}))


def test_duplicates_and_backward_rows_are_named_in_one_line():
    t = np.arange(20) * 0.01
    both = np.concatenate([t[:5], t[4:5], t[5:10], t[11:12], t[10:11], t[12:]])  # a repeat, then two rows swapped
    with pytest.raises(DataError) as exc:
        check_timestamps(both, "x/fAccelerometer.csv")
    msg = str(exc.value)
    assert "1 duplicate timestamp(s) (first at line 7)" in msg
    assert "also go backwards 1 time(s) (first at line 14): sort the file by timestamp too (decision B477)" in msg


def test_backward_rows_that_hide_a_duplicate_name_it_too():
    t = np.arange(20) * 0.01
    hidden = np.concatenate([t[:5], t[6:7], t[5:]])  # the stamp 0.06 on lines 7 and 9, 0.05 between them
    with pytest.raises(DataError) as exc:
        check_timestamps(hidden, "x/fAccelerometer.csv")
    msg = str(exc.value)
    assert "timestamps go backwards 1 time(s)" in msg
    assert "1 row(s) also repeat an earlier row's timestamp (first at line 9)" in msg
    assert "once sorted, drop the duplicated rows too (decision B477)" in msg


def test_one_problem_alone_keeps_its_line():
    t = np.arange(20) * 0.01
    for bad, other in ((np.concatenate([t[:5], t[4:]]), "backwards"), (np.concatenate([t[:5], t[6:7], t[5:6], t[7:]]),
                                                                          "repeat")):
        with pytest.raises(DataError) as exc:
            check_timestamps(bad, "x/fAccelerometer.csv")
        assert other not in str(exc.value).split(";", 1)[1] and "B477" not in str(exc.value)
