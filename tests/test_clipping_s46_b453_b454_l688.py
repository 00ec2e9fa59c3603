"""Decisions B453 / B454 / L688 (session 46, FE, trial T3 findings F1 / F2): a clipped foot accelerometer's line states
the size of the effect and the range to buy (B453, figures from experiments/clip_range_s46.py); the ZUPT error put at
the clipped samples is an option, ``clip_noise`` (B454: not adopted by its rule; session 48, B470: the offline track's
default when the foot accelerometer clips); the barometer line names the clipping and ``--altitude fused`` (L688)."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.io.validate import (
    FOOT_ACCEL_CLIP_COST,
    FOOT_ACCEL_CLIP_NOISE,
    FOOT_UNCLIPPED_PCT,
    foot_accel_clip_g,
    saturation_warning,
)
from pdrlearn.kernels.barometer_check import barometer_warning
from pdrlearn.kernels.clip_noise import clip_variance
from pdrlearn.track.evaluate import track_summary
from pdrlearn.track.plasys import track_plasys

G = 9.80665
RESULTS = Path(__file__).resolve().parents[1] / "experiments" / "results"


@pytest.fixture(scope="module")
def walks(tmp_path_factory):
    """A fast stair walk up and back down (user 14320, outside B454's measured 14300-14305) and the same files with
    the foot accelerometer and gyroscope clipped flat at +-4 g / 500 deg/s, as B454 measured (the simulated heel
    strikes reach 6-16 g, the swings 400-900 deg/s)."""
    root = tmp_path_factory.mktemp("clip46")
    clean = root / "clean"
    assert main(["simulate", "--route", "stand:3, straight:8, up:12, turn:180, down:12, straight:4, stand:3",
                 "--speed", "fast", "--rate", "100", "--user-seed", "14320", "--out", str(clean)]) == 0
    clip = root / "clip"
    clip.mkdir()
    for f in clean.iterdir():
        (clip / f.name).write_bytes(f.read_bytes())
    for name, full in (("fAccelerometer", 4 * G), ("fGyroscope", np.deg2rad(500.0))):
        a = pd.read_csv(clean / f"{name}.csv")
        a[["x", "y", "z"]] = np.clip(a[["x", "y", "z"]].to_numpy(), -full, full)
        a.to_csv(clip / f"{name}.csv", index=False)
    return clean, clip


def test_b453_the_foot_accelerometer_line_gives_the_cost_and_the_range_to_buy():
    line = saturation_warning("f.csv", "accelerometer", 46, 6878, 4 * G, "foot")
    # before B453: "record with a range above +-4 g" alone, with no size of the effect
    assert "-1.26 / -2.75 / -8.25 / -26.85 %, 1.06 m off" in line
    assert "a foot: +-8 g or more for walking, +-16 g for brisk walking or running" in line
    assert "by default (B470; --params '{\"clip_noise\": false}' turns it off)" in line  # B454's option, B470
    assert "+0.35 / -0.39 / -1.04 / -21.40 %, 0.01 m (B454)" in line
    eight = saturation_warning("f.csv", "accelerometer", 6, 6878, 8 * G, "foot")
    assert "-3.20 %" in eight and "(a foot: +-16 g for brisk walking or running)" in eight
    assert "simulated walks" not in saturation_warning("f.csv", "accelerometer", 6, 6878, 16 * G, "foot")
    waist = saturation_warning("w.csv", "accelerometer", 6, 6878, 2 * G, "waist")
    assert "simulated walks" not in waist and "a foot:" not in waist


def test_b453_b454_the_line_s_figures_are_the_experiment_s():
    """The constants are the medians experiments/clip_range_s46.py printed (its rows are committed)."""
    df = pd.concat([pd.read_csv(p) for p in sorted(RESULTS.glob("clip_range_s46_part*.csv"))])
    for table, dc in ((FOOT_ACCEL_CLIP_COST, False), (FOOT_ACCEL_CLIP_NOISE, True)):
        for scale, row in table.items():
            g = df[(df["range"] == f"{scale:g}g") & (df.declip == dc)]
            med = [g[g.speed == sp].distance_error_pct.median() for sp in ("slow", "normal", "fast", "brisk")]
            alt = g[g.speed == "normal"].final_altitude_error_m.abs().median()
            assert np.allclose(row, [*med, alt], atol=0.005), (scale, dc)
    base = df[df["range"] == "none"].groupby("speed").distance_error_pct.median()
    assert base.abs().max() <= FOOT_UNCLIPPED_PCT + 0.005


def test_b454_clip_noise_is_an_option_that_puts_the_zupt_error_at_the_clipped_samples(walks):
    clean, clip = walks
    s = read_session(clip)
    truth = track_summary(track_plasys(read_session(clean)), read_session(clean))
    default = track_summary(track_plasys(s), s)
    noise = track_summary(track_plasys(s, params={"clip_noise": True}), s)
    off = track_summary(track_plasys(s, params={"clip_noise": False}), s)
    # the option recovers most of the distance and part of the phantom climb (before: no such keyword)
    assert abs(noise["distance_error_pct"]) < 0.5 * abs(off["distance_error_pct"])
    assert abs(noise["altitude_change_m"]) < abs(off["altitude_change_m"]) - 0.5
    assert abs(truth["distance_error_pct"]) < 1.5
    # B470 (session 48; B454 had kept it an option): the default sets it on a clipped foot accelerometer, with a
    # line; {"clip_noise": false} gives L21's track back
    assert noise["distance_m"] == default["distance_m"]
    assert any("decision B470" in w for w in default["info"]["warnings"])
    assert off["distance_error_pct"] < -2.0 and not any("decision B470" in w for w in off["info"]["warnings"])


def test_b454_an_unclipped_file_is_unchanged_bit_for_bit(walks):
    clean, _ = walks
    s = read_session(clean)
    assert clip_variance(s.streams["fAccelerometer"].values, 5, 0.002) is None
    a = track_plasys(s, params={"clip_noise": True}).steps
    b = track_plasys(s).steps
    pd.testing.assert_frame_equal(a, b)
    pd.testing.assert_frame_equal(track_plasys(s, params={"clip_noise": False}).steps, b)  # B470 (e)


def test_l688_the_barometer_line_names_the_clipping_and_altitude_fused(walks):
    clean, clip = walks
    assert foot_accel_clip_g(read_session(clean)) is None
    s = read_session(clip)
    assert foot_accel_clip_g(s) == pytest.approx(4.0)
    out = track_summary(track_plasys(s, params={"clip_noise": False}), s)  # B470's default leaves no such climb
    line = next(w for w in out["info"]["warnings"] if "disagrees with the waist barometer" in w)
    # before L688: it blamed a lift, an escalator or slopes only
    assert "the foot accelerometer clips at +-4 g (B77), the likely cause here" in line
    assert "`track --altitude fused` (L154) takes the height from the barometer instead (decision L688)" in line
    summary = {"altitude_change_m": 2.45, "barometer_altitude_change_m": -0.38, "barometer_unused": True}
    assert "clips" not in barometer_warning(summary)
    fused = barometer_warning({**summary, "barometer_unused": False}, foot_clip_g=4.0)
    assert "likely cause here" in fused and "takes the height from the barometer instead" not in fused
