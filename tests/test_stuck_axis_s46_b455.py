"""Decision B455 (session 46, FF, trial T3 finding F4): one axis of an accelerometer / gyroscope held at one value
while the sensor's other axes move is a stuck axis, said by ``read_session`` (so ``info`` / ``track`` / ``run``) and
by the live Tracker (decision E303) through one kernel, :func:`pdrlearn.kernels.clipping.stuck_runs`; no line on a
clean walk, its 16-bit quantised copy, or a quantised resting sensor's noise."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.kernels.clipping import STUCK_MIN_RUNS, stuck_runs
from pdrlearn.runtime.__main__ import replay
from pdrlearn.warning_lines import captured_warnings

BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"


def _copy(src: Path, dst: Path) -> Path:
    dst.mkdir()
    for f in src.iterdir():
        (dst / f.name).write_bytes(f.read_bytes())
    return dst


@pytest.fixture(scope="module")
def walks(tmp_path_factory):
    """A simulated walk (user 14330, 100 Hz), its copy whose foot gyroscope's z axis holds its last value for 8
    samples (80 ms) in every stride's mid-swing (trial T3's stuck.py), and a 16-bit quantised copy (+-8 g /
    1000 deg/s, still periods included)."""
    root = tmp_path_factory.mktemp("stuck46")
    clean = root / "clean"
    assert main(["simulate", "--route", "stand:3, straight:12, stand:3", "--rate", "100", "--user-seed", "14330",
                 "--out", str(clean)]) == 0
    stuck = _copy(clean, root / "stuck")
    steps = pd.read_csv(clean / "steps.csv")
    g = pd.read_csv(stuck / "fGyroscope.csv")
    t = g["timestamp"].to_numpy()
    for _, r in steps.iterrows():
        a = int(np.searchsorted(t, (r["tc_ms"] + r["ic_ms"]) / 2)) - 4
        g.loc[a:a + 7, "z"] = g.loc[a - 1, "z"]
    g.to_csv(stuck / "fGyroscope.csv", index=False, float_format="%.17g")
    quant = _copy(clean, root / "quant")
    for name, full in (("fAccelerometer", 8 * 9.80665), ("fGyroscope", np.deg2rad(1000.0)),
                       ("wAccelerometer", 8 * 9.80665), ("wGyroscope", np.deg2rad(1000.0))):
        d = pd.read_csv(quant / f"{name}.csv")
        lsb = full / 32768
        d[["x", "y", "z"]] = np.round(d[["x", "y", "z"]].to_numpy() / lsb) * lsb
        d.to_csv(quant / f"{name}.csv", index=False, float_format="%.17g")
    return clean, stuck, quant


def _lines(folder: Path) -> list[str]:
    with captured_warnings(echo=False) as logged:
        read_session(folder)
    return [w for w in logged if "B455" in w]


def test_b455_a_stuck_gyroscope_axis_is_said_offline_naming_file_and_axis(walks):
    _, stuck, _ = walks
    lines = _lines(stuck)
    assert len(lines) == 1  # one line per stuck axis
    assert "fGyroscope.csv: axis z held one value for" in lines[0] and "longest 9 samples" in lines[0]


def test_b455_no_line_on_the_clean_walk_or_its_16_bit_copy(walks):
    clean, _, quant = walks
    assert _lines(clean) == []
    assert _lines(quant) == []


def test_b455_a_quantised_resting_sensor_s_noise_is_no_stuck_axis():
    """The amendment (a resting 50 Hz accelerometer quantised at 0.0192 m/s^2 with float noise in its values: its
    axes hop between a few levels and repeat one for 3+ samples now and then; the rule as first written said it)."""
    rng = np.random.default_rng(0)
    step = 8 * 9.80665 / 4096
    v = np.array([0.6, 9.78, 0.8]) + rng.normal(0.0, 0.03, (3000, 3))
    v = np.round(v / step) * step + rng.uniform(-1e-16, 1e-16, v.shape)  # converted counts' float noise
    assert all(len(r) == 0 for r in stuck_runs(v, 0.02, "accelerometer"))


def test_b455_the_kernel_needs_the_other_axes_moving_and_min_runs():
    t = np.arange(0, 20, 0.01)
    w = np.column_stack([3 * np.sin(2 * np.pi * t), 2 * np.cos(2 * np.pi * 0.9 * t), 4 * np.sin(2 * np.pi * 1.1 * t)])
    held = w.copy()
    for a in range(150, 1900, 200):
        held[a:a + 8, 2] = held[a - 1, 2]
    assert len(stuck_runs(held, 0.01, "gyroscope")[2]) >= STUCK_MIN_RUNS
    frozen = held.copy()
    for a in range(150, 1900, 200):
        frozen[a:a + 8] = frozen[a - 1]  # all three axes held: B120's frozen sensor, not one stuck axis
    assert all(len(r) == 0 for r in stuck_runs(frozen, 0.01, "gyroscope"))


def test_b455_e303_the_live_tracker_says_the_stuck_axis(walks):
    clean, stuck, _ = walks
    tracker, _ = replay(BUNDLE, stuck)
    lines = [w for w in tracker.warnings if "B455" in w]
    assert len(lines) == 1 and lines[0].startswith("stream fGyroscope: axis z held one value")
    tracker, _ = replay(BUNDLE, clean)
    assert not [w for w in tracker.warnings if "B455" in w or "E303" in w]


@pytest.mark.parametrize(("user", "rate", "length"), [(7960, 50.0, 30), (3, 20.0, None)])
def test_b455_no_line_on_clean_simulated_walks_at_50_and_20_hz(user, rate, length):
    """The amendments: user 7960's simulated 50 Hz walk (tests/test_machine_contract's) holds its foot accelerometer's
    z for 3 samples (0.06 s) 3 times while the foot moves (STUCK_S 0.05 -> 0.08 s); user 3's 20 Hz walk (the
    simulator's default rate) holds it 3 samples (0.15 s) before heel strikes 11 times, left by a step or two of the
    axis (the jump against the axis's typical change, not its smallest step, which float noise makes 1e-4)."""
    from pdrlearn.io.sensors import SENSORS
    from pdrlearn.sim import simulate

    walk = simulate("walk", user, **({"length_m": length} if length else {}), rate_hz=rate)
    for name, s in walk.streams.items():
        if SENSORS[name].kind in ("accelerometer", "gyroscope"):
            runs = stuck_runs(s.values, 1.0 / rate, SENSORS[name].kind)
            assert all(len(r) < STUCK_MIN_RUNS for r in runs), name
