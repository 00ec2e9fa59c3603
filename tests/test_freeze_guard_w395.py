"""The lower back's freeze index by default and its guard: W395's one-line hint when counted steps lie in a freeze
episode (the index off), W396's unreliable episodes (covering most of a walking bout: reported, not vetoed)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pandas as pd
import pytest

from pdrlearn.io import Session
from pdrlearn.sim import Freeze, Stand, Straight, UserProfile, simulate_path
from pdrlearn.track.freezes import freeze_hint, unreliable_mask


def _lower_back(session: Session) -> Session:
    """The session with its waist streams only (T6's set-up: one lower-back IMU, no foot unit)."""
    return dataclasses.replace(session, streams={k: v for k, v in session.streams.items() if k.startswith("w")})


def _sim(route, seed: int, step_length_m: float, step_time_s: float) -> Session:
    user = dataclasses.replace(UserProfile.from_seed(seed), step_length_m=step_length_m, step_time_s=step_time_s)
    return _lower_back(simulate_path(route, user, rate_hz=100, seed=0, bounce="pendulum", pelvis="realistic"))


@pytest.fixture(scope="module")
def fog():  # T6's freeze route (user 9305 of this session's 9300-9309)
    return _sim([Stand(3.0), Straight(6.0), Freeze(10.0, 5.0, 8.0), Straight(6.0), Stand(3.0)], 9305, 0.3, 0.5)


@pytest.fixture(scope="module")
def slow():  # T6's slow PD walk (0.3 m steps every 0.95 s, 63 steps/min), user 9306
    return _sim([Stand(3.0), Straight(15.0), Stand(3.0)], 9306, 0.3, 0.95)


def _steps(times) -> pd.DataFrame:
    t = np.asarray(times, dtype=float)
    return pd.DataFrame({"start_s": t, "end_s": t + 0.5, "event_s": t, "has_next": True})


def test_unreliable_mask_is_most_of_a_bout_w396():
    steps = _steps(np.arange(10.0, 40.0, 0.5))  # one bout, 10-40 s
    rows = [{"start_s": 8.0, "end_s": 42.0, "duration_s": 34.0}, {"start_s": 20.0, "end_s": 25.0, "duration_s": 5.0},
            {"start_s": 12.0, "end_s": 28.0, "duration_s": 16.0}, {"start_s": 12.0, "end_s": 37.0, "duration_s": 25.0}]
    # under 2 x 4 s of the 10-40.5 s bout left uncovered: unreliable; 14.5 s left (a freeze inside walking): kept
    assert [bool(unreliable_mask([r], steps)[0]) for r in rows] == [True, False, False, True]
    pair = [{"start_s": 11.0, "end_s": 25.0}, {"start_s": 25.5, "end_s": 39.0}]  # together they cover the walk
    assert list(unreliable_mask(pair, steps)) == [True, True]
    assert freeze_hint(rows[1:2], steps).startswith("11 counted step(s) lie in 5.0 s")  # 20.0-25.0 s, every 0.5 s
    assert freeze_hint(rows[:1], steps) is None  # an unreliable episode gives no hint
    assert freeze_hint(None, steps) is None and list(unreliable_mask(None, steps)) == []


def test_default_track_hints_at_a_freeze_without_changing_steps_w395(fog):
    from pdrlearn.track.waist import track_waist

    fz = fog.extras["freezes"]
    a, b = float(fz["start_s"].iloc[0]), float(fz["end_s"].iloc[0])
    res = track_waist(fog, pipeline="waist-pendulum")
    ev = res.steps["event_s"].to_numpy(float)
    n_in = int(((ev >= a - 0.5) & (ev <= b + 0.5)).sum())
    assert n_in >= 5  # T6's finding: the trembling is counted as steps
    lines = [w for w in res.info["warnings"] if "W395" in w]
    assert len(lines) == 1 and "--freeze-index" in lines[0]
    assert n_in >= int(lines[0].split(" counted step")[0]) >= n_in // 2  # (the episode is the index's 4 s windows)
    assert res.info["freezes"] is None  # the index stays off (W216): no freezes.csv
    on = track_waist(fog, pipeline="waist-pendulum", freeze_index=True)
    assert len(on.steps) == len(res.steps)  # the hint changes no step
    assert not any("W395" in w for w in on.info["warnings"])  # with the index on, W215's line says it


def test_slow_walk_episode_is_unreliable_and_not_vetoed_w396(slow):
    from pdrlearn.track.waist import track_waist

    off = track_waist(slow, pipeline="waist-pendulum")
    veto = track_waist(slow, pipeline="waist-pendulum", freeze_veto=True)
    assert len(veto.info["freezes"]) >= 1  # T6: the index reads the slow walk as freezing
    assert len(veto.steps) == len(off.steps) > 30 and veto.info["n_frozen_contacts"] == 0
    assert any("W396" in w and "unreliable" in w for w in veto.info["warnings"])
    assert not any("W395" in w for w in off.info["warnings"])  # nor a default hint


def test_no_steps_line_names_the_veto_w396(slow, monkeypatch):
    import pdrlearn.track.waist as tw

    monkeypatch.setattr(tw, "unreliable_mask", lambda rows, steps: np.zeros(len(rows or []), dtype=bool))
    res = tw.track_waist(slow, pipeline="waist-pendulum", freeze_veto=True)  # the old veto: every contact dropped
    assert res.info["n_frozen_contacts"] > 30
    assert any("no steps found" in w and "freeze_veto" in w and "W396" in w for w in res.info["warnings"])


def test_track_writes_freeze_columns_when_the_index_ran_w397(fog, tmp_path):
    from pdrlearn.cli import main
    from pdrlearn.io import write_session

    d = tmp_path / "s"
    write_session(fog, d)
    assert main(["track", "--no-plot", str(d), "--out", str(tmp_path / "on"), "--freeze-index"]) == 0
    bouts, steps = pd.read_csv(tmp_path / "on" / "bouts.csv"), pd.read_csv(tmp_path / "on" / "steps.csv")
    episodes = pd.read_csv(tmp_path / "on" / "freezes.csv")
    assert bouts["freeze_time_s"].sum() == pytest.approx(episodes["duration_s"].sum(), abs=0.6)
    inside = (steps["event_s"] >= episodes["start_s"].iloc[0]) & (steps["event_s"] <= episodes["end_s"].iloc[0])
    assert steps["in_freeze"].astype(bool).tolist() == inside.tolist() and inside.sum() >= 5
    assert main(["track", "--no-plot", str(d), "--out", str(tmp_path / "off")]) == 0  # not measured: no column
    assert "freeze_time_s" not in pd.read_csv(tmp_path / "off" / "bouts.csv")
    assert "in_freeze" not in pd.read_csv(tmp_path / "off" / "steps.csv")


def test_turns_csv_counts_the_steps_inside_each_turn_w398(tmp_path):
    from pdrlearn.sim import Turn
    from pdrlearn.track.clinical import add_turn_steps
    from pdrlearn.track.folder import clinical_tables
    from pdrlearn.track.waist import track_waist

    s = _sim([Stand(3.0), Straight(6.0), Turn(2 * np.pi), Straight(6.0), Stand(3.0)], 9307, 0.3, 0.5)
    res = track_waist(s, pipeline="waist-pendulum")
    turns = clinical_tables(res, None)["turns.csv"]
    ev = res.steps["event_s"].to_numpy(float)
    assert len(turns) and "turn_steps" in turns
    for _, r in turns.iterrows():
        assert r["turn_steps"] == int(((ev >= r["start_s"]) & (ev <= r["end_s"])).sum())
    hand = add_turn_steps(pd.DataFrame({"start_s": [1.0, 5.0], "end_s": [2.0, 6.0]}),
                          _steps([0.5, 1.0, 1.5, 2.0, 2.5, 5.5]).assign(unit="waist"))
    assert hand["turn_steps"].tolist() == [3, 1]  # the ends are inside
    foot = _steps([1.0, 1.5]).assign(unit="foot")
    # decision L749 (amends W398's empty foot column): a foot alone estimates 2 x its strides inside the turn
    foot_only = add_turn_steps(pd.DataFrame({"start_s": [1.0], "end_s": [2.0]}), foot)
    assert foot_only["turn_steps"].tolist() == [4] and foot_only["turn_steps_source"].tolist() == ["foot_x2"]


def test_hint_and_in_freeze_read_a_step_at_the_same_time_closing_reread():
    """Closing re-read (session 37): freeze_hint read the raw event_s (a NaN contact not counted) while in_freeze fell
    back to start_s; both now read :func:`pdrlearn.track.freezes.contact_times`."""
    import numpy as np
    import pandas as pd

    from pdrlearn.track.freezes import add_freeze_columns, contact_times, freeze_hint

    steps = pd.DataFrame({"start_s": np.arange(0.0, 30.0, 0.5), "end_s": np.arange(0.5, 30.5, 0.5)})
    steps["event_s"] = steps["start_s"] + 0.1
    steps.loc[24:27, "event_s"] = np.nan  # four contacts without a time inside the episode (12-14 s)
    assert np.array_equal(contact_times(steps)[24:28], steps["start_s"].to_numpy()[24:28])
    rows = [{"start_s": 11.0, "end_s": 15.0, "duration_s": 4.0}]
    add_freeze_columns(pd.DataFrame(columns=["start_s", "end_s"]), steps, rows)
    line = freeze_hint(rows, steps)
    n = int(steps["in_freeze"].sum())
    assert line is not None and line.startswith(f"{n} counted step(s)"), (n, line)


def test_track_all_keeps_the_freeze_column_in_the_combined_bouts_w397(fog, tmp_path):
    """Review R5 (session 37): track-all's combined bouts.csv kept only BOUT_COLUMNS and dropped W397's
    freeze_time_s, which each session's bouts.csv has with --freeze-index."""
    from pdrlearn.cli import main
    from pdrlearn.io import write_session

    write_session(fog, tmp_path / "study" / "a")
    assert main(["track-all", "--no-plot", str(tmp_path / "study"), "--out", str(tmp_path / "ta"),
                 "--freeze-index"]) == 0
    one = pd.read_csv(tmp_path / "ta" / "a" / "bouts.csv")
    both = pd.read_csv(tmp_path / "ta" / "bouts.csv")
    assert "freeze_time_s" in one and "freeze_time_s" in both
    assert both["freeze_time_s"].tolist() == one["freeze_time_s"].tolist()
