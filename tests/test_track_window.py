"""`pdrlearn track --window START,END` (decision L105): the steps whose middle lies in the window, its
references cut alike; bad windows are one error line, nothing written."""

from __future__ import annotations

import json

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    root = tmp_path_factory.mktemp("window")
    s = simulate_path(parse_route("stand:2, straight:24, turn:180, straight:10, stand:2"), UserProfile.from_seed(1),
                      speed="slow", rate_hz=20, seed=0)
    write_session(s, root / "walk")
    return root, s


def _track(root, *args):
    out = root / ("t" + "_".join(a.replace(",", "-") for a in args))
    assert main(["track", "--no-plot", str(root / "walk"), "--out", str(out), "--json", *args]) == 0  # no figure read
    return json.loads((out / "summary.json").read_text()), out


@pytest.mark.parametrize("pipeline", ["plasys", "waist-pendulum"])
def test_window_keeps_the_steps_inside_and_cuts_the_reference(walk, pipeline, capsys):
    root, s = walk
    full, _ = _track(root, "--pipeline", pipeline)
    win, out = _track(root, "--pipeline", pipeline, "--window", "12,22")
    capsys.readouterr()
    assert win["window_start_s"] == 12.0 and win["window_end_s"] == 22.0
    assert win["info"]["window"] == {"start_s": 12.0, "end_s": 22.0}
    steps = np.loadtxt(out / "steps.csv", delimiter=",", skiprows=1, usecols=(0, 1))
    mid = steps.mean(axis=1) - s.t_start
    assert len(steps) == win["n_steps"] and ((mid >= 12) & (mid <= 22)).all()
    assert 0 < win["n_steps"] < full["n_steps"]
    # the middle of the 24 m straight (walking from ~7 s to ~34 s): about 10 s of it at the straight speed
    speed = full["median_speed_straight_mps"]
    assert 0.8 * 10 * speed <= win["distance_m"] <= 1.2 * 10 * speed
    # the reference is the window's too: its error is small (the whole walk's reference is ~36 m)
    assert win["distance_ref_m"] < 0.5 * full["distance_ref_m"]
    assert abs(win["distance_m"] - win["distance_ref_m"]) <= 0.2 * win["distance_ref_m"] + 0.1
    # a window over the whole recording is the whole track
    whole, _ = _track(root, "--pipeline", pipeline, "--window", f"0,{s.duration_s:.6f}")
    assert whole["n_steps"] == full["n_steps"] and whole["distance_m"] == pytest.approx(full["distance_m"])


@pytest.mark.parametrize("window, message", [("15,5", "must be later than START"), ("5,5", "must be later"),
                                             ("0,nan", "finite"), ("inf,5", "finite"), ("-1,5", "before the session"),
                                             ("5", "two numbers"), ("a,b", "two numbers"),
                                             ("9000,9999", "lies outside the recording")])
