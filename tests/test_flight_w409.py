"""Decision W409 (session 38, trial T5 finding 10): a flight phase needs its first and last low samples 0.1 s apart;
a slow walker's late swing that dips under 0.3 g for two samples at 20 Hz is not a jump."""

from __future__ import annotations

import numpy as np

from pdrlearn.track.flight import flight_phases


def test_two_low_samples_at_20_hz_are_not_a_flight_three_are():
    t = np.arange(0, 4, 0.05)  # 20 Hz, the simulator's foot rate
    acc = np.tile([0.0, 9.81, 0.0], (len(t), 1))
    acc[[20, 21]] = [0.0, 2.5, 0.0]  # 0.25 g at 1.00 and 1.05 s: a swing's dip (main: one "0.1 s" flight)
    acc[[50, 51, 52]] = [0.0, 0.2, 0.0]  # 2.50-2.60 s: seen in free fall for 0.1 s
    phases = flight_phases(t, acc)
    assert len(phases) == 1 and np.allclose(phases[0], (2.5, 2.65))


def test_slow_cane_walk_has_no_flight_phase(tmp_path):
    """User 9785, 0.5 m steps in 0.7 s (0.71 m/s, trial T5's cane walk): main counted 2 flight phases."""
    from pdrlearn.cli import main
    from pdrlearn.io import read_session
    from pdrlearn.track import get_pipeline
    from pdrlearn.track.evaluate import track_summary

    ses = tmp_path / "cane"
    assert main(["simulate", "--route", "straight:20", "--step-length", "0.5", "--step-time", "0.7",
                 "--user-seed", "9785", "--out", str(ses)]) == 0
    session = read_session(ses)
    summary = track_summary(get_pipeline("plasys")(session), session, pipeline="plasys")
    assert summary["n_flight_phases"] == 0
    assert not any("decision W363" in w for w in summary["info"]["warnings"])


def test_at_100_hz_ten_low_samples_are_not_a_flight_eleven_are_and_the_line_says_more_than_0_1_s():
    """Decision W412 (review R3 finding 5): W409 needs the first and last low samples 0.1 s apart, so an exact
    0.1 s run at 100 Hz (10 samples, 0.09 s apart) is not a flight; the warning says "more than 0.1 s" (it said
    "0.1 s or more")."""
    from types import SimpleNamespace

    from pdrlearn.track.flight import flight_summary

    t = np.arange(0, 4, 0.01)  # 100 Hz
    acc = np.tile([0.0, 9.81, 0.0], (len(t), 1))
    acc[100:110] = [0.0, 0.98, 0.0]  # 0.1 g: 10 samples, 1.00-1.09 s
    assert flight_phases(t, acc) == []
    acc[200:211] = [0.0, 0.98, 0.0]  # 11 samples, 2.00-2.10 s
    assert np.allclose(flight_phases(t, acc), [(2.0, 2.11)])
    session = SimpleNamespace(streams={"fAccelerometer": SimpleNamespace(t=t, values=acc)})
    keys, line = flight_summary(session, "plasys")
    assert keys["n_flight_phases"] == 1
    assert "under 0.3 g for more than 0.1 s" in line and "0.1 s or more apart" in line
    assert "for 0.1 s or more" not in line
