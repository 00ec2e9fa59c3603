"""Decisions L315 / L316 (session 31 prosthesis trial, findings 4 and 9): `track --toe-off` warns, as `gait` does (L285,
the same bound), when the foot's median stance is under 55 % of the cycle; the foot track's step-time reason names
`--pipeline waist-pendulum`, and its posture line, on a session with a lower-back unit, says to track that unit."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.cli.common import posture_line
from pdrlearn.track.bilateral import STANCE_MIN_PCT
from pdrlearn.track.clinical import step_time_asymmetry_report
from pdrlearn.track.gait import stance_share_warning


def test_stance_under_l285s_bound_warns_and_names_both_decisions():
    st = pd.DataFrame({"stance_pct": [48.0, 49.5, 50.0, 47.0, 52.0, np.nan]})
    line = stance_share_warning(st)
    assert line is not None and "median stance 49.5 %" in line and "L285" in line and "L315" in line
    assert f"under {STANCE_MIN_PCT:.0f} %" in line and "5 strides" in line
    assert stance_share_warning(st.assign(stance_pct=st["stance_pct"] + 15)) is None  # ~63 %: walking
    assert stance_share_warning(st.iloc[:3]) is None  # too few stance times to judge
    assert stance_share_warning(pd.DataFrame({"length_m": [1.0]})) is None  # no --toe-off


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    d = tmp_path_factory.mktemp("l315") / "sim"
    assert main(["simulate", "--route", "stand:3, straight:20, stand:3", "--user-seed", "6077", "--rate", "100",
                 "--out", str(d)]) == 0
    return d


def test_track_toe_off_warns_on_an_early_toe_off(walk, tmp_path, capsys, monkeypatch):
    assert main(["track", "--no-plot", str(walk), "--toe-off", "--out", str(tmp_path / "a")]) == 0
    assert "L315" not in capsys.readouterr().err  # a simulated walker's stance is ~63 %

    import pdrlearn.track.toeoff as toeoff

    def early(t, gyr, start_s, end_s, event_s, **kw):  # the toe-off half way from the window start to the IC
        s, e = np.asarray(start_s, float), np.asarray(event_s, float)
        return s + 0.2 * (e - s)

    monkeypatch.setattr(toeoff, "toe_off_times", early)
    assert main(["track", "--no-plot", str(walk), "--toe-off", "--out", str(tmp_path / "b")]) == 0
    cap = capsys.readouterr()
    assert "toe-off: median stance" in cap.err and "L315" in cap.err
    # L316 / W586: this session has a lower-back unit, so the foot track's posture line is that unit's split
    assert "posture: standing" in cap.out and "decisions W222, W586" in cap.out
    assert "a foot unit sees no trunk" not in cap.out


def test_posture_line_without_a_lower_back_unit_is_unchanged():
    assert "a foot unit sees no trunk" in posture_line({"standing_time_s": None})
    assert "--pipeline waist-pendulum" in posture_line({"standing_time_s": None}, waist_unit=True)


def test_foot_step_time_reason_names_the_waist_pipeline():
    reason = step_time_asymmetry_report(pd.DataFrame({"unit": ["foot"], "stride_time_s": [1.1]}))["reason"]
    assert "pdrlearn gait LEFT_DIR RIGHT_DIR" in reason and "--pipeline waist-pendulum" in reason
