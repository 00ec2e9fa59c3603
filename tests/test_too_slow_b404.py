"""Decision B404 refused a unit sampled under 15 Hz in `track` and `steps`; decision B416 (session 40, review R0
finding 2) re-measured it with the downsamplers in the repository (experiments/low_rate_track.py: no tested rate was
unusable) and removed the refusal: `track`, `track --streaming`, `steps` and `run` treat a 10 Hz session alike, with
B23's one warning per slow unit, which now says the distance may come out short."""

from __future__ import annotations

from pathlib import Path

import pandas as pd

import pdrlearn.io.plasys as io_plasys
from pdrlearn.cli import main

BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"


def _every_other_row(src, dst) -> None:
    dst.mkdir()
    for p in src.iterdir():
        if p.name in ("fAccelerometer.csv", "fGyroscope.csv", "wAccelerometer.csv", "wGyroscope.csv"):
            pd.read_csv(p).iloc[::2].to_csv(dst / p.name, index=False)  # 20 Hz -> 10 Hz
        elif p.is_file():
            (dst / p.name).write_bytes(p.read_bytes())


def test_every_command_tracks_a_10_hz_session_with_one_warning_per_unit_b416(tmp_path, capsys):
    assert not hasattr(io_plasys, "MIN_RATE_HZ") and not hasattr(io_plasys, "refuse_too_slow")  # no switch left
    good = tmp_path / "u20"
    assert main(["simulate", "--route", "stand:2, straight:12, stand:2", "--user-seed", "10764", "--rate", "20",
                 "--out", str(good)]) == 0
    slow = tmp_path / "u10"
    _every_other_row(good, slow)
    capsys.readouterr()
    for cmd in (["track", "--no-plot", str(slow), "--out", str(tmp_path / "t")],
                ["track", "--no-plot", str(slow), "--streaming", "--out", str(tmp_path / "ts")],
                ["steps", str(slow), "--out", str(tmp_path / "s.csv")],
                ["run", "--no-plot", str(BUNDLE), str(slow), "--out", str(tmp_path / "r")]):
        assert main(cmd) == 0, cmd
        err = capsys.readouterr().err
        low = [ln for ln in err.splitlines() if "below the 20 Hz its step detectors are validated at" in ln]
        assert len(low) == 2 and "error:" not in err, (cmd, err)  # B23: the foot line and the waist line
        assert "the foot unit is sampled at 10 Hz" in low[0] and "a short distance" in low[0], low
        assert "up to 62 % short, decision B416); record at 20 Hz or more" in low[0], low
    assert (tmp_path / "t" / "summary.json").exists() and (tmp_path / "s.csv").exists()
    assert (tmp_path / "r" / "summary.json").exists()
