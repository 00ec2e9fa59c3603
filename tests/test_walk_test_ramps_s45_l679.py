"""Decision L679 (trial T1, finding F5): the walk tests (10 m walk, its trials, T25FW) are not timed on a ramp the
track found (a 1:12 ramp's strides rise under L434's 0.10 m, so no flight refused it), and a 10 m walk found in free
walking (no ``--ten-m-walk``) says so on the console and in clinical.md."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd

from pdrlearn.cli.common import transfer_line
from pdrlearn.report.clinical import clinical_markdown
from pdrlearn.track.walk_test import ramp_numbers, t25fw, ten_metre_walk, ten_metre_walk_trials


def _walk(n=30, stride_m=0.6, stride_s=1.8):
    start = np.arange(n) * stride_s
    return pd.DataFrame({"start_s": start, "end_s": start + stride_s, "event_s": start + 0.9 * stride_s,
                         "length_m": stride_m, "heading_rad": 0.0, "dz_m": 0.05, "gap_s": 0.0, "unit": "foot"})


def _ramp_rows(st, first, last):
    return ramp_numbers(st, ([{"first": first, "last": last}], np.zeros(0), np.zeros(0)))


def test_a_walk_on_a_ramp_is_no_ten_m_walk():
    st = _walk()  # 18 m of 0.6 m strides at 1:12 (dz 0.05 m, under L434's 0.10 m)
    timed = ten_metre_walk(st)
    assert timed["ten_m_walk_time_s"] is not None  # without the ramp it is timed (as main timed T1's ramps)
    ramps = _ramp_rows(st, 5, 25)
    out = ten_metre_walk(st, ramps=ramps)
    assert out["ten_m_walk_time_s"] is None and out["n_ten_m_walk_trials"] == 0
    assert "ramp 1 of ramps.csv (9.0-46.8 s)" in out["ten_m_walk_note"] and "L679" in out["ten_m_walk_note"]
    assert len(ten_metre_walk_trials(st, ramps=ramps)) == 0
    assert t25fw(st, ramps=ramps)["t25fw_time_s"] is None
    assert t25fw(st)["t25fw_time_s"] is not None


def test_a_ramp_after_the_walkway_leaves_it_timed():
    st = _walk(n=40)  # 24 m: the walkway's 14 m (rows 0-23) are level, the ramp comes after
    out = ten_metre_walk(st, ramps=_ramp_rows(st, 30, 39))
    assert out["ten_m_walk_time_s"] is not None and out["ten_m_walk_declared"] is False
    assert ten_metre_walk(st, zones=(2.0, 10.0, 2.0))["ten_m_walk_declared"] is True


def test_an_automatic_ten_m_walk_is_labelled_free_walking(tmp_path):
    base = {"pipeline": "plasys", "gait_speed_mps": 0.34, "ten_m_walk_time_s": 29.04, "ten_m_walk_speed_mps": 0.344,
            "n_ten_m_walk_trials": 1, "ten_m_walk_zones_m": [2.0, 10.0, 2.0]}
    for name, declared in (("free", False), ("declared", True)):
        folder = tmp_path / "out" / name
        folder.mkdir(parents=True)
        (folder / "summary.json").write_text(json.dumps({**base, "session": name, "ten_m_walk_declared": declared}))
    lines = [x for x in clinical_markdown(tmp_path / "out").splitlines() if x.startswith("- 10 m walk")]
    assert sorted(lines) == [
        "- 10 m walk: 0.34 m/s (29.0 s over the middle 10 m of a 14 m walkway; foot unit)",
        "- 10 m walk: 0.34 m/s (29.0 s over the middle 10 m of a 14 m walkway; foot unit; found in free walking, no "
        "walkway declared (track --ten-m-walk), L679)"], lines
    assert "found in free walking" in transfer_line({**base, "ten_m_walk_declared": False})
    assert "found in free walking" not in transfer_line({**base, "ten_m_walk_declared": True})
