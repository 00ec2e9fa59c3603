"""Decision L413 (session 34, trial T3 finding 3): a freeze-index episode that the foot track's side-stepping
strides fill is a side shuffle, not a freeze: left out of freezes.csv / n_freezes, with one line naming it."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.track.freezes import side_step_freezes


def _steps(starts, sideways, stride_s=1.4):
    s = np.asarray(starts, float)
    return pd.DataFrame({"start_s": s, "end_s": s + stride_s, "length_m": 0.45, "sideways": sideways,
                         "gap_s": 0.0, "unit": "foot"})


def _episode(k, a, b, fi=5.2):
    return {"freeze": k, "start_s": a, "end_s": b, "duration_s": b - a, "peak_fi": fi}


def test_an_episode_filled_by_side_strides_is_left_out_and_named():
    """Side strides 25-36 s (a run of 8, L228) fill the episode 25.25-35.75 s (the trial's): left out, one line;
    a freeze at 50-56 s while standing (no stride) and one at 60-64 s over forward strides stay, renumbered."""
    side = _steps(25.0 + 1.4 * np.arange(8), True)
    fwd = _steps(58.0 + 1.1 * np.arange(6), False, 1.1)
    steps = pd.concat([side, fwd], ignore_index=True)
    rows = [_episode(1, 25.25, 35.75), _episode(2, 50.0, 56.0), _episode(3, 60.0, 64.0)]
    kept, lines = side_step_freezes(rows, steps)
    assert [(r["freeze"], r["start_s"]) for r in kept] == [(1, 50.0), (2, 60.0)]
    assert len(lines) == 1 and "25.2-35.8 s" in lines[0] and "side-stepping run" in lines[0] and "L413" in lines[0]


def test_an_episode_only_touched_by_side_strides_stays():
    """A freeze of 10 s of which side strides cover 2.8 s (under half) stays; no side column: all stay."""
    steps = _steps([20.0, 21.4], True)
    rows = [_episode(1, 20.0, 30.0)]
    kept, lines = side_step_freezes(rows, steps)
    assert kept == rows and lines == []
    kept, lines = side_step_freezes(rows, steps.drop(columns="sideways"))
    assert kept == rows and lines == []


def _tracked(session):
    from pdrlearn.track import get_pipeline
    from pdrlearn.track.evaluate import track_summary

    result = get_pipeline("plasys")(session)
    return result, track_summary(result, session, pipeline="plasys")


def test_a_trembling_side_shuffle_is_no_freeze_but_a_freeze_still_is(tmp_path):
    """User 7945's side shuffle (``side:4, side:-4``) with a 1 m/s^2 5 Hz shake along gravity over its side strides
    (the freeze index then fires there, as it did on the trial's user 7842 without one; main: 2 episodes): no
    episode, one L413 line, strides and distance unchanged. Control (user 7946): a simulated freeze of 6 s while
    standing (``freeze:6:5:8``, decision S51) is still an episode."""
    from pdrlearn.cli import main
    from pdrlearn.io import read_session

    ses = tmp_path / "side"
    assert main(["simulate", "--route", "straight:5, side:4, side:-4, straight:5", "--user-seed", "7945",
                 "--out", str(ses)]) == 0
    session = read_session(ses)
    plain, _ = _tracked(session)
    side = plain.steps[plain.steps["sideways"].astype(bool)]
    assert len(side) >= 6
    acc = session.streams["fAccelerometer"]
    inside = (acc.t > side["start_s"].min()) & (acc.t < side["end_s"].max())
    unit = acc.values / np.linalg.norm(acc.values, axis=1, keepdims=True)
    acc.values[inside] += 1.0 * np.sin(2 * np.pi * 5.0 * acc.t[inside])[:, None] * unit[inside]
    shaken, summary = _tracked(session)
    assert summary["n_freezes"] == 0 and shaken.info["freezes"] == []
    assert sum("decision L413" in w for w in shaken.info["warnings"]) >= 1
    assert summary["n_side_strides"] == len(side)
    fog = tmp_path / "fog"
    assert main(["simulate", "--route", "straight:4, freeze:6:5:8, straight:4", "--user-seed", "7946",
                 "--out", str(fog)]) == 0
    _, fog_summary = _tracked(read_session(fog))
    assert fog_summary["n_freezes"] >= 1
