"""Decision B358 (session 35, new-user report NU #4): a lower-back unit imported from a MAT file (the README's
Mobilise-D command, ``--unit waist --acc-unit g --gyro-unit deg/s``) gets no iPhone note (B146): a MAT file is no
phone app's export. The same arrays as a CSV still get it."""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd
import scipy.io

from pdrlearn.cli import main
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route

G = 9.80665
P = "TimeMeasure1.Test11.Trial1.SU.LowerBack"


def test_mat_lower_back_in_g_gets_no_iphone_note_b358(tmp_path, capsys):
    logging.disable(logging.WARNING)
    try:
        walk = simulate_path(parse_route("straight:12"), UserProfile.from_seed(8643), rate_hz=100.0, seed=1,
                             scenario="route")
    finally:
        logging.disable(logging.NOTSET)
    a, g = walk["wAccelerometer"], walk["wGyroscope"]
    acc, gyr = a.values / G, np.degrees(g.values)
    lb = {"Acc": acc, "Gyr": gyr, "Fs": 100.0}
    trial = {"Trial1": {"SU": {"LowerBack": lb}}}
    scipy.io.savemat(tmp_path / "data.mat", {"data": {"TimeMeasure1": {"Test11": trial}}})
    cmd = ["--unit", "waist", "--acc-unit", "g", "--gyro-unit", "deg/s"]
    assert main(["import", str(tmp_path / "data.mat"), "--acc", f"{P}.Acc", "--gyro", f"{P}.Gyr", *cmd,
                 "--out", str(tmp_path / "m")]) == 0
    err = capsys.readouterr().err
    assert "wAccelerometer:" in err and "in g (given" in err
    assert "iPhone" not in err and "B146" not in err
    pd.DataFrame({"time": a.t - a.t[0], **{f"acc_{c}": acc[:, k] for k, c in enumerate("xyz")},
                  **{f"gyr_{c}": gyr[:, k] for k, c in enumerate("xyz")}}).to_csv(tmp_path / "lb.csv", index=False)
    assert main(["import", str(tmp_path / "lb.csv"), *cmd, "--out", str(tmp_path / "c")]) == 0
    assert "iPhone" in capsys.readouterr().err  # B146 stays for a CSV
