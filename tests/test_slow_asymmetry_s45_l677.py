"""Decision L677: L416's foot + lower-back step-time asymmetry's standard error counts the lower back's lag (the
median of its own contacts' offsets, taken off the other foot's contacts) as well as the other foot's phases (L490).

Trial T1's slow ward walker (0.9 s steps) read 11.95 % for a true 0 % with L490's standard error 2.66 points (no
"uncertain" note); its lower back's own contacts scatter bimodally ~0.1 s about the foot's, so the lag is as loose
as the phases."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.track import labelled_asymmetry as la
from tests.fakes import FakeWaistSession


def _slow_walk(seed: int = 677):
    """A symmetric slow walker's contacts: 1.8 s strides; the lower back's own contacts bimodal about the foot's
    (a third at +0.02 s, the rest spread -0.24..-0.04 s, as T1's s2), the other foot's tight at mid-stride."""
    rng = np.random.default_rng(seed)
    foot = np.arange(81) * 1.8
    near = rng.random(81) < 1 / 3
    own = foot + np.where(near, 0.02 + rng.normal(0.0, 0.01, 81), rng.uniform(-0.24, -0.04, 81))
    other = foot[:-1] + 0.9 - 0.08 + rng.normal(0.0, 0.03, 80)
    return foot, np.sort(np.concatenate([own, other]))


def test_standard_error_counts_the_lag_l677():
    """The standard error is 400 x sqrt(se_phi^2 + (se_lag / T)^2) (L677), over L490's phases-only one and over 3
    points for a loose lag; the index itself is L416's."""
    foot, waist = _slow_walk()
    res = la.labelled_step_asymmetry(foot, waist)
    phases, lags = la._phases_and_lags(foot, waist, tolerance_steps=la.LABEL_TOLERANCE_STEPS)
    old = la.index_standard_error_pct(phases)
    want = 400.0 * np.hypot(la.median_standard_error(phases), la.median_standard_error(lags) / 1.8)
    # decision L686: a 0.9 s step also carries the slow asymmetric walk's bias allowance, in quadrature
    want = np.hypot(want, la.bias_allowance_points(res["step_time_asymmetry_pct"], 1.8))
    assert res["standard_error_points"] == pytest.approx(want, rel=1e-9)
    assert old <= la.UNCERTAIN_SE_POINTS < res["standard_error_points"], (old, res)
    assert res["step_time_asymmetry_pct"] is not None and res["n_strides"] >= 70


def test_a_tight_lag_adds_nothing_l677():
    """Own contacts at one constant lag (MAD 0): the standard error is L490's of the phases alone."""
    rng = np.random.default_rng(678)
    foot = np.arange(41) * 1.1
    waist = np.sort(np.concatenate([foot - 0.03, foot[:-1] + 0.52 + rng.normal(0.0, 0.04, 40)]))
    phases = la.other_foot_phases(foot, waist)
    assert la.labelled_step_asymmetry(foot, waist)["standard_error_points"] == pytest.approx(
        la.index_standard_error_pct(phases), rel=1e-12)


def test_track_calls_the_slow_walkers_index_uncertain_l677(monkeypatch):
    """The plasys track's reason of the slow walker's index carries L490's "uncertain" note (it did not before)."""

    foot, waist = _slow_walk()
    monkeypatch.setattr(la, "waist_ic_contacts", lambda session: waist)
    out = la.track_asymmetry(FakeWaistSession(), pd.DataFrame({"event_s": foot, "unit": "foot"}))
    assert out["step_time_asymmetry_pct"] is not None
    assert "uncertain" in out["step_time_asymmetry_reason"] and "L677" in out["step_time_asymmetry_reason"]
    assert out["step_time_asymmetry_se_points"] > la.UNCERTAIN_SE_POINTS


def test_gait_line_says_uncertain_over_three_points_l677():
    """The console's gait line (L671) says "uncertain" where the reason does: T1's s2 printed "12.0 % (standard
    error 2.7 points; ...)" bare; 3.0 points exactly is not over."""
    from pdrlearn.cli.common import asymmetry_clause

    line = asymmetry_clause({"step_time_asymmetry_pct": 11.950455, "step_time_asymmetry_se_points": 3.64})
    assert "12.0 %" in line and "standard error 3.6 points, uncertain" in line and "within noise" not in line
    line = asymmetry_clause({"step_time_asymmetry_pct": 1.0, "step_time_asymmetry_se_points": 3.0})
    assert "uncertain" not in line and "within noise" in line


def test_report_lists_a_given_but_uncertain_asymmetry_c184(tmp_path):
    """Decision C184: report.md's gait table printed T1's 9.671 % bare although summary.json called it uncertain;
    a given index over 3 standard-error points now gets a row in "gait parameters given but uncertain, and why"."""
    import json

    from pdrlearn.report.build import build_report

    for name, pct, se in (("slow", 11.95, 3.64), ("steady", 4.25, 1.2)):
        folder = tmp_path / "res" / name
        folder.mkdir(parents=True)
        (folder / "summary.json").write_text(json.dumps({
            "session": name, "pipeline": "plasys", "distance_m": 10.0, "n_steps": 12, "median_cadence_spm": 66.3,
            "median_stride_time_s": 1.81, "walking_time_s": 30.0, "step_time_asymmetry_pct": pct,
            "step_time_asymmetry_se_points": se,
            "step_time_asymmetry_reason": f"labelled ({name}){'; uncertain: over 3 points' if se > 3 else ''}"}))
    build_report(tmp_path / "res", tmp_path / "rep")
    md = (tmp_path / "rep" / "report.md").read_text()
    why = md.split("**gait parameters given but uncertain, and why**")[1].split("**")[0]
    assert "slow" in why and "3.64" in why and "uncertain: over 3 points" in why
    assert "steady" not in why
