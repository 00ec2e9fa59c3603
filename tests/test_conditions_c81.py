"""Session 34, trial T1 (a dual-task gait researcher; findings F4-F6): condition comparisons in a cohort - unknown
measure names are an error (B302, B303), each change has its percent change, the dual-task cost (C81), every table
joins on (subject, visit) after --visit-map (C82), and repeated trials of a condition are averaged (C83)."""

from __future__ import annotations

import json

import pandas as pd
import pytest

from pdrlearn.errors import DataError
from pdrlearn.visits import change_summary, change_table


def _sessions(rows) -> pd.DataFrame:
    """sessions.csv rows ``(path, subject, visit, gait speed, stride-time CV)``, all tracked by plasys."""
    return pd.DataFrame([{"path": p, "group": "g", "subject": s, "visit": v, "status": "ok", "pipeline": "plasys",
                          "duplicate_of": None, "gait_speed_mps": g, "stride_time_cv_pct": cv}
                         for p, s, v, g, cv in rows])


def test_unknown_measures_are_one_line_naming_them_and_the_valid_ones_b302():
    """F4: metrics=('gait_speed_mps', 'stride_time_cv', 'cadence') returned only gait_speed_mps_change, the two
    misspelled names silently left out; now one line naming them, the nearest valid names and the common ones."""
    rows = _sessions([("a", "S1", "single", 1.0, 2.0), ("b", "S1", "dual", 0.8, 5.0)])
    with pytest.raises(DataError) as err:
        change_table(rows, metrics=("gait_speed_mps", "stride_time_cv", "cadence"))
    line = str(err.value)
    assert "unknown measure 'stride_time_cv', 'cadence'" in line and "\n" not in line
    assert "did you mean stride_time_cv_pct" in line and "did you mean median_cadence_spm" in line
    assert "median_stride_time_s" in line and "pdrlearn columns sessions.csv" in line and "B302" in line
    got = change_table(rows, metrics=("gait_speed_mps", "stride_time_cv_pct"))  # valid names: as before
    assert got["gait_speed_mps_change"].iloc[0] == pytest.approx(0.2)  # text order: dual is the baseline (C24)


def test_each_change_has_its_percent_change_the_dual_task_cost_c81():
    """F5: changes.csv had only absolute changes; now <m>_change_pct = 100 x (dual - single) / single beside each,
    and changes_summary.csv its mean with the paired 95 % t-interval; a zero baseline gives an empty cell."""
    rows = _sessions([("a", "S1", "single", 1.0, 2.0), ("b", "S1", "dual", 0.8, 5.0),
                      ("c", "S2", "single", 1.25, 0.0), ("d", "S2", "dual", 1.0, 4.0)])
    got = change_table(rows, metrics=("gait_speed_mps", "stride_time_cv_pct"),
                       visit_map={"single": "baseline", "dual": "followup"}).set_index("subject")
    assert got.loc["S1", "gait_speed_mps_change_pct"] == pytest.approx(-20.0)
    assert got.loc["S2", "gait_speed_mps_change_pct"] == pytest.approx(-20.0)
    assert got.loc["S1", "stride_time_cv_pct_change"] == pytest.approx(3.0)  # the absolute change stays
    assert got.loc["S1", "stride_time_cv_pct_change_pct"] == pytest.approx(150.0)
    assert pd.isna(got.loc["S2", "stride_time_cv_pct_change_pct"])  # baseline 0
    summary = change_summary(got.reset_index()).set_index("measure")
    assert summary.loc["gait_speed_mps", "mean_pct_change"] == pytest.approx(-20.0)
    assert summary.loc["gait_speed_mps", "sd_pct_change"] == pytest.approx(0.0)
    assert summary.loc["stride_time_cv_pct", "n_subjects"] == 2 and list(summary.index) == ["gait_speed_mps",
                                                                                           "stride_time_cv_pct"]


