"""Decision W173: a stretch of backward-looking steps on the lower back is warned (the waist pipelines count every
step as forward distance), by the foot unit's push-off per stride (D9's swing-pitch asymmetry)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.backward import MIN_BACKWARD_STEPS, backward_runs
from tests.test_classify_training import labelled_session


def _lines(res) -> list[str]:
    return [w for w in res.info["warnings"] if "decision W173" in w]


def _sim(route: str, user: int, seed: int = 0):
    return simulate_path(parse_route(route), UserProfile.from_seed(user), rate_hz=20.0, seed=seed, scenario="route")


@pytest.mark.parametrize("pipeline", ["waist-pendulum", "waist-pll"])
def test_backward_walking_on_the_lower_back_is_warned(pipeline):
    """The trial's backward walk (user 11): tracked forward (+5.7 m for -3.8 m), now with one line."""
    res = track_waist(_sim("stand:3, backward:10, stand:3", 11), pipeline=pipeline)
    lines = _lines(res)
    assert len(lines) == 1, res.info["warnings"]
    assert "look backward (the foot unit pitches toes-up more than toes-down" in lines[0]
    assert "count every step as forward distance" in lines[0]
    assert res.trajectory["x"].iloc[-1] > 0  # the steps themselves are unchanged (their sign is W175's question)


def test_forward_backward_forward_warns_for_the_backward_stretch_only():
    s = _sim("straight:10, backward:10, straight:6", 14, seed=3)
    back = s.steps[s.steps["direction"] == "backward"]  # the simulated strides of the backward stretch
    lines = _lines(track_waist(s, pipeline="waist-pendulum"))
    assert len(lines) == 1, lines
    n, span = lines[0].split(" steps at ")[0], lines[0].split(" steps at ")[1].split(" s look")[0]
    t0, t1 = (float(x) for x in span.split("-"))
    assert int(n) >= MIN_BACKWARD_STEPS
    # the line's span lies in the simulated backward stretch (+- a step), away from the forward walking
    assert back["start_s"].min() - 0.8 <= t0 and t1 <= back["end_s"].max() + 0.8


def test_a_forward_walk_gives_no_backward_line_with_or_without_the_foot_unit():
    s = _sim("stand:3, straight:20, turn:90, straight:5, stand:3", 3401)
    waist = dataclasses.replace(s, streams={k: v for k, v in s.streams.items() if k.startswith("w")},
                                frames={"waist": s.frames["waist"]})
    for ss in (s, waist):
        assert not _lines(track_waist(ss, pipeline="waist-pendulum"))


def test_backward_runs_need_four_steps_inside_one_sequence():
    has_next = np.array([True] * 9 + [False] + [True] * 5 + [False])
    back = np.zeros(16, dtype=bool)
    back[1:4] = True  # three: a stumble
    assert backward_runs(back, has_next) == []
    back[4] = True
    back[10:16] = True
    assert backward_runs(back, has_next) == [(1, 4), (10, 15)]
    back[10:16] = False
    back[8:12] = True  # two steps each side of a sequence break: no run
    assert backward_runs(back, has_next) == [(1, 4)]


def test_units_waist_on_a_foot_and_waist_session_still_warns(tmp_path):
    """Decision W253 (trial 31 finding 1): ``track --units waist`` / ``track-all --units waist`` leave the foot files
    out of the track, and had lost W173's line with them (+44 % distance, no word); the left-out foot unit's cue is
    read as ``--pipeline waist-pendulum`` reads it."""
    from pdrlearn.cli.track import track_session, track_settings
    from pdrlearn.io import write_session

    s = _sim("stand:2, backward:12, stand:2", 6140, seed=1)
    write_session(s, tmp_path / "back")
    res = track_session(tmp_path / "back", track_settings(units="waist"))["result"]
    assert res.info["pipeline"].startswith("waist"), res.info["pipeline"]
    assert len(_lines(res)) == 1, res.info["warnings"]


def test_units_waist_with_a_foot_option_names_the_left_out_foot(tmp_path, capsys):
    """Decision W254 (trial 31 finding 8): ``--units waist --model`` on a foot + waist session had said the folder
    "has no fAccelerometer"; now one line naming --units and the foot option."""
    from pdrlearn.classify import train_user
    from pdrlearn.cli import main
    from pdrlearn.io import write_session

    s = _sim("stand:2, straight:6, stand:2", 6144)
    write_session(s, tmp_path / "walk")
    model = train_user([labelled_session(1, 8)], tasks=["direction"], methods=["svm"], cv=2)
    model.save(tmp_path / "model")
    for extra, named in ((["--model", str(tmp_path / "model")], "--model"),
                         (["--pipeline", "plasys"], "--pipeline plasys"), (["--method", "M2"], "--method")):
        rc = main(["track", "--no-plot", str(tmp_path / "walk"), "--units", "waist", "--out", str(tmp_path / "o"),
                   *extra])
        err = capsys.readouterr().err.strip()
        assert rc == 2 and "\n" not in err and "fAccelerometer" not in err, err
        assert f"{named} needs the foot unit (PLASYS tracks the foot), which --units waist leaves out" in err, err
        assert err.endswith("or drop --units (decision W254)") and not (tmp_path / "o").exists()


def test_units_foot_with_a_waist_pipeline_names_the_left_out_lower_back(tmp_path, capsys):
    """Decision W260 (session 31 review, F3), W254's mirror: ``--units foot --pipeline waist-pendulum`` on a foot +
    waist session had said "has no wAccelerometer ... record that sensor"; now one line naming --units."""
    from pdrlearn.cli import main
    from pdrlearn.io import write_session

    write_session(_sim("stand:2, straight:6, stand:2", 6301), tmp_path / "walk")
    for pipeline in ("waist-pendulum", "waist-pll"):
        rc = main(["track", "--no-plot", str(tmp_path / "walk"), "--units", "foot", "--pipeline", pipeline,
                   "--out", str(tmp_path / "o")])
        err = capsys.readouterr().err.strip()
        assert rc == 2 and "\n" not in err and "record that sensor" not in err, err
        assert f"--pipeline {pipeline} needs the lower-back unit, which --units foot leaves out" in err, err
        assert err.endswith("or drop --units (decision W260)") and not (tmp_path / "o").exists()
    assert main(["track", "--no-plot", str(tmp_path / "walk"), "--units", "foot", "--out",
                 str(tmp_path / "f")]) == 0  # foot
