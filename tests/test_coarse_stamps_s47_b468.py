"""Session 47, trial T3 (a 1125 Hz lab unit stamped in whole milliseconds) finding F5: every ninth stamp repeats,
and the duplicate-timestamp advice (B150: drop them) deleted 11 % of real samples. Decision B468: stamps coarser
than the samples' own interval are said to be samples to re-time, and a drop of over 1 % of the rows is said."""
from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.cli import main
from pdrlearn.kernels.clock import coarse_stamp_rate


def _export(path, hz=1125.0, n=4000):
    t = np.arange(n) / hz
    rng = np.random.default_rng(3)
    acc = np.column_stack([rng.normal(0, 0.05, n), rng.normal(0, 0.05, n), 1.0 + rng.normal(0, 0.05, n)])
    df = pd.DataFrame({"time_ms": np.floor(t * 1e3).astype(int), "ax": acc[:, 0], "ay": acc[:, 1], "az": acc[:, 2]})
    df.to_csv(path, index=False)
    return df


def test_coarse_stamp_rate_tells_quantised_samples_from_repeats():
    t = np.floor(np.arange(2000) / 1125.0 * 1e3) / 1e3
    assert abs(coarse_stamp_rate(t) - 1125.0) < 2.0
    phone = np.sort(np.r_[np.arange(500) * 0.01, np.arange(0, 500, 100) * 0.01])  # 5 repeated rows at 100 Hz
    assert coarse_stamp_rate(phone) is None
    assert coarse_stamp_rate(np.arange(100) * 0.01) is None


def test_b468_import_names_retime_and_a_large_drop_is_said(tmp_path, capsys):
    csv = tmp_path / "foot.csv"
    df = _export(csv)
    args = ["import", str(csv), "--unit", "foot", "--time", "time_ms", "--time-unit", "ms", "--acc", "ax,ay,az",
            "--acc-unit", "g", "--out", str(tmp_path / "s")]
    assert main(args) != 0
    err = capsys.readouterr().err
    assert "coarser than the samples' own interval" in err and "--retime HZ" in err and "B468" in err
    assert "--drop-duplicate-timestamps" in err  # review R1 F3: the other reading is named too
    assert main([*args, "--drop-duplicate-timestamps"]) == 0
    err = capsys.readouterr().err
    dropped = int(len(df) - df.time_ms.nunique())
    assert f"{dropped} rows repeating a timestamp dropped" in err and "import again with --retime HZ" in err
    assert main([*args[:-1], str(tmp_path / "r"), "--retime", "1125"]) == 0


def test_r1_f2_inline_params_longer_than_a_file_name(tmp_path):
    import json

    from pdrlearn.cli.track import read_params

    obj = {f"key_{i:02d}": 0.123456789 for i in range(20)}
    text = json.dumps(obj)
    assert len(text) > 255
    assert read_params(text) == obj


def test_r1_f6_sosfilt_refuses_a_2d_signal_on_both_paths():
    import pytest

    from pdrlearn.kernels import dsp

    sos = np.array([[0.2, 0.4, 0.2, 1.0, -0.3, 0.1]])
    with pytest.raises(ValueError, match="one signal"):
        dsp.sosfilt(sos, np.zeros((10, 3)))
