"""Session 41, fixer FP (trial T4 finding 2): a curb inside a ramp or a lagging barometric climb is kept when its
neighbours are level (L587); a ramp's steady rise is not a curb."""

from __future__ import annotations

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.track.curbs import isolated_rows

#: T4's route: a 6 % ramp up, 4 m level, a 0.15 m curb up, 4 m level, a 10 % ramp down
T4_ROUTE = ("stand:2, straight:4, slope:10:6, straight:4, up:1:0.15:0.3, straight:4, slope:6:-10, straight:4, "
            "stand:2")


@pytest.fixture(scope="module")
def t4_session(tmp_path_factory):
    d = tmp_path_factory.mktemp("t4") / "s"
    assert main(["simulate", "--route", T4_ROUTE, "--user-seed", "11645", "--rate", "50", "--out", str(d)]) == 0
    return d


@pytest.mark.parametrize("fused_climb", [False, True])
def test_a_curb_after_a_ramp_is_listed_l587(t4_session, tmp_path, fused_climb):
    args = []
    if fused_climb:
        (tmp_path / "fc.json").write_text('{"fused_climb": true}')
        args = ["--params", str(tmp_path / "fc.json")]
    out = tmp_path / "t"
    assert main(["track", str(t4_session), "--altitude", "fused", "--no-plot", "--out", str(out), *args]) == 0
    curbs = pd.read_csv(out / "curbs.csv")
    assert len(curbs) == 1 and curbs["direction"].tolist() == ["up"]  # not the 10 % ramp down's strides
    assert 0.10 <= curbs["dz_m"].iloc[0] <= 0.20
    assert 21.5 <= (curbs["start_s"].iloc[0] + curbs["end_s"].iloc[0]) / 2 <= 23.5  # the curb: 22.06-22.74 s


def test_isolated_rows_kernel_l587():
    # a curb between level strides; a 1:12 ramp's steady 0.10 m strides; a curb at each end of the table
    assert isolated_rows([0, 0.14, 0.045]).tolist() == [False, True, False]
    assert not isolated_rows([0, 0.10, 0.10, 0.10, 0]).any()
    assert isolated_rows([-0.12, 0.0, 0.0, 0.15]).tolist() == [True, False, False, True]
    assert isolated_rows([float("nan"), 0.12, 0.06]).tolist() == [False, False, False]
