"""Decision L792: ``track --window A,B --window-margin M`` tracks the window and M s either side, not the whole
recording; inside the window the steps are the whole track's (same times; the lower back's lengths to 1e-12, the
foot's to millimetres: a gyroscope bias read at another standstill), the positions re-anchored at the margin's start."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.io.plasys import write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline
from pdrlearn.track.window import check_margin, margin_session, window_track


@pytest.fixture(scope="module")
def session():
    route = parse_route("stand:5, straight:10, stand:6, straight:10, turn:180, straight:10, stand:6, straight:10, "
                        "stand:5")
    return simulate_path(route, UserProfile.from_seed(18890), rate_hz=20.0, seed=1, scenario="route")


def _window(session):
    return session.t_recording_start + 20.0, session.t_recording_start + 40.0


def test_margin_session_holds_the_window_and_its_margin_only(session):
    t0, t1 = _window(session)
    cut = margin_session(session, t0, t1, 5.0)
    for name, s in cut.streams.items():
        assert s.t[0] >= t0 - 5.0 and s.t[-1] <= t1 + 5.0, name
        assert len(s) < len(session.streams[name])
    assert cut.t_recording_start == session.t_recording_start  # the window's seconds keep their meaning
    assert len(session.streams["fAccelerometer"].t) > len(cut.streams["fAccelerometer"].t)  # the original intact


@pytest.mark.parametrize("pipeline, length_tol, step_tol_m", [("waist-pendulum", 1e-12, 1e-3),
                                                              ("plasys", 5e-3, 3e-2)])
def test_window_steps_match_the_whole_track_cut(session, pipeline, length_tol, step_tol_m):
    t0, t1 = _window(session)
    fn = get_pipeline(pipeline)
    whole, _ = window_track(fn(session), session, t0, t1)
    cut, _ = window_track(fn(margin_session(session, t0, t1, 15.0)), session, t0, t1)
    assert len(whole.steps) >= 8 and len(cut.steps) == len(whole.steps)
    for c in ("start_s", "end_s"):
        assert np.array_equal(cut.steps[c].to_numpy(), whole.steps[c].to_numpy())
    assert np.abs(cut.steps["length_m"].to_numpy() - whole.steps["length_m"].to_numpy()).max() <= length_tol
    assert np.array_equal(cut.trajectory["t"].to_numpy(), whole.trajectory["t"].to_numpy())
    moves = [np.diff(r.trajectory[["x", "y"]].to_numpy(), axis=0) for r in (whole, cut)]
    assert np.abs(moves[0] - moves[1]).max() <= step_tol_m  # the same steps, re-anchored at the margin's start


def test_track_command_tracks_the_margin_only(session, tmp_path, monkeypatch):
    from pdrlearn.cli.track import track_session, track_settings
    from pdrlearn.track import window as window_module

    folder = write_session(session, tmp_path / "s")
    seen = []
    real = window_module.margin_session

    def spy(s, t0, t1, margin_s):
        seen.append((t0 - s.t_recording_start, t1 - s.t_recording_start, margin_s))
        return real(s, t0, t1, margin_s)

    monkeypatch.setattr(window_module, "margin_session", spy)
    logging.disable(logging.WARNING)
    try:
        tracked = track_session(folder, track_settings(pipeline="waist-pendulum", window="20,40", window_margin=15.0,
                                                       no_plot=True))
    finally:
        logging.disable(logging.NOTSET)
    assert seen == [(20.0, 40.0, 15.0)]
    assert tracked["summary"]["n_steps"] >= 8 and tracked["summary"]["window_start_s"] == 20.0


@pytest.mark.parametrize("margin, window, words", [(-1.0, (1.0, 2.0), "> 0"), (float("nan"), (1.0, 2.0), "> 0"),
                                                   (30.0, None, "add --window")])
def test_bad_margin_is_one_line(margin, window, words):
    with pytest.raises(DataError) as e:
        check_margin(margin, window)
    assert words in str(e.value) and "\n" not in str(e.value)
    assert check_margin(None, window) is None
