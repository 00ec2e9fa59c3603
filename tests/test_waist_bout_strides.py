"""Decision W25: each reference bout's length also from its own strides (steps x half the mean stride),
because INDIP's bout `Length` leaves out steps without a time (docs/external-data.md X2b)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.io import Session
from pdrlearn.waist.evaluate import bout_stride_length, distance_metrics
from pdrlearn.waist.events import steps_from_events

REAL = Path(__file__).resolve().parents[1] / "datasets" / "real"


def _session(length_m: float, *, untimed: bool = True, duplicate: bool = True) -> Session:
    # contacts every 0.5 s from 1.0 to 4.0 s; the one at 2.5 s has no time (INDIP NaN)
    ic = [1.0, 1.5, 2.0, 3.0, 3.5, 4.0] + ([3.505] if duplicate else []) + ([] if untimed else [2.5])
    ics = pd.DataFrame({"ic_s": sorted(ic)})
    strides = pd.DataFrame({"start_s": [1.0, 1.5, 2.0, 2.5, 3.0],
                            "end_s": [2.0, 2.5, 3.0, 3.5, 4.0],
                            "length_m": [1.2, 1.4, np.nan, np.nan, 1.0]})
    extras = {"bouts": pd.DataFrame({"start_s": [1.0], "end_s": [4.0], "length_m": [length_m]}), "ics": ics}
    if untimed:
        extras["ics_untimed"] = pd.DataFrame({"after_s": [2.0], "before_s": [3.0]})
    return Session(name="strides", streams={}, steps=strides, extras=extras)


def test_stride_length_counts_untimed_contacts_and_merges_duplicates():
    s = _session(2.0)
    length, n = bout_stride_length(s, 1.0, 4.0)
    assert n == 6  # 7 contacts (6 timed + 1 untimed; the duplicate 10 ms apart is one) -> 6 steps
    assert length == pytest.approx(6 * np.mean([1.2, 1.4, 1.0]) / 2)
    # the same bout with every contact timed and no duplicate gives the same count
    assert bout_stride_length(_session(2.0, untimed=False, duplicate=False), 1.0, 4.0)[1] == 6


def test_distance_metrics_reports_both_references():
    s = _session(3.0)  # INDIP-like Length shorter than the steps x mean step (X2b)
    t = np.arange(0.0, 5.0, 0.01)
    st = steps_from_events(t, np.round(np.arange(1.0, 4.01, 0.5) * 100).astype(int), max_step_s=1.5)
    st["length_m"] = np.where(st["has_next"], 0.6, 0.0)
    m = distance_metrics(st, s)
    ref_s = 6 * np.mean([1.2, 1.4, 1.0]) / 2
    assert m["distance_error_pct"] == pytest.approx(100 * (3.6 - 3.0) / 3.0)
    assert m["distance_error_strides_pct"] == pytest.approx(100 * (3.6 - ref_s) / ref_s)
    assert m["bout_distance_error_strides_median_pct"] == pytest.approx(abs(100 * (3.6 - ref_s) / ref_s))
    b = m["bouts"][0]
    assert b["n_steps"] == 6 and b["n_reference_steps"] == 6


def test_without_reference_strides_only_the_length_error():
    s = _session(3.0)
    s.steps = None
    t = np.arange(0.0, 5.0, 0.01)
    st = steps_from_events(t, np.round(np.arange(1.0, 4.01, 0.5) * 100).astype(int), max_step_s=1.5)
    st["length_m"] = np.where(st["has_next"], 0.6, 0.0)
    m = distance_metrics(st, s)
    assert "distance_error_pct" in m and "distance_error_strides_pct" not in m
    assert np.isnan(m["bouts"][0]["reference_strides_m"])


@pytest.mark.skipif(not (REAL / "mobgap_HA001_Test5_Trial1").exists(), reason="real data not bundled")
def test_complete_indip_bout_agrees_with_its_length():
    """On a bout where INDIP times every contact the two references agree within 2 % (X2b)."""
    from pdrlearn.io import read_session
    from pdrlearn.waist.evaluate import reference_bouts

    s = read_session(REAL / "mobgap_HA001_Test5_Trial1")
    b = reference_bouts(s).iloc[0]
    length, n = bout_stride_length(s, b.start_s, b.end_s)
    assert n == 8 and length == pytest.approx(b.length_m, rel=0.02)
