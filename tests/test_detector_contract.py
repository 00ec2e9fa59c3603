"""The contract every registered step detector keeps (docs/extending.md): the
steps table's columns, unit and times in s inside the session, and online == offline whatever the chunks.
Parametrised over :data:`pdrlearn.steps.DETECTORS`, so a detector registered before collection (or an installed
plug-in) is tested too."""

from __future__ import annotations

import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from pdrlearn.io import read_session
from pdrlearn.steps import DETECTORS, STEPS_COLUMNS, get_detector
from tests.conftest import REAL
from tests.steps_helpers import chunked
from tests.test_steps import foot_session

_CACHE: dict = {}


def _case(name):
    if name not in _CACHE:
        det = get_detector(name)
        if det.unit == "foot":  # a hand-made foot unit with force sensors (accel-force needs them)
            s, _ = foot_session(fs=50.0, force=True, n_strides=12, seed=7)
        else:  # a real lower-back walk with its frame (waist-ic needs one)
            s = read_session(REAL / "mobgap_HA001_Test5_Trial1")
        _CACHE[name] = (s, det, det._inputs(s), det.detect(s))
    return _CACHE[name]


@pytest.mark.parametrize("name", list(DETECTORS))
def test_steps_table_contract(name):
    s, det, (t, _, _), table = _case(name)
    assert det.name == name and det.unit in ("foot", "waist")
    assert list(table.columns[:len(STEPS_COLUMNS)]) == list(STEPS_COLUMNS)
    assert set(det.extra_columns) <= set(table.columns)
    assert len(table) > 5, f"{name} found {len(table)} steps on its unit's hand-made walk"
    assert (table["unit"] == det.unit).all() and table.attrs["detector"] == name
    ev = table["event_s"].to_numpy(float)
    assert (ev[1:] >= ev[:-1]).all()  # sorted, seconds on the session's clock
    assert t[0] <= ev.min() and ev.max() <= t[-1]
    assert (table["start_s"] <= table["end_s"]).all()
    assert table["confidence"].between(0, 1).all()


@pytest.mark.parametrize("name", list(DETECTORS))  # steps decision 79: every detector its own chunkings
@settings(max_examples=8, deadline=None)
@given(cuts=st.lists(st.integers(0, 150), min_size=1, max_size=10))
def test_online_equals_offline_for_every_detector(name, cuts):
    s, det, inputs, offline = _case(name)
    pd.testing.assert_frame_equal(offline.reset_index(drop=True), chunked(det, inputs, cuts), check_dtype=False)
