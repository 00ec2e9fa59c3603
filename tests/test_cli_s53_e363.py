"""Decision E363 (session 53, FA; review s53r1 findings F5 and F6): ``track --window A,B --window-margin M`` on a
window without walking is L105's empty window (its note, exit 0), not L792's margin session's "no strides" (exit 4);
``run --altitude fused`` on a session without the waist barometer names the session's folder, not the bundle, and
the live ``Tracker`` says its declared streams lack it. One short simulated two-unit walk."""

from __future__ import annotations

import logging
from pathlib import Path

import pytest

from pdrlearn.errors import NoStridesError

SHIPPED = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    from pdrlearn.io import write_session
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    s = simulate_path(parse_route("stand:6, straight:8, stand:2"), UserProfile.from_seed(5363), seed=5363,
                      scenario="route")
    folder = tmp_path_factory.mktemp("e363") / "walk"
    write_session(s, folder)
    (folder / "wBarometer.csv").unlink()  # F6: a two-unit session without the waist barometer
    return s, folder


def _track(folder, **kw):
    from pdrlearn.cli.track import track_session, track_settings

    return track_session(folder, track_settings(window="0,4", no_plot=True, **kw))


def test_an_empty_window_with_a_margin_is_l105s_empty_window_e363(walk, capsys):
    from pdrlearn.track import get_pipeline
    from pdrlearn.track.window import margin_session

    s, folder = walk
    t0 = s.t_recording_start
    logging.disable(logging.WARNING)
    try:
        with pytest.raises(NoStridesError):  # what L792's margin session alone gives (exit 4 before E363)
            get_pipeline("plasys")(margin_session(s, t0, t0 + 4.0, 1.0))
        plain = _track(folder)["summary"]
        note = capsys.readouterr().err
        margin = _track(folder, window_margin=1.0)["summary"]
    finally:
        logging.disable(logging.NOTSET)
    assert plain["n_steps"] == margin["n_steps"] == 0
    assert plain["window_start_s"] == margin["window_start_s"] == 0.0
    assert "--window 0,4 holds no step: walking 0 s, 0 m (the session's steps lie between" in note
    assert capsys.readouterr().err == note  # L105's very note


def test_run_fused_without_the_waist_barometer_names_the_session_e363(walk, tmp_path, capsys):
    from pdrlearn.cli import main
    from pdrlearn.kernels.barometer import FUSED_WITHOUT_BAROMETER
    from pdrlearn.runtime import Tracker, load_bundle

    _, folder = walk
    assert main(["run", str(SHIPPED), str(folder), "--altitude", "fused", "--no-plot", "--out",
                 str(tmp_path / "r")]) == 0
    err = capsys.readouterr().err
    line = err.split(FUSED_WITHOUT_BAROMETER)[0].splitlines()[-1]  # what the line starts with
    assert line == f"warning: {folder}: " and "bundle" not in line
    assert err.count("needs the waist barometer") == 1
    tr = Tracker(load_bundle(SHIPPED), altitude="fused",
                 sensors=["fAccelerometer", "fGyroscope", "wAccelerometer", "wGyroscope"])
    assert tr.warnings[:1] == ['altitude "fused" needs the waist barometer (wBarometer.csv), which the declared '
                               "streams (sensors=fAccelerometer, fGyroscope, wAccelerometer, wGyroscope) lack: the "
                               "altitude is the foot's own (L39 / the terrain classes)"]