def test_repeated_trials_of_a_condition_are_averaged_c83():
    """F6: a second single-task trial of S1 made its row `several` (unpaired, out of the summary); now the trials are
    averaged (mean of the session values) with their number in baseline_n_trials / n_trials; a failed trial is left
    out and said; a copy of a trial counts once; trials of one visit tracked by two pipelines are not averaged."""
    rows = _sessions([("a", "S1", "single", 1.0, 2.0), ("a2", "S1", "single", 1.2, 3.0), ("b", "S1", "dual", 0.88, 5.0),
                      ("c", "S2", "single", 1.0, 2.0), ("d", "S2", "dual", 0.9, 4.0), ("d2", "S2", "dual", 0.7, 6.0),
                      ("d3", "S2", "dual", 0.1, 1.0)])
    rows.loc[rows["path"] == "d3", "status"] = "failed"
    vmap = {"single": "baseline", "dual": "followup"}
    got = change_table(rows, metrics=("gait_speed_mps", "stride_time_cv_pct"), visit_map=vmap).set_index("subject")
    assert got["status"].tolist() == ["ok", "ok"]
    assert got.loc["S1", ["baseline_n_trials", "n_trials"]].tolist() == [2, 1]
    assert got.loc["S1", "baseline_path"] == "a; a2" and got.loc["S1", "gait_speed_mps_baseline"] == pytest.approx(1.1)
    assert got.loc["S1", "gait_speed_mps_change_pct"] == pytest.approx(-20.0)
    assert got.loc["S1", "stride_time_cv_pct_baseline"] == pytest.approx(2.5)
    assert got.loc["S2", ["baseline_n_trials", "n_trials"]].tolist() == [1, 2]
    assert got.loc["S2", "gait_speed_mps_change"] == pytest.approx(-0.2)  # mean(0.9, 0.7) - 1.0; d3 failed
    assert got.loc["S2", "reason"] == "followup: d3 failed, the mean of the other 2"
    assert change_summary(got.reset_index()).set_index("measure").loc["gait_speed_mps", "n_subjects"] == 2
    copy = rows.copy()
    copy.loc[copy["path"] == "a2", ["duplicate_of", "gait_speed_mps"]] = ["a", 1.0]  # a re-upload of trial a
    got = change_table(copy, visit_map=vmap).set_index("subject")
    assert got.loc["S1", "baseline_n_trials"] == 1 and "a2 is a copy of a, counted once" in got.loc["S1", "reason"]
    mixed = rows.copy()
    mixed.loc[mixed["path"] == "a2", "pipeline"] = "waist-pendulum"
    got = change_table(mixed, visit_map=vmap).set_index("subject")
    assert got.loc["S1", "status"] == "pipelines" and pd.isna(got.loc["S1", "gait_speed_mps_change"])
    assert "plasys, waist-pendulum" in got.loc["S1", "reason"]


def _dual_task_study(root):
    """Users 7880-7882: 20 m at 100 Hz, single = normal pace, dual = slow pace with 2.5 x the stride variability;
    7880 walks the single task twice."""
    from pdrlearn.io import write_session
    from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path

    for uid in (7880, 7881, 7882):
        trials = [("single", "normal", 1.0, 1), ("dual", "slow", 2.5, 1)] + ([("single", "normal", 1.0, 2)]
                                                                            if uid == 7880 else [])
        for cond, speed, var, k in trials:
            s = simulate_path([Stand(2), Straight(20), Stand(2)], UserProfile.from_seed(uid), speed=speed,
                              rate_hz=100, seed=uid * 10 + k, variability=var, name=f"u{uid}_{cond}{k}")
            folder = root / f"u{uid}" / f"{cond}{k}"
            write_session(s, folder)
            meta = json.loads((folder / "meta.json").read_text())
            (folder / "meta.json").write_text(json.dumps({**meta, "subject": f"P{uid}", "visit": cond}))


