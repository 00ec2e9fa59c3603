"""Session 20's rehab trial on slow foot strides: the streamed segmenter keeps a slow stride whole (decision L120)
and `pdrlearn steps` counts the strides `track` integrates (decision steps 34)."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.kernels.stride import STANCE_GAP_SWING_FRAC_OPTION, StanceSegmenter, stance_strides

#: decision L120's option (not the default: its rule failed on the 0.1 m/s walks)
L120 = {"stance_gap_swing_frac": STANCE_GAP_SWING_FRAC_OPTION}


@pytest.fixture(scope="module")
def slow_walk(tmp_path_factory):
    """The trial's 0.45 m / 1.0 s walker (user 412, 100 Hz), 6 m: 7 strides of the tracked foot."""
    out = tmp_path_factory.mktemp("slow") / "v045"
    assert main(["simulate", "--route", "stand:3, straight:6, stand:3", "--step-length", "0.45", "--step-time", "1.0",
                 "--user-seed", "412", "--rate", "100", "--out", str(out)]) == 0
    return out


def _track(session, out, *extra) -> dict:
    assert main(["track", "--no-plot", str(session), "--out", str(out), *extra]) == 0
    return json.loads((out / "summary.json").read_text())


def test_streamed_slow_strides_are_not_split(slow_walk, tmp_path):
    """L120 (an option): the slow terminal swing's ~0.1 s under the threshold before the heel strike, and the heel
    rocker after it, no longer end a streamed stance: streamed = offline = the truth (the trial: 22 streamed for
    12)."""
    off = _track(slow_walk, tmp_path / "off")
    (tmp_path / "l120.json").write_text(json.dumps(L120))
    st = _track(slow_walk, tmp_path / "st", "--streaming", "--params", str(tmp_path / "l120.json"))
    n_true = len(pd.read_csv(slow_walk / "steps.csv"))
    assert off["n_strides_one_foot"] == st["n_strides_one_foot"] == n_true, (off["n_strides_one_foot"],
                                                                             st["n_strides_one_foot"], n_true)
    assert abs(st["distance_error_pct"]) < 5.0
    # without L120's option and without L684's rhythm rule (`{"stance_rhythm_frac": 0}`) the split is there
    (tmp_path / "old.json").write_text(json.dumps({"stance_rhythm_frac": 0}))
    old = _track(slow_walk, tmp_path / "old", "--streaming", "--params", str(tmp_path / "old.json"))
    assert old["n_strides_one_foot"] >= 1.5 * n_true
    # decision L684 (the default since L696): its rhythm rule keeps this slow walk whole too (printed: 7 strides for 7)
    new = _track(slow_walk, tmp_path / "new", "--streaming")
    assert new["n_strides_one_foot"] == n_true


def test_a_long_foot_flat_ends_on_the_fixed_gap():
    """L120: a stance that closed its stride early (a slow foot-flat) ends on stance_gap_s, so a slow swing whose
    |w| dips under the threshold for a moment still ends it: three strides, not one."""
    fs = 100.0
    t = np.arange(0, 6.0, 1 / fs)
    w = np.full(len(t), 0.02)
    for a in (1.0, 2.6, 4.2):  # 0.9 s swings with a 0.05 s dip to 0.1 rad/s in the middle
        sw = (t >= a) & (t < a + 0.9)
        w[sw] = 3.0
        w[(t >= a + 0.4) & (t < a + 0.45)] = 0.1
    gyr = np.column_stack([w, np.zeros_like(w), np.zeros_like(w)])
    assert len(stance_strides(t, gyr, L120)) == len(stance_strides(t, gyr)) == 3
    seg = StanceSegmenter.from_params(L120)
    assert seg.swing_frac == 0.35 and seg.gap_max == 0.5 and StanceSegmenter().swing_frac == 0.0


def test_steps_counts_the_strides_track_integrates(tmp_path):
    """steps 34: `pdrlearn steps` (foot accel detector) found a slow stride's toe-off and landing both (20 strides
    for 11 at 0.3 m / 1.0 s, user 409); it now keeps one detection per rest-to-rest stride, as `track`."""
    s = tmp_path / "v03"
    assert main(["simulate", "--route", "stand:3, straight:3, stand:3", "--step-length", "0.3", "--step-time", "1.0",
                 "--user-seed", "409", "--rate", "100", "--out", str(s)]) == 0
    assert main(["steps", str(s), "--detector", "accel", "--json", "--out", str(tmp_path / "st.csv")]) == 0

    found = pd.read_csv(tmp_path / "st.csv")
    truth = pd.read_csv(s / "steps.csv")
    tracked = _track(s, tmp_path / "o")
    n_tracked = tracked["n_strides_one_foot"]
    assert len(found) == n_tracked == len(truth), (len(found), n_tracked, len(truth))
