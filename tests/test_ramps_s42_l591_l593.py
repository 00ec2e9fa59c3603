"""Session 42, implementer I2: a written track finds its ramps once and passes them down (``found=``, L593; the
tables and summary keys the same as when each finds its own), and L591's not-adopted candidate's kernel
(``without_stair_climbs``: a stair climb keeps L39's level heights)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.kernels.barometer import without_stair_climbs
from pdrlearn.track.curbs import curb_table
from pdrlearn.track.grade import grade_summary, ramp_table, track_ramps
from pdrlearn.track.ramp_audit import ramp_run_table

INFO = {"altitude_source": "fused"}


def _steps(dz) -> pd.DataFrame:
    n = len(dz)
    t = np.arange(n + 1) * 1.0
    return pd.DataFrame({"start_s": t[:-1], "end_s": t[1:], "length_m": np.full(n, 1.4), "dz_m": dz,
                         "unit": "foot"})


#: level, a 7 % ramp of 8 strides, level, a 0.15 m curb between level strides, level, a 5 % ramp down
DZ = [0.0] * 4 + [0.098] * 8 + [0.0] * 4 + [0.15] + [0.0] * 3 + [-0.07] * 4 + [0.0] * 3


def test_found_ramps_give_the_tables_each_finds_alone_l593():
    st = _steps(DZ)
    traj = pd.DataFrame({"t": np.arange(len(st) + 1.0), "x": np.arange(len(st) + 1.0) * 1.4,
                         "y": 0.0, "z": np.concatenate([[0.0], np.cumsum(DZ)])})
    found = track_ramps(st, INFO)
    assert len(found[0]) == 2
    pd.testing.assert_frame_equal(ramp_table(st, INFO, traj, found=found), ramp_table(st, INFO, traj))
    pd.testing.assert_frame_equal(ramp_run_table(st, INFO, traj, found=found), ramp_run_table(st, INFO, traj))
    pd.testing.assert_frame_equal(curb_table(st, traj, INFO, found=found), curb_table(st, traj, INFO))
    assert grade_summary(st, INFO, found=found) == grade_summary(st, INFO)
    # the found ramps are what the tables list: another table's ramps change them
    other = track_ramps(_steps(DZ[:14] + [0.0] * (len(DZ) - 14)), INFO)
    assert len(ramp_table(st, INFO, traj, found=other)) == 1
    assert grade_summary(st, INFO, found=other)["n_ramps"] == 1


def test_curbs_find_their_own_ramps_on_rows_out_of_time_order_l593(monkeypatch):
    import pdrlearn.track.grade as grade

    seen, orig = [], grade.table_ramps

    def spy(steps, info, found=None):
        seen.append(found)
        return orig(steps, info, found)

    monkeypatch.setattr(grade, "table_ramps", spy)
    st = _steps(DZ)
    found = track_ramps(st, INFO)
    curb_table(st, None, INFO, found=found)
    shuffled = st.iloc[::-1].reset_index(drop=True)  # curb_table sorts it: the given ramps' rows are not its rows
    curb_table(shuffled, None, INFO, found=track_ramps(shuffled, INFO))
    assert seen[0] is found and seen[1] is None


def test_without_stair_climbs_clears_a_climb_with_a_stair_stride_l591():
    climbing = np.array([0, 1, 1, 1, 0, 0, 1, 1, 1, 0], bool)
    raw = np.array([0, 0.07, 0.07, 0.07, 0, 0, 0.05, 0.17, 0.05, 0])  # a 5 % ramp; a climb with a 0.17 m stair
    length = np.full(10, 1.4)
    length[7] = 0.3
    out = without_stair_climbs(climbing, raw, length, 20.0)
    assert out.tolist() == [False, True, True, True, False, False, False, False, False, False]
    assert without_stair_climbs(climbing, raw, length, 60.0).tolist() == climbing.tolist()
    assert climbing[7]  # the input is not changed


@pytest.mark.parametrize("n", [0, 1])
def test_without_stair_climbs_edges_l591(n):
    assert without_stair_climbs(np.ones(n, bool), np.zeros(n), np.ones(n), 20.0).tolist() == [True] * n
