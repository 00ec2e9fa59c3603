"""Decisions E127-E128: across a foot dropout the tracks hold the position (one row of length 0 with `gap_s`); its
`pos_sigma_m` grows by the displacement that row misses, radius^2 + (v g)^2, the same way offline, streamed and in
`pdrlearn run` (one function reads steps.csv for all three)."""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from typer.testing import CliRunner

from pdrlearn.cli import app
from pdrlearn.io import write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.plasys import track_plasys
from pdrlearn.track.position_sigma import (
    GAP_FALLBACK_SPEED_MPS,
    SIGMA_PARAMS,
    held_gap_variance,
    missed_walk,
    reach_bound,
    sigma_per_row,
)
from tests.runtime_helpers import without

BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"
FOOT = ("fAccelerometer", "fGyroscope", "fForceA", "fForceB")
A, B = 15.0, 35.0  # the foot unit silent for 20 s of walking


@pytest.fixture(scope="module")
def dropout(tmp_path_factory):
    """A fresh simulated user (4738) walking 40 m, turning 90 deg, walking 40 m; the foot unit silent 15-35 s."""
    s = simulate_path(parse_route("straight:40, turn:90, straight:40"), UserProfile.from_seed(4738), speed="normal",
                      rate_hz=20.0, seed=4738, name="dropout", scenario="route")
    cut = without(s, A, B, FOOT)
    folder = tmp_path_factory.mktemp("e127") / "dropout"
    write_session(cut, folder)
    return cut, folder


def _across(traj: pd.DataFrame, steps: pd.DataFrame) -> tuple[float, float, float]:
    """The radius before and after the held row, and the growth E127 asks: (v g)^2 of the row."""
    held = steps[(steps["gap_s"] > 0) & (steps["length_m"] == 0)]
    assert len(held) == 1  # the dropout is one held row
    row = held.iloc[0]
    before = float(traj.loc[traj["t"] < row["end_s"] - 1e-6, "pos_sigma_m"].iloc[-1])
    after = float(traj.loc[traj["t"] >= row["end_s"] - 1e-6, "pos_sigma_m"].iloc[0])
    growth = 2 * float(held_gap_variance(steps)[held.index[0]])  # radius^2: both axes
    return before, after, growth


def test_the_radius_grows_across_a_held_foot_dropout_offline_streamed_and_run(dropout, tmp_path):
    cut, folder = dropout
    runs = {"offline": track_plasys(cut), "streamed": track_plasys(cut, streaming=True)}
    r = CliRunner().invoke(app, ["run", "--no-plot", str(BUNDLE), str(folder), "--out", str(tmp_path / "run")])
    assert r.exit_code == 0, r.output
    got = {k: (v.trajectory, v.steps) for k, v in runs.items()}
    got["run"] = (pd.read_csv(tmp_path / "run" / "trajectory.csv"), pd.read_csv(tmp_path / "run" / "steps.csv"))
    for name, (traj, steps) in got.items():
        before, after, growth = _across(traj, steps)
        gap = float(steps.loc[steps["gap_s"] > 0, "gap_s"].iloc[0])
        assert gap == pytest.approx(B - A, abs=1.0), name
        # v: the walker's speed, ~1 m/s or more for a normal pace; the missed displacement is metres, not a stride
        assert growth > (0.8 * gap) ** 2, name
        # sigma after >= before plus the gap's growth, or L333's cut: half the radius the walk can reach
        k = int(np.flatnonzero(((steps["gap_s"] > 0) & (steps["length_m"] == 0)).to_numpy())[0])
        L = np.nan_to_num(steps["length_m"].to_numpy(float))
        cap = 0.5 * reach_bound(L, np.nan_to_num(steps["heading_rad"].to_numpy(float)),
                                missed_walk(L, np.zeros(len(L), bool), held_gap_variance(steps)))[k]
        assert after ** 2 >= min(before ** 2 + growth, cap ** 2) - 1e-6, name
        assert after > before + 5.0, name
        assert float(traj["pos_sigma_m"].iloc[-1]) >= after, name  # kept by every later row
    # the three agree on the growth: one formula on their own steps (speeds within 10 %)
    g = [_across(*got[k])[2] for k in ("offline", "streamed", "run")]
    assert max(g) / min(g) < 1.25


def test_main_kept_the_radius_flat_across_the_gap(dropout):
    """What E127 fixed: without the held row's variance (main's model) the radius does not move across the gap."""
    cut, _ = dropout
    res = track_plasys(cut)
    steps, t = res.steps, res.trajectory["t"].to_numpy(float)
    main = sigma_per_row(steps.drop(columns=["gap_s"]), t, SIGMA_PARAMS["plasys-fused"])
    row = steps[steps["gap_s"] > 0].iloc[0]
    i = np.searchsorted(t, row["end_s"] - 1e-6)
    assert main[i] == pytest.approx(main[i - 1])
    assert res.trajectory["pos_sigma_m"].to_numpy()[i] > main[i - 1] + 5.0


def test_a_gap_without_walking_strides_uses_the_stated_speed():
    steps = pd.DataFrame({"start_s": [0.0], "end_s": [10.0], "length_m": [0.0], "heading_rad": [0.0],
                          "gap_s": [10.0]})
    assert held_gap_variance(steps) == pytest.approx([0.5 * (GAP_FALLBACK_SPEED_MPS * 10.0) ** 2])
    s = sigma_per_row(steps, np.array([0.0, 10.0]), SIGMA_PARAMS["plasys-fused"])
    # E127's radius, cut by L333 to half the 14 m the walker can have gone in the gap
    assert s[1] == pytest.approx(min(np.hypot(GAP_FALLBACK_SPEED_MPS * 10.0, np.sqrt(2) * 1.5),
                                     0.5 * GAP_FALLBACK_SPEED_MPS * 10.0))
    # a stride with a gap that was walked (a length) holds nothing; no gap column: nothing
    walked = steps.assign(length_m=[12.0])
    assert held_gap_variance(walked) is None and held_gap_variance(steps.drop(columns=["gap_s"])) is None
