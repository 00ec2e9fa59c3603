"""Decisions C163 / C164 (session 41, trial T1 finding 9): a lower-back-only recording tracked with a foot option.

C163: ``track --model M`` on a recording without a foot unit had said "no foot unit ... track it with --pipeline
waist-pendulum", and that command then refused ``--model`` too (two errors in a row); now one line names the option,
why no lower-back pipeline reads it, and the command that works, which then tracks.
C164: a per-user model's waist direction classifier is not read by a lower-back track (it failed its adoption rule,
docs/decisions/cohort.md C164); the line says that a lower-back track counts backward steps as forward."""

from __future__ import annotations

import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from tests.test_classify_training import labelled_session


@pytest.fixture(scope="module")
def lower_back_walk(tmp_path_factory):
    from pdrlearn.classify import train_user
    from pdrlearn.io import write_session

    root = tmp_path_factory.mktemp("c163")
    s = simulate_path(parse_route("stand:2, straight:4, backward:4, straight:3, stand:2"),
                      UserProfile.from_seed(11590), rate_hz=20.0, seed=0, scenario="route")
    write_session(s, root / "walk")
    for f in (root / "walk").glob("f*.csv"):  # the foot unit's files: a lower-back-only recording
        f.unlink()
    model = train_user([labelled_session(1, 8)], tasks=["direction"], methods=["svm"], cv=2)
    model.save(root / "model")
    return root


@pytest.mark.parametrize("extra, named, drop", [
    (["--model", "MODEL"], "--model is a foot-pipeline (PLASYS) option", "drop --model to track"),
    (["--pipeline", "plasys", "--model", "MODEL"], "--model is a foot-pipeline (PLASYS) option",
     "drop --pipeline plasys and --model to track"),
    (["--streaming"], "--streaming is a foot-pipeline (PLASYS) option", "drop --streaming to track"),
])
def test_a_foot_option_on_a_lower_back_recording_is_one_line_naming_what_works_c163(lower_back_walk, capsys, extra,
                                                                                   named, drop):
    from pdrlearn.cli import main

    root = lower_back_walk
    extra = [str(root / "model") if a == "MODEL" else a for a in extra]
    rc = main(["track", str(root / "walk"), "--out", str(root / "o"), *extra])
    err = capsys.readouterr().err.strip()
    assert rc == 2 and "\n" not in err and "Traceback" not in err, err
    assert "has no foot unit (fAccelerometer.csv)" in err and named in err and drop in err, err
    assert "--pipeline auto chooses waist-pendulum" in err and err.endswith("(decision C163)"), err
    assert ("counts backward steps as forward, decision C164" in err) == ("--model" in extra), err
    assert not (root / "o").exists()
    # the command the line names works: the same track without the foot option(s) (no second error)
    assert main(["track", str(root / "walk"), "--out", str(root / "ok"), "--force"]) == 0
    assert '"pipeline": "waist-pendulum"' in (root / "ok" / "summary.json").read_text()  # what the line says
