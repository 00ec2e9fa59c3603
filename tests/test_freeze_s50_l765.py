"""Decision L765 (not adopted: ``foot_freezes(..., walked_strides=True)``, off): the time walking strides (at least
0.15 m within at most 3 s) cover is cut out of a foot freeze-index episode. Trial s50t3 (F2): slow shufflers'
steady 0.4 m strides every 1.4 s read as 22 freeze episodes on user 17401 (little 0.5-3 Hz power, heel strikes in
3-8 Hz)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pandas as pd

from pdrlearn.track.freezes import foot_freezes, walked_freezes


def _steps(a: float, b: float, every: float = 1.4, length: float = 0.4) -> pd.DataFrame:
    start = np.arange(a, b, every)
    return pd.DataFrame({"start_s": start, "end_s": start + every, "length_m": length, "sideways": False})


def _row(a: float, b: float) -> dict:
    return {"freeze": 1, "start_s": a, "end_s": b, "duration_s": b - a, "peak_fi": 4.0}


def test_an_episode_filled_by_walking_strides_is_left_out_and_named_l765():
    kept, lines = walked_freezes([_row(20.0, 24.0), _row(40.0, 44.0)], _steps(0.0, 30.0))
    assert [(r["freeze"], r["start_s"]) for r in kept] == [(1, 40.0)]  # the one with no stride stays, renumbered
    assert len(lines) == 1 and "20.0-24.0 s" in lines[0] and "L765" in lines[0]


def test_short_or_long_strides_are_no_walking_l765():
    short = _steps(0.0, 30.0, length=0.1)  # trembling steps under 0.15 m
    long = _steps(0.0, 30.0, every=6.0, length=1.0)  # a 6 s "stride" holds a pause
    for steps in (short, long):
        kept, lines = walked_freezes([_row(20.0, 24.0)], steps)
        assert len(kept) == 1 and not lines


def test_the_foot_track_leaves_out_a_trembling_walk_but_keeps_a_freeze_l765():
    t = np.arange(0.0, 60.0, 1 / 50.0)
    shake = np.where(((t > 10) & (t < 20)) | ((t > 40) & (t < 50)), 2.0 * np.sin(2 * np.pi * 5.0 * t), 0.0)
    acc = np.column_stack([np.zeros_like(t), np.zeros_like(t), 9.81 + shake])
    session = SimpleNamespace(streams={"fAccelerometer": SimpleNamespace(t=t, values=acc)})
    steps = pd.concat([_steps(2.0, 21.0), _steps(30.0, 39.0), _steps(51.0, 58.0)], ignore_index=True)
    rows, lines = foot_freezes(session, "plasys", steps, walked_strides=True)
    assert len(foot_freezes(session, "plasys", steps)[0]) == 2  # off by default (not adopted)
    assert len(rows) == 1 and 38.0 <= rows[0]["start_s"] <= 42.0  # the stride-free tremble stays
    assert any("L765" in line for line in lines)


def test_a_freeze_the_shuffling_ran_into_keeps_its_stride_free_time_l765():
    """Users 17614 / 17619 (the first rule, failed): the shuffle's false episodes ran into the freeze (35.2-41.2 s)
    as one episode (27.75-56.75 s) that the strides around it filled for more than half; the stride-free time stays."""
    steps = pd.concat([_steps(20.0, 35.0), _steps(41.2, 60.0)], ignore_index=True)
    kept, lines = walked_freezes([_row(27.75, 56.75)], steps)
    assert [(r["start_s"], r["end_s"]) for r in kept] == [(35.4, 41.2)]  # the last stride before ends at 35.4 s
    assert len(lines) == 1 and "shortened" in lines[0]
