"""Decisions D31 (the innovation gate), D32 (the stretched path ends at the filter's posterior) and E212 (``add_fix``
refuses a fix time far after the pushed samples): session 38, trial T5 findings 5, 6 and 9."""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd
import pytest

from pdrlearn.aid.sporadic import SporadicFixFusion
from pdrlearn.errors import DataError
from pdrlearn.kernels.fixes import GATE_CHI2_2DOF, FixConfig, LiveFixes
from pdrlearn.runtime.fixes import FixInput


def _walk(n: int = 60):
    """A straight walk east, 0.7 m steps of 1 s, and fixes on it every 10 s: per-axis noise 0.3 m (accuracy 0.5 m),
    the third one 10 m north with accuracy 3 m (3.3 sigma; the trial's wrong beacon)."""
    steps = pd.DataFrame({"start_s": np.arange(n, dtype=float), "end_s": np.arange(1, n + 1, dtype=float),
                          "length_m": 0.7, "heading_rad": 0.0})
    rng = np.random.default_rng(9763)
    ts = np.arange(5.5, n - 1, 10.0)
    fx = pd.DataFrame({"t": ts, "x": 0.7 * ts + rng.normal(0, 0.3, len(ts)), "y": rng.normal(0, 0.3, len(ts)),
                       "accuracy_m": 0.5})
    fx.loc[2, "y"] += 10.0
    fx.loc[2, "accuracy_m"] = 3.0
    return steps, fx


def test_the_gate_rejects_a_wrong_fix_and_names_it_d31():
    assert GATE_CHI2_2DOF == pytest.approx(11.62, abs=0.01)  # chi-square, 2 dof, 0.997
    steps, fx = _walk()
    plain = SporadicFixFusion(period_s=None, innovation_gate=False).run(steps, fx)
    gated = SporadicFixFusion(period_s=None, innovation_gate=True).run(steps, fx)
    assert plain.stats_["fixes_used"] == len(fx)
    assert gated.stats_["fixes_rejected"] == 1 and gated.stats_["fixes_used"] == len(fx) - 1
    assert [r[0] for r in gated.rejected_] == [fx["t"][2]]
    # the wrong fix no longer pulls the path: largest |y| (the truth is y = 0)
    assert np.abs(gated.trajectory_["y"]).max() < 1.0 < np.abs(plain.trajectory_["y"]).max()


def test_two_fixes_in_a_row_beyond_the_gate_are_not_both_rejected_d31():
    steps, fx = _walk()
    fx.loc[3:, "y"] += 10.0  # the walker is elsewhere from the fourth fix on: the filter is wrong, not the fixes
    gated = SporadicFixFusion(period_s=None, innovation_gate=True).run(steps, fx)
    assert gated.stats_["fixes_rejected"] <= 2
    assert abs(gated.trajectory_["y_rt"].iloc[-1] - 10.0) < 1.0


class _Live(FixInput):
    """The fix side of a live tracker alone: its newest pushed sample at ``latest`` s."""

    def __init__(self, latest: float, cfg: FixConfig | None = None):
        self.warnings = []
        self._latest = latest
        self._init_fixes((0.0, 0.0))
        if cfg is not None:
            self._fixes = LiveFixes(cfg, start_xy=(0.0, 0.0), initial_sigma_m=1.0)


def test_a_live_rejected_fix_is_named_at_once_d31(caplog):
    steps, fx = _walk()
    live = _Live(0.0, FixConfig(innovation_gate=True))
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        for _, st in steps.iterrows():
            for f in fx[(fx.t > st.start_s) & (fx.t <= st.end_s)].itertuples():
                live.add_fix(f.t, f.x, f.y, f.accuracy_m)
            live._fuse_step(st.start_s, st.end_s, st.length_m, st.heading_rad)
    lines = [w for w in live.warnings if "decision D31" in w]
    assert len(lines) == 1 and "t 25.5 s" in lines[0], live.warnings
    assert live.fix_stats()["fixes_rejected"] == 1


def test_the_posterior_stretch_ends_each_segment_at_the_causal_estimate_d32():
    steps, fx = _walk()
    fx = fx.drop(index=2).assign(accuracy_m=3.0)
    fix = SporadicFixFusion(period_s=None, stretch_to="fix").run(steps, fx).trajectory_
    post = SporadicFixFusion(period_s=None, stretch_to="posterior").run(steps, fx).trajectory_
    at = fix["fix_used"].to_numpy(bool)
    rows = np.flatnonzero(at)[1:]  # where a segment ends on a fix
    np.testing.assert_allclose(post["x"].to_numpy()[rows], post["x_rt"].to_numpy()[rows], atol=1e-9)
    # seed 004 eq. 26: through the fix itself (moved to the step's end), not the filter's estimate
    assert np.abs(fix["y"].to_numpy()[rows] - fix["y_rt"].to_numpy()[rows]).max() > 0.05


def test_add_fix_refuses_a_time_in_milliseconds_at_once_e212():
    live = _Live(78.0)
    with pytest.raises(DataError, match=r"add_fix\(t=20000.*in seconds.*t=20 if it was ms"):
        live.add_fix(20000.0, 1.0, 2.0, accuracy_m=3.0)
    live.add_fix(79.0, 1.0, 2.0, accuracy_m=3.0)  # a fix just ahead of the samples is held, as before
    assert live.fix_stats()["fixes_read"] == 1
