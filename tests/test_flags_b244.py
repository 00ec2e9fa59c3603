"""A steps table's true/false columns read back from CSV strings (decision B244)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.track.bilateral import bilateral_gait, foot_events
from pdrlearn.track.flags import flag_values


def test_flag_values_spellings():
    col = pd.Series([True, False, "True", "False", " true ", "1", "0", 1, 0, 1.0, np.nan, None, ""], dtype=object)
    assert flag_values(col).tolist() == [True, False, True, False, True, True, False, True, False, True,
                                         False, False, False]


def _foot(ic, impossible) -> pd.DataFrame:
    ic = np.asarray(ic, float)
    return pd.DataFrame({"start_s": ic - 0.6, "end_s": ic + 0.2, "event_s": ic, "tc_s": ic - 0.45, "length_m": 1.2,
                         "gap_s": 0.0, "unit": "foot", "impossible": impossible})


@pytest.mark.parametrize("flag", ["False", np.nan, False, "0"])
def test_bilateral_reads_not_impossible_strings(flag):  # review S29 item 6: "False" and NaN read as True on main
    left, right = _foot([1.0, 2.0, 3.0], [flag] * 3), _foot([1.5, 2.5, 3.5], [flag] * 3)
    assert np.isfinite(foot_events(left)["length_m"]).all()
    assert bilateral_gait(left, right)["walk"]["stride_length_m_left"] == pytest.approx(1.2)
    assert not np.isfinite(foot_events(_foot([1.0, 2.0], ["True", "False"]))["length_m"][0])


def _ics(start, step, n):
    return start + step * np.arange(n)


def test_two_walks_whose_clocks_overlap_warn_b245(caplog):
    one = bilateral_gait(_foot(_ics(1.0, 1.1, 20), False), _foot(_ics(1.55, 1.1, 20), False))  # one walk
    assert not [r for r in caplog.records if "B245" in r.getMessage()]
    assert one["walk"]["n_steps_left"] > 15
    # a short walk on one foot and a long one on the other (the review's stairs-down left + level right)
    bilateral_gait(_foot(_ics(1.0, 1.1, 15), False), _foot(_ics(1.55, 1.1, 30), False))
    lines = [r.getMessage() for r in caplog.records if "B245" in r.getMessage()]
    assert len(lines) == 1 and "one walk on one clock" in lines[0]


STAIRS, LEVEL = "datasets/real/gaitmap_stairs_down_left", "datasets/real/gaitmap_level_right"


@pytest.mark.skipif(not __import__("os").path.isdir(STAIRS), reason="real gaitmap recordings absent")
def test_gait_refuses_two_recordings_of_different_activities_b245(capsys):
    from pdrlearn.cli import main

    assert main(["gait", STAIRS, LEVEL]) != 0
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "different recordings" in err[0] and "activity" in err[0]
