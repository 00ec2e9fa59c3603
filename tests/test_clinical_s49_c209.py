"""Decision C209 (session 49, I3; trial T2 finding F4 of session 48): clinical.md's track warnings are no longer
codes alone: each warning is listed under the count with its code and its text (what it means, what to do)."""

from __future__ import annotations

from pdrlearn.report.clinical import warnings_line


def test_each_warning_is_given_with_its_meaning_c209():
    info = {"warnings": ["no per-user calibration: step length from meta.json defaults (run 'pdrlearn calibrate' "
                         "on walks of known length: decision W169)", "a line without a code", "a line without a code",
                         "waist heading relative to the start;\n give the start direction with --initial-heading DEG"],
            "warning_codes": ["W169", None, None, "W5"]}
    lines = warnings_line({"info": info}).split("\n")
    assert lines[0].startswith("- Track warnings: 4 (W169, W5), what each means and what to do (C209")
    assert lines[1] == ("  - W169: no per-user calibration: step length from meta.json defaults (run 'pdrlearn "
                        "calibrate' on walks of known length: decision W169)")
    assert lines[2] == "  - a line without a code"  # one line per distinct warning
    assert lines[3] == ("  - W5: waist heading relative to the start; give the start direction with "
                        "--initial-heading DEG")
    assert len(lines) == 4
    assert warnings_line({"info": {}}) is None
