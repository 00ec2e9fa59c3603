"""Decision B383 and trial T1 findings 8-9 (session 37): a phone's two files imported in two steps.

- B383: ``import --sort-timestamps`` sorts rows a batched log wrote out of order, with one line saying how many rows
  moved; without it the refusal names the option; a clock reset is not sorted;
- finding 9: the ``--merge`` step does not claim a missing accelerometer that the folder already holds.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.cli import main
from pdrlearn.io import read_session

FS = 50.0


def _phone_file(path, kind_seed: int, swaps=(100, 300, 700), reset_at: int | None = None):
    """An Android-style export (ns stamps, 50 Hz, 20 s): ``swaps`` neighbouring rows exchanged."""
    n = int(20 * FS)
    rng = np.random.default_rng(kind_seed)
    ts = (987_654_321_000_000 + np.arange(n) * 1e9 / FS).astype(np.int64)
    if reset_at is not None:
        ts[reset_at:] -= 10_000_000_000  # the clock jumps back 10 s
    xyz = rng.normal(0.0, 0.3, (n, 3)) + ([0.0, 9.81, 0.0] if kind_seed == 1 else 0.0)
    df = pd.DataFrame({"timestamp": ts, "x": xyz[:, 0], "y": xyz[:, 1], "z": xyz[:, 2]})
    for i in swaps:
        df.iloc[[i, i + 1]] = df.iloc[[i + 1, i]].to_numpy()
    df.to_csv(path, index=False)
    return path, df


def test_sort_timestamps_sorts_and_says_how_many_rows_moved(tmp_path, capsys):
    csv, df = _phone_file(tmp_path / "Accelerometer.csv", 1)
    out = tmp_path / "s"
    assert main(["import", str(csv), "--unit", "waist", "--acc", "x,y,z", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert "timestamps go backwards 3 time(s)" in err and "--sort-timestamps" in err and "Traceback" not in err
    assert not out.exists()
    assert main(["import", str(csv), "--unit", "waist", "--acc", "x,y,z", "--out", str(out),
                 "--sort-timestamps"]) == 0
    err = capsys.readouterr().err
    assert "6 row(s) out of time order moved by --sort-timestamps (decision B383)" in err
    s = read_session(out)["wAccelerometer"]
    want = df.sort_values("timestamp")
    assert np.all(np.diff(s.t) > 0) and np.allclose(s.values, want[["x", "y", "z"]].to_numpy())


def test_sort_timestamps_refuses_a_clock_reset(tmp_path, capsys):
    csv, _ = _phone_file(tmp_path / "Accelerometer.csv", 1, swaps=(), reset_at=600)
    assert main(["import", str(csv), "--unit", "waist", "--acc", "x,y,z", "--out", str(tmp_path / "s"),
                 "--sort-timestamps"]) == 2
    assert "--split-at-clock-reset" in capsys.readouterr().err  # B73's refusal comes first, unchanged
    assert main(["import", str(csv), "--unit", "waist", "--acc", "x,y,z", "--out", str(tmp_path / "s"),
                 "--sort-timestamps", "--split-at-clock-reset"]) == 2
    err = capsys.readouterr().err
    assert "would interleave the recordings" in err and "decision B383" in err and "Traceback" not in err


def test_the_merge_step_does_not_claim_a_missing_accelerometer(tmp_path, capsys):
    acc, _ = _phone_file(tmp_path / "Accelerometer.csv", 1, swaps=())
    gyr, _ = _phone_file(tmp_path / "Gyroscope.csv", 2, swaps=())
    out = tmp_path / "s"
    assert main(["import", str(acc), "--unit", "waist", "--acc", "x,y,z", "--out", str(out)]) == 0
    first = capsys.readouterr().err
    assert "note: no gyroscope columns recognised" in first and "--gyro X,Y,Z --merge" in first
    assert main(["import", str(gyr), "--unit", "waist", "--gyro", "x,y,z", "--merge", "--out", str(out)]) == 0
    second = capsys.readouterr().err
    assert "no accelerometer columns recognised" not in second
    assert "wAccelerometer: kept from the session" in second
    assert set(read_session(out).streams) >= {"wAccelerometer", "wGyroscope"}
