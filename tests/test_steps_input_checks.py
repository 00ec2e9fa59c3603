"""Step scoring refuses what it used to score silently wrong (trial `extend`, session 23): a tolerance in
milliseconds (decision B167), an unknown ``unit`` (B168), events off the session's clock and an ``ic_ms`` column
in seconds (B169), tables that are not steps tables (B170); ``match_events`` gives the caller's indices (steps 36)."""

from __future__ import annotations

import shutil

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.steps import StepDetector, WaistICStepDetector, match_events, score_events, score_steps


@pytest.fixture(scope="module")
def foot(real_dir):
    return read_session(real_dir / "gaitmap_level_left")


def _ics(session) -> pd.DataFrame:
    """The session's own labelled contacts as a foot detector's table (F1 0.98: the reference also has the
    pre_ic_s that opens the walk)."""
    return pd.DataFrame({"event_s": session.steps["ic_s"].to_numpy(float), "unit": "foot"})


# -- B167: tolerance in seconds ------------------------------------------------------------------------------------
def test_tolerance_in_milliseconds_is_refused_in_python_and_the_cli(foot, real_dir, capsys):
    with pytest.raises(DataError, match=r"tolerance_s 250: the tolerance is in seconds.*250 ms is 0.25 s"):
        score_events([101.0], [1.0], tolerance_s=250)
    with pytest.raises(DataError, match="score_steps: tolerance_s 250"):
        score_steps(_ics(foot), foot, tolerance_s=250)
    assert score_events([1.1], [1.0], tolerance_s=2.0)["true_positives"] == 1  # the limit itself is allowed
    assert main(["steps", str(real_dir / "gaitmap_level_left"), "--tolerance", "250"]) != 0
    err = capsys.readouterr().err
    assert "--tolerance 250.0: the tolerance is in seconds" in err and "Traceback" not in err


# -- B168: the unit column ---------------------------------------------------------------------------------------
@pytest.mark.parametrize("bad", ["Waist", "lower_back"])
def test_unknown_unit_is_refused_not_scored_as_the_foot(foot, bad):
    with pytest.raises(DataError, match=f"score_steps: unit '{bad}' is not a steps-table unit; use one of foot, "
                                        "waist"):
        score_steps(_ics(foot).assign(unit=bad), foot)
    assert score_steps(_ics(foot), foot)["f1"] > 0.95


def test_a_detector_class_with_an_unknown_unit_is_refused(foot):
    class MyWaist(WaistICStepDetector):
        name, unit = "my-waist", "lower_back"

    with pytest.raises(DataError, match="detector my-waist: unit 'lower_back' is not a steps-table unit"):
        MyWaist().detect(read_session(foot.folder.parent / "mobgap_HA001_Test11_Trial1"))


# -- B170: not a steps table --------------------------------------------------------------------------------------
def test_tables_without_unit_or_event_s_and_arrays_get_one_line(foot):
    ev = foot.steps["ic_s"].to_numpy(float)
    with pytest.raises(DataError, match="no unit column; add one"):
        score_steps(pd.DataFrame({"event_s": ev}), foot)
    with pytest.raises(DataError, match="no event_s column"):
        score_steps(pd.DataFrame({"t": ev, "unit": "foot"}), foot)
    with pytest.raises(DataError, match="steps is a ndarray, not a steps table"):
        score_steps(ev, foot)
    assert score_steps(pd.DataFrame({"event_s": ev}), foot, unit="foot")["f1"] > 0.95


# -- B169: range checks -------------------------------------------------------------------------------------------
def test_events_off_the_session_clock_are_refused(foot):
    """A detector that returns sample indices: events far past the recording's end."""
    idx = np.round((foot.steps["ic_s"].to_numpy(float) - foot.t_start) * 102.4)
    with pytest.raises(DataError, match=r"score_steps: \d+ of \d+ step event\(s\).*lie outside the session's"):
        score_steps(pd.DataFrame({"event_s": idx, "unit": "foot"}), foot)

    class Indices(StepDetector):
        name = "indices"
        unit = "foot"
        input_columns = ("ax", "ay", "az")

        def _inputs(self, session):
            acc = session.streams["fAccelerometer"]
            return acc.t, acc.values, {}

        def _make_processor(self, fs, **context):
            class P:  # the sample index of every 100th sample from the 200th, as a user's detector did
                n = 0

                def process(self, t, v):
                    self.n += len(t)
                    return []

                def flush(self):
                    return [(float(i), float(i), float(i) + 1, 1.0, {}) for i in range(200, self.n, 100)]
            return P()

    with pytest.raises(DataError, match="indices on 'gaitmap_level_left': .* lie outside the session's"):
        Indices().detect(foot)


def test_steps_csv_with_ic_ms_in_seconds_is_refused(real_dir, tmp_path):
    d = tmp_path / "s"
    shutil.copytree(real_dir / "gaitmap_level_left", d)
    st = pd.read_csv(d / "steps.csv")
    st["ic_ms"] = st["ic_ms"] / 1000.0
    st.to_csv(d / "steps.csv", index=False)
    with pytest.raises(DataError, match=r"steps.csv: none of the 28 ic_ms values lies within its own stride's "
                                        r"\[start_ms, end_ms\].*multiply by 1000"):
        read_session(d)


# -- steps decision 36: the caller's indices ----------------------------------------------------------------------
def test_match_events_returns_the_callers_indices_of_unsorted_input():
    det, ref = np.array([3.05, 1.02, 4.1, 2.0]), np.array([4.0, 1.0, 2.0, 3.0])
    i, j = match_events(det, ref, 0.25)
    assert np.allclose(det[i], ref[j], atol=0.11) and len(i) == 4
    assert j.tolist() == [1, 2, 3, 0]  # reference-time order
    sc = score_events(det, ref, tolerance_s=0.25)
    assert sc["timing_error_mean_s"] == pytest.approx((0.05 + 0.02 + 0.1 + 0.0) / 4)
