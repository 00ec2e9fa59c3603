"""Decision B443 (session 43, fixer FJ; docs/decisions/bad-input.md): with ``import --add-gravity`` only the
accelerometer skips B436's unit checks (it has no gravity yet, B166); a gyroscope in deg/s keeps B30's deg/s line
(review R1 finding 3: it was called "a corrupt sample" with ~half its rows to delete)."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.cli import main


def _export(tmp_path):
    """R1's reproducer (its grav/mk.py): 20 s at 100 Hz, linear acceleration, a gyroscope of 150 deg/s peaks written
    as if rad/s, and a Gravity export whose columns match --acc."""
    t = np.arange(0, 20, 0.01)
    rng = np.random.default_rng(1)
    lin = np.column_stack([np.sin(2 * np.pi * t), 0.5 * np.cos(2 * np.pi * t), 0.3 * np.sin(4 * np.pi * t)])
    lin += rng.normal(0, 0.05, (len(t), 3))
    gyr = np.column_stack([150 * np.sin(2 * np.pi * t), 40 * np.cos(2 * np.pi * t), 20 * np.sin(np.pi * t)])
    pd.DataFrame({"time": t, "ax": lin[:, 0], "ay": lin[:, 1], "az": lin[:, 2], "gx": gyr[:, 0], "gy": gyr[:, 1],
                  "gz": gyr[:, 2]}).to_csv(tmp_path / "lin.csv", index=False)
    pd.DataFrame({"time": t, "ax": 0.0, "ay": 9.80665, "az": 0.0}).to_csv(tmp_path / "Gravity.csv", index=False)
    return tmp_path / "lin.csv", tmp_path / "Gravity.csv"


def test_a_deg_s_gyroscope_keeps_its_unit_line_with_add_gravity_b443(tmp_path, capsys):
    lin, grav = _export(tmp_path)
    rc = main(["import", str(lin), "--add-gravity", str(grav), "--unit", "waist", "--time-unit", "s",
               "--acc", "ax,ay,az", "--gyro", "gx,gy,gz", "--out", str(tmp_path / "o")])
    err = capsys.readouterr().err.strip()
    assert rc == 2 and "\n" not in err and not (tmp_path / "o").exists()
    # B30's deg/s line (within B438's "fixed by an option" line), not B425's "corrupt sample"
    assert err.startswith(f"error: {lin}: ") and "gx, gy, gz as rad/s: 99th percentile |rate| is 150" in err
    assert "looks like deg/s" in err and "--gyro-unit deg/s" in err and "B425" not in err

