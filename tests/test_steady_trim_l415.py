"""Decision L415 (session 34, trial T1 finding F8): ``track --steady-trim N`` leaves the first and last N strides of
each walking bout out of the steady measures, and steps.csv's ``steady`` column marks the CV strides so that
``n_cv_strides`` and ``stride_time_cv_pct`` can be reproduced from steps.csv."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from tests.sim_helpers import straight_walk


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    """A fresh simulated user (8041) walking 40 m between two stands, at 100 Hz."""
    return straight_walk(tmp_path_factory.mktemp("l415"), 8041)


def _track(walk, capsys, *extra):
    out = walk / ("t" + "_".join(extra))
    code = main(["track", "--no-plot", str(walk / "u8041"), "--pipeline", "plasys", "--out", str(out), "--force",
                 "--json",
                 *extra])
    text, err = capsys.readouterr()
    assert code == 0, err
    return json.loads(text), pd.read_csv(out / "steps.csv")


def test_steps_csv_steady_rows_reproduce_the_cv_l415(walk, capsys):
    for extra in ((), ("--steady-trim", "3")):
        summary, steps = _track(walk, capsys, *extra)
        flagged = steps.loc[steps["steady"].astype(bool), "stride_time_s"].to_numpy(float)
        assert len(flagged) == summary["n_cv_strides"] >= 10
        cv = 100.0 * flagged.std(ddof=1) / flagged.mean()
        assert round(cv, 3) == round(summary["stride_time_cv_pct"], 3)  # the printed precision (3 decimals)
        length = np.abs(steps.loc[steps["steady"].astype(bool), "length_m"].to_numpy(float))
        assert round(100.0 * length.std(ddof=1) / length.mean(), 3) == round(summary["stride_length_cv_pct"], 3)


def test_steady_trim_leaves_each_bouts_ends_out_l415(walk, capsys):
    base, steps0 = _track(walk, capsys)
    trim, steps3 = _track(walk, capsys, "--steady-trim", "3")
    assert base["steady_trim"] == 0 and trim["steady_trim"] == 3
    # the stride medians and the walking time over the strides left: 3 fewer with a stride time at the start (the
    # first stride of a bout has none) and 3 at the end
    assert trim["n_stride_times"] == base["n_stride_times"] - 5
    # L426: the trimmed time and speed under their own keys; walking_time_s / gait_speed_mps keep every stride
    assert trim["steady_time_s"] < base["walking_time_s"] - 4 * base["median_stride_time_s"]
    assert trim["steady_gait_speed_mps"] > base["gait_speed_mps"]  # the speed-up and the slow-down are out
    assert trim["walking_time_s"] == base["walking_time_s"] and base["steady_time_s"] is None
    assert trim["n_cv_strides"] < base["n_cv_strides"]
    s0, s3 = steps0["steady"].astype(bool).to_numpy(), steps3["steady"].astype(bool).to_numpy()
    assert not (s3 & ~s0).any()  # the trim only leaves strides out
    assert not s3[:3].any() and not s3[-3:].any()


def test_trimmed_rows_per_bout_and_setting_l415():
    from pdrlearn.track.steady import steady_trim_set, trimmed_rows

    # two bouts of 8 rows (a 5 s pause between), rows given out of time order
    start = np.r_[np.arange(8) * 1.0, 12.0 + np.arange(8) * 1.0]
    steps = pd.DataFrame({"start_s": start, "end_s": start + 0.8})[::-1].reset_index(drop=True)
    assert not trimmed_rows(steps).any()  # default 0: nothing left out
    with steady_trim_set(2):
        got = trimmed_rows(steps)
    want = np.isin(start, [0, 1, 6, 7, 12, 13, 18, 19])[::-1]
    np.testing.assert_array_equal(got, want)
    assert not trimmed_rows(steps).any()  # the setting ends with its block


@pytest.mark.parametrize("bad", ["-1", "1.5"])
def test_bad_steady_trim_is_one_line_l415(walk, capsys, bad):
    code = main(["track", "--no-plot", str(walk / "u8041"), "--out", str(walk / "bad"), f"--steady-trim={bad}"])
    out, err = capsys.readouterr()
    assert code == 2 and "--steady-trim" in err and err.count("\n") == 1
    assert not (walk / "bad").exists()


def test_track_all_passes_steady_trim_l415(walk, tmp_path, capsys):
    import shutil

    shutil.copytree(walk / "u8041", tmp_path / "study" / "u8041")
    rows = {}
    for n in ("0", "3"):
        code = main(["track-all", "--no-plot", str(tmp_path / "study"), "--pipeline", "plasys", "--out",
                     str(tmp_path / n),
                     "--steady-trim", n])
        _, err = capsys.readouterr()
        assert code == 0, err
        rows[n] = pd.read_csv(tmp_path / n / "sessions.csv").iloc[0]
    assert rows["0"]["steady_trim"] == 0 and rows["3"]["steady_trim"] == 3
    assert rows["3"]["n_cv_strides"] < rows["0"]["n_cv_strides"]
    assert "steady" in pd.read_csv(tmp_path / "3" / "u8041" / "steps.csv")
