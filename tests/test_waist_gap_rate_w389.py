"""Decision W389 (session 37, trial T1 finding 1): W34's straight line through the waist gyroscope across a short
gap makes up a turn. The pre-gap mean rate was measured and not adopted (its option removed since, W401); the
dropped-samples warning says what such a gap costs the heading."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.io import read_session
from pdrlearn.io.plasys import write_session
from pdrlearn.io.session import Session, Stream
from pdrlearn.kernels import gaps as G
from pdrlearn.kernels.waist_stream import Bridge
from pdrlearn.waist import body_data

FS = 50.0


def _session(gap_s: float, name: str = "w389") -> Session:
    """50 Hz waist data: a 1 Hz yaw oscillation of 0.5 rad/s about a 0.1 rad/s turn, a gap of ``gap_s`` at 5.13 s."""
    t = np.arange(int(12 * FS)) / FS
    cut = (t > 5.13) & (t < 5.13 + gap_s)
    acc = np.column_stack([0.3 * np.sin(2 * np.pi * 2 * t), np.zeros_like(t), np.full_like(t, 9.81)])
    gyr = np.column_stack([np.zeros_like(t), np.zeros_like(t), 0.1 + 0.5 * np.sin(2 * np.pi * t)])
    return Session(name=name, streams={"wAccelerometer": Stream("wAccelerometer", t[~cut], acc[~cut]),
                                       "wGyroscope": Stream("wGyroscope", t[~cut], gyr[~cut])},
                   meta={"frames": {"waist": {"x": "forward", "y": "left", "z": "up"}}})


def test_a_short_gap_is_one_line_offline_and_streamed_and_no_module_switch_w401():
    """Decision W401: W389's candidate (the pre-gap mean rate) and its module switch are gone; inside a 0.6 s gap
    ``body_data`` and the stream ``Bridge`` both carry W34's straight line between the gap's edge samples."""
    import pdrlearn.waist.ahrs as ahrs

    assert not hasattr(G, "PRE_GAP_RATE") and not hasattr(G, "pre_gap_rate") and not hasattr(ahrs, "pre_gap_rate")
    s = _session(0.6)
    g = s["wGyroscope"]
    t, _, line = body_data(s)
    inside = (t > 5.13) & (t < 5.73)  # the samples 5.14-5.72 s dropped
    assert inside.sum() >= 25
    edge = np.flatnonzero(g.t <= 5.13)[-1]  # the last sample before the gap and the first after it
    w = ((t[inside] - g.t[edge]) / (g.t[edge + 1] - g.t[edge]))[:, None]
    assert np.allclose(line[inside], (1.0 - w) * g.values[edge] + w * g.values[edge + 1])
    v = np.column_stack([s["wAccelerometer"].values, g.values])
    bt, bv = Bridge(FS, {})(g.t, v)
    assert np.allclose(bt, t, atol=1e-9) and np.allclose(bv[:, 3:], line, atol=1e-9)


@pytest.mark.parametrize("gap_s,warned", [(0.6, True), (0.2, False)])
def test_the_waist_drops_warning_says_what_a_gap_costs_the_heading(tmp_path, caplog, gap_s, warned):
    """A 0.6 s waist gyroscope gap: the dropped-samples line says the line across it makes up or loses part of a
    turn (W389's numbers); a 0.2 s one (0.3 s moved no heading in W389's measurement) does not."""
    folder = write_session(_session(gap_s), tmp_path / "w")
    with caplog.at_level(logging.WARNING):
        read_session(folder)
    lines = [r.getMessage() for r in caplog.records if "dropped samples" in r.getMessage()]
    assert len(lines) == 1
    assert ("makes up or loses part of a turn" in lines[0] and "decision W389" in lines[0]) is warned
