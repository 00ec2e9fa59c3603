"""Decisions L684 / L685 (session 46, trial T1 F1 / F7): a slow limp's short-stance foot at 100 Hz.

L684: the streamed stance segmenter (``track --streaming``, ``run``, ``runtime.Tracker``) took the terminal swing's lull
before the heel strike (|w| under E7's 0.8 rad/s for 0.07-0.10 s) for a stance and split the operated foot's strides
(T1: 46 strides for 36); where L597's rule finds the foot's own rhythm slow, a streamed stance must last
``STREAMED_RHYTHM_FRAC`` x the foot's stride period (an option in session 46, the default since L696). L685:
``--toe-off``'s short-stance line names an antalgic gait."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main as cli
from pdrlearn.io.plasys import read_session
from pdrlearn.kernels import foot_rhythm as FR
from pdrlearn.kernels import stride as SK

OLD = {"stance_rhythm_frac": 0}  # the segmenter before L684 (L684 the default since L696)

#: trial T1's operated-foot walk (session 46, F1), shortened: 0.42 m x 0.7 s steps, the right foot's stance short
LIMP = ["--route", "stand:3, straight:15, stand:3", "--step-length", "0.42", "--step-time", "0.7",
        "--stance-time-asymmetry", "0.15", "--step-time-asymmetry", "0.25", "--paretic-side", "right",
        "--bounce", "pendulum", "--user-seed", "4601"]


@pytest.fixture(scope="module")
def limp(tmp_path_factory):
    out = {}
    for hz in (100, 20):
        d = tmp_path_factory.mktemp("l684") / f"limp{hz}"
        assert cli(["simulate", *LIMP, "--rate", str(hz), "--out", str(d)]) == 0
        out[hz] = d
    return out


def _true_strides(folder) -> int:
    ics = pd.read_csv(folder / "ics.csv")
    return int((ics["foot"] == "right").sum())


def test_the_rhythm_rule_is_shared_and_asks_nothing_at_a_normal_rhythm_l684():
    # offline (L597: the 0.1 s window) and streamed (L29's 0.07 s minimum run) read the same kernel
    assert FR.min_rest_s(1.0, 0.07) == 0.0  # a normal stride: no rule (0.06 s under the run)
    assert FR.min_rest_s(1.4, 0.07) == pytest.approx(0.084)
    assert FR.min_rest_s(1.4, 0.1) == 0.0 and FR.min_rest_s(2.0, 0.1) == pytest.approx(0.12)  # L597 offline
    assert FR.min_rest_s(float("nan"), 0.07) == 0.0
    t = np.arange(0, 12, 0.01)
    w = 1 + np.sin(2 * np.pi * t / 1.4)
    assert FR.trailing_period(t, w) == pytest.approx(1.4, abs=0.02)
    assert np.isnan(FR.trailing_period(t[:50], w[:50]))  # 0.5 s: no period to read
    # a 3 s gap in the means (dropped samples, a restart) neither stretches the lags: the samples' median rate (the
    # mean rate over the span read 1.81 s here; E300's restart test lost a stride to it)
    gap = (t < 4) | (t >= 7)
    assert FR.trailing_period(t[gap], w[gap]) == pytest.approx(1.4, abs=0.05)


def test_streamed_limp_strides_are_whole_l684(limp):
    """Printed on this walk (100 Hz): the old segmenter 35 strides for 19 (the lulls' fragments), now 20: the first
    stride's 0.40 s fragment stays (no period read yet), every other stride 1.11 s or longer."""
    truth = _true_strides(limp[100])
    g = read_session(limp[100]).streams["fGyroscope"]
    new = SK.stance_strides(g.t, g.values)  # the default (L696)
    old = SK.stance_strides(g.t, g.values, OLD)
    assert len(old) >= truth + 5  # the split L684 fixes (fails here if the lull were no stance anyway)
    assert truth <= len(new) <= truth + 1
    assert np.sort(np.diff(new, axis=1).ravel())[1] > 1.0  # at most one fragment


def test_the_20_hz_limp_and_a_normal_walk_keep_their_strides_l684(limp, tmp_path):
    g = read_session(limp[20]).streams["fGyroscope"]
    assert len(SK.stance_strides(g.t, g.values)) == _true_strides(limp[20])  # printed: 19 (old 19)
    d = tmp_path / "normal"
    assert cli(["simulate", "--route", "stand:3, straight:12, stand:3", "--user-seed", "4601", "--rate", "100",
                "--out", str(d)]) == 0
    g = read_session(d).streams["fGyroscope"]
    np.testing.assert_array_equal(SK.stance_strides(g.t, g.values), SK.stance_strides(g.t, g.values, OLD))


def test_live_equals_track_streaming_on_the_limp_l684(limp):
    """One segmenter: the runtime Tracker (the shipped bundle, no classifier) and ``track --streaming`` give the same
    strides and positions on the limping walk."""
    import logging

    from pdrlearn.track.plasys import track_plasys
    from tests.test_live_heading_s45_e289 import _live

    session = read_session(limp[100])
    steps = _live(session)
    logging.disable(logging.WARNING)
    try:
        res = track_plasys(session, streaming=True, method="M2")
    finally:
        logging.disable(logging.NOTSET)
    st = res.steps  # the default segmenter (L684's rule, L696): live and streamed one mechanism
    assert [(x.start_s, x.end_s) for x in steps] == list(zip(st["start_s"], st["end_s"], strict=True))
    traj = res.trajectory.iloc[1:]
    d = np.hypot([x.x for x in steps] - traj["x"].to_numpy(), [x.y for x in steps] - traj["y"].to_numpy())
    assert d.max() < 1e-6


def test_a_bad_rhythm_fraction_is_refused_l684():
    from pdrlearn.errors import DataError

    with pytest.raises(DataError, match="stance_rhythm_frac"):
        SK.StanceSegmenter(stance_rhythm_frac=-0.1)


def test_short_stance_line_names_an_antalgic_gait_l685():
    from pdrlearn.track.gait import stance_share_warning
    from pdrlearn.warning_lines import warning_code

    line = stance_share_warning(pd.DataFrame({"stance_pct": np.full(12, 46.0)}))
    assert "antalgic" in line and "operated" in line and "--stance-time-asymmetry" in line
    assert "a unit on each foot" in line and "L685" in line
    assert "prosthetic foot's, if it is one" in line  # the sensor cause stays named (L763: on no foot by default)
    assert warning_code(line) == "L285"  # E170's code unchanged
