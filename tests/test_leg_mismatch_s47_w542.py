"""Session 47, trial T2 finding F5: another subject's waist calibration file was applied without a word (+5.48 %
distance); decision W542 warns when the calibration's leg is more than 5 % off the session's meta.json leg."""
from __future__ import annotations

import json

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.waist.params import LEG_MISMATCH, WaistParams, leg_mismatch, resolve_params


class _S:
    def __init__(self, meta):
        self.meta = meta


def test_w542_the_line_names_both_legs_and_the_fix():
    p = WaistParams(leg_m=0.8778, k=1.26, source="calibrated")
    line = leg_mismatch(p, _S({"leg_length_m": 1.0182}), "p.json")
    assert line.startswith("p.json was calibrated for a leg of 0.878 m") and "gives 1.018 m (+16.0 %)" in line
    assert "W542" in line
    assert leg_mismatch(p, _S({"leg_length_m": 0.8778 * (1 + 0.9 * LEG_MISMATCH)}), "p.json") is None
    assert leg_mismatch(p, _S({"sensor_height_m": 1.0}), "p.json") is not None  # B155: the sensor height stands in
    assert leg_mismatch(p, _S({}), "p.json") is None  # meta.json without a leg: nothing to compare
    assert leg_mismatch(WaistParams(leg_m=0.8778, source="defaults"), _S({"leg_length_m": 1.0182})) is None


def test_w542_resolve_params_warns_on_a_calibration_file_of_another_leg(tmp_path):
    assert main(["simulate", "--route", "stand:1, straight:5, stand:1", "--user-seed", "15152", "--out",
                 str(tmp_path / "s")]) == 0
    s = read_session(tmp_path / "s")
    leg = s.meta["leg_length_m"]
    f = tmp_path / "cal.json"
    f.write_text(json.dumps({"leg_m": round(0.8 * leg, 4), "k": 1.2, "source": "calibrated"}))
    _, lines = resolve_params(s, str(f))
    assert any("W542" in x for x in lines)
    f.write_text(json.dumps({"leg_m": leg, "k": 1.2, "source": "calibrated"}))
    _, lines = resolve_params(s, str(f))
    assert not any("W542" in x for x in lines)
