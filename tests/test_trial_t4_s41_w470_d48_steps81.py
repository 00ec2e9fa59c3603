"""Session 41, trial T4 findings 3, 5 and 6: the weinberg gain's advice names --length-model and a PARAMS.json whose
``length_models`` no --length-model uses says so (W470); ``experiments/step_count.py --help`` gives the docstring's
whole first paragraph and helps ``--real-dir`` (steps decision 81); ``--gnss`` prints one line on the fusion (D48)."""

from __future__ import annotations

import pytest

from pdrlearn.errors import DataError
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.calibration import calibrate

USER = 11680  # this fix's simulated users: 11680-11689


@pytest.fixture(scope="module")
def walk():
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    return simulate_path(parse_route("stand:3, straight:20, stand:3"), UserProfile.from_seed(USER), seed=0)


@pytest.fixture(scope="module")
def fitted(walk):
    return calibrate([walk], "waist-pendulum", distances=[20.0], length_model="weinberg")


def test_w470_the_missing_gain_line_names_length_model_with_params(walk):
    """T4 #3: it said "then track with --params PARAMS.json", which tracks with the pendulum."""
    with pytest.raises(DataError, match=r"then track with --length-model weinberg --params PARAMS\.json"):
        track_waist(walk, pipeline="waist-pendulum", length_model="weinberg")


def test_w470_a_params_file_gain_without_length_model_is_said_once(walk, fitted):
    plain = track_waist(walk, pipeline="waist-pendulum", params=fitted).info["warnings"]
    said = [w for w in plain if "W470" in w]
    assert len(said) == 1 and "add --length-model weinberg to use it" in said[0]
    used = track_waist(walk, pipeline="waist-pendulum", params=fitted, length_model="weinberg").info["warnings"]
    assert not [w for w in used if "W470" in w]
    from pdrlearn.track.waist import unused_length_models_line

    assert unused_length_models_line(fitted, None, "waist-pll") == ""  # another pipeline's file: its own lines say so


def test_steps81_step_count_help_is_the_whole_first_paragraph(capsys):
    from experiments import step_count

    with pytest.raises(SystemExit):
        step_count.build_parser().parse_args(["--help"])
    out = " ".join(capsys.readouterr().out.split())
    assert ("at slow, normal and fast walking) on simulated users, and report the detectors on the real "
            "recordings.") in out
    assert "--real-dir DIR the real recordings" in out


GNSS = {"fixes_total": 46, "fixes_used": 30, "fixes_outside_track": 13, "fixes_before_ttff": 1,
        "fixes_superseded": 2, "fixes_gated": 0, "distance_pdr_m": 39.79, "distance_scale": None,
        "distance_scale_cover_m": 0.0, "distance_scaled": False}


def test_d48_gnss_line_says_fixes_used_and_which_distance():
    from pdrlearn.aid.track import gnss_line

    assert gnss_line({}) == ""
    line = gnss_line(GNSS)
    assert line.startswith("gnss: 30 of 46 fixes used (13 outside the walk, 1 before the first fix time, 2 superseded")
    assert "distance kept from the PDR (docs/decisions/aided.md D39" in line and "gated" not in line
    kept = gnss_line({**GNSS, "distance_scale": 1.012, "distance_scale_cover_m": 1500.0})
    assert "distance kept from the PDR (docs/decisions/aided.md D45" in kept
    scaled = gnss_line({**GNSS, "distance_scale": 1.012, "distance_scale_cover_m": 1500.0, "distance_scaled": True})
    assert "distance scaled by 1.0120 from the PDR's 39.79 m (docs/decisions/aided.md D39, D45)" in scaled


def test_d48_track_gnss_prints_the_line(tmp_path, capsys):
    """T4 #6: the CLI printed nothing on the fusion but a blank-hdop warning."""
    from pdrlearn.aid.fixgen import gnss_fixes
    from pdrlearn.cli import main
    from pdrlearn.io import write_session
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    ses = simulate_path(parse_route("stand:2, straight:30, stand:2"), UserProfile.from_seed(USER + 1), seed=0)
    write_session(ses, tmp_path / "walk")
    fx = gnss_fixes(ses.trajectory, accuracy_m=4.0, origin=(45.4642, 9.19), seed=7)
    fx[["t", "lat", "lon", "accuracy_m"]].to_csv(tmp_path / "gnss.csv", index=False)
    assert main(["track", "--no-plot", str(tmp_path / "walk"), "--gnss", str(tmp_path / "gnss.csv"),
                 "--out", str(tmp_path / "out")]) == 0
    lines = [x for x in capsys.readouterr().out.splitlines() if x.startswith("gnss: ")]
    assert len(lines) == 1 and " fixes used" in lines[0]
    assert "distance kept from the PDR (docs/decisions/aided.md D39" in lines[0]
