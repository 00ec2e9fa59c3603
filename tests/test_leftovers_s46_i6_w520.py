"""Decision W520 (session 46, I6): a symmetric slow walker (0.9 s steps, where W3's contact is bimodal, L677) is not
called asymmetric: the lower back alone's index stays under L121's 20 % floor, and the foot + lower-back index
carries L677's "uncertain" note (measured on users 14080-14089: 0 of 10 called asymmetric either way)."""

from __future__ import annotations

import json

from pdrlearn.cli import main
from pdrlearn.track.clinical import ASYMMETRY_FLOOR_PCT


def test_a_symmetric_slow_walker_is_not_called_asymmetric_w520(tmp_path):
    sim = tmp_path / "u14083"
    assert main(["simulate", "--route", "stand:3, straight:40, stand:3", "--step-length", "0.4", "--step-time",
                 "0.900", "--bounce", "pendulum", "--rocker", "smooth", "--rate", "100", "--user-seed", "14083",
                 "--out", str(sim)]) == 0
    assert main(["track", str(sim), "--units", "waist", "--out", str(tmp_path / "tw")]) == 0
    alone = json.loads((tmp_path / "tw" / "summary.json").read_text())
    assert alone["step_time_asymmetry_pct"] is None  # measured raw 7.35 %: under the floor, not judged
    assert 0 < alone["step_time_asymmetry_raw_pct"] < ASYMMETRY_FLOOR_PCT
    assert main(["track", str(sim), "--out", str(tmp_path / "t2")]) == 0
    both = json.loads((tmp_path / "t2" / "summary.json").read_text())
    assert both["step_time_asymmetry_pct"] is not None  # measured 3.99 %, standard error 6.25 points
    assert both["step_time_asymmetry_se_points"] > 3.0 and "uncertain" in both["step_time_asymmetry_reason"]
