"""Session 47, trial T1 F1: L416's foot + lower-back step-time index is withheld under 0.45 s foot steps (decision
W532, W531's fallback); the console's gait line and clinical.md's line say why and point to ``pdrlearn gait``."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.cli.common import asymmetry_clause
from pdrlearn.report.stairs_asymmetry import asymmetry_line
from pdrlearn.track import labelled_asymmetry as la
from tests.fakes import FakeWaistSession


def _walk(step_s: float, n: int = 40, seed: int = 14940):
    """One foot's contacts every 2 x ``step_s`` and the lower back's: the foot's own 0.045 s early, the other foot's
    half a stride later and 0.045 s early, both scattering 0.01 s (a symmetric walker)."""
    rng = np.random.default_rng(seed)
    foot = np.arange(n + 1) * 2.0 * step_s
    own = foot - 0.045 + rng.normal(0.0, 0.01, len(foot))
    other = foot[:-1] + step_s - 0.045 + rng.normal(0.0, 0.01, n)
    return foot, np.sort(np.concatenate([own, other]))


def test_a_childs_short_steps_give_no_index_but_a_standard_error_w532():
    res = la.labelled_step_asymmetry(*_walk(0.40))
    assert res["step_time_asymmetry_pct"] is None and res["n_strides"] >= la.MIN_STRIDES
    assert abs(res["short_step_s"] - 0.40) < 1e-9 and np.isfinite(res["standard_error_points"])
    slow = la.labelled_step_asymmetry(*_walk(0.46))  # at 0.46 s steps the index is L416's, as before
    assert slow["step_time_asymmetry_pct"] is not None and "short_step_s" not in slow
    assert slow["step_time_asymmetry_pct"] < 3.0


def test_the_track_reason_console_and_clinical_line_say_why_and_name_gait_w532(monkeypatch):
    foot, waist = _walk(0.38)
    monkeypatch.setattr(la, "waist_ic_contacts", lambda session: waist)
    out = la.track_asymmetry(FakeWaistSession(), pd.DataFrame({"event_s": foot, "unit": "foot"}))
    assert out["step_time_asymmetry_pct"] is None
    reason = out["step_time_asymmetry_reason"]
    assert reason.startswith("not given: the foot's median step 0.380 s is under 0.45 s") and "W532" in reason
    assert "pdrlearn gait LEFT_DIR RIGHT_DIR" in reason
    summary = {"step_time_asymmetry_pct": None, "step_time_asymmetry_reason": reason}
    line = asymmetry_line(summary, "foot unit")
    assert line.startswith("- Step-time asymmetry: not given (the foot's median step 0.380 s") and "W532" in line
    assert line.endswith("(foot + lower-back units)")
    assert asymmetry_clause(summary).startswith("; step-time asymmetry not given: the foot's median step 0.380 s")
    other = {"step_time_asymmetry_pct": None, "step_time_asymmetry_reason": "not given: 4 of the foot's strides"}
    assert asymmetry_line(other, "foot unit") is None and asymmetry_clause(other) == ""  # C190 / L671 as before
