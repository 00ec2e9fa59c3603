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
