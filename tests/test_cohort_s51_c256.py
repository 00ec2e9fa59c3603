"""Decisions C256-C259 (session 51, FJ, trial s51t3 finding F4: nurses' repeated shifts). C256: groups.csv
summarises the ``--metrics`` measures too. C257: ``track-all --repeated`` pools each subject's sessions in
subjects_pooled.csv (mean per session, rate per hour) and writes no changes.csv. C258: groups_pooled.csv, the same
per group with the subject as the unit. C259: visits named as shifts are hinted ``--repeated``."""

from __future__ import annotations

import json
import logging

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.cohort import group_measures, group_table
from pdrlearn.repeated import pooled_groups, pooled_subjects, repeated_visits_hint


def _shifts():
    """Three nurses' shifts as sessions.csv rows: A three shifts (one 2 h, two 1 h; one with a data gap), B one
    shift tracked and one failed, C a foot track (no posture) and a copy of it."""
    rows = [  # path, group, subject, visit, status, time_span_s, time_no_data_s, steps, sitting_time_s, duplicate_of
        ("wA/A/s1", "wA", "A", "shift1", "ok", 7200.0, 0.0, 2000, 600.0, None),
        ("wA/A/s2", "wA", "A", "shift2", "ok", 3600.0, 0.0, 1000, 900.0, None),
        ("wA/A/s3", "wA", "A", "shift3", "ok", 4000.0, 400.0, 700, None, None),
        ("wB/B/s1", "wB", "B", "shift1", "ok", 3600.0, 0.0, 500, 1800.0, None),
        ("wB/B/s2", "wB", "B", "shift2", "failed", None, None, None, None, None),
        ("wB/C/s1", "wB", "C", "shift1", "ok", 1800.0, 0.0, 300, None, None),
        ("wB/C/s2", "wB", "C", "shift2", "ok", 1800.0, 0.0, 300, None, "wB/C/s1"),
    ]
    cols = ["path", "group", "subject", "visit", "status", "time_span_s", "time_no_data_s", "n_steps_both_feet",
            "sitting_time_s", "duplicate_of"]
    return pd.DataFrame(rows, columns=cols)


def test_subjects_pooled_means_per_session_and_rates_per_hour_c257():
    p = pooled_subjects(_shifts()).set_index("subject")
    assert p.index.tolist() == ["A", "B", "C"]
    assert p.loc["A", "n_tracked"] == 3 and p.loc["B", "n_failed"] == 1 and p.loc["C", "n_tracked"] == 1
    assert p.loc["A", "hours_recorded"] == pytest.approx(4.0)  # 2 h + 1 h + (4000 - 400) s
    assert p.loc["A", "n_steps_both_feet_per_session"] == pytest.approx(3700 / 3)
    assert p.loc["A", "n_steps_both_feet_per_h"] == pytest.approx(3700 / 4.0)  # a ratio of totals, not 3 rates
    # sitting: two of three shifts have it, over their 3 h; the reason says so
    assert p.loc["A", "sitting_time_s_per_session"] == pytest.approx(750.0)
    assert p.loc["A", "sitting_time_s_per_h"] == pytest.approx(1500.0 / 3.0)
    assert "sitting_time_s from 2 of 3 sessions" in p.loc["A", "reason"]
    assert "wB/B/s2 failed" in p.loc["B", "reason"] and p.loc["B", "n_steps_both_feet_per_h"] == pytest.approx(500)
    assert p.loc["C", "n_steps_both_feet_per_session"] == 300 and "copy of wB/C/s1" in p.loc["C", "reason"]
    assert pd.isna(p.loc["C", "sitting_time_s_per_h"]) and p.loc["A", "visits"] == "shift1; shift2; shift3"
    assert pooled_subjects(_shifts().assign(subject=None)) is None


def test_groups_pooled_counts_each_subject_once_c258():
    g = pooled_groups(pooled_subjects(_shifts())).set_index("group")
    assert g["n_subjects"].tolist() == [1, 2]
    assert g.loc["wB", "n_steps_both_feet_per_h_n"] == 2
    assert g.loc["wB", "n_steps_both_feet_per_h_mean"] == pytest.approx((500 + 600) / 2)
    assert g.loc["wB", "n_steps_both_feet_per_h_sd"] == pytest.approx(abs(500 - 600) / 2 ** 0.5)
    assert g.loc["wB", "sitting_time_s_per_h_n"] == 1 and pd.isna(g.loc["wA", "n_steps_both_feet_per_h_sd"])


