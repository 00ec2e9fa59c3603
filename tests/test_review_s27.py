"""Session 27 review fixes: numpy scalars are numbers where session 27's new checks read them (gait ranges L95 /
L195, ride rises S45), as the code before those decisions took them."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.errors import DataError
from pdrlearn.sim.ride import check_rise
from pdrlearn.track.gait import bout_range_flags, gait_range_warning, session_range_side


@pytest.mark.parametrize("kind", [float, np.float64, np.float32, np.int64, int])
def test_the_walking_range_reads_numpy_scalars(kind):
    """L95's line and L195's flag judged a numpy cadence before the session-27 refactor (``float(cad)``); a
    float32 or int64 figure (a table read back with its own dtypes) must not silently pass the range."""
    summary = {"median_cadence_spm": kind(200), "leg_length_m": kind(1) if kind is not int else 1}
    assert session_range_side(summary) == "fast"
    assert gait_range_warning(summary) is not None
    table = pd.DataFrame({"n_strides": np.array([10], dtype=kind), "cadence_spm": np.array([200], dtype=kind),
                          "speed_mps": np.array([1], dtype=kind)})
    assert bout_range_flags(table, None).tolist() == [True]
    assert gait_range_warning({"median_cadence_spm": kind(100)}) is None
    assert gait_range_warning({"median_cadence_spm": True}) is None  # a flag is no figure


@pytest.mark.parametrize("rise", [np.int64(9), np.int32(-9), np.float32(6.0), 9])
def test_a_ride_rise_may_be_a_numpy_number(rise):
    check_rise("lift", rise, "Lift")
    check_rise("escalator", rise, "Escalator")


@pytest.mark.parametrize("rise", [0, np.int64(0), float("nan"), np.float64("inf"), True, "9", 400, 0.5])
def test_a_bad_ride_rise_is_still_refused(rise):
    with pytest.raises(DataError, match="rise must be"):
        check_rise("escalator" if rise == 0.5 else "lift", rise, "Lift")


def test_the_unlocked_clock_line_names_the_option_that_gives_the_offset():
    """E111 added ``--clock-offset`` because L186's line tells the user to give the offset by hand; the line named
    only the Python keyword and editing the files."""
    from pdrlearn.kernels.align import unlocked_message

    line = unlocked_message({"offset_s": -0.226, "drift": 1.3e-3, "matched": 15, "foot_events": 18,
                             "residual_sd_s": 0.064}, "--align-units")
    assert "--clock-offset SECONDS instead of --align-units" in line and "waist_clock_offset_s" in line
    assert "by hand" in line and "decision L186" in line and "\n" not in line
