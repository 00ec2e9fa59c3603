"""Decision B404: `track` and `steps` refuse a unit sampled too slowly to support a result (trial T2 finding 6:
10 Hz gave step F1 0.045 and -99.81 % distance with exit 0), in one line with exit 2 and nothing written; the thesis
rate, 20 Hz, keeps working."""

from __future__ import annotations

import pandas as pd

from pdrlearn.cli import main
from pdrlearn.io.plasys import MIN_RATE_HZ


def _every_other_row(src, dst) -> None:
    dst.mkdir()
    for p in src.iterdir():
        if p.name in ("fAccelerometer.csv", "fGyroscope.csv", "wAccelerometer.csv", "wGyroscope.csv"):
            pd.read_csv(p).iloc[::2].to_csv(dst / p.name, index=False)  # 20 Hz -> 10 Hz
        elif p.is_file():
            (dst / p.name).write_bytes(p.read_bytes())


def test_track_and_steps_refuse_a_10_hz_session_b404(tmp_path, capsys):
    assert MIN_RATE_HZ > 10.0
    good = tmp_path / "u20"
    assert main(["simulate", "--route", "stand:2, straight:12, stand:2", "--user-seed", "10198", "--rate", "20",
                 "--out", str(good)]) == 0
    slow = tmp_path / "u10"
    _every_other_row(good, slow)
    capsys.readouterr()
    assert main(["track", str(slow), "--out", str(tmp_path / "t10")]) == 2
    err = capsys.readouterr().err
    lines = [ln for ln in err.splitlines() if ln.startswith("error:")]
    assert len(lines) == 1 and "the foot unit is sampled at 10 Hz, too slow for track" in lines[0], err
    assert "record at 20 Hz or more (decision B404)" in lines[0] and "Traceback" not in err
    assert not (tmp_path / "t10").exists()
    assert main(["steps", str(slow), "--out", str(tmp_path / "s10.csv")]) == 2
    assert "too slow for steps" in capsys.readouterr().err and not (tmp_path / "s10.csv").exists()
    assert main(["track", str(good), "--out", str(tmp_path / "t20")]) == 0  # the thesis rate keeps working


def _slow_unit(src, dst, unit: str) -> None:
    dst.mkdir()
    for p in src.iterdir():
        if p.name in (f"{unit}Accelerometer.csv", f"{unit}Gyroscope.csv"):
            pd.read_csv(p).iloc[::2].to_csv(dst / p.name, index=False)  # 20 Hz -> 10 Hz on this unit only
        elif p.is_file():
            (dst / p.name).write_bytes(p.read_bytes())


def test_only_the_read_unit_is_refused_b410(tmp_path, capsys):
    """Decision B410 (review R3 finding 1): a slow waist does not refuse `steps --detector accel` (a foot detector);
    it refuses a waist detector, and `track` names --units foot, which works."""
    good = tmp_path / "u20"
    assert main(["simulate", "--route", "stand:2, straight:12, stand:2", "--user-seed", "10350", "--rate", "20",
                 "--out", str(good)]) == 0
    slow = tmp_path / "w10"
    _slow_unit(good, slow, "w")
    capsys.readouterr()
    assert main(["steps", str(slow), "--detector", "accel", "--out", str(tmp_path / "s.csv")]) == 0
    assert (tmp_path / "s.csv").exists() and "B404" not in capsys.readouterr().err
    assert main(["steps", str(slow), "--detector", "waist-ic"]) == 2
    assert "the waist unit is sampled at 10 Hz, too slow for steps" in capsys.readouterr().err
    assert main(["track", str(slow), "--out", str(tmp_path / "t")]) == 2
    err = capsys.readouterr().err
    lines = [ln for ln in err.splitlines() if ln.startswith("error:")]
    assert len(lines) == 1 and "or track the foot unit alone with --units foot (decision B404)" in lines[0], err
    assert main(["track", str(slow), "--units", "foot", "--out", str(tmp_path / "t")]) == 0
    both = tmp_path / "both10"
    _every_other_row(good, both)
    capsys.readouterr()
    assert main(["track", str(both), "--out", str(tmp_path / "t2")]) == 2
    assert "--units" not in capsys.readouterr().err  # no unit is fast enough to name
