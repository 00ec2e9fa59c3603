"""Decision L715 (session 48, review R1 F1; measured, not adopted - its rule's distance clause failed): the candidate
``StanceSegmenter(foot_gap_cut=True)`` cuts the streamed rhythm's series at a gap in the foot's own samples, not at the
hole a stand leaves in it (L696 keeps a stand inside a walk out of the means; L698, the default, reads that hole as a
foot gap, so after every stand no period is read and a limping walk's lull fragments come back)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main as cli
from pdrlearn.io.plasys import read_session
from pdrlearn.kernels import foot_rhythm as FR
from pdrlearn.kernels import stride as SK

ROUTE = "stand:1, straight:6, stand:3, straight:5, stand:1"  # R1's stand walk, shortened
LIMP = ["--step-time", "0.70", "--step-length", "0.400", "--stance-time-asymmetry", "0.10",
        "--step-time-asymmetry", "0.25", "--paretic-side", "right"]  # L684's limping walker 2 (experiments' limp_gait)


@pytest.fixture(scope="module")
def walks(tmp_path_factory):
    out = {}
    for name, extra in (("stands", []), ("gap", ["--gap", "foot:4:1"])):
        d = tmp_path_factory.mktemp("l715") / name
        assert cli(["simulate", "--route", ROUTE, "--user-seed", "15742", "--rate", "100", "--out", str(d),
                    *LIMP, *extra]) == 0
        out[name] = (read_session(d).streams["fGyroscope"], len(pd.read_csv(d / "steps.csv")))
    return out


def test_a_stand_inside_a_walk_is_no_foot_gap_l715(walks, monkeypatch):
    g, truth = walks["stands"]
    assert SK.StanceSegmenter().foot_gap_cut is False  # not adopted: L698's series cut is the default (R1 F1's split)
    assert len(SK.stance_strides(g.t, g.values)) == 17
    seg, holes = SK.StanceSegmenter(foot_gap_cut=True), []
    rest = seg._rhythm_rest

    def logged(min_run: float) -> float:
        tt, _ = seg._rhythm.arrays()
        holes.append(float(np.diff(tt).max()) if len(tt) > 2 else 0.0)
        return rest(min_run)

    seg._rhythm_rest = logged
    strides = seg.update(g.t, g.values)
    assert max(holes) > 2.5  # the stand's hole in the means (L696's skip) ...
    assert seg.foot_gap_end == g.t[0]  # ... is no gap in the foot's own samples
    # printed: truth 15; L698's series cut 17 (two lull fragments after the stand), the old segmenter 23
    assert len(strides) == truth == 15
    assert len(SK.stance_strides(g.t, g.values, {"stance_rhythm_frac": 0})) > truth


def test_a_foot_gap_still_cuts_the_series_l715(walks):
    g, _ = walks["gap"]
    after = g.t[g.t > 4.5][0]  # the first sample after the dropped second
    first = g.t < after + 1.0  # up to a second after the gap: under two periods, no reading
    seg = SK.StanceSegmenter()
    seg.update(g.t[first], g.values[first])
    assert np.diff(g.t).max() > FR.PERIOD_RANGE_S[0] and seg.foot_gap_end == after
    tt, m = seg._rhythm.arrays()
    assert tt[0] < 4.0 and np.isnan(FR.trailing_period(tt, m, since=seg.foot_gap_end))  # the candidate cuts, ...
    assert np.isnan(FR.trailing_period(tt, m))  # ... as L698's series cut does
    assert np.isfinite(FR.trailing_period(tt, m, since=-np.inf))  # joined across the gap, a period would be read
