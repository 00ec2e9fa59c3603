"""Decision L332 (trial 31 finding 2): `pdrlearn evaluate` judges each evaluated session's labelled gait by L95's
walking range (the track's own test) and lists the sessions outside it; the one warning line is opt-in
(``--warn-gait-range``: L332's adoption rule was not met)."""

from __future__ import annotations

import dataclasses
import logging

import numpy as np
import pandas as pd
import pytest

from pdrlearn.classify.evaluation import evaluate_model
from pdrlearn.classify.gait_range import labelled_gait, labelled_strides, out_of_range_sessions, range_line
from pdrlearn.classify.training import train_user
from pdrlearn.cli import main
from pdrlearn.cli.simulate import _custom_gait
from pdrlearn.io import write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.sim.simulate import simulate
from pdrlearn.track.gait import _judged, session_range_side

SLOWBACK = "stand:2, backward:20, stand:2"  # trial 31's `slowback`: slow, 0.3 m steps


def _slowback(user: int):
    return simulate_path(parse_route(SLOWBACK), _custom_gait(UserProfile.from_seed(user), "slow", 0.3, None, SLOWBACK),
                         speed="slow", rate_hz=20.0, seed=1, scenario="route", name="slowback")


@pytest.fixture(scope="module")
def sessions():
    normal = dataclasses.replace(simulate("direction", user_seed=6517, seed=1), name="normal")
    return normal, _slowback(6517)


@pytest.fixture(scope="module")
def model():
    return train_user([simulate("direction", user_seed=6517, seed=0)], tasks=["direction"], methods=["svm"],
                      units=["foot"], cv=3, distance_calibration=False)


def test_the_labelled_gait_is_the_tracks_figures(sessions):
    normal, slow = sessions
    assert session_range_side(labelled_gait(normal)) is None
    assert session_range_side(labelled_gait(slow)) == "slow"
    cad, speed, what = _judged(labelled_gait(slow))
    # 0.3 m steps: 0.6 m strides at the slow cadence, under L95's 0.5 m/s
    assert what == "straight-walking speed" and speed < 0.3 and 60 < cad < 100
    got = out_of_range_sessions([normal, slow])
    assert [g["session"] for g in got] == ["slowback"] and got[0]["side"] == "slow"
    line = range_line(got, 2)
    assert line.startswith("1 of 2 evaluated sessions walk slower than the walking the pipelines are validated on")
    assert "slowback (median cadence" in line and "decision L332" in line
    assert range_line([], 2) is None


def test_labels_of_both_feet_are_timed_foot_by_foot():
    t = np.arange(8) * 1.1  # each foot's strides 1.1 s apart, the other foot half a stride later
    right = pd.DataFrame({"start_s": t, "end_s": t + 1.1, "ic_s": t, "foot": "right", "length_m": 1.1})
    both = pd.concat([right, right.assign(start_s=t + 0.55, end_s=t + 1.65, ic_s=t + 0.55, foot="left")])
    table = labelled_strides(both)
    assert np.nanmedian(table["stride_time_s"]) == pytest.approx(1.1)
    assert np.isfinite(table["stride_time_s"]).sum() == 14  # 7 per foot (the first of each has none)


def test_evaluate_lists_the_sessions_and_warns_only_when_asked(sessions, model, caplog):
    normal, slow = sessions
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        res = evaluate_model(model, [normal, slow], latency=False)
    assert [g["session"] for g in res["gait_out_of_range_sessions"]] == ["slowback"]
    assert not [r for r in caplog.records if "decision L332" in r.getMessage()]
    caplog.clear()
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        evaluate_model(model, [normal, slow], latency=False, warn_gait_range=True)
    lines = [r.getMessage() for r in caplog.records if "decision L332" in r.getMessage()]
    assert len(lines) == 1 and "slowback" in lines[0] and "normal (" not in lines[0]


def test_the_cli_option(sessions, model, tmp_path, capsys):
    normal, _ = sessions
    write_session(normal, tmp_path / "normal")
    model.save(tmp_path / "m")
    write_session(_slowback(6518), tmp_path / "slowback")
    assert main(["evaluate", str(tmp_path / "m"), str(tmp_path / "normal"), str(tmp_path / "slowback"),
                 "--warn-gait-range"]) == 0
    err = capsys.readouterr().err
    assert err.count("decision L332") == 1 and "1 of 2 evaluated sessions walk slower" in err