def test_groups_csv_takes_the_metrics_measures_c256():
    s = _shifts().assign(gait_speed_mps=1.0)
    assert group_measures(["n_steps_both_feet", "gait_speed_mps"]) == (
        "distance_error_pct", "gait_speed_mps", "median_cadence_spm", "median_stride_length_m", "n_steps_both_feet")
    g = group_table(s, group_measures(["n_steps_both_feet"])).set_index("group")
    assert g.loc["wA", "n_steps_both_feet_mean"] == pytest.approx(3700 / 3) and g.loc["wB", "n_steps_both_feet_n"] == 3
    assert list(g.columns[:4]) == ["n_tracked", "n_failed", "gait_speed_mps_n", "gait_speed_mps_mean"]


def test_shift_visits_are_hinted_repeated_c259(caplog):
    from pdrlearn.cli.cohort import _repeated_hint

    assert "pass --repeated" in repeated_visits_hint(["shift1", "shift2", "Shift3"])
    assert repeated_visits_hint(["day1", "day30"]) is None and repeated_visits_hint(["baseline", "week12"]) is None
    assert repeated_visits_hint(["shift1", "followup"]) is None
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        _repeated_hint(pd.DataFrame({"baseline_visit": ["shift1"], "visit": ["shift2"]}))
    assert any("look like repeated recordings" in r.getMessage() for r in caplog.records)


def test_the_report_of_a_repeated_batch_pools_instead_of_pairing_c257():
    from pdrlearn.report.batch import batch_tables

    s = _shifts().assign(error=None)
    titles = [t for t, _ in batch_tables(s, group_table(s), repeated=True)[1]]
    assert any("subjects_pooled.csv" in t for t in titles) and not any("paired change" in t for t in titles)
    assert any("paired change" in t for t, _ in batch_tables(s, group_table(s))[1])


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    from pdrlearn import sim
    from pdrlearn.io import write_session

    root = tmp_path_factory.mktemp("c257") / "study"
    for user, subject, visit in ((18555, "N1", "shift1"), (18555, "N1", "shift2"), (18556, "N2", "shift1")):
        d = root / "wardA" / subject / visit
        write_session(sim.simulate("walk", user, length_m=8, seed=int(visit[-1])), d)
        meta = json.loads((d / "meta.json").read_text())
        (d / "meta.json").write_text(json.dumps({**meta, "subject": subject, "visit": visit}))
    return root


def test_track_all_repeated_writes_the_pooled_tables_and_no_changes_c256_c257(study, tmp_path, capsys):
    out = tmp_path / "o"
    assert main(["track-all", str(study), "--out", str(out), "--no-plot", "--repeated",
                 "--metrics", "n_steps_both_feet,distance_m"]) == 0
    printed = capsys.readouterr().out
    assert "no changes.csv" in printed and "subjects_pooled.csv, groups_pooled.csv" in printed
    assert not (out / "changes.csv").exists() and not (out / "changes_summary.csv").exists()
    sessions = pd.read_csv(out / "sessions.csv")
    pooled = pd.read_csv(out / "subjects_pooled.csv")
    assert pooled["subject"].tolist() == ["N1", "N2"] and pooled["n_tracked"].tolist() == [2, 1]
    n1 = sessions[sessions["subject"] == "N1"]
    assert pooled.loc[0, "distance_m_per_session"] == pytest.approx(n1["distance_m"].mean())
    hours = (n1["time_span_s"] - n1["time_no_data_s"]).sum() / 3600
    assert pooled.loc[0, "distance_m_per_h"] == pytest.approx(n1["distance_m"].sum() / hours)
    groups = pd.read_csv(out / "groups.csv")  # C256: the --metrics measures beside C12's four
    assert groups.loc[0, "n_steps_both_feet_mean"] == pytest.approx(sessions["n_steps_both_feet"].mean())
    gp = pd.read_csv(out / "groups_pooled.csv")
    assert gp["n_subjects"].tolist() == [2] and gp.loc[0, "distance_m_per_h_n"] == 2
    assert json.loads((out / "run.json").read_text())["options"]["repeated"] is True


def test_repeated_without_subjects_is_one_line_before_tracking_c257(tmp_path, capsys):
    (tmp_path / "study" / "s1").mkdir(parents=True)
    (tmp_path / "study" / "s1" / "meta.json").write_text(json.dumps({"visit": "shift1"}))
    assert main(["track-all", str(tmp_path / "study"), "--out", str(tmp_path / "o"), "--repeated"]) == 2
    assert "--repeated pools each subject's sessions" in capsys.readouterr().err
    assert not (tmp_path / "o").exists()


def test_repeated_batch_still_warns_an_id_in_two_groups_c257(caplog):
    from pdrlearn.cli.cohort import _pooled

    s = _shifts()
    s.loc[s["path"] == "wA/A/s3", "group"] = "wB"  # A's third shift filed under the other ward
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        pooled, groups = _pooled(s, None)
    assert any("decision C32" in r.getMessage() for r in caplog.records)
    assert pooled.set_index("subject").loc["A", "group"] == "wA; wB" and "wA; wB" in groups["group"].tolist()
