"""Decision L496: `pdrlearn report`'s gait parameters table carries the median stride length and the step-time
asymmetry, and says why an empty stride-time CV or asymmetry is empty (session 38, trial T1 finding 4)."""

import json

from pdrlearn.report.build import build_report


def _summary(folder, **extra):
    folder.mkdir(parents=True)
    summary = {"session": folder.name, "pipeline": "plasys", "distance_m": 10.0, "n_steps": 12,
               "median_cadence_spm": 156.4, "median_stride_time_s": 0.767, "walking_time_s": 9.6, **extra}
    (folder / "summary.json").write_text(json.dumps(summary))


def test_report_gait_table_has_stride_length_asymmetry_and_why_empty(tmp_path):
    _summary(tmp_path / "res" / "given", median_stride_length_m=0.8967, step_time_asymmetry_pct=4.25,
             step_time_asymmetry_reason="the lower back's contacts labelled by the foot unit's",
             stride_time_cv_pct=2.5, stride_time_cv_withheld=None)
    _summary(tmp_path / "res" / "short", median_stride_length_m=0.812, step_time_asymmetry_pct=None,
             step_time_asymmetry_reason="not given: 8 of the foot's strides hold one lower-back contact",
             stride_time_cv_pct=None, stride_time_cv_withheld={
                 "cause": "too_few_strides", "reason": "9 steady level forward strides, 10 needed"})
    build_report(tmp_path / "res", tmp_path / "rep")
    md = (tmp_path / "rep" / "report.md").read_text()
    gait = md.split("**gait parameters**")[1].split("**")[0]
    assert "median_stride_length_m" in gait and "0.8967" in gait and "0.812" in gait
    assert "step_time_asymmetry_pct" in gait and "4.25" in gait
    why = md.split("**gait parameters not given, and why**")[1].split("**")[0]
    assert "9 steady level forward strides, 10 needed" in why and "stride_time_cv_pct" in why
    assert "8 of the foot's strides" in why and "step_time_asymmetry_pct" in why
    assert "labelled by the foot unit's" not in why  # a given value's reason is not a withheld one
