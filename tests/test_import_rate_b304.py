"""Decision B304 (session 34, trial T3 finding 6): ``pdrlearn track`` reads a 1000 Hz folder that ``pdrlearn import``
wrote (integer ms timestamps, the rate only under meta.json's ``imported.streams``), and B31's walking-rhythm
statement no longer reads a 1000 Hz foot recording's autocorrelation decay as a 93 ms rhythm."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest
from scipy.interpolate import CubicSpline

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.io.validate import implausible_rhythm
from tests.sim_helpers import quiet_walk

G = 9.80665


@pytest.fixture(scope="module")
def walk100():
    return quiet_walk("straight:15", 7921, seed=1)


def _export_1000(session, path):
    """A lab export at 1000 Hz in g and deg/s (the trial's mkexport.py: cubic splines of the 100 Hz walk)."""
    a, g = session["fAccelerometer"], session["fGyroscope"]
    t = np.arange(0.0, a.t[-1] - a.t[0], 0.001)
    df = pd.DataFrame({"Time (s)": t})
    for k, c in enumerate("XYZ"):
        df[f"Acc{c} (g)"] = CubicSpline(a.t - a.t[0], a.values[:, k])(t) / G
    for k, c in enumerate("XYZ"):
        df[f"Gyro{c} (deg/s)"] = np.degrees(CubicSpline(g.t - g.t[0], g.values[:, k])(t))
    df.to_csv(path, index=False, float_format="%.5f")
    return t


def test_track_reads_a_1000_hz_folder_import_wrote(tmp_path, walk100, capsys):
    _export_1000(walk100, tmp_path / "export.csv")
    out = tmp_path / "imp"
    assert main(["import", str(tmp_path / "export.csv"), "--out", str(out)]) == 0
    meta = json.loads((out / "meta.json").read_text())
    assert "rate_hz" not in meta  # only the import's record holds it
    assert meta["imported"]["streams"]["fAccelerometer"]["rate_hz"] == pytest.approx(1000.0)
    s = read_session(out)
    assert s["fAccelerometer"].rate_hz == pytest.approx(1000.0)
    capsys.readouterr()
    assert main(["track", "--no-plot", str(out), "--out", str(tmp_path / "t"), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    summary = summary.get("summary", summary)
    assert summary["distance_m"] == pytest.approx(15.0, rel=0.05)


def _stance_plateau_walk(fs: float, seed: int = 7924) -> np.ndarray:
    """(n, 3) |acc| of 30 s: a broad pulse (sigma 0.2 s) per 1.0 s stride (onsets jittered by 30 ms) over gravity,
    plus a small 10.75 Hz ringing: its autocorrelation decays slowly from lag 0 with wiggles, as the trial's 1000 Hz
    foot export did (a 93 ms local peak above its 1 s stride's)."""
    t = np.arange(0.0, 30.0, 1.0 / fs)
    onsets = np.arange(1, 29) + np.random.default_rng(seed).normal(0.0, 0.03, 28)
    x = 5.0 * np.exp(-0.5 * ((t[:, None] - onsets[None, :]) / 0.2) ** 2).sum(axis=1)
    x += 0.5 * np.sin(2 * np.pi * 10.75 * t)
    return np.column_stack([G + x, np.zeros_like(t), np.zeros_like(t)])


def test_rhythm_of_a_1000_hz_walk_is_not_its_decay_wiggle():
    walk = _stance_plateau_walk(1000.0)
    assert implausible_rhythm(walk, 1000.0) is None  # a 1 s stride at 1000 Hz: no gait faster than any gait
    # B31's own case, the same walk's 100 Hz sample indices read as 1000 Hz, still names its 0.1 s "stride"
    assert implausible_rhythm(walk[::10], 1000.0) == pytest.approx(0.1, abs=0.005)
