"""Steps decision 86: `track`'s step_f1 scores the stride onto a labelled chain's first contact as `steps` does."""

from __future__ import annotations

import pandas as pd
import pytest

from pdrlearn.io import read_session
from pdrlearn.steps.evaluate import score_steps
from pdrlearn.track.base import TrackResult
from pdrlearn.track.evaluate import evaluate_track


@pytest.fixture(scope="module")
def level_right(real_dir):
    return read_session(real_dir / "gaitmap_level_right")


def _strides(level_right) -> pd.DataFrame:
    """The labelled strides as a track would give them (event_s = the IC) plus, before the first chain, the stride
    whose IC is the chain's opening contact (pre_ic_s): its middle lies inside the labelled interval."""
    st = level_right.steps
    rows = st[["start_s", "end_s"]].assign(event_s=st["ic_s"].to_numpy(float))
    pre0 = float(st["pre_ic_s"].min())
    first = pd.DataFrame({"start_s": [pre0 - 0.6], "end_s": [pre0 + 0.3], "event_s": [pre0]})
    return pd.concat([first, rows], ignore_index=True).assign(length_m=1.0, heading_rad=0.0, unit="foot")


def test_the_stride_onto_a_chains_first_contact_is_no_false_positive(level_right):
    steps = _strides(level_right)
    traj = pd.DataFrame({"t": [0.0], "x": [0.0], "y": [0.0], "z": [0.0]})
    m = evaluate_track(TrackResult(steps=steps, trajectory=traj, info={}), level_right)
    sc = score_steps(steps, level_right)
    assert sc["f1"] == 1.0  # `steps`' rule: the chain's opening contact is a reference event, matched
    assert m["step_precision"] == 1.0 and m["step_f1"] == 1.0  # before: precision 0.967, that stride a false positive


def test_a_stride_matching_no_contact_stays_a_false_positive(level_right):
    steps = _strides(level_right)
    steps.loc[0, "event_s"] = steps.loc[0, "event_s"] - 0.4  # its IC 0.4 s from every labelled contact
    traj = pd.DataFrame({"t": [0.0], "x": [0.0], "y": [0.0], "z": [0.0]})
    m = evaluate_track(TrackResult(steps=steps, trajectory=traj, info={}), level_right)
    n = len(level_right.steps)
    assert m["step_precision"] == pytest.approx(n / (n + 1))
