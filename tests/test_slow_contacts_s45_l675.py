"""Session 45 trial T1 finding F1 (decision L675): without insoles, at slow gait with a long stance, the foot detector
fires twice in a rest-to-rest stride (the foot's landing and, ~0.85 s before it, the other foot's contact felt through
the stance foot); `track` keeps the contact `pdrlearn steps` keeps (the latest, steps decision 34), one mechanism."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.displace.foot import one_per_rest_stride, rest_to_rest


def _rests():
    """Rests 0-1, 2-3 and 4-5 s at 100 Hz: two rest-to-rest strides."""
    t = np.arange(0, 6.0, 0.01)
    stance = ((t % 2.0) < 1.0)
    return t, stance


def test_rest_to_rest_keeps_the_latest_event_of_a_stride_given_events():
    """Two detections between the same two rests: the first row without events (as before), the later event with
    them, as `one_per_rest_stride` (steps decision 34) - the same rows."""
    t, stance = _rests()
    starts = np.array([1.05, 1.55, 3.1])
    ends = np.array([1.5, 1.95, 3.9])
    events = np.array([1.3, 1.9, 3.85])  # rows 0 and 1 make the first stride; row 1 is its landing
    i0, i1, rows = rest_to_rest(t, stance, starts, ends)
    assert list(rows) == [0, 2]
    j0, j1, latest = rest_to_rest(t, stance, starts, ends, events=events)
    assert list(latest) == [1, 2]
    assert np.array_equal(i0, j0) and np.array_equal(i1, j1)  # the strides (so the displacements) do not move
    assert list(one_per_rest_stride(t, stance, starts, ends, events)) == list(latest)


@pytest.fixture(scope="module")
def slow_long_stance(tmp_path_factory):
    """Trial T1's user 12760 (stance fraction 0.670), 0.3 m / 0.9 s, smooth rocker, no insoles, 8 m."""
    out = tmp_path_factory.mktemp("l675") / "u12760"
    assert main(["simulate", "--route", "stand:3, straight:8, stand:3", "--step-length", "0.3", "--step-time", "0.9",
                 "--rocker", "smooth", "--user-seed", "12760", "--rate", "100", "--out", str(out)]) == 0
    for f in out.glob("fForce*.csv"):
        f.unlink()
    return out


def test_track_takes_the_tracked_foots_contact_on_a_long_stance(slow_long_stance, tmp_path):
    """Every stride's event_s is the tracked (right) foot's labelled contact, not the other foot's (before L675 about
    half of them were 0.83-0.88 s late, on the left foot's contact), and the stride-time CV is near the truth's."""
    out = tmp_path / "t"
    assert main(["track", "--no-plot", str(slow_long_stance), "--out", str(out)]) == 0
    steps = pd.read_csv(out / "steps.csv")
    ics = pd.read_csv(slow_long_stance / "ics.csv")
    right = np.sort(ics.loc[ics["foot"] == "right", "ic_ms"].to_numpy(float) / 1000)
    ev = steps["event_s"].dropna().to_numpy(float)
    off = np.abs(ev[:, None] - right[None, :]).min(axis=1)
    assert len(ev) >= 10 and (off < 0.1).all(), np.round(off, 2)
    summary = json.loads((out / "summary.json").read_text())
    st = np.diff(right)
    st = st[st < 2.2 * np.median(st)]
    true_cv = 100 * st.std(ddof=1) / st.mean()
    cv = summary.get("stride_time_cv_pct")
    assert cv is not None and abs(cv - true_cv) < 2.0, (cv, true_cv)
