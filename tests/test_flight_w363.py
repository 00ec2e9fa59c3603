"""Decision W363 (session 34, trial T3 finding 4): flight phases in a foot recording (the accelerometer near 0 g for
0.1 s or more: both feet off the ground) are counted and warned: strides across them may be jumps."""

from __future__ import annotations

import numpy as np

from pdrlearn.track.flight import flight_phases


def test_flight_phases_need_0_1_s_under_0_3_g():
    t = np.arange(0, 3, 0.01)
    acc = np.tile([0.0, 9.81, 0.0], (len(t), 1))
    acc[(t >= 1.0) & (t < 1.5)] = [0.0, 0.5, 0.0]  # 0.05 g for 0.5 s: a flight
    acc[(t >= 2.0) & (t < 2.05)] = 0.0  # 0.05 s: too short
    phases = flight_phases(t, acc)
    assert len(phases) == 1 and np.allclose(phases[0], (1.0, 1.5), atol=0.011)


def test_synthetic_jumps_are_warned(tmp_path):
    """User 7957 walking 4 m, then standing, with three synthetic jumps while standing in the foot accelerometer
    (push-off, 0.5 s of free fall, landing, as trial T3's mkjump.py): 3 flight phases and the W363 line (main: no key,
    no line)."""
    from pdrlearn.cli import main
    from pdrlearn.io import read_session
    from pdrlearn.track import get_pipeline
    from pdrlearn.track.evaluate import track_summary

    ses = tmp_path / "still"
    assert main(["simulate", "--route", "straight:4, stand:15", "--user-seed", "7957", "--out", str(ses)]) == 0
    session = read_session(ses)
    acc = session.streams["fAccelerometer"]
    for t0 in acc.t[-1] - np.array([12.0, 9.0, 6.0]):  # inside the final stand
        u = acc.t - t0
        push = (u >= 0) & (u < 0.25)
        acc.values[push] *= 1.0 + 1.6 * np.sin(np.pi * u[push] / 0.25)[:, None]
        acc.values[(u >= 0.25) & (u < 0.75)] = 0.02  # free fall: the accelerometer reads ~0 g
    result = get_pipeline("plasys")(session)
    summary = track_summary(result, session, pipeline="plasys")
    assert summary["n_flight_phases"] == 3 and 1.3 < summary["flight_time_s"] < 1.7
    assert sum("decision W363" in w for w in summary["info"]["warnings"]) == 1