def test_track_all_compares_conditions_the_user_names_and_the_tables_join_c81_c82(tmp_path, capsys):
    """F5: track-all --metrics names the measures of changes.csv (each with its percent change); after --visit-map
    sessions.csv / bouts.csv said single / dual while subjects.csv / changes.csv said baseline / followup - now every
    table's visit is the paired name and visit_as_written meta.json's, so they join on (subject, visit); repeated
    trials are averaged (C83); a bad --metrics is one line before any tracking (B303)."""
    from pdrlearn.cli import main

    root = tmp_path / "study"
    _dual_task_study(root)
    (tmp_path / "map.json").write_text('{"single": "baseline", "dual": "followup"}')
    measures = "gait_speed_mps,median_cadence_spm,median_stride_time_s,stride_time_cv_pct,median_stride_length_m"
    out = tmp_path / "o"
    assert main(["track-all", "--no-plot", str(root), "--out", str(out), "--visit-map", str(tmp_path / "map.json"),
                 "--metrics", measures, "--group-by", "visit"]) == 0  # decision C202: groups.csv per visit
    assert "mean % change [95 % CI]" in capsys.readouterr().out
    read = {"dtype": {"subject": str, "visit": str}}
    sessions = pd.read_csv(out / "sessions.csv", **read)
    assert set(zip(sessions["visit"], sessions["visit_as_written"], strict=True)) == {("baseline", "single"),
                                                                                      ("followup", "dual")}
    bouts = pd.read_csv(out / "bouts.csv", **read)
    assert set(bouts["visit"]) == {"baseline", "followup"} and set(bouts["visit_as_written"]) == {"single", "dual"}
    subjects = pd.read_csv(out / "subjects.csv", **read)
    changes = pd.read_csv(out / "changes.csv", **read)
    keys = ["subject", "visit"]
    assert len(subjects.merge(sessions[keys], on=keys)) == len(sessions)  # every session has its subjects.csv row
    assert len(changes.merge(sessions[keys], on=keys)) == 3  # each subject's followup session
    assert changes[["baseline_visit_as_written", "visit_as_written"]].drop_duplicates().values.tolist() == [
        ["single", "dual"]]
    assert changes["status"].eq("ok").all() and changes["baseline_n_trials"].tolist() == [2, 1, 1]
    s = sessions.set_index("path")
    single = s.loc[["u7880/single1", "u7880/single2"], "median_stride_time_s"].mean()
    dual = s.loc["u7880/dual1", "median_stride_time_s"]
    row = changes.set_index("subject").loc["P7880"]
    assert row["median_stride_time_s_baseline"] == pytest.approx(single)
    assert row["median_stride_time_s_change_pct"] == pytest.approx(100 * (dual - single) / single)
    assert {f"{m}_change_pct" for m in measures.split(",")} <= set(changes.columns)
    assert "distance_error_pct_change" not in changes  # only the measures asked for
    assert json.loads((out / "run.json").read_text())["options"]["metrics"] == measures
    # decision C202: groups.csv has a row per visit across the subjects (sessions.csv's group: still the folder)
    groups = pd.read_csv(out / "groups.csv", dtype={"group": str}).set_index("group")
    assert groups.index.tolist() == ["baseline", "followup"] and set(sessions["group"]) == {"u7880", "u7881", "u7882"}
    for visit in ("baseline", "followup"):
        assert groups.loc[visit, "n_tracked"] == (sessions["visit"] == visit).sum()
        assert groups.loc[visit, "gait_speed_mps_mean"] == pytest.approx(
            sessions.loc[sessions["visit"] == visit, "gait_speed_mps"].mean(), rel=1e-9)
    assert main(["report", str(out), "--out", str(tmp_path / "rep")]) == 0  # the run's measures, from run.json
    text = (tmp_path / "rep" / "report.md").read_text()
    assert "stride_time_cv_pct" in text and "| followup " in text  # C202: the report reads the visit groups
    capsys.readouterr()
    assert main(["track-all", "--no-plot", str(root), "--out", str(tmp_path / "o2"), "--metrics",
                 "gait_speed_mps,cadence"]) == 2
    err = capsys.readouterr().err
    assert "--metrics gait_speed_mps,cadence: unknown measure 'cadence'" in err and "B303" in err
    assert "Traceback" not in err and len(err.strip().splitlines()) == 1 and not (tmp_path / "o2").exists()
