"""Session 47 FD, trial T1 F7 (decisions C195, C196): clinical.md's "Spatiotemporal" line (stride length, stance /
swing %, double support of two feet, stride-time CV) and the leg-length-normalised speed and stride length (Hof
1996) for a measured meta.json leg_length_m, only from what the track measured."""

from __future__ import annotations

import json
import math

from pdrlearn.report.clinical import asymmetry_lines, clinical_markdown

FOOT = {"pipeline": "plasys", "subject": "C01", "gait_speed_mps": 0.92, "median_cadence_spm": 149.0,
        "median_stride_length_m": 0.82, "median_stance_pct": 59.1, "stride_time_cv_pct": 1.77, "n_cv_strides": 10,
        "leg_length_m": 0.68, "leg_length_source": "meta.json leg_length_m"}


def _lines(tmp_path, **summary) -> list[str]:
    folder = tmp_path / "out" / "s"
    folder.mkdir(parents=True)
    (folder / "summary.json").write_text(json.dumps({"session": "s", **summary}))
    return clinical_markdown(tmp_path / "out").splitlines()


def _line(lines, head):
    hits = [x for x in lines if x.startswith(head)]
    return hits[0] if hits else None


def test_foot_track_gives_stride_stance_swing_and_cv_c195(tmp_path):
    line = _line(_lines(tmp_path, **FOOT), "- Spatiotemporal:")
    assert line is not None
    assert "stride length 0.82 m, stance 59.1 % / swing 40.9 % of the stride, stride-time CV 1.8 % (10 strides)" \
        in line, line
    assert "(foot unit;" in line and "double support needs a unit on each foot" in line


def test_without_toe_off_no_stance_is_invented_c195(tmp_path):
    summary = {**FOOT, "median_stance_pct": None}
    line = _line(_lines(tmp_path, **summary), "- Spatiotemporal:")
    assert "stance" not in line.split("(")[0] and "swing" not in line, line
    assert "stride length 0.82 m" in line


def test_lower_back_track_has_no_spatiotemporal_line_c195(tmp_path):
    # what an uncalibrated lower-back track writes since W537: its stride length (the height model's, C197)
    summary = {"pipeline": "waist-pll", "gait_speed_mps": 1.66, "median_stride_length_m": 1.19,
               "info": {"params_source": "defaults"},
               "stride_time_cv_withheld": {"cause": "lower_back", "reason": "x"},
               "leg_length_m": 0.68, "leg_length_source": "meta.json leg_length_m"}
    lines = _lines(tmp_path, **summary)
    assert _line(lines, "- Spatiotemporal") is None, lines
    # decisions C196, C197: an uncalibrated lower-back speed and stride length are the height model's, not normalised
    assert _line(lines, "- Leg-length normalised") is None, lines


def test_normalised_speed_and_stride_follow_hof_c196(tmp_path):
    line = _line(_lines(tmp_path, **FOOT), "- Leg-length normalised")
    v_hat = 0.92 / math.sqrt(9.80665 * 0.68)
    assert f"speed v / sqrt(g L) {v_hat:.2f}" in line and "stride length / leg 1.21" in line, line
    assert "leg 0.68 m, meta.json leg_length_m" in line and line.endswith("(foot unit)")


def test_height_estimated_leg_gives_no_normalised_line_c196(tmp_path):
    summary = {**FOOT, "leg_length_m": 0.689, "leg_length_source": "0.53 x meta.json height_m"}
    assert _line(_lines(tmp_path, **summary), "- Leg-length normalised") is None


def test_calibrated_lower_back_speed_is_normalised_c196(tmp_path):
    summary = {"pipeline": "waist-pendulum", "gait_speed_mps": 1.0, "info": {"params_source": "calibrated"},
               "leg_length_m": 0.68, "leg_length_source": "meta.json leg_length_m"}
    line = _line(_lines(tmp_path, **summary), "- Leg-length normalised")
    assert line is not None and "stride length" not in line and line.endswith("(lower-back unit)"), line


def test_two_feet_walk_gives_stance_pct_and_double_support_c195_c196():
    walk = {"stride_length_m_left": 0.7135, "stride_length_m_right": 0.7151, "stride_time_s_left": 0.7612,
            "stride_time_s_right": 0.7592, "stance_time_s_left": 0.3997, "stance_time_s_right": 0.4620,
            "double_support_pct": 13.46, "gait_speed_mps": 0.875, "cadence_spm": 157.8}
    lines = asymmetry_lines(walk, None, 0.60)
    spatio = _line(lines, "- Spatiotemporal (both foot units):")
    assert spatio == ("- Spatiotemporal (both foot units): stride length L/R 0.71 / 0.72 m, stance L/R 52.5 / 60.9 % "
                      "of the stride, double support 13.5 % of the gait cycle"), lines
    normal = _line(lines, "- Leg-length normalised")
    assert "stride length / leg 1.19" in normal and normal.endswith("(both foot units)"), normal
    assert _line(asymmetry_lines(walk, None, None), "- Leg-length normalised") is None
