"""Decision E344 (session 52, FB, review s52r1 F2): ``run --at-times`` gives, per time, the streamed trajectory row
the live device had been *returned* by then (the push that returned the stride, E288's data time), not the last
stride that had *ended* by then (a stride comes back 0.5-0.9 s after its end in 1 s pushes: E332's table read one
stride ahead); ``stride_end_s`` and the new ``returned_s`` are empty while the start row is shown. Kernel level;
`run --at-times` end to end: ``tests/test_export_s51_e332.py::test_at_times_holds_the_last_returned_row``."""

from __future__ import annotations

import pandas as pd
import pytest

from pdrlearn.track.at_times import live_positions


def test_a_stride_is_shown_from_its_return_not_its_end_e344():
    traj = pd.DataFrame({"t": [0.5, 1.6, 2.7], "x": [0.0, 1.4, 2.8], "y": 0.0, "z": 0.0, "pos_sigma_m": [0, .1, .2]})
    got = live_positions(traj, [0.0, 1.0, 1.7, 2.3, 2.5, 3.5], returned_s=[2.4, 3.4])
    # between the first stride's start and its return: the start row, with no stride time (was 0.5, the start's)
    assert got["stride_end_s"].iloc[:4].isna().all() and got["returned_s"].iloc[:4].isna().all()
    assert list(got["x"]) == [0.0, 0.0, 0.0, 0.0, 1.4, 2.8]  # 1.7 and 2.3: ended, not yet returned
    assert list(got["stride_end_s"].iloc[4:]) == [1.6, 2.7] and list(got["returned_s"].iloc[4:]) == [2.4, 3.4]
    assert list(got.columns[:3]) == ["t", "stride_end_s", "returned_s"]
    with pytest.raises(ValueError):
        live_positions(traj, [1.0], returned_s=[2.4])  # one return time per stride row


def test_no_stride_returned_gives_empty_positions_e344():
    got = live_positions(pd.DataFrame(columns=["t", "x", "y", "z"], dtype=float), [1.0, 2.0], returned_s=[])
    assert len(got) == 2 and got[["stride_end_s", "returned_s", "x"]].isna().all().all()
