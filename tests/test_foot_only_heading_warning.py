"""The streamed PLASYS path says when a session without the waist gyroscope is headed by the foot's own yaw,
as offline M2/M3 do (decision B17): once in ``info["warnings"]`` and once in the log, numbers unchanged."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.track.plasys import NO_WAIST_HEADING


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
    with caplog.at_level(logging.WARNING, logger="pdrlearn.track.plasys"):
        auto = track_streaming(s, method="M2")
    assert auto.info["warnings"].count(NO_WAIST_HEADING) == 1
    assert sum(NO_WAIST_HEADING in r.getMessage() for r in caplog.records) == 1
    foot = track_streaming(s, method="M2", heading="foot")  # asked for: nothing to say
    assert NO_WAIST_HEADING not in foot.info["warnings"]
    np.testing.assert_array_equal(auto.trajectory[["x", "y", "z"]].to_numpy(),
                                  foot.trajectory[["x", "y", "z"]].to_numpy())


def test_streaming_with_the_waist_gyroscope_says_nothing(walk):
    from pdrlearn.track.plasys import track_streaming

    assert NO_WAIST_HEADING not in track_streaming(walk, method="M2").info["warnings"]
