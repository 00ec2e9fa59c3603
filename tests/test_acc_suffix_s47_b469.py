"""Session 47, trial T1 finding F9: ``AccX_g`` accelerometer columns were not recognised (``GyrX_dps`` were), so a
lower-back export was written without its accelerometer; decision B469."""
from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.cli import main
from pdrlearn.io.importer import _suffix_unit


def test_b469_a_g_after_an_accelerometer_axis_is_its_unit():
    assert _suffix_unit("AccX_g") == ("AccX", "g")
    assert _suffix_unit("ax_g") == ("ax", "g")
    assert _suffix_unit("acc_x_g") == ("acc_x", "g")  # D12's form, unchanged
    assert _suffix_unit("GyrX_g") is None and _suffix_unit("x_g") is None  # a g after anything else: no unit
    assert _suffix_unit("time_s") == ("time", "s")


def test_b469_import_guesses_accx_g_columns(tmp_path, capsys):
    n = 600
    rng = np.random.default_rng(2)
    pd.DataFrame({"Time_s": np.arange(n) / 100, "AccX_g": rng.normal(0, .05, n), "AccY_g": rng.normal(0, .05, n),
                  "AccZ_g": 1 + rng.normal(0, .05, n), "GyrX_dps": rng.normal(0, 1, n),
                  "GyrY_dps": rng.normal(0, 1, n), "GyrZ_dps": rng.normal(0, 1, n)}).to_csv(tmp_path / "lb.csv",
                                                                                          index=False)
    assert main(["import", str(tmp_path / "lb.csv"), "--unit", "waist", "--out", str(tmp_path / "s")]) == 0
    err = capsys.readouterr().err
    assert "wAccelerometer: AccX_g,AccY_g,AccZ_g (guessed) in g" in err and "no accelerometer columns" not in err