def test_bad_window_is_one_line_and_writes_nothing(walk, window, message, capsys):
    root, _ = walk
    out = root / "bad"
    assert main(["track", str(root / "walk"), "--out", str(out), "--window", window]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("error: ") and message in err and "\n" not in err, err
    assert "--window" in err and not out.exists()


def test_a_window_past_the_end_is_clipped_with_one_line(walk, capsys):
    """Decision B242: a window that starts inside the recording and ends after it is the recording's last part
    (per-hour bins), said in one warning line; one wholly after the end stays refused (above)."""
    root, s = walk
    capsys.readouterr()
    full, _ = _track(root)
    dur = round(s.duration_s, 2)
    capsys.readouterr()
    win, _ = _track(root, "--window", "10,9999")
    err = [ln for ln in capsys.readouterr().err.splitlines() if "--window" in ln]
    assert len(err) == 1 and "ends after the recording" in err[0] and f"clipped to 10,{dur:.2f}" in err[0], err
    assert win["window_start_s"] == 10.0 and win["window_end_s"] == pytest.approx(dur, abs=0.01)
    same, _ = _track(root, "--window", f"10,{dur:.2f}")
    assert win["n_steps"] == same["n_steps"] and win["distance_m"] == pytest.approx(same["distance_m"])
    assert 0 < win["n_steps"] < full["n_steps"]


def test_window_counts_from_the_recording_start_with_common_span(walk, tmp_path, capsys):
    """--window with --common-span (decisions L105 / B81): a cut that drops the start of the files does not move
    the window's seconds - "5,15" keeps the same steps as on the whole session (it kept those of 8-18 s)."""
    import shutil

    import pandas as pd

    root, s = walk
    d = tmp_path / "late"
    shutil.copytree(root / "walk", d)
    g = pd.read_csv(d / "fGyroscope.csv")
    g[g.timestamp >= g.timestamp.iloc[0] + 3e3].to_csv(d / "fGyroscope.csv", index=False)  # starts 3 s late
    whole, _ = _track(root, "--window", "5,15")
    out = tmp_path / "cut"
    assert main(["track", "--no-plot", str(d), "--out", str(out), "--json", "--common-span", "--window", "5,15"]) == 0
    capsys.readouterr()
    cut = json.loads((out / "summary.json").read_text())
    assert cut["info"]["window"] == {"start_s": 5.0, "end_s": 15.0}
    a = np.loadtxt(out / "steps.csv", delimiter=",", skiprows=1, usecols=(0, 1))
    mid = a.mean(axis=1) - s.t_start
    assert len(a) and ((mid >= 5) & (mid <= 15)).all(), mid
    assert abs(cut["n_steps"] - whole["n_steps"]) <= 1


def test_window_path_png_draws_the_windows_reference_from_the_tracks_start(walk):
    """path.png of a window (L105): the reference drawn is the window's, starting at the track's first point
    (the walker's position at the window start), not the whole walk shifted to the origin."""
    from pdrlearn.cli.track import track_session, track_settings
    from pdrlearn.track.plots import path_figure
    from pdrlearn.track.window import parse_window

    root, _ = walk
    settings = track_settings(streaming=True)
    settings["window"] = parse_window("15,25")
    tracked = track_session(root / "walk", settings)
    tr = tracked["result"].trajectory
    assert np.hypot(tr["x"].iloc[0], tr["y"].iloc[0]) > 4.0  # the window starts metres into the walk
    plt, fig = path_figure({"track": tracked["result"]}, session=tracked["session"])
    gx, gy = fig.axes[0].lines[-1].get_data()
    plt.close(fig)
    assert np.hypot(gx[0] - tr["x"].iloc[0], gy[0] - tr["y"].iloc[0]) < 0.3
    # only the window's reference: about the track's own length, not the whole ~36 m walk
    assert np.hypot(np.diff(gx), np.diff(gy)).sum() < 1.5 * tracked["result"].distance_m + 1.0


def test_window_without_a_step_notes_in_one_line(walk, capsys):
    """L107, L276: a window that holds no step (here the 2 s stand before the walk) says so in one "note:" line
    naming the window and the span of the session's steps (summary.json's info notes too); walking 0 s, not null."""
    root, _ = walk
    capsys.readouterr()
    win, _ = _track(root, "--window", "0,1")
    err = [ln for ln in capsys.readouterr().err.splitlines() if "holds no step" in ln]
    assert win["n_steps"] == 0 and len(err) == 1, err
    assert err[0].startswith("note: ") and "--window 0,1 holds no step: walking 0 s, 0 m" in err[0]
    assert "the session's steps lie between " in err[0]
    assert any("holds no step" in w for w in win["info"]["notes"]) and win["walking_time_s"] == 0.0
    assert not any("holds no step" in w for w in win["info"].get("warnings", []))
    full, _ = _track(root, "--window", "0,20")
    assert full["n_steps"] > 0 and not any("holds no step" in w for w in full["info"].get("warnings", []))
