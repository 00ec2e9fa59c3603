"""Decisions B77 / B78 (docs/decisions/bad-input.md): clipped accelerometer / gyroscope samples get one warning
naming the file, the fraction and the consequence; the accelerometer's unit is judged on its quietest 0.5 s
windows, so a running foot (whole-file median |acc| ~30 m/s^2) is read while g / mg / counts files are refused."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.io.sensors import SENSORS
from pdrlearn.io.validate import check_units, clipped_samples

G = 9.80665


def _running_foot(seconds: float = 20.0, fs: float = 100.0, seed: int = 0):
    """A foot accelerometer of continuous running: per 0.7 s cycle a 0.12 s stance at gravity and a swing of
    large specific force (|acc| ~25-50 m/s^2; mostly the centripetal pull along the shank, sensor +y, as the
    simulator's running foot, plus a forward swing): whole-file median |acc| above 25."""
    rng = np.random.default_rng(seed)
    t = np.arange(0.0, seconds, 1.0 / fs)
    ph = (t % 0.7) / 0.7
    swing = ph > 0.17
    ang = 2 * np.pi * ph * 3
    mag = 35.0 + 10.0 * np.sin(2 * np.pi * ph * 5)
    v = np.column_stack([0.6 * mag * np.cos(ang), G + mag * (0.8 + 0.2 * np.sin(ang)), 3 * np.sin(ang / 2)])
    v[~swing] = [0.0, G, 0.0]
    return t, v + rng.normal(0, 0.05, v.shape)


def test_running_foot_passes_the_unit_check_and_unit_mistakes_do_not():
    t, v = _running_foot()
    assert np.median(np.linalg.norm(v, axis=1)) > 25.0  # the whole-file median refused it before B78
    spec = SENSORS["fAccelerometer"]
    check_units(spec, v, "f.csv", t=t)  # no error
    with pytest.raises(DataError, match="implausible for a body-worn unit"):
        check_units(spec, v, "f.csv")  # without timestamps: the whole-file median (the old check)
    with pytest.raises(DataError, match=r"f\.csv: median \|acc\| is 1\.00, which looks like "
                                        "units of g"):
        check_units(spec, v / G, "f.csv", t=t)
    with pytest.raises(DataError, match="raw counts or mm/s"):
        check_units(spec, v / G * 1000.0, "f.csv", t=t)  # mg


def _write(folder, name, t, v):
    folder.mkdir(exist_ok=True)
    rows = "\n".join(f"{round(a * 1000)},{x:.6f},{y:.6f},{z:.6f}" for a, (x, y, z) in zip(t, v, strict=True))
    (folder / f"{name}.csv").write_text("timestamp,x,y,z\n" + rows + "\n")


def test_clipped_samples_get_one_warning_naming_the_file_and_fraction(tmp_path, caplog):
    t, v = _running_foot()
    full = 16 * G
    clipped = v * 5.0
    clipped[~(np.linalg.norm(v, axis=1) < 11)] = np.clip(clipped[~(np.linalg.norm(v, axis=1) < 11)], -full, full)
    clipped[np.linalg.norm(v, axis=1) < 11] = v[np.linalg.norm(v, axis=1) < 11]
    n, top = clipped_samples(clipped, "accelerometer")
    assert n > 50 and top == pytest.approx(full)
    assert clipped_samples(v, "accelerometer") == (0, 0.0)  # the unclipped run
    gyr = np.column_stack([np.zeros_like(t), np.zeros_like(t), 12.0 * np.sin(2 * np.pi * t / 0.7)])
    _write(tmp_path / "s", "fAccelerometer", t, clipped)
    _write(tmp_path / "s", "fGyroscope", t, np.clip(gyr, -8.7266, 8.7266))  # a 500 deg/s gyroscope
    with caplog.at_level(logging.WARNING):
        read_session(tmp_path / "s")
    lines = [r.getMessage() for r in caplog.records if "clipped" in r.getMessage()]
    assert len(lines) == 2, lines
    acc = next(m for m in lines if "fAccelerometer.csv" in m)
    assert f"{n} of {len(t)} samples (" in acc and "%) are clipped at +-156.9 m/s^2" in acc and "decision B77" in acc
    assert "stride lengths" in acc and "record with a range above +-16 g" in acc
    gy = next(m for m in lines if "fGyroscope.csv" in m)
    assert "are clipped at +-8.727 rad/s" in gy and "heading" in gy and "above +-500 deg/s" in gy
    caplog.clear()
    _write(tmp_path / "c", "fAccelerometer", t, v)
    _write(tmp_path / "c", "fGyroscope", t, gyr)
    with caplog.at_level(logging.WARNING):
        read_session(tmp_path / "c")
    assert not [r for r in caplog.records if "clipped" in r.getMessage()]  # its gyroscope peak: 2 equal samples


def _impact_walk(seconds: float = 20.0, fs: float = 100.0, seed: int = 7980):
    """A 100 Hz foot accelerometer at rest (gravity on +z) with one sharp heel-strike a second: a single-sample
    spike of 45-70 m/s^2 whose neighbours reach half of it (an impact at 100 Hz peaks on one sample)."""
    rng = np.random.default_rng(seed)
    t = np.arange(0.0, seconds, 1.0 / fs)
    v = np.column_stack([np.zeros_like(t), np.zeros_like(t), np.full_like(t, G)]) + rng.normal(0, 0.05, (t.size, 3))
    for k in np.arange(50, t.size - 1, int(fs)):
        peak = rng.uniform(45.0, 70.0)
        v[k, 2], v[k - 1, 2], v[k + 1, 2] = peak, 0.5 * peak, 0.5 * peak
    return t, v


def test_single_sample_clips_at_a_pinned_full_scale_are_said_b311(tmp_path, caplog):
    t, v = _impact_walk()
    full = 4 * G  # a +-4 g firmware range: every impact clips one sample, never 3 in a row (B77's runs)
    clipped = np.clip(v, -full, full)
    n, top = clipped_samples(clipped, "accelerometer")
    assert n == 20 and top == pytest.approx(full)  # the 20 impacts, each alone at +-4 g
    assert clipped_samples(v, "accelerometer") == (0, 0.0)  # unclipped: each peak reaches its own height
    few = v.copy()
    few[np.flatnonzero(v[:, 2] > full)[:4], 2] = 80.0  # 4 samples at one extreme: under CLIP_PINNED, not said
    assert clipped_samples(few, "accelerometer") == (0, 0.0)
    gyr = np.zeros_like(v)
    _write(tmp_path / "s", "fAccelerometer", t, clipped)
    _write(tmp_path / "s", "fGyroscope", t, gyr)
    with caplog.at_level(logging.WARNING):
        read_session(tmp_path / "s")
    lines = [r.getMessage() for r in caplog.records if "clipped" in r.getMessage()]
    assert len(lines) == 1 and "fAccelerometer.csv: 20 of 2000 samples" in lines[0], lines
    # decision B453 (session 46): a foot accelerometer's line names the range to buy
    assert "reached by 5+ samples one at a time" in lines[0] and "above +-4 g (a foot: +-8 g or more" in lines[0]


def _filtered_impact_walk(full: float | None, fs_out: int = 52, seconds: float = 40.0, seed: int = 10180):
    """A 400 Hz foot with one 25-60 m/s^2 heel-strike pulse (37 ms, Hann) a second on +z, optionally clipped at
    ``full`` there, then decimated to ``fs_out`` Hz by an anti-aliased polyphase filter: a sensor whose converter
    saturates ahead of its own decimation filter (trial T2 finding 3)."""
    from scipy.signal import resample_poly

    rng = np.random.default_rng(seed)
    fs = 400
    t = np.arange(0.0, seconds, 1.0 / fs)
    v = np.column_stack([np.zeros_like(t), np.zeros_like(t), np.full_like(t, G)]) + rng.normal(0, 0.05, (t.size, 3))
    pulse = np.hanning(15)
    for k in np.arange(200, t.size - 20, fs):
        v[k:k + 15, 2] += rng.uniform(25.0, 60.0) * pulse
    if full is not None:
        v = np.clip(v, -full, full)
    out = resample_poly(v, fs_out, fs, axis=0)
    return np.arange(len(out)) / fs_out, out


def test_clipped_before_the_sensors_filter_is_found_by_ceiling_clip_b403(tmp_path, caplog):
    """Decision B403's check finds the ceiling; decisions B411 / B415: no pipeline says it (not adopted, no switch)."""
    from pdrlearn.io.validate import ceiling_clip

    full = 4 * G
    t, clipped = _filtered_impact_walk(full)
    assert clipped_samples(clipped, "accelerometer") == (0, 0.0)  # no flat top left for B77 / B311
    assert ceiling_clip(clipped) == pytest.approx(full)
    assert ceiling_clip(_filtered_impact_walk(None)[1]) == 0.0  # the same walk unclipped: its peaks spread
    _write(tmp_path / "s", "fAccelerometer", t, clipped)
    _write(tmp_path / "s", "fGyroscope", t, np.zeros_like(clipped))
    with caplog.at_level(logging.WARNING):
        read_session(tmp_path / "s")
    assert not [r for r in caplog.records if "B403" in r.getMessage()]


def test_a_faster_unclipped_real_walker_is_not_called_clipped_b411(tmp_path, caplog):
    """Decision B411 (review R3 finding 2): the real gaitmap_ms_right walk with its dynamics x1.3 (gravity kept, not
    clipped) put its top 10 peaks within 7 % just under 8 g and B403 warned; B403 is now off by default."""
    import pandas as pd

    from pdrlearn.io.validate import ceiling_clip
    from tests.conftest import external_session

    src = external_session("gaitmap_ms_right")
    dst = tmp_path / "m1.3"
    dst.mkdir()
    for p in src.iterdir():
        if p.is_file():
            (dst / p.name).write_bytes(p.read_bytes())
    d = pd.read_csv(src / "fAccelerometer.csv")
    v = d.iloc[:, 1:4].to_numpy(float)
    n = int(round(read_session(src).streams["fAccelerometer"].rate_hz))  # a 1 s moving-average gravity
    grav = np.column_stack([np.convolve(np.pad(c, (n // 2, n - 1 - n // 2), mode="edge"), np.ones(n) / n, "valid")
                            for c in v.T])
    d.iloc[:, 1:4] = grav + 1.3 * (v - grav)
    d.to_csv(dst / "fAccelerometer.csv", index=False)
    assert ceiling_clip(d.iloc[:, 1:4].to_numpy(float)) == pytest.approx(8 * G)  # the rule alone still fires
    with caplog.at_level(logging.WARNING):
        read_session(dst)
    assert not [r for r in caplog.records if "B403" in r.getMessage()]
