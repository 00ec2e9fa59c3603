"""Trial s52t3 (session 52, FD): changes.csv lost every subject once one subject had no session at the first visit
(C264), a failed session's warnings started with ROOT's path (C265), and a foot unit without its gyroscope beside a
complete lower-back unit was refused without naming ``--units waist`` (C266). Small sessions.csv tables, no
tracking; one short simulated session read (not tracked) for C266's CLI line."""

from __future__ import annotations

import contextlib
import io

import numpy as np
import pandas as pd
import pytest

from pdrlearn.visits import change_summary, change_table, label_warnings


def _sessions(rows) -> pd.DataFrame:
    """sessions.csv rows ``(subject, visit, gait speed)``: each subject its own group (a ROOT/SUBJECT/VISIT tree
    without meta.json groups, as track-all writes it), tracked by plasys."""
    return pd.DataFrame([{"path": f"{s}/{v}", "group": s, "subject": s, "visit": v, "status": "ok",
                          "pipeline": "plasys", "duplicate_of": None, "gait_speed_mps": g} for s, v, g in rows])


#: S1, S2 at V1 and V2; S3 at V2 only (its V1 import refused); S4 at V1 only
ROWS = [("S1", "V1", 1.0), ("S1", "V2", 1.2), ("S2", "V1", 1.1), ("S2", "V2", 1.4), ("S3", "V2", 1.3),
        ("S4", "V1", 0.9)]


def _pairs(changes) -> list[list]:
    cols = changes[["subject", "baseline_visit", "visit", "status", "reason"]].astype(object)
    return cols.where(cols.notna(), None).values.tolist()


def test_a_subject_seen_at_the_later_visit_only_keeps_every_subject_c264():
    """Before C264: S3's only visit, V2, became its baseline (C40's group rule, each subject its own group), so V2
    was nobody's later visit: changes.csv had no row at all (header-only with the visit map)."""
    expected = [["S1", "V1", "V2", "ok", None], ["S2", "V1", "V2", "ok", None],
                ["S3", "V1", "V2", "missing", "V1: no session"], ["S4", "V1", "V2", "missing", "V2: no session"]]
    assert _pairs(change_table(_sessions(ROWS))) == expected
    mapped = change_table(_sessions(ROWS), visit_map={"V1": "baseline", "V2": "week12"})
    assert _pairs(mapped) == [[s, "baseline", "week12", st, r and r.replace("V1", "baseline").replace(
        "V2", "week12")] for s, _, _, st, r in expected]
    assert mapped["gait_speed_mps_change"].round(12).tolist()[:2] == [0.2, 0.3]
    summary = change_summary(mapped)
    assert summary[["visit", "n_subjects", "n_not_paired"]].values.tolist() == [["week12", 2, 2]]
    assert label_warnings(_sessions(ROWS)) == []  # one naming: nothing to warn


def test_a_study_mixing_visit_namings_is_warned_c264():
    """baseline / week12 beside V1 / V2 (no --visit-map): each naming paired on its own, and said once; a pre / post
    site beside a baseline one (C28, named so) is not warned."""
    rows = ROWS + [("S5", "baseline", 1.0), ("S5", "week12", 1.1), ("S6", "week12", 1.2)]
    changes = change_table(_sessions(rows))
    assert changes.set_index("subject").loc[["S5", "S6"], ["baseline_visit", "visit", "status"]].values.tolist() == [
        ["baseline", "week12", "ok"], ["baseline", "week12", "missing"]]
    assert len(changes) == 6  # every subject a row
    [line] = label_warnings(_sessions(rows))
    assert line.startswith("the subjects' baseline visits are named differently: 'baseline' (2 subjects), 'V1' (4 "
                           "subjects)") and "--visit-map" in line and "C264" in line
    assert label_warnings(_sessions(rows), {"V1": "baseline", "V2": "week12"}) == []
    prepost = [("S1", "baseline", 1.0), ("S1", "week12", 1.1), ("S2", "pre", 1.0), ("S2", "post", 1.1)]
    assert label_warnings(_sessions(prepost)) == []


def test_a_failed_sessions_warnings_are_the_same_from_a_copy_elsewhere_c265():
    """Before C265: a failed session's `ROOT/S1/V1/meta.json: ...` kept ROOT in sessions.csv's warnings."""
    from pdrlearn.cli.cohort import job_warnings
    from pdrlearn.cohort import JobResult

    text = "session 'V1' declares no axis frame for the foot unit; inferred from the data"
    got = []
    for root in ("cohort", "/tmp/copy/study"):
        r = JobResult("V1", False, error="boom", extra={"warnings": [f"{root}/S1/V1/meta.json: {text}",
                                                                    f"{root}/S1/V1: other"]})
        got.append(job_warnings(r, f"{root}/S1/V1"))
    assert got[0] == got[1] == [f"meta.json: {text}", "other"]


def _session(*names):
    from pdrlearn.io.session import Session, Stream

    t = np.arange(0.0, 2.0, 0.01)
    return Session("V2", streams={n: Stream(n, t, np.tile([0.0, 0.0, 9.81], (len(t), 1))) for n in names})


def test_an_incomplete_foot_unit_names_units_waist_c266():
    from pdrlearn.cli.track import refuse_incomplete_foot
    from pdrlearn.errors import MissingSensorError

    both = _session("fAccelerometer", "wAccelerometer", "wGyroscope")
    with pytest.raises(MissingSensorError, match=r"no fGyroscope\.csv.*track it with --units waist, or record"):
        refuse_incomplete_foot("plasys", {"pipeline": "auto"}, both)
    with pytest.raises(MissingSensorError, match=r"--units waist \(drop --pipeline plasys\)"):
        refuse_incomplete_foot("plasys", {"pipeline": "plasys"}, both)
    refuse_incomplete_foot("plasys", {"units": "foot,waist"}, both)  # --units given: the session's own refusal
    refuse_incomplete_foot("waist-pendulum", {}, both)
    refuse_incomplete_foot("plasys", {}, _session("fAccelerometer", "wAccelerometer"))  # no complete waist unit
    refuse_incomplete_foot("plasys", {}, _session("fAccelerometer", "fGyroscope", "wAccelerometer", "wGyroscope"))


def test_track_refuses_the_foot_without_gyroscope_naming_units_waist_c266(tmp_path):
    """The trial's `track cohort/S19201/V2`: exit 2, one line naming --units waist (no silent fallback)."""
    from pdrlearn.cli import main

    out = tmp_path / "s"
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        assert main(["simulate", "--route", "straight:3", "--user-seed", "18981", "--rate", "20", "--out",
                     str(out)]) == 0
    (out / "fGyroscope.csv").unlink()
    err = io.StringIO()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
        assert main(["track", str(out), "--no-plot", "--out", str(tmp_path / "t")]) == 2
    assert "track it with --units waist" in err.getvalue() and "C266" in err.getvalue()
