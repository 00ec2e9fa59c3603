"""The streamed PLASYS path says when a session without the waist gyroscope is headed by the foot's own yaw,
as offline M2/M3 do (decision B17): once in ``info["warnings"]`` and once in the log, numbers unchanged."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.track.plasys import NO_WAIST_HEADING, no_waist_heading


@pytest.fixture(scope="module")
def walk():
    from pdrlearn.sim import simulate

    return simulate("walk", user_seed=2, length_m=30.0)


def _without(session, *names):
    import copy

    s = copy.copy(session)
    s.streams = {n: st for n, st in session.streams.items() if n not in names}
    return s


@pytest.mark.parametrize("drop", [("wGyroscope",), ("wAccelerometer", "wGyroscope", "wMagneticField",
                                                    "wBarometer")])
def test_streaming_warns_once_when_no_waist_gyroscope_heads_the_walk(walk, caplog, drop):
    from pdrlearn.track.plasys import track_streaming

    s = _without(walk, *drop)
    said = no_waist_heading(s)  # decision B153: an incomplete waist unit names its missing file
    assert (said == NO_WAIST_HEADING) == (len(drop) == 4)
    with caplog.at_level(logging.WARNING, logger="pdrlearn.track.plasys"):
        auto = track_streaming(s, method="M2")
    assert auto.info["warnings"].count(said) == 1
    assert sum(said in r.getMessage() for r in caplog.records) == 1
    foot = track_streaming(s, method="M2", heading="foot")  # asked for: nothing to say
    assert said not in foot.info["warnings"]
    np.testing.assert_array_equal(auto.trajectory[["x", "y", "z"]].to_numpy(),
                                  foot.trajectory[["x", "y", "z"]].to_numpy())


def test_streaming_with_the_waist_gyroscope_says_nothing(walk):
    from pdrlearn.track.plasys import track_streaming

    assert NO_WAIST_HEADING not in track_streaming(walk, method="M2").info["warnings"]


def test_a_waist_unit_without_its_gyroscope_is_named_not_called_absent(walk):
    """Decision B153: a session whose waist accelerometer, magnetometer and barometer are present but whose
    wGyroscope.csv is missing (an incomplete upload) said "no waist unit"; offline and streamed tracks now name the
    missing file and the present ones."""
    from pdrlearn.track.plasys import track_plasys, track_streaming

    s = _without(walk, "wGyroscope")
    want = ("waist unit incomplete: wGyroscope.csv missing (wAccelerometer.csv, wMagneticField.csv, wBarometer.csv "
            "present): heading from the foot's own integrated yaw (relative to the start); add wGyroscope.csv to head "
            "by the waist unit (decision B153)")
    assert want in track_plasys(s, method="M2").info["warnings"]
    assert want in track_streaming(s, method="M2").info["warnings"]
    assert NO_WAIST_HEADING not in track_plasys(s, method="M2").info["warnings"]
