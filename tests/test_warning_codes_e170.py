"""Decision E170 (session 35): a warning line carries its code from where it is raised (``coded``) to
summary.json's ``warning_codes``; the text stays the same, and the lines not coded are read as before (E168)."""

from __future__ import annotations

import json
import logging
import pickle

import numpy as np
import pandas as pd

from pdrlearn.warning_lines import CodedLine, captured_warnings, coded, machine_summary, warning_code


def test_a_coded_line_keeps_its_code_through_the_log_and_the_summary():
    """The code given where the line is made wins over what its text names; JSON and pickle see the same."""
    log = logging.getLogger("pdrlearn.test_e170")
    with captured_warnings() as logged:
        log.warning("%s: %s", "/data/s", coded("checked against decision L73 there (decision L414)", "Z9"))
        log.warning("/data/s: plain text naming decision B1", extra={"code": "Q1"})
        log.warning("/data/s: uncoded line (decision B2)")
    summary = machine_summary({"info": {"warnings": [coded("kept line (decision B3)", "K1")]}}, logged, "/data/s")
    info = summary["info"]
    assert info["warnings"] == ["kept line (decision B3)", "checked against decision L73 there (decision L414)",
                                "plain text naming decision B1", "uncoded line (decision B2)"]
    assert info["warning_codes"] == ["K1", "Z9", "Q1", "B2"]  # the last one from its text (E168)
    text = json.dumps(summary)
    assert text == json.dumps(json.loads(text)) and '"Z9"' in text  # plain strings in JSON
    back = pickle.loads(pickle.dumps(info["warnings"][1]))
    assert isinstance(back, CodedLine) and back.code == "Z9" and back == info["warnings"][1]


def test_common_warnings_are_coded_where_raised_with_the_code_of_their_text():
    """The most common lines (E168's gaitmap track's six, B77's clipping, B153's incomplete waist unit) are coded
    where they are made, each with the code their text gives: every output stays the same."""
    from pdrlearn.io import Session
    from pdrlearn.io.validate import saturation_warning
    from pdrlearn.track.gait import stance_share_warning
    from pdrlearn.track.plasys import (
        NO_FORCE_STANCE,
        NO_MODEL_WARNING,
        NO_WAIST_HEADING,
        coded_altitude_check,
        no_waist_heading,
    )
    from pdrlearn.track.toeoff import stance_range_warning

    class _Partial(Session):
        def has(self, *names):  # a waist magnetometer without the waist accelerometer and gyroscope
            return all(n == "wMagneticField" for n in names)

    lines = [NO_MODEL_WARNING, NO_FORCE_STANCE, coded_altitude_check(np.array([0.2, 0.0, 0.15, 0.3]))[0],
             NO_WAIST_HEADING, stance_share_warning(pd.DataFrame({"stance_pct": np.full(12, 52.0)})),
             stance_range_warning({"median_stance_time_s": 0.635}),
             saturation_warning("s/fAccelerometer.csv", "accelerometer", 40, 1000, 156.9),
             no_waist_heading(_Partial(name="p"))]
    codes = ["E153", "no-force-sensors", "L69", "no-waist-unit", "L285", "L414", "B77", "B153"]
    for line, code in zip(lines, codes, strict=True):
        assert isinstance(line, CodedLine) and line.code == code, line
        assert warning_code(str(line)) == code, line  # the text's own code (E168): nothing printed changes


def test_a_track_keeps_the_codes_its_lines_were_raised_with(tmp_path, monkeypatch):
    """Through the pipeline, the captured log, track_summary's JSON round trip and the machine summary of
    ``pdrlearn track``: with the text reader of E168 blinded (every text code "other"), the coded lines still get
    their codes, so the codes came from where the lines were raised."""
    import re

    import pdrlearn.warning_lines as wl
    from pdrlearn.cli.track import track_session, track_settings
    from pdrlearn.io import write_session
    from pdrlearn.sim import simulate

    session = simulate("A", user_seed=8364)
    for name in [n for n in session.streams if n.startswith("w")]:
        del session.streams[name]  # a foot unit alone: "no model" and "no waist unit"
    write_session(session, tmp_path / "s")
    never = re.compile(r"(?!)")
    for name in ("_DECISION", "_BARE_ID", "_LEAD"):
        monkeypatch.setattr(wl, name, never)
    summary = track_session(tmp_path / "s", track_settings())["summary"]
    warned = dict(zip(summary["info"]["warnings"], summary["info"]["warning_codes"], strict=True))
    from pdrlearn.track.plasys import NO_MODEL_WARNING, NO_WAIST_HEADING

    assert warned[NO_MODEL_WARNING] == "E153" and warned[NO_WAIST_HEADING] == "no-waist-unit"
    assert json.loads(json.dumps(summary))["info"]["warning_codes"] == summary["info"]["warning_codes"]
