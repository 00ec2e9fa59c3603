"""Decisions L436 / L437: the two feet of one stair walk must agree on its height (trial T3 finding 3)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.foot_heights import height_agreement, height_warning
from pdrlearn.track.plasys import track_plasys

ROOT = Path(__file__).resolve().parents[1]


def _steps(dz) -> pd.DataFrame:
    return pd.DataFrame({"dz_m": np.asarray(dz, float), "unit": "foot"})


def _flight(median: float, n: int = 15, seed: int = 0) -> list[float]:
    rng = np.random.default_rng(seed)
    return [0.0, 0.0] + list(median + rng.normal(0.0, 0.02, n)) + [0.0, 0.0]


def test_a_biased_foot_is_warned_about_and_agreeing_feet_are_not():
    agree = height_warning(_steps(_flight(0.30, seed=1)), _steps(_flight(0.30, seed=2)))
    assert agree is None
    left, right = _steps(_flight(0.30, seed=1)), _steps(_flight(0.33, seed=2))  # 10 % per stride: 0.45 m
    a = height_agreement(left, right)["up"]
    assert a["n"] == [15, 15] and 0.01 < a["sd_m"] < 0.03  # the within-foot spread, not the feet's bias
    assert a["bound_m"] == pytest.approx(1.96 * a["sd_m"] * np.sqrt(30))  # Bland-Altman limits of agreement
    line = height_warning(left, right)
    assert line is not None and "ascent left" in line and "L436" in line and "descent" not in line
    # descents too (dz < 0)
    assert "descent left" in height_warning(_steps(-np.array(_flight(0.30, seed=1))),
                                            _steps(-np.array(_flight(0.33, seed=2))))


def test_the_bound_is_at_least_one_levelled_stride_and_few_strides_are_not_compared():
    same = [0.0, 0.30, 0.30, 0.30, 0.30, 0.0]
    a = height_agreement(_steps(same), _steps(same[:-2] + [0.38, 0.0]))["up"]
    assert a["sd_m"] == 0.0 and a["bound_m"] == pytest.approx(0.10)  # L39: a stride under 0.10 m is levelled
    assert height_warning(_steps(same), _steps(same[:-2] + [0.38, 0.0])) is None  # 0.08 m apart
    assert height_agreement(_steps([0.3, 0.3]), _steps([0.5, 0.5])) == {}


def test_simulated_feet_of_one_stair_walk_raise_no_warning(tmp_path, capsys):
    """No false alarm: the left and the right foot of one simulated stair walk (S54, same seed and clock)."""
    route = parse_route("stand:2, straight:2, up:12, turn:180, down:12, straight:2, stand:2")
    tracks = []
    for foot in ("left", "right"):
        s = simulate_path(route, UserProfile.from_seed(8480), rate_hz=50.0, seed=8480, instrumented_foot=foot)
        write_session(s, tmp_path / foot)
        tracks.append(track_plasys(s, toe_off=True).steps)
    assert set(height_agreement(*tracks)) == {"up", "down"}  # both directions compared (6-7 strides a foot)
    assert main(["gait", str(tmp_path / "left"), str(tmp_path / "right")]) == 0
    assert "L436" not in capsys.readouterr().err


@pytest.mark.skipif(not (ROOT / "datasets/external/gaitmap_stairs_up_right").is_dir(),
                    reason="datasets/external (pdrlearn fetch) not present")
def test_the_real_stair_pair_disagrees_on_the_ascent(capsys):
    """Gaitmap's stairs (one staircase, both feet on one clock): the left foot's ascent reads 0.35 m under the
    right's, beyond the 0.22 m the feet's per-stride spread explains (0.39 / 0.24 m before L627's start tilt)."""
    rc = main(["gait", str(ROOT / "datasets/real/gaitmap_stairs_up_left"),
               str(ROOT / "datasets/external/gaitmap_stairs_up_right")])
    assert rc == 0
    err = capsys.readouterr().err
    assert "ascent left 4.52 m / right 4.87 m" in err and "L437" in err
