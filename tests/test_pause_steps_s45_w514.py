"""Trial T1 F2 (session 45): W134's stand steps on a walking aid's steadied trunk. Decision W516: a walking
sequence with over a quarter of its steps read as stands has none (the kernel by hand; end to end on a simulated
slow walk whose lower-back motion is damped as docs/waist.md describes a rollator user). Decision W514: the track
warns when over a tenth of its steps were shortened as pauses / stands, and ``calibrate`` says how many of its
walk's steps were (W514's own candidate, a rhythm test, was measured and not adopted: docs/decisions/waist.md)."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pandas as pd
import pytest

from pdrlearn.waist import _kernels as K
from pdrlearn.waist.lengths import PAUSE_SCALED_WARN_SHARE, pause_scaled_count, pause_scaled_message


def _standing(run_s, durations, closes=None):
    d = np.asarray(durations, dtype=float)
    closes = np.zeros(d.size, bool) if closes is None else np.asarray(closes, bool)
    return K.standing_step_mask(np.asarray(run_s, dtype=float), d, ~closes, closes)


def test_a_walk_still_on_every_other_step_has_no_stand():
    n = np.nan
    # 0.9 s steps, a still run of half the step on every other inner step: 5 of 12 (> a quarter) -> none
    run = [n, 0.5, n, 0.5, n, 0.5, n, 0.5, n, 0.5, n, n]
    assert not _standing(run, [0.9] * 12).any()
    # one stand among 12 steps (W134's event) stays a stand; so do 3 of 12 (exactly a quarter)
    run = [n] * 5 + [0.5] + [n] * 6
    assert _standing(run, [0.9] * 12)[5]
    run = [n, n, 0.5, n, n, 0.5, n, n, 0.5, n, n, n]
    np.testing.assert_array_equal(np.flatnonzero(_standing(run, [0.9] * 12)), [2, 5, 8])
    assert K.STANDS_MAX_SHARE == 0.25


def test_the_share_is_per_walking_sequence():
    n = np.nan
    # sequence 1 (rows 0-9): still every other step -> none; sequence 2 (rows 10-19, closing row 9): one stand, kept
    run = [n, 0.5, n, 0.5, n, 0.5, n, 0.5, n, n] + [n, n, n, n, 0.5, n, n, n, n, n]
    closes = [False] * 9 + [True] + [False] * 10
    out = _standing(run, [0.9] * 20, closes)
    np.testing.assert_array_equal(np.flatnonzero(out), [14])


def test_the_count_and_the_warning_line():
    st = pd.DataFrame({"has_next": [True] * 9 + [False], "merged": [False] * 8 + [True, False],
                       "pause_factor": [0.1, 1, 0.2, 1, 1, 1, 1, 1, 0.3, 1.0]})
    assert pause_scaled_count(st) == (2, 8)  # the merged fragment and the closing contact are not steps
    assert pause_scaled_count(st.drop(columns="pause_factor")) == (0, 8)
    assert PAUSE_SCALED_WARN_SHARE == 0.10
    assert pause_scaled_message(10, 100) is None  # a tenth: no line
    line = pause_scaled_message(11, 100)
    assert line is not None and "\n" not in line and line.startswith("11 of 100 steps (11 %)")
    assert '{"options": {"pause_steps": false}}' in line and "W134" in line
    from pdrlearn.warning_lines import warning_code

    assert warning_code(line) == "W514"  # E155: the line's own decision is its code
    assert "W122" in pause_scaled_message(5, 10, "progression")
    assert "pause_steps true" in pause_scaled_message(5, 10, True)


@pytest.fixture(scope="module")
def rollator_walk(tmp_path_factory):
    """Trial T1's calibration walk (user 12760, 0.3 m steps of 0.9 s, 14 m) with the lower back's dynamic part damped
    around a 2 s moving mean (acceleration x0.4, rotation rate x0.5), as T1 made its rollator sessions."""
    from pdrlearn.io import read_session
    from pdrlearn.io.session import Stream

    out = tmp_path_factory.mktemp("w514") / "c10"
    subprocess.run([sys.executable, "-m", "pdrlearn", "simulate", "--route", "stand:3, straight:14, stand:3",
                    "--step-length", "0.3", "--step-time", "0.9", "--bounce", "pendulum", "--rocker", "smooth",
                    "--rate", "100", "--user-seed", "12760", "--seed", "3", "--out", str(out)],
                   check=True, capture_output=True)
    s = read_session(out)
    for name, k in (("wAccelerometer", 0.4), ("wGyroscope", 0.5)):
        st, w = s.streams[name], 200
        pad = np.pad(st.values, ((w // 2, w - 1 - w // 2), (0, 0)), mode="edge")
        mean = np.column_stack([np.convolve(pad[:, j], np.ones(w) / w, mode="valid") for j in range(pad.shape[1])])
        s.streams[name] = Stream(name, st.t, mean + k * (st.values - mean))
    return s


def test_a_steadied_trunk_walks_whole_and_calibrate_says_so(rollator_walk, caplog):
    from pdrlearn.track.waist import track_waist
    from pdrlearn.waist.calibration import calibrate

    on = track_waist(rollator_walk, pipeline="waist-pendulum")  # the default, pause_steps "standing"
    off = track_waist(rollator_walk, pipeline="waist-pendulum", pause_steps=False)
    n_scaled, n_steps = pause_scaled_count(on.steps)
    assert n_steps >= 40 and n_scaled == 0  # W134 alone: 16 of these steps cut to ~5 % of their length (T1)
    assert on.steps["length_m"].sum() == pytest.approx(off.steps["length_m"].sum(), rel=1e-9)
    assert not any("shortened as pauses" in w for w in on.info["warnings"])
    p = calibrate([rollator_walk], "waist-pendulum", distances=[14.0])
    assert any(n.startswith(f"0 of the {n_steps} steps shortened as pauses / stands") for n in p.notes)


def test_the_warning_names_the_option_when_most_steps_are_cut(rollator_walk):
    from pdrlearn.track.waist import track_waist

    res = track_waist(rollator_walk, pipeline="waist-pendulum", pause_steps="progression")  # W122: every still run
    n_scaled, n_steps = pause_scaled_count(res.steps)
    assert n_scaled > PAUSE_SCALED_WARN_SHARE * n_steps
    lines = [w for w in res.info["warnings"] if "shortened as pauses" in w]
    assert len(lines) == 1 and lines[0].startswith(f"{n_scaled} of {n_steps} steps") and "W122" in lines[0]
