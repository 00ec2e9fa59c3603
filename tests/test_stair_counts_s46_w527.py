"""Decision W527 (trial T1 F3): on the lower back, n_stair_strides_up / _down count the steps of W108's climbs by
their climb's sign (W526's pieces), not the steps whose own barometric change reaches 0.10 m - a step-to flight's
steps split each riser ~0.03 / ~0.15 m, so L179's rule counted about a third of them (T1: 8 / 8 of 24 / 24)."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.track.gait import stair_counts


def _flight(seed: int, climb: bool = True) -> pd.DataFrame:
    rng = np.random.default_rng(seed)
    rise = np.tile([0.03, 0.14], 12)  # 24 step-to steps up, then 24 down, one run of climb rows (no step at the top)
    level = rng.normal(0.0, 0.03, 10)
    dz = np.concatenate([level, rise + rng.normal(0.0, 0.02, 24), -rise + rng.normal(0.0, 0.02, 24), level])
    return pd.DataFrame({"unit": "waist", "dz_m": dz, "pause_dz_m": 0.0,
                         "climb": np.r_[np.zeros(10, bool), np.full(48, climb), np.zeros(10, bool)]})


def test_a_step_to_flights_steps_count_as_its_climbs():
    for seed in range(5):
        steps = _flight(seed)
        assert stair_counts(steps, np.ones(len(steps), bool)) == (24, 24)
        # an invalid row is not counted
        valid = np.ones(len(steps), bool)
        valid[20] = False
        assert stair_counts(steps, valid) == (23, 24)


def test_without_climbs_l179_counts_as_before():
    steps = _flight(0, climb=False)
    dz = steps["dz_m"].to_numpy(float)
    expect = (int((dz >= 0.10).sum()), int((dz <= -0.10).sum()))
    assert stair_counts(steps, np.ones(len(steps), bool)) == expect
    assert expect[0] < 16 and expect[1] < 16  # about half the steps reach 0.10 m: what T1 saw
    # a foot track (no climb column) keeps L179's rule by each row's sign
    foot = steps.drop(columns="climb").assign(unit="foot")
    assert stair_counts(foot, np.ones(len(foot), bool)) == expect
