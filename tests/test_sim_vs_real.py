"""Simulated foot signals against the real gaitmap foot recordings (level walking, stairs up and down).

Per stride: peak |acc| (m/s^2), peak pitch rate (|gyroscope| about the foot's lateral axis, rad/s) and
stride period (s, start of one stride to the start of the next). Both sides are resampled to 100 Hz with
pdrlearn.signal.resample_stream. Run with ``pytest -s`` to see the side-by-side table.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.io import read_session
from pdrlearn.signal import resample_stream
from pdrlearn.sim import simulate

RATE = 100.0
REAL = {
    "flat": ["gaitmap_level_left", "gaitmap_level_right"],
    "up": ["gaitmap_stairs_up_left"],
    "down": ["gaitmap_stairs_down_left"],
}
SIM_USERS = (1, 2, 3, 4)


def _lateral_axis(session) -> int:
    frame = session.frames["foot"]
    return next(i for i, ax in enumerate((frame.x, frame.y, frame.z)) if ax in ("left", "right"))


def stride_features(session, rows: pd.DataFrame) -> pd.DataFrame:
    """Peak |acc|, peak |lateral gyro| and stride period of the strides in ``rows`` (consecutive rows)."""
    acc = resample_stream(session["fAccelerometer"], RATE)
    gyr = resample_stream(session["fGyroscope"], RATE)
    lat = _lateral_axis(session)
    starts = session.steps.start_s.to_numpy()
    ends = session.steps.end_s.to_numpy()
    out = []
    for i, r in rows.iterrows():
        pos = session.steps.index.get_loc(i)
        # stride period: to the start of the next stride when it follows without a pause
        contiguous = pos + 1 < len(starts) and starts[pos + 1] - ends[pos] < 0.5
        m = (acc.t >= r.start_s) & (acc.t < r.end_s)
        g = (gyr.t >= r.start_s) & (gyr.t < r.end_s)
        out.append(
            {
                "peak_acc": float(np.linalg.norm(acc.values[m], axis=1).max()),
                "peak_pitch_rate": float(np.abs(gyr.values[g, lat]).max()),
                "peak_offaxis_rate": float(np.abs(np.delete(gyr.values[g], lat, axis=1)).max()),
                "period_s": float(starts[pos + 1] - r.start_s) if contiguous else np.nan,
            }
        )
    return pd.DataFrame(out)


@pytest.fixture(scope="module")
def real_features(real_dir) -> dict[str, pd.DataFrame]:
    feats = {}
    for terrain, names in REAL.items():
        parts = []
        for name in names:
            s = read_session(real_dir / name)
            st = s.steps
            keep = st.terrain == terrain
            if "turn" in st:
                keep &= ~st.turn.astype(bool)
            parts.append(stride_features(s, st[keep]))
        feats[terrain] = pd.concat(parts, ignore_index=True)
    return feats


@pytest.fixture(scope="module")
def sim_features() -> dict[str, pd.DataFrame]:
    parts: dict[str, list[pd.DataFrame]] = {"flat": [], "up": [], "down": []}
    for user in SIM_USERS:
        level = simulate("A", user, rate_hz=RATE, seed=user)
        st = level.steps
        parts["flat"].append(stride_features(level, st[st.steady & (st.terrain == "flat")]))
        stairs = simulate("terrain", user, rate_hz=RATE, seed=user)
        st = stairs.steps
        for terrain in ("up", "down"):
            parts[terrain].append(stride_features(stairs, st[st.steady & (st.terrain == terrain)]))
    return {k: pd.concat(v, ignore_index=True) for k, v in parts.items()}


def _summary(df: pd.DataFrame, col: str) -> str:
    q = df[col].dropna().quantile([0.0, 0.5, 1.0]).to_numpy()
    return f"{q[0]:6.2f} {q[1]:6.2f} {q[2]:6.2f}"


def test_print_side_by_side(real_features, sim_features):
    lines = ["", f"{'terrain':7} {'feature':18} {'real min/median/max':>22} {'sim min/median/max':>22}  n real/sim"]
    for terrain in ("flat", "up", "down"):
        for col in ("peak_acc", "peak_pitch_rate", "peak_offaxis_rate", "period_s"):
            r, s = real_features[terrain], sim_features[terrain]
            lines.append(f"{terrain:7} {col:18} {_summary(r, col):>22} {_summary(s, col):>22}  {len(r)}/{len(s)}")
    print("\n".join(lines))
    assert all(len(v) >= 10 for v in sim_features.values())


@pytest.mark.parametrize("terrain", ["flat", "up", "down"])
@pytest.mark.parametrize("col", ["peak_acc", "peak_pitch_rate", "period_s"])
def test_simulated_strides_fall_in_real_range(real_features, sim_features, terrain, col):
    real, sim = real_features[terrain][col].dropna(), sim_features[terrain][col].dropna()
    lo, hi = real.min(), real.max()
    assert lo <= sim.median() <= hi, f"{terrain} {col}: sim median {sim.median():.2f} outside real [{lo:.2f}, {hi:.2f}]"
    inside = ((sim >= lo) & (sim <= hi)).mean()
    assert inside >= 0.8, f"{terrain} {col}: only {inside:.0%} of simulated strides within real [{lo:.2f}, {hi:.2f}]"


def test_level_offaxis_rotation_like_real(real_features, sim_features):
    """Roll/yaw of the swinging foot (the gyroscope axes other than the lateral one) on level ground.

    Only level walking: the real stair recordings are mounted on the instep pitched ~50 deg, which mixes
    the pitch rate into the other axes."""
    ratio = sim_features["flat"].peak_offaxis_rate.median() / real_features["flat"].peak_offaxis_rate.median()
    assert 0.6 < ratio < 1.6


# -- waist: simulated pelvis vs the real lower-back recordings (mobgap) ---------------------------------
def _axis(session, direction: str) -> tuple[int, float]:
    frame = session.frames["waist"]
    opposite = {"up": "down", "forward": "backward"}[direction]
    for i, ax in enumerate((frame.x, frame.y, frame.z)):
        if ax in (direction, opposite):
            return i, 1.0 if ax == direction else -1.0
    raise AssertionError(f"no {direction} axis in {frame}")


def waist_features(session, rows: pd.DataFrame) -> pd.DataFrame:
    acc = resample_stream(session["wAccelerometer"], RATE)
    gyr = resample_stream(session["wGyroscope"], RATE)
    up, _ = _axis(session, "up")
    fwd, _ = _axis(session, "forward")
    out = []
    for _, r in rows.iterrows():
        m = (acc.t >= r.start_s) & (acc.t < r.end_s)
        g = (gyr.t >= r.start_s) & (gyr.t < r.end_s)
        out.append(
            {
                "vert_acc_range": float(np.ptp(acc.values[m, up])),
                "ap_acc_sd": float(acc.values[m, fwd].std()),
                "yaw_rate_range": float(np.ptp(gyr.values[g, up])),
            }
        )
    return pd.DataFrame(out)


def test_waist_signals_match_real_lower_back(real_dir):
    names = ["mobgap_HA001_Test5_Trial1", "mobgap_HA001_Test5_Trial2"]
    if not all((real_dir / n).exists() for n in names):
        pytest.skip("mobgap lower-back recordings not in datasets/real")
    real = []
    for n in names:
        s = read_session(real_dir / n)
        st = s.steps
        real.append(waist_features(s, st[~st.turn.astype(bool)]))
    real_df = pd.concat(real, ignore_index=True)
    sim = []
    for user in SIM_USERS:
        s = simulate("A", user, "slow", rate_hz=RATE, seed=user)  # the mobgap walk is at ~1 m/s
        sim.append(waist_features(s, s.steps[s.steps.steady]))
    sim_df = pd.concat(sim, ignore_index=True)
    lines = ["", f"{'waist feature':16} {'real min/median/max':>22} {'sim min/median/max':>22}"]
    for col in real_df:
        lines.append(f"{col:16} {_summary(real_df, col):>22} {_summary(sim_df, col):>22}")
        ratio = sim_df[col].median() / real_df[col].median()
        assert 0.5 < ratio < 2.0, f"waist {col}: sim/real median ratio {ratio:.2f}"
    print("\n".join(lines))
