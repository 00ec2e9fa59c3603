"""Session 45 trial T1 finding F6 (decision L676): `--bout-rule mobgap` on a foot track compares the same-foot contact
gap less one step time (the other foot's unseen contact) with Mobilise-D's 3 s break between consecutive contacts of
both feet; a lower-back track's contacts are both feet's and are compared as they are."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.track.bouts import bout_rule, contact_gaps, detected_bouts


def _table(contacts: np.ndarray, unit: str) -> pd.DataFrame:
    """A steps table whose rows end at ``contacts`` (s), each 0.3 m."""
    c = np.asarray(contacts, dtype=float)
    start = np.r_[c[0] - 1.0, c[:-1]]
    return pd.DataFrame({"start_s": start, "end_s": c + 0.2, "event_s": c, "length_m": 0.3, "unit": unit})


def _walk(stride_s: float, stop_gaps: list[float], n: int = 6) -> np.ndarray:
    """One foot's contacts: ``n`` strides of ``stride_s``, then each stop's same-foot gap and ``n`` more strides."""
    out = list(np.arange(n) * stride_s)
    for gap in stop_gaps:
        out.append(out[-1] + gap)
        out += list(out[-1] + np.arange(1, n) * stride_s)
    return np.array(out)


def test_a_slow_walkers_short_stop_does_not_split_a_foot_bout():
    """The trial's stops: 1.8 s strides, same-foot gaps 3.33 and 3.19 s (both feet's 2.43 / 2.32 s): one bout, as
    Mobilise-D's rule gives on both feet's contacts (it gave three before L676)."""
    rule = bout_rule(preset="mobgap")
    foot = _table(_walk(1.8, [3.33, 3.19]), "foot")
    bouts = detected_bouts(foot, rule)
    assert len(bouts) == 1, bouts[["start_s", "end_s"]]
    assert np.allclose(np.sort(contact_gaps(foot, 3.0))[-2:], [3.19 - 0.9, 3.33 - 0.9])


def test_a_foot_gap_over_the_break_after_one_step_still_splits():
    """A same-foot gap of 4.2 s (both feet's ~3.3 s) still ends the bout; a lower-back track's contacts are both
    feet's, so its 3.33 s gap ends a bout as before."""
    rule = bout_rule(preset="mobgap")
    assert len(detected_bouts(_table(_walk(1.8, [4.2]), "foot"), rule)) == 2
    waist = _table(_walk(0.9, [3.33], n=12), "waist")
    assert np.allclose(contact_gaps(waist, 3.0), np.diff(waist["event_s"]))
    assert len(detected_bouts(waist, rule)) == 2
